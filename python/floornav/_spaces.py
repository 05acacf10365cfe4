"""Observation and action spaces shaped like Gymnasium's ``Box`` and ``Dict`` (``shape``,
``dtype``, ``low``, ``high``, ``spaces``, seeded ``sample()``, ``contains()``), without depending
on Gymnasium: an adapter maps them one to one (examples/python/gymnasium_adapter.py)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Iterator, Optional, Sequence, Union

import numpy as np

SeedLike = Union[None, int, np.random.SeedSequence]


class Space:
    """What every space has: ``shape``, ``dtype``, a random generator ``np_random`` seeded by
    :meth:`seed` (from the operating system's entropy until then), ``sample()`` and
    ``contains(x)`` (also ``x in space``)."""

    def __init__(self, shape: Optional[tuple], dtype: Any, seed: SeedLike = None) -> None:
        self.shape = shape
        self.dtype = None if dtype is None else np.dtype(dtype)
        self._np_random: Optional[np.random.Generator] = None
        if seed is not None:
            self.seed(seed)

    @property
    def np_random(self) -> np.random.Generator:
        if self._np_random is None:
            self.seed()
        assert self._np_random is not None
        return self._np_random

    def seed(self, seed: SeedLike = None) -> list:
        """Seeds the generator behind :meth:`sample`: the same seed, the same samples.
        Returns the seeds used (Gymnasium's convention)."""
        if seed is not None and not isinstance(seed, np.random.SeedSequence):
            if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
                raise ValueError(f"a space's seed is a non-negative integer or None, got {seed!r}")
        sequence = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
        self._np_random = np.random.Generator(np.random.PCG64(sequence))
        return [sequence.entropy]

    def sample(self) -> Any:
        raise NotImplementedError

    def contains(self, x: Any) -> bool:
        raise NotImplementedError

    def __contains__(self, x: Any) -> bool:
        return self.contains(x)


class Box(Space):
    """A box in R^shape (or in the integers, for an integer dtype): ``low <= x <= high``
    element-wise, bounds that may be infinite. ``sample()`` draws as Gymnasium's Box does:
    uniformly where both bounds are finite, from a normal distribution where neither is, and
    from an exponential one off the finite bound otherwise; integer boxes uniformly among the
    integers of [low, high]."""

    def __init__(self, low: Any, high: Any, shape: Optional[Sequence[int]] = None,
                 dtype: Any = np.float64, seed: SeedLike = None) -> None:
        dtype = np.dtype(dtype)
        if shape is None:
            shape = np.broadcast(np.asarray(low), np.asarray(high)).shape
        shape = tuple(int(n) for n in shape)
        low_a = np.broadcast_to(np.asarray(low, dtype=np.float64), shape).astype(dtype, copy=True)
        high_a = np.broadcast_to(np.asarray(high, dtype=np.float64), shape).astype(dtype, copy=True)
        if np.any(low_a > high_a):
            raise ValueError("a Box's low must not exceed its high")
        super().__init__(shape, dtype, seed)
        self.low: np.ndarray = low_a
        self.high: np.ndarray = high_a
        self.low.setflags(write=False)
        self.high.setflags(write=False)

    @property
    def bounded_below(self) -> np.ndarray:
        return np.isfinite(self.low) if self.dtype.kind == "f" else np.ones(self.shape, bool)

    @property
    def bounded_above(self) -> np.ndarray:
        return np.isfinite(self.high) if self.dtype.kind == "f" else np.ones(self.shape, bool)

    def is_bounded(self, manner: str = "both") -> bool:
        below, above = bool(np.all(self.bounded_below)), bool(np.all(self.bounded_above))
        if manner == "both":
            return below and above
        if manner == "below":
            return below
        if manner == "above":
            return above
        raise ValueError(f"manner is 'both', 'below' or 'above', got {manner!r}")

    def sample(self) -> np.ndarray:
        rng = self.np_random
        if self.dtype.kind in "iu":
            return rng.integers(self.low, self.high, endpoint=True, dtype=self.dtype)
        low, high = self.low.astype(np.float64), self.high.astype(np.float64)
        below, above = np.isfinite(low), np.isfinite(high)
        out = np.empty(self.shape, dtype=np.float64)
        both, neither = below & above, ~below & ~above
        only_low, only_high = below & ~above, ~below & above
        out[both] = rng.uniform(low[both], high[both])
        out[neither] = rng.normal(size=int(neither.sum()))
        out[only_low] = low[only_low] + rng.exponential(size=int(only_low.sum()))
        out[only_high] = high[only_high] - rng.exponential(size=int(only_high.sum()))
        return out.astype(self.dtype)

    def contains(self, x: Any) -> bool:
        if not isinstance(x, np.ndarray):
            try:
                x = np.asarray(x, dtype=self.dtype)
            except (ValueError, TypeError):
                return False
        if x.shape != self.shape or not np.can_cast(x.dtype, self.dtype):
            return False
        return bool(np.all(x >= self.low) and np.all(x <= self.high))

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Box) and self.shape == other.shape and self.dtype == other.dtype
                and np.array_equal(self.low, other.low) and np.array_equal(self.high, other.high))

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        def bound(a: np.ndarray) -> str:
            return str(a.flat[0]) if a.size and np.all(a == a.flat[0]) else "array"
        return f"Box({bound(self.low)}, {bound(self.high)}, {self.shape}, {self.dtype})"


