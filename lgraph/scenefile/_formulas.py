"""Formulas in scene files: ``[constants]``, surfaces, curves, profiles and
level functions written as text (:mod:`lgraph.formula`, never evaluated as
Python), and numbers written as formulas of the constants (``"2*pi"``).

The constants are read first (:func:`read_constants`) and held while the
rest of the file is read (``_values.constants_of``).  No formula of
docs/mathematics.rst.
"""

from __future__ import annotations

import keyword
from collections.abc import Mapping
from typing import Any

from ._errors import Key, _Invalid
from ._locate import _show
from ._values import (
    _CONSTANTS,
    _boolean,
    _call,
    _formula,
    _number,
    _only,
    _required,
    _styles,
    _transform,
    _vector,
)

#: names a constant may not take: the variables of the formulas
_VARIABLES = ("u", "v", "t", "x", "y", "z")

#: the keys of a formula surface, curve and surface of revolution
PARAMETRIC = ("x", "y", "z", "u", "v", "periodic", "poles")
REVOLUTION = ("rho", "z", "t", "axis", "angle")
CURVE = ("x", "y", "z", "t", "closed", "style", "transform")
ALGEBRAIC = ("F", "radius", "center", "bounds", "grid")


def read_constants(key: Key, table: Any) -> dict[str, float]:
    """The ``[constants]`` table: numbers or formulas of the constants above
    them (``b = "2*a"``), in the order written."""
    from ..formula import FUNCTIONS

    if not isinstance(table, dict):
        raise _Invalid(key, f"expected a table of named numbers, got {_show(table)}")
    out: dict[str, float] = {}
    reserved = set(FUNCTIONS) | set(_VARIABLES) | {"pi", "e"}
    for name, value in table.items():
        k = key + (name,)
        if not name.isidentifier() or keyword.iskeyword(name) or name.startswith("_"):
            raise _Invalid(k, f"a constant needs a name like a or r_1, got {name!r}")
        if name in reserved:
            raise _Invalid(
                k,
                f"{name!r} cannot name a constant: it is a variable (u, v, t, x, y, z), "
                "a function or pi / e",
            )
        token = _CONSTANTS.set(out)
        try:
            out[name] = _number(k, value)
        finally:
            _CONSTANTS.reset(token)
    return out


def _range(key: Key, value: Any) -> tuple[float, float]:
    if not (isinstance(value, list) and len(value) == 2):
        raise _Invalid(key, f"expected a range [lo, hi] (numbers or formulas), got {_show(value)}")
    lo, hi = (_number(key + (k,), x) for k, x in enumerate(value))
    if not lo < hi:
        raise _Invalid(key, f"expected lo < hi, got [{lo:g}, {hi:g}]")
    return lo, hi


def _texts(
    key: Key, obj: Mapping[str, Any], names: tuple[str, ...], variables: tuple[str, ...]
) -> tuple[str, ...]:

    texts = []
    for n in names:
        f = _formula(key + (n,), _required(key, obj, n), variables)
        texts.append(f.text)
    return tuple(texts)


def _flags(key: Key, value: Any, what: str) -> Any:
    """``periodic`` / ``poles``: a bool, or an array of bools (pairs nested);
    ``periodic`` also takes ``"twisted"`` (glued with a twist)."""
    if isinstance(value, bool) or (what == "periodic" and value == "twisted"):
        return value
    if isinstance(value, list) and len(value) == 2:
        return tuple(_flags(key + (k,), x, what) for k, x in enumerate(value))
    allowed = 'true, false, "twisted"' if what == "periodic" else "true/false"
    raise _Invalid(
        key, f"expected {allowed} or a pair [u, v] of them for {what}, got {_show(value)}"
    )


def parametric_surface(key: Key, obj: Mapping[str, Any]) -> Any:
    """``surface = "parametric"``: ``x, y, z`` formulas of ``u, v`` over the
    ranges ``u`` and ``v``; ``periodic`` and ``poles`` as for
    :class:`~lgraph.ParametricSurface`."""
    from ..surfaces.parametric import ParametricSurface

    texts = _texts(key, obj, ("x", "y", "z"), ("u", "v"))
    u = _range(key + ("u",), _required(key, obj, "u"))
    v = _range(key + ("v",), _required(key, obj, "v"))
    kw: dict[str, Any] = {}
    for flag in ("periodic", "poles"):
        if flag in obj:
            kw[flag] = _flags(key + (flag,), obj[flag], flag)
    c = _CONSTANTS.get()

    def build(**k: Any) -> Any:
        return ParametricSurface.from_formulas(*texts, u, v, constants=c, **k)

    return _call(key, "surface 'parametric'", build, kw)


