"""The members of a scene file: ``[[object]]`` (a surface by registry name, its
parameters and families), ``[[labels]]`` and ``[[points]]`` tables.

Parameters are checked against the constructor's signature (attrs fields or
:func:`inspect.signature`): known names, numbers or arrays of numbers,
strings only where the constructor declares a ``str`` (elsewhere a string is
a formula of the file's constants, ``"2*pi"``).  Surfaces written as formulas
(``surface = "parametric"``, ``"revolution"``) are built in ``_formulas.py``.
No formula of docs/mathematics.rst.
"""

from __future__ import annotations

import re
from typing import Any

from ._errors import Key, _Collect, _fail, _Invalid
from ._formulas import (
    ALGEBRAIC,
    PARAMETRIC,
    REVOLUTION,
    algebraic_surface,
    level_function,
    parametric_surface,
    revolution_surface,
)
from ._locate import _show
from ._values import (
    _boolean,
    _call,
    _is_number,
    _number,
    _only,
    _required,
    _string,
    _styles,
    _table,
    _transform,
    _vector,
)

#: surfaces written as formulas: their keys (besides those of every object)
#: and their builders
_FORMULA_SURFACES = {
    "parametric": (PARAMETRIC, parametric_surface),
    "revolution": (REVOLUTION, revolution_surface),
    "algebraic": (ALGEBRAIC, algebraic_surface),
}

_OBJECT = (
    "surface",
    "params",
    "families",
    "transform",
    "style",
    "contour",
    "hides",
    "intersections",
)


def _object(
    key: Key, obj: dict[str, Any], check: _Collect
) -> tuple[Any, list[Any], dict[str, Any]] | None:
    """One ``[[object]]``: its surface, then its families, transform, style and
    flags, each checked on its own (all their problems are reported)."""
    from ..plugins import get_surface

    name = obj.get("surface")
    if isinstance(name, str) and name in _FORMULA_SURFACES:  # formulas: keys in the table
        keys, build = _FORMULA_SURFACES[name]
        check(_only, key, obj, tuple(k for k in _OBJECT if k != "params") + keys)
        surface = build(key, obj)
    else:
        check(_only, key, obj, _OBJECT)
        name = _string(key + ("surface",), _required(key, obj, "surface"))
        if name == "parametric_surface":
            raise _Invalid(
                key + ("surface",),
                "a parametric_surface needs a Python function; in a scene file write "
                'surface = "parametric" with formulas x, y, z of u, v and ranges u, v',
            )
        if name in ("implicit_surface", "algebraic_surface"):
            raise _Invalid(
                key + ("surface",),
                f"{name} needs a function or a polynomial; in a scene file write "
                'surface = "algebraic" with a formula F of x, y, z and radius or bounds',
            )
        try:
            cls = get_surface(name)
        except KeyError as exc:
            raise _Invalid(key + ("surface",), str(exc.args[0])) from None
        params = _table(key + ("params",), obj.get("params", {}))
        kwargs = _params(key + ("params",), cls, name, params)
        surface = _call(key + ("params",), f"surface {name!r}", cls, kwargs)
    families = []
    # default: the class's own (parameter lines for most; an arrow: its outline)
    fams = obj.get("families", list(getattr(surface, "default_families", ("parameter_lines",))))
    if not isinstance(fams, list):
        check(_fail, key + ("families",), f"expected an array of families, got {_show(fams)}")
        fams = []
    for k, f in enumerate(fams):
        families.append(check(_family, key + ("families", k), f, surface))
    kw: dict[str, Any] = {}
    if "transform" in obj:
        kw["transform"] = check(_transform, key + ("transform",), obj["transform"])
    if "style" in obj:
        kw["style"] = check(_styles, key + ("style",), obj["style"])
    for flag in ("contour", "hides", "intersections"):
        if flag in obj:
            kw[flag] = check(_boolean, key + (flag,), obj[flag])
    if any(f is None for f in families) or any(v is None for v in kw.values()):
        return None  # the problems are recorded already
    return surface, families, kw


def _parameters(cls: Any) -> tuple[dict[str, str], set[str]]:
    """Keyword parameters of a constructor -> their annotation text, and the required ones."""
    import inspect

    import attrs

    if attrs.has(cls):
        fields = [f for f in attrs.fields(cls) if f.init]
        ann = {f.alias or f.name: str(f.type or "") for f in fields}
        req = {f.alias or f.name for f in fields if f.default is attrs.NOTHING}
        return ann, req
    try:
        sig = inspect.signature(cls)
    except (TypeError, ValueError):
        return {}, set()
    ann, req = {}, set()
    for p in sig.parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        ann[p.name] = "" if p.annotation is p.empty else str(p.annotation)
        if p.default is p.empty:
            req.add(p.name)
    return ann, req


def _params(key: Key, cls: Any, what: str, params: dict[str, Any]) -> dict[str, Any]:
    """Check keyword arguments: known names, numbers (or arrays of numbers);
    strings only where the constructor declares a ``str`` parameter."""
    ann, required = _parameters(cls)
    known = ", ".join(ann) or "(none)"
    for name in params:
        if ann and name not in ann:
            raise _Invalid(key + (name,), f"unknown parameter {name!r} of {what}; known: {known}")
    for name in sorted(required):
        if name not in params:
            raise _Invalid(key, f"missing required parameter {name!r} of {what} ({known})")
    return {n: _param_value(key + (n,), v, ann.get(n, "")) for n, v in params.items()}