class Dict(Space, Mapping):
    """A dict of spaces, keyed as the observation is (``spaces``); ``sample()`` gives a dict
    with a sample of each; ``contains(x)`` holds for a dict with exactly these keys whose every
    entry its space contains. Seeding the Dict seeds every subspace from one seed."""

    def __init__(self, spaces: Mapping[str, Space], seed: SeedLike = None) -> None:
        self.spaces: dict = dict(spaces)
        for k, s in self.spaces.items():
            if not isinstance(s, Space):
                raise ValueError(f"Dict: {k!r} is not a space")
        super().__init__(None, None, seed)

    def seed(self, seed: SeedLike = None) -> list:
        sequence = seed if isinstance(seed, np.random.SeedSequence) else None
        if sequence is None:
            if seed is not None and (isinstance(seed, bool) or not isinstance(seed, (int, np.integer))
                                     or seed < 0):
                raise ValueError(f"a space's seed is a non-negative integer or None, got {seed!r}")
            sequence = np.random.SeedSequence(seed)
        children = sequence.spawn(len(self.spaces))
        self._np_random = np.random.Generator(np.random.PCG64(sequence))
        for space, child in zip(self.spaces.values(), children):
            space.seed(child)
        return [sequence.entropy]

    def sample(self) -> dict:
        return {k: s.sample() for k, s in self.spaces.items()}

    def contains(self, x: Any) -> bool:
        return (isinstance(x, Mapping) and set(x.keys()) == set(self.spaces.keys())
                and all(self.spaces[k].contains(x[k]) for k in self.spaces))

    def __getitem__(self, key: str) -> Space:
        return self.spaces[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.spaces)

    def __len__(self) -> int:
        return len(self.spaces)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Dict) and self.spaces == other.spaces

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return "Dict(" + ", ".join(f"{k!r}: {s!r}" for k, s in self.spaces.items()) + ")"


def batch_space(space: Space, n: int) -> Space:
    """``n`` copies of ``space`` stacked along a new first axis (Gymnasium's batch_space)."""
    if isinstance(space, Box):
        return Box(np.broadcast_to(space.low, (n,) + space.shape),
                   np.broadcast_to(space.high, (n,) + space.shape), (n,) + space.shape, space.dtype)
    if isinstance(space, Dict):
        return Dict({k: batch_space(s, n) for k, s in space.spaces.items()})
    raise ValueError(f"cannot batch {space!r}")
