"""floornav's spaces as gymnasium.spaces, for libraries that check isinstance(space, gymnasium...).

floornav does not depend on Gymnasium (it is not in Debian 12); its Box and Dict carry what
Gymnasium's do (shape, dtype, low, high, spaces), so the mapping is one to one:

    import floornav
    from gymnasium_adapter import to_gymnasium, wrap_vec_env

    env = wrap_vec_env(floornav.VecEnv("scenarios/rectangle.yaml", 64,
                                       randomize={"start": "free", "goal": "free"}))
    env.single_observation_space      # gymnasium.spaces.Dict
"""

from __future__ import annotations

from typing import Any

import gymnasium

import floornav


def to_gymnasium(space: Any) -> gymnasium.spaces.Space:
    """The gymnasium.spaces equivalent of a floornav Box or Dict (same bounds, shape, dtype)."""
    if isinstance(space, floornav.Box):
        return gymnasium.spaces.Box(low=space.low, high=space.high, shape=space.shape,
                                    dtype=space.dtype)
    if isinstance(space, floornav.Dict):
        return gymnasium.spaces.Dict({k: to_gymnasium(s) for k, s in space.spaces.items()})
    raise TypeError(f"not a floornav space: {space!r}")


def wrap_vec_env(env: floornav.VecEnv) -> floornav.VecEnv:
    """Replaces the VecEnv's four spaces by their gymnasium equivalents (in place)."""
    for name in ("observation_space", "action_space", "single_observation_space",
                 "single_action_space"):
        setattr(env, name, to_gymnasium(getattr(env, name)))
    return env