def algebraic_surface(key: Key, obj: Mapping[str, Any]) -> Any:
    """``surface = "algebraic"``: the polynomial ``F`` (a formula of ``x, y, z``
    and the constants; degree at most 12, expanded by
    :mod:`lgraph.surfaces.implicit._polynomial`) clipped by the ball ``radius`` (about
    ``center``) or the box ``bounds = [[x0, x1], [y0, y1], [z0, z1]]``."""
    from ..surfaces.implicit.algebraic import AlgebraicSurface

    (text,) = _texts(key, obj, ("F",), ("x", "y", "z"))
    kw: dict[str, Any] = {"polynomial": text}
    if "radius" in obj:
        kw["radius"] = _number(key + ("radius",), obj["radius"], positive=True)
    if "center" in obj:
        kw["center"] = _vector(key + ("center",), obj["center"])
    if "bounds" in obj:
        b = obj["bounds"]
        if not (isinstance(b, list) and len(b) == 3):
            raise _Invalid(
                key + ("bounds",),
                f"expected [[x0, x1], [y0, y1], [z0, z1]], got {_show(b)}",
            )
        kw["bounds"] = tuple(_range(key + ("bounds", k), r) for k, r in enumerate(b))
    if "grid" in obj:
        g = obj["grid"]
        if isinstance(g, bool) or not isinstance(g, int):
            raise _Invalid(key + ("grid",), f"expected an integer, got {_show(g)}")
        kw["grid"] = g
    if "radius" not in kw and "bounds" not in kw:
        raise _Invalid(key, "an algebraic surface needs radius (a ball) or bounds (a box)")
    c = _CONSTANTS.get()

    def build(**k: Any) -> Any:
        # F's errors name the key F
        return AlgebraicSurface(**k, constants=c)

    try:
        return _call(key, "surface 'algebraic'", build, kw)
    except _Invalid as exc:
        if "polynomial" in str(exc):
            raise _Invalid(key + ("F",), str(exc).split(": ", 1)[-1]) from None
        raise


def revolution_surface(key: Key, obj: Mapping[str, Any]) -> Any:
    """``surface = "revolution"``: the profile ``rho, z`` (formulas of ``t``)
    over the range ``t``, turned about ``axis`` (3 numbers, default z) by
    ``angle`` (a range, default a full turn)."""
    from ..surfaces.revolution import SurfaceOfRevolution
    from ..surfaces.revolution.profiles import Profile

    rho, z = _texts(key, obj, ("rho", "z"), ("t",))
    t = _range(key + ("t",), _required(key, obj, "t"))
    kw: dict[str, Any] = {}
    if "axis" in obj:
        kw["axis"] = _vector(key + ("axis",), obj["axis"])
    if "angle" in obj:
        kw["angle_range"] = _range(key + ("angle",), obj["angle"])
    profile = Profile.from_formulas(rho, z, t, constants=_CONSTANTS.get())
    return _call(key, "surface 'revolution'", lambda **k: SurfaceOfRevolution(profile, t, **k), kw)


def curve(key: Key, table: Mapping[str, Any]) -> tuple[Any, dict[str, Any]]:
    """A ``[[curve]]``: ``x, y, z`` formulas of ``t`` over the range ``t``,
    ``closed``, ``style`` and ``transform`` as for objects."""
    from ..curves import Curve

    _only(key, table, CURVE)
    x, y, z = _texts(key, table, ("x", "y", "z"), ("t",))
    t = _range(key + ("t",), _required(key, table, "t"))
    closed = _boolean(key + ("closed",), table["closed"]) if "closed" in table else False
    c = _CONSTANTS.get()
    item = _call(
        key, "curve", lambda: Curve.from_formulas(x, y, z, t, constants=c, closed=closed), {}
    )
    kw: dict[str, Any] = {}
    if "transform" in table:
        kw["transform"] = _transform(key + ("transform",), table["transform"])
    if "style" in table:
        kw["style"] = _styles(key + ("style",), table["style"])
    return item, kw


def level_function(key: Key, text: str, argument: Any) -> Any:
    """``function = "x^2 - y^2"`` of ``LevelLines``: a formula of ``x, y, z``
    (or of ``u, v`` with ``argument = "uv"``)."""
    from ..formula.maps import formula_function

    variables = ("u", "v") if argument == "uv" else ("x", "y", "z")
    f = _formula(key, text, variables)
    return formula_function(f.text, "uv" if argument == "uv" else "xyz", constants=_CONSTANTS.get())