def _param_value(key: Key, v: Any, annotation: str) -> Any:
    if isinstance(v, bool):
        if "bool" in annotation:
            return v
        raise _Invalid(key, f"expected a number, got {_show(v)}")
    if _is_number(v) or callable(v):  # callable: a formula built here (level functions)
        return v
    if isinstance(v, str):
        if re.search(r"\bstr\b|Literal|\bAny\b", annotation):  # label = "$N$"
            return v
        return _number(key, v)  # a formula of the file's constants
    if isinstance(v, list):
        return tuple(_param_value(key + (k,), x, "") for k, x in enumerate(v))
    raise _Invalid(key, f"expected a number or an array of numbers, got {_show(v)}")


def _family(key: Key, f: Any, surface: Any) -> Any:
    from types import SimpleNamespace

    from ..families.cache import family_batches
    from ..families.level import NAMED_FUNCTIONS
    from ..plugins import get_family

    if isinstance(f, str):
        f = {"name": f}
        name_key = key
    else:
        f = _table(key, f)
        name_key = key + ("name",)
    name = _string(name_key, _required(key, f, "name"))
    try:
        cls = get_family(name)
    except KeyError as exc:
        raise _Invalid(name_key, str(exc.args[0])) from None
    args = {k: v for k, v in f.items() if k != "name"}
    fn = args.get("function")
    if name == "level_lines" and isinstance(fn, str) and fn not in NAMED_FUNCTIONS:
        args["function"] = level_function(key + ("function",), fn, args.get("argument"))
    kwargs = _params(key, cls, f"family {name!r}", args)
    family = _call(key, f"family {name!r}", cls, kwargs)
    # catch families the surface cannot draw (no closed forms) and budgets
    # that need the surface (integrated lines) before rendering; through the
    # family cache, so the render does not compute view-independent lines again
    try:
        family_batches(SimpleNamespace(surface=surface), 0, family, None)
    except (NotImplementedError, AttributeError) as exc:
        raise _Invalid(
            name_key, f"family {name!r} cannot be drawn on this surface: {exc}"
        ) from None
    except ValueError as exc:  # a budget or a parameter the surface refuses
        raise _Invalid(key, f"family {name!r}: {str(exc).splitlines()[0]}") from None
    return family


_LABEL = ("text", "at", "offset", "anchor", "size", "color", "always", "halo")


def _halo(key: Key, v: Any) -> bool | float:
    """``halo = true | false | <gap in pt>``."""
    if isinstance(v, bool):
        return v
    return _number(key, v)


def _label(key: Key, t: dict[str, Any]) -> Any:
    from ..scene.objects import Label

    _only(key, t, _LABEL)
    text = _string(key + ("text",), _required(key, t, "text"))
    kw: dict[str, Any] = {"at": _vector(key + ("at",), _required(key, t, "at"))}
    if "offset" in t:
        off = t["offset"]
        if not (isinstance(off, list) and len(off) == 2):
            raise _Invalid(key + ("offset",), f"expected [dx, dy] in pt, got {_show(off)}")
        kw["offset"] = [_number(key + ("offset", k), x) for k, x in enumerate(off)]
    if "anchor" in t:
        kw["anchor"] = _string(key + ("anchor",), t["anchor"])
    if "size" in t:
        kw["size"] = _number(key + ("size",), t["size"], positive=True)
    if "color" in t:
        kw["color"] = _color_value(key + ("color",), t["color"])
    if "always" in t:
        kw["always"] = _boolean(key + ("always",), t["always"])
    if "halo" in t:
        kw["halo"] = _halo(key + ("halo",), t["halo"])
    return _call(key, "label", lambda **kw: Label(text, **kw), kw)


def _point(key: Key, t: dict[str, Any]) -> Any:
    from ..scene.objects import Point
    from ..scene.style import Style

    _only(key, t, ("at", "size", "color", "always", "halo"))
    kw: dict[str, Any] = {}
    if "size" in t:
        kw["size"] = _number(key + ("size",), t["size"], positive=True)
    if "color" in t:
        kw["style"] = _call(key + ("color",), "point", Style,
                            {"color": _color_value(key + ("color",), t["color"])})  # fmt: skip
    if "always" in t:
        kw["always"] = _boolean(key + ("always",), t["always"])
    if "halo" in t:
        kw["halo"] = _halo(key + ("halo",), t["halo"])
    at = _vector(key + ("at",), _required(key, t, "at"))
    return _call(key, "point", lambda **kw: Point(at, **kw), kw)


def _color_value(key: Key, v: Any) -> Any:
    if isinstance(v, str):
        return v
    if isinstance(v, list) and len(v) == 3:
        return [_number(key + (k,), x) for k, x in enumerate(v)]
    raise _Invalid(key, f"expected a colour '#rrggbb', a name or [r, g, b], got {_show(v)}")
