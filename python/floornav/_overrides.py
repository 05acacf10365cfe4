"""Overrides as the command line's ``--set KEY=VALUE``: a dict of dotted keys to Python values,
each value rendered as YAML text exactly as one would type it after the ``=``."""

from __future__ import annotations

import json
import math
import numbers
import re
from collections.abc import Iterable, Mapping
from typing import Any

_PLAIN = re.compile(r"^[A-Za-z_][A-Za-z0-9_.\-]*$")


def _nested_string(text: str) -> str:
    # Inside a flow list or map a plain word stays plain; anything else is quoted (JSON's
    # double-quoted strings are valid YAML).
    return text if _PLAIN.match(text) else json.dumps(text)


def render_value(value: Any, top: bool = True) -> str:
    """YAML text for one override value: a string as given (like ``--set k=text``), numbers as
    the shortest text that reads back to the same float, lists, tuples and numpy arrays as
    ``[a, b]``, dicts as ``{k: v}``, None as ``null``, booleans as ``true``/``false``."""
    if isinstance(value, str):
        return value if top else _nested_string(value)
    if value is None:
        return "null"
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        f = float(value)
        if math.isnan(f):
            return ".nan"
        if math.isinf(f):
            return ".inf" if f > 0 else "-.inf"
        return repr(f)
    if isinstance(value, Mapping):
        items = []
        for k, v in value.items():
            if not isinstance(k, str):
                raise TypeError(f"override map keys are strings, got {k!r}")
            items.append(f"{_nested_string(k)}: {render_value(v, top=False)}")
        return "{" + ", ".join(items) + "}"
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return render_value(value.tolist(), top)
    if isinstance(value, Iterable):
        return "[" + ", ".join(render_value(v, top=False) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} ({type(value).__name__}) as a scenario value")


def render_overrides(overrides: Mapping[str, Any] | Iterable[str] | None) -> list[str]:
    """The ``KEY=VALUE`` texts of ``--set`` for a dict of dotted keys to values (in order), or
    for an iterable of such texts given as they are."""
    if overrides is None:
        return []
    if isinstance(overrides, str):
        raise TypeError("overrides are a dict {'sim.dt': 0.02} or a list of 'key=value' texts")
    if isinstance(overrides, Mapping):
        out = []
        for key, value in overrides.items():
            if not isinstance(key, str):
                raise TypeError(f"override keys are dotted strings like 'sim.dt', got {key!r}")
            out.append(f"{key}={render_value(value)}")
        return out
    out = []
    for item in overrides:
        if not isinstance(item, str):
            raise TypeError(f"an override text is 'key=value', got {item!r}")
        out.append(item)
    return out


def encode_text(text: Any, where: str, file: str = "") -> bytes:
    """The bytes the command line would pass for ``text`` (a path, a ``KEY=VALUE``): UTF-8, with
    the surrogate escapes that stand for bytes that are not UTF-8 (``os.fsdecode``,
    ``surrogateescape``) turned back into those bytes, so that the loader refuses them with the
    command line's own message. Any other lone surrogate is no text at all: :class:`InputError`
    naming ``file`` and ``where``, as the command line names its inputs."""
    if isinstance(text, bytes):
        return text
    try:
        return text.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError as e:
        from ._floornav import InputError

        shown = lambda t: t.encode("utf-8", "backslashreplace").decode("ascii", "replace")
        place = ":".join(p for p in (shown(file), shown(where)) if p)
        detail = (f"character U+{ord(text[e.start]):04X} at position {e.start + 1} is a lone "
                  "surrogate, which is not text (UTF-8 cannot hold it)")
        err = InputError(f"floornav: error: {place}: {detail}" if place else
                         f"floornav: error: {detail}")
        err.file, err.where, err.detail = shown(file), shown(where), detail
        raise err from None

