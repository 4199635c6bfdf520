"""The tables of a scene file and what they build: projector, objects, labels,
points, groups, page, render and save options."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from typing import Any

from ._errors import Key, _Collect, _Invalid
from ._locate import _show
from ._values import (
    _boolean,
    _call,
    _is_number,
    _number,
    _only,
    _required,
    _string,
    _table,
    _vector,
)

# -- the schema ------------------------------------------------------------------------
_TOP = ("projector", "object", "labels", "points", "group", "page", "render", "save")
_MEMBERS = ("object", "labels", "points", "group")


def parse_scene(data: Mapping[str, Any], suffix: str = ".pdf") -> tuple[Any, Any, dict[str, Any]]:
    """Build ``(scene, projector, options)`` from parsed TOML ``data``.

    ``suffix`` is that of the output file: ``[save]`` keys are checked
    against the options of its backend.  Raises ``_Invalid`` (with the
    offending key, and every further problem in ``more``) when anything is
    wrong; nothing is rendered here.
    """

    check = _Collect()
    check(_only, (), data, _TOP)
    projector = check(lambda: _projector(("projector",), _required((), data, "projector")))
    if not any(k in data for k in _MEMBERS):
        check(_required, (), data, "object")
    scene = _members((), data, check)
    render: dict[str, Any] = {}
    if "render" in data:
        render = check(
            lambda: _render(("render",), _table(("render",), data["render"])), default={}
        )
    if "page" in data:
        page = check(lambda: _page(("page",), _table(("page",), data["page"])))
        if page is not None:
            render["page"] = page
    if projector is not None:
        for k, node in enumerate(scene):
            check(_in_front, ("projector",), projector, node, k)
    save: dict[str, Any] = {}
    if "save" in data:
        save = check(lambda: _save(("save",), _table(("save",), data["save"]), suffix), default={})
    check.raise_all()
    return scene, projector, {"render": render, "save": save}


def _array_of_tables(key: Key, v: Any, name: str) -> list[dict[str, Any]]:
    if not isinstance(v, list) or not v:
        raise _Invalid(key, f"expected one or more [[{name}]] tables")
    return [_table(key + (k,), t) for k, t in enumerate(v)]


def _members(key: Key, table: Mapping[str, Any], check: _Collect | None = None) -> Any:
    """A scene of the ``object``, ``labels``, ``points`` and ``group`` tables in
    ``table``; with ``check``, every problem is recorded there and the members
    that are fine are built (otherwise the first problem is raised)."""
    import lgraph as lg

    own = check is None
    check = _Collect() if check is None else check
    scene = lg.Scene()
    objects = (
        check(_array_of_tables, key + ("object",), table["object"], "object", default=[])
        if "object" in table
        else []
    )
    for k, obj in enumerate(objects):
        ok = key + ("object", k)
        built = check(_object, ok, obj, check)
        if built is None:
            continue
        item, families, kw = built
        try:
            scene.add(item, *families, **kw)
        except (TypeError, ValueError) as exc:
            check(_fail, ok, str(exc))
    for name, build in (("labels", _label), ("points", _point)):
        if name in table:
            tables = check(_array_of_tables, key + (name,), table[name], name, default=[])
            for k, t in enumerate(tables):
                member = check(build, key + (name, k), t)
                if member is not None:
                    scene.add(member)
    if "group" in table:
        groups = check(_array_of_tables, key + ("group",), table["group"], "group", default=[])
        for k, g in enumerate(groups):
            check(_group, key + ("group", k), g, scene, check)
    if own:
        check.raise_all()
    return scene


def _group(gk: Key, g: dict[str, Any], scene: Any, check: _Collect) -> None:
    _only(gk, g, ("transform", "style") + _MEMBERS)
    if not any(m in g for m in _MEMBERS):
        raise _Invalid(gk, "a group needs members: object, labels, points or group tables")
    kw: dict[str, Any] = {}
    if "transform" in g:
        kw["transform"] = _transform(gk + ("transform",), g["transform"])
    if "style" in g:
        kw["style"] = _styles(gk + ("style",), g["style"])
    scene.add(_members(gk, g, check), **kw)


_LABEL = ("text", "at", "offset", "anchor", "size", "color", "always")


def _label(key: Key, t: dict[str, Any]) -> Any:
    from ..objects import Label

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
    return _call(key, "label", lambda **kw: Label(text, **kw), kw)


def _point(key: Key, t: dict[str, Any]) -> Any:
    from ..drawing import Style
    from ..objects import Point

    _only(key, t, ("at", "size", "color", "always"))
    kw: dict[str, Any] = {}
    if "size" in t:
        kw["size"] = _number(key + ("size",), t["size"], positive=True)
    if "color" in t:
        kw["style"] = _call(key + ("color",), "point", Style,
                            {"color": _color_value(key + ("color",), t["color"])})  # fmt: skip
    if "always" in t:
        kw["always"] = _boolean(key + ("always",), t["always"])
    at = _vector(key + ("at",), _required(key, t, "at"))
    return _call(key, "point", lambda **kw: Point(at, **kw), kw)


def _color_value(key: Key, v: Any) -> Any:
    if isinstance(v, str):
        return v
    if isinstance(v, list) and len(v) == 3:
        return [_number(key + (k,), x) for k, x in enumerate(v)]
    raise _Invalid(key, f"expected a colour '#rrggbb', a name or [r, g, b], got {_show(v)}")


def _fail(key: Key, message: str) -> None:
    raise _Invalid(key, message)


def _in_front(key: Key, projector: Any, node: Any, k: int) -> None:
    """A central projector's eye must see every object in front of it: checked
    on a 17 x 17 grid of each surface before any rendering (the renderer
    checks every sample again)."""
    import numpy as np

    import lgraph as lg

    surface = node.surface
    if not isinstance(projector, lg.CentralProjector) or surface is None:
        return
    d = surface.domain
    g = [np.linspace(*d.range(i), 17) for i in (0, 1)]
    u1, u2 = np.meshgrid(*g, indexing="ij")
    with np.errstate(all="ignore"):
        x = node.transform.apply(np.asarray(surface.point(u1, u2), float).reshape(-1, 3))
    x = x[np.isfinite(x).all(axis=1)]
    if len(x) and (projector.depth(x) <= 0).any():
        raise _Invalid(
            key + ("eye",),
            f"object[{k}] ({surface!r}) lies partly at or behind the eye "
            f"{projector.eye.tolist()}; move the eye farther away",
        )


def _projector(key: Key, p: Any) -> Any:
    import lgraph as lg

    p = _table(key, p)
    kind = _string(key + ("kind",), _required(key, p, "kind"), ("parallel", "central"))
    if kind == "parallel":
        _only(key, p, ("kind", "direction", "azimuth", "elevation", "up"))
        if "direction" in p:
            if "azimuth" in p or "elevation" in p:
                raise _Invalid(key + ("azimuth",), "give direction or azimuth/elevation, not both")
            kw: dict[str, Any] = {"direction": _vector(key + ("direction",), p["direction"])}
            if "up" in p:
                kw["up"] = _vector(key + ("up",), p["up"])
            return _call(key, "projector", lg.ParallelProjector, kw)
        if "azimuth" not in p and "elevation" not in p:
            raise _Invalid(key, "a parallel projector needs direction or azimuth and elevation")
        az = _number(key + ("azimuth",), _required(key, p, "azimuth"))
        el = _number(key + ("elevation",), _required(key, p, "elevation"))
        if "up" in p:
            raise _Invalid(key + ("up",), "up goes with direction, not with azimuth/elevation")
        if not -90 <= el <= 90:
            raise _Invalid(key + ("elevation",), f"must lie in [-90, 90] degrees, got {el!r}")
        return lg.ParallelProjector.from_angles(az, el)
    _only(key, p, ("kind", "eye", "target", "up", "azimuth", "elevation", "distance"))
    target = _vector(key + ("target",), p["target"]) if "target" in p else [0.0, 0.0, 0.0]
    if "eye" in p:
        for k in ("azimuth", "elevation", "distance"):
            if k in p:
                raise _Invalid(key + (k,), "give eye or azimuth/elevation/distance, not both")
        kw = {"eye": _vector(key + ("eye",), p["eye"]), "target": target}
        if "up" in p:
            kw["up"] = _vector(key + ("up",), p["up"])
        return _call(key, "projector", lg.CentralProjector, kw)
    if not any(k in p for k in ("azimuth", "elevation", "distance")):
        raise _Invalid(key, "a central projector needs eye or azimuth, elevation and distance")
    az = _number(key + ("azimuth",), _required(key, p, "azimuth"))
    el = _number(key + ("elevation",), _required(key, p, "elevation"))
    dist = _number(key + ("distance",), _required(key, p, "distance"), positive=True)
    if "up" in p:
        raise _Invalid(key + ("up",), "up goes with eye, not with azimuth/elevation/distance")
    if not -90 <= el <= 90:
        raise _Invalid(key + ("elevation",), f"must lie in [-90, 90] degrees, got {el!r}")
    return lg.CentralProjector.from_angles(az, el, dist, target=target)


_OBJECT = ("surface", "params", "families", "transform", "style", "contour", "hides")


def _object(
    key: Key, obj: dict[str, Any], check: _Collect
) -> tuple[Any, list[Any], dict[str, Any]] | None:
    """One ``[[object]]``: its surface, then its families, transform, style and
    flags, each checked on its own (all their problems are reported)."""
    from ..plugins import get_surface

    check(_only, key, obj, _OBJECT)
    name = _string(key + ("surface",), _required(key, obj, "surface"))
    try:
        cls = get_surface(name)
    except KeyError as exc:
        raise _Invalid(key + ("surface",), str(exc.args[0])) from None
    params = _table(key + ("params",), obj.get("params", {}))
    kwargs = _params(key + ("params",), cls, name, params)
    surface = _call(key + ("params",), f"surface {name!r}", cls, kwargs)
    families = []
    fams = obj.get("families", ["parameter_lines"])
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
    for flag in ("contour", "hides"):
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
    if _is_number(v):
        return v
    if isinstance(v, str):
        if re.search(r"\bstr\b|Literal", annotation):
            return v
        raise _Invalid(key, f"expected a number, got {_show(v)}")
    if isinstance(v, list):
        return tuple(_param_value(key + (k,), x, "") for k, x in enumerate(v))
    raise _Invalid(key, f"expected a number or an array of numbers, got {_show(v)}")


def _family(key: Key, f: Any, surface: Any) -> Any:
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
    kwargs = _params(key, cls, f"family {name!r}", args)
    family = _call(key, f"family {name!r}", cls, kwargs)
    try:  # catch families the surface cannot draw (no closed forms) before rendering
        family.batches(surface, None)
    except (NotImplementedError, AttributeError) as exc:
        raise _Invalid(
            name_key, f"family {name!r} cannot be drawn on this surface: {exc}"
        ) from None
    return family


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
    from ..drawing import Style

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


def _render(key: Key, r: dict[str, Any]) -> dict[str, Any]:
    _only(key, r, ("hidden_lines", "tolerance", "hidden_style"))
    out: dict[str, Any] = {}
    if "hidden_lines" in r:
        out["hidden_lines"] = _boolean(key + ("hidden_lines",), r["hidden_lines"])
    if "tolerance" in r:
        from .._tolerance import MIN_CHORD_TOLERANCE

        tol = _number(key + ("tolerance",), r["tolerance"], positive=True)
        if not MIN_CHORD_TOLERANCE <= tol <= 0.1:
            raise _Invalid(
                key + ("tolerance",),
                f"expected a fraction of the figure's diagonal from {MIN_CHORD_TOLERANCE:g} "
                f"to 0.1 (like 1e-4), got {tol!r}",
            )
        out["tolerance"] = tol
    if "hidden_style" in r:
        out["hidden_style"] = _style(key + ("hidden_style",), r["hidden_style"])
    return out


def _page(key: Key, p: dict[str, Any]) -> Any:
    from ..drawing import Page

    _only(key, p, ("preset", "landscape", "width", "height", "margin", "extent"))
    if "preset" in p:
        preset = _string(key + ("preset",), p["preset"], ("a4", "a5", "letter"))
        for k in ("width", "height", "extent"):
            if k in p:
                raise _Invalid(key + (k,), "give preset or width/height, not both")
        landscape = _boolean(key + ("landscape",), p.get("landscape", False))
        w, h = {"a4": (595.2756, 841.8898), "a5": (419.5276, 595.2756), "letter": (612.0, 792.0)}[
            preset
        ]
        if landscape:
            w, h = h, w
        margin = _number(key + ("margin",), p.get("margin", 36.0))
        return _call(key, "page", Page, {"width": w, "height": h, "margin": margin})
    if "landscape" in p:
        raise _Invalid(key + ("landscape",), "landscape goes with preset")
    kw = {k: _number(key + (k,), p[k]) for k in ("width", "height", "margin", "extent") if k in p}
    if ("width" in kw) != ("height" in kw):
        missing = "height" if "width" in kw else "width"
        raise _Invalid(key, f"missing required key {missing!r} in page (give both or neither)")
    return _call(key, "page", Page, kw)


#: extra checks of options of the built-in backends (the backend checks again)
_SAVE: dict[str, Callable[[Key, Any], Any]] = {
    "dpi": lambda k, v: _number(k, v, positive=True),
    "supersample": lambda k, v: _int(k, v, 1, 8),
    "precision": lambda k, v: _int(k, v, 0, 6),
    "title": lambda k, v: _string(k, v),
    "width": lambda k, v: _length(k, v),
    "height": lambda k, v: _length(k, v),
}


def _length(key: Key, v: Any) -> float:
    from ..units import length_pt

    if isinstance(v, bool) or not isinstance(v, (str, int, float)):
        raise _Invalid(key, f"expected a length such as '8.5cm', got {_show(v)}")
    try:
        return length_pt(v, "length")
    except ValueError as exc:
        raise _Invalid(key, str(exc)) from None


#: options of Drawing.save itself, for every format
_DRAWING_SAVE = ("width", "height")


def _int(key: Key, v: Any, lo: int, hi: int) -> int:
    if not (isinstance(v, int) and not isinstance(v, bool) and lo <= v <= hi):
        raise _Invalid(key, f"expected an integer from {lo} to {hi}, got {_show(v)}")
    return v


def _typed(key: Key, v: Any, default: Any) -> Any:
    """Check a backend option against the type of its default."""
    if isinstance(default, bool):
        return _boolean(key, v)
    if isinstance(default, int):
        if not (isinstance(v, int) and not isinstance(v, bool)):
            raise _Invalid(key, f"expected an integer, got {_show(v)}")
        return v
    if isinstance(default, float):
        return _number(key, v)
    if isinstance(default, str):
        return _string(key, v)
    return v


def _save(key: Key, s: dict[str, Any], suffix: str = ".pdf") -> dict[str, Any]:
    """``[save]``: options of the backend that writes ``suffix`` files
    (:func:`lgraph.backends.backend_options`; plugin backends included)."""
    from ..backends import backend_options
    from ..plugins import PluginError

    try:
        known = backend_options(suffix)
    except (ValueError, PluginError) as exc:
        raise _Invalid(key, str(exc).splitlines()[0]) from None
    known = {**known, **{k: None for k in _DRAWING_SAVE}}
    check = _Collect()
    out: dict[str, Any] = {}
    for k, v in s.items():
        if k not in known:
            allowed = ", ".join(sorted(known)) or "(none)"
            check(
                _fail, key + (k,), f"unknown option {k!r} for {suffix} output; allowed: {allowed}"
            )
            continue
        extra = _SAVE.get(k)
        out[k] = check(extra or _typed, key + (k,), v, *(() if extra else (known[k],)))
    check.raise_all()
    return out
