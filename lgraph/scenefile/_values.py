"""Typed values of a scene file: numbers, vectors, strings, tables, each checked
and reported by key."""

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Callable, Mapping
from typing import Any

from ._errors import Key, _Invalid
from ._locate import _key_text, _show


# -- typed getters ---------------------------------------------------------------
def _is_number(v: Any) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _number(key: Key, v: Any, *, positive: bool = False) -> float:
    if not _is_number(v):
        raise _Invalid(key, f"expected a number, got {_show(v)}")
    if not math.isfinite(v):
        raise _Invalid(key, f"expected a finite number, got {v!r}")
    if positive and not v > 0:
        raise _Invalid(key, f"expected a positive number, got {v!r}")
    return v


def _vector(key: Key, v: Any) -> list[float]:
    if not isinstance(v, list) or len(v) != 3:
        raise _Invalid(key, f"expected an array of 3 numbers, got {_show(v)}")
    return [_number(key + (k,), x) for k, x in enumerate(v)]


def _table(key: Key, v: Any) -> dict[str, Any]:
    if not isinstance(v, dict):
        raise _Invalid(key, f"expected a table, got {_show(v)}")
    return v


def _string(key: Key, v: Any, choices: tuple[str, ...] | None = None) -> str:
    if not isinstance(v, str):
        raise _Invalid(key, f"expected a string, got {_show(v)}")
    if choices is not None and v not in choices:
        raise _Invalid(key, f"expected one of {', '.join(map(repr, choices))}, got {v!r}")
    return v


def _boolean(key: Key, v: Any) -> bool:
    if not isinstance(v, bool):
        raise _Invalid(key, f"expected true or false, got {_show(v)}")
    return v


def _only(key: Key, table: Mapping[str, Any], allowed: tuple[str, ...]) -> None:
    for k in table:
        if k not in allowed:
            where = f" in [{_key_text(key)}]" if key else ""
            raise _Invalid(key + (k,), f"unknown key {k!r}{where}; allowed: {', '.join(allowed)}")


def _required(key: Key, table: Mapping[str, Any], name: str) -> Any:
    if name not in table:
        where = _key_text(key) or "the file"
        raise _Invalid(key, f"missing required key {name!r} in {where}")
    return table[name]


def _call(key: Key, what: str, func: Callable[..., Any], kwargs: dict[str, Any]) -> Any:
    """Call a constructor; its ValueError/TypeError names the key it is about."""
    from ..plugins import PluginError

    try:
        return func(**kwargs)
    except PluginError as exc:
        first = str(exc).splitlines()[0].removeprefix("lgraph: ").removesuffix("; original error:")
        cause = exc.__cause__
        why = f" ({type(cause).__name__}: {cause})" if cause is not None else ""
        raise _Invalid(key, f"{what}: {first}{why}; see 'lgraph plugins'") from None
    except (ValueError, TypeError, NotImplementedError) as exc:
        msg = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        m = re.match(r"^\s*[\w.]+: (\w+) must", msg)
        sub = key + (m.group(1),) if m and m.group(1) in kwargs else key
        raise _Invalid(sub, f"{what}: {msg}") from None
