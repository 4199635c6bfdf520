"""How a scene file's figure is viewed and written: the ``[projector]``,
``[page]``, ``[render]`` and ``[save]`` tables.

``[save]`` keys are checked against the options of the backend that writes
the output's suffix (:func:`lgraph.backends.backend_options`, plugin
backends included).  No formula of docs/mathematics.rst.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ._errors import Key, _Collect, _fail, _Invalid
from ._locate import _show
from ._values import (
    _boolean,
    _call,
    _number,
    _only,
    _required,
    _string,
    _styles,
    _table,
    _vector,
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


def _render(key: Key, r: dict[str, Any]) -> dict[str, Any]:
    _only(key, r, ("hidden_lines", "tolerance", "hidden_style", "intersections", "max_occlusion"))
    out: dict[str, Any] = {}
    for flag in ("hidden_lines", "intersections"):
        if flag in r:
            out[flag] = _boolean(key + (flag,), r[flag])
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
    if "hidden_style" in r or "max_occlusion" in r:
        from ..style import HiddenStyles, Style

        # one style table, or one per family name ("default" for the rest)
        styles = _styles(key + ("hidden_style",), r.get("hidden_style", {}))
        limit = None
        if "max_occlusion" in r:
            limit = _int(key + ("max_occlusion",), r["max_occlusion"], 0, 1_000_000)
        if isinstance(styles, Style):
            out["hidden_style"] = HiddenStyles(default=styles, max_occlusion=limit)
        else:
            default = styles.pop("default", None)
            out["hidden_style"] = HiddenStyles(styles, default, limit)
    return out


def _page(key: Key, p: dict[str, Any]) -> Any:
    from ..page import Page

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
