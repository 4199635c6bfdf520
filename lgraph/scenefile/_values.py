"""Typed values of a scene file: numbers, vectors, strings, tables, and the
compound values that objects, groups and ``[render]`` share (transform steps,
style tables), each checked and reported by key.

A number may be written as a formula of the file's constants (``"2*pi"``):
the constants are held in a context variable while the file is read
(:func:`constants_of`)."""

from __future__ import annotations

import contextvars
import math
import numbers
import re
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from types import MappingProxyType
from typing import Any

from ._errors import Key, _Invalid
from ._locate import _key_text, _show

#: the constants of the scene file being read (name -> value)
_CONSTANTS: contextvars.ContextVar[Mapping[str, float]] = contextvars.ContextVar(
    "lgraph_scene_constants", default=MappingProxyType({})
)


@contextmanager
def constants_of(values: Mapping[str, float]) -> Iterator[None]:
    """Make ``values`` the constants of the file while it is read: every
    number of the file may be a formula of them."""
    token = _CONSTANTS.set(values)
    try:
        yield
    finally:
        _CONSTANTS.reset(token)


def _formula(key: Key, text: Any, variables: tuple[str, ...]) -> Any:
    """A :class:`~lgraph.formula.Formula` of ``variables`` and the file's
    constants; a problem names the key."""
    from ..formula import FormulaError, formula

    if not isinstance(text, str):
        raise _Invalid(key, f"expected a formula (a string), got {_show(text)}")
    try:
        return formula(text, variables, _CONSTANTS.get())
    except FormulaError as exc:
        raise _Invalid(key, str(exc)) from None


# -- typed getters ---------------------------------------------------------------
def _is_number(v: Any) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _number(key: Key, v: Any, *, positive: bool = False) -> float:
    if isinstance(v, str):  # a formula of the file's constants ("2*pi")
        v = _formula(key, v, ()).value()
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
    """Every key of ``table`` not in ``allowed`` is a problem (all reported at once)."""
    where = f" in [{_key_text(key)}]" if key else ""
    bad = [
        _Invalid(key + (k,), f"unknown key {k!r}{where}; allowed: {', '.join(allowed)}")
        for k in table
        if k not in allowed
    ]
    if bad:
        raise _Invalid(bad[0].key, bad[0].message, bad[1:])


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


# -- compound values ---------------------------------------------------------------
def _transform(key: Key, items: Any) -> Any:
    import lgraph as lg

    if isinstance(items, dict):
        items = [items]
    if not isinstance(items, list):
        raise _Invalid(
            key, f"expected an array of {{ translate | rotate | scale = ... }}, got {_show(items)}"
        )
    total = None
    for k, step in enumerate(items):
        sk = key + (k,)
        step = _table(sk, step)
        if len(step) != 1 or next(iter(step)) not in ("translate", "rotate", "scale"):
            raise _Invalid(
                sk,
                "each transform step is one of { translate = [x, y, z] }, "
                "{ rotate = { axis = ..., degrees = ... } }, { scale = s | [sx, sy, sz] }",
            )
        op, arg = next(iter(step.items()))
        ak = sk + (op,)
        if op == "translate":
            t = lg.translate(*_vector(ak, arg))
        elif op == "rotate":
            arg = _table(ak, arg)
            _only(ak, arg, ("axis", "degrees"))
            axis = _required(ak, arg, "axis")
            if isinstance(axis, str):
                axis = _string(ak + ("axis",), axis, ("x", "y", "z"))
            else:
                axis = _vector(ak + ("axis",), axis)
            deg = _number(ak + ("degrees",), _required(ak, arg, "degrees"))
            t = _call(
                ak,
                "rotate",
                lambda **kw: lg.rotate(kw["axis"], kw["degrees"]),
                {"axis": axis, "degrees": deg},
            )
        else:
            factors = [_number(ak, arg)] if _is_number(arg) else _vector(ak, arg)
            if any(x == 0 for x in factors):
                raise _Invalid(ak, f"scale factors must be non-zero, got {arg!r}")
            t = lg.scale(*factors)
        total = t if total is None else t @ total
    return total


_STYLE = ("color", "width", "dash")


def _style(key: Key, s: Any) -> Any:
    from ..scene.style import Style

    s = _table(key, s)
    _only(key, s, _STYLE)
    kw: dict[str, Any] = {}
    if "color" in s:
        c = s["color"]
        kw["color"] = (
            _string(key + ("color",), c)
            if not isinstance(c, list)
            else tuple(_number(key + ("color", k), x) for k, x in enumerate(c))
        )
    if "width" in s:
        kw["width"] = _number(key + ("width",), s["width"], positive=True)
    if "dash" in s:
        d = s["dash"]
        if d is False:
            kw["dash"] = None
        elif isinstance(d, list):
            kw["dash"] = tuple(
                _number(key + ("dash", k), x, positive=True) for k, x in enumerate(d)
            )
        else:
            raise _Invalid(
                key + ("dash",), f"expected an array of lengths in pt or false, got {_show(d)}"
            )
    return _call(key, "style", Style, kw)


def _styles(key: Key, s: Any) -> Any:
    s = _table(key, s)
    if s and all(isinstance(v, dict) for v in s.values()):  # per family
        return {fam: _style(key + (fam,), v) for fam, v in s.items()}
    return _style(key, s)
