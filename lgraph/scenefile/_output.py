"""How a scene file's figure is viewed and written: the ``[projector]``,
``[page]``, ``[render]`` and ``[save]`` tables.

``[save]`` keys are checked against the options of the backend that writes
the output's suffix (:func:`lgraph.output.backends.backend_options`, plugin
backends included); for several outputs at once, against those of all their
backends (an option only some of them take is ignored for the others, with a
``SceneFileWarning`` issued by :func:`lgraph.load_scene_file`).  No formula of
docs/mathematics.rst.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
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
        from ..scene.style import HiddenStyles, Style

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
    from ..output.page import Page

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
    # decimals, or (curves = "bezier") the deviation as a length
    "precision": lambda k, v: _length(k, v) and v if isinstance(v, str) else _int(k, v, 0, 6),
    "title": lambda k, v: _string(k, v),
    "width": lambda k, v: _length(k, v),
    "height": lambda k, v: _length(k, v),
    "margin": lambda k, v: _length(k, v, zero=True),
    "background": lambda k, v: _string(k, v),
}


def _length(key: Key, v: Any, zero: bool = False) -> float:
    from ..output.units import length_pt

    if isinstance(v, bool) or not isinstance(v, (str, int, float)):
        raise _Invalid(key, f"expected a length such as '8.5cm', got {_show(v)}")
    try:
        return length_pt(v, "length", zero=zero)
    except ValueError as exc:
        raise _Invalid(key, str(exc)) from None


#: options of Drawing.save itself, for every format
_DRAWING_SAVE = ("width", "height", "margin", "background")


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


class SceneFileWarning(UserWarning):
    """A part of a scene file that is ignored: a ``[save]`` option that the
    backend of one of several outputs does not take (the others do)."""


@dataclass
class _SaveOutputs:
    """``[save]`` checked for several outputs: ``options`` holds the options of
    each output (in the order given), ``ignored`` the options left out for an
    output whose backend does not take them, as ``(key, output index)``."""

    options: list[dict[str, Any]]
    ignored: list[tuple[Key, int]] = field(default_factory=list)


_FAILED = object()


def _save(
    key: Key, s: dict[str, Any], suffix: str | Sequence[str] = ".pdf"
) -> dict[str, Any] | _SaveOutputs:
    """``[save]``: options of the backend that writes ``suffix`` files
    (:func:`lgraph.output.backends.backend_options`; plugin backends included).

    With one suffix (a string) an option its backend does not take is an
    error, and the checked options are returned.  With a sequence of
    suffixes (several outputs, rendered once) only an option that none of
    their backends takes is an error; one that some do not take is left out
    for those outputs and listed in the returned ``_SaveOutputs``.
    """
    if isinstance(suffix, str):
        return _save_outputs(key, s, [suffix]).options[0]
    return _save_outputs(key, s, list(suffix))


def _save_outputs(key: Key, s: dict[str, Any], suffixes: list[str]) -> _SaveOutputs:
    from ..output.backends import backend_options
    from ..plugins import PluginError

    known: dict[str, dict[str, Any]] = {}  # lower-case suffix -> option -> default
    for suffix in suffixes:
        if suffix.lower() in known:
            continue
        try:
            options = backend_options(suffix)
        except (ValueError, PluginError) as exc:
            raise _Invalid(key, str(exc).splitlines()[0]) from None
        known[suffix.lower()] = {**options, **{k: None for k in _DRAWING_SAVE}}
    if len(known) == 1:
        shown = suffixes[0]
    else:
        *rest, last = known
        shown = f"{', '.join(rest)} and {last}"
    allowed = ", ".join(sorted({k for options in known.values() for k in options})) or "(none)"
    check = _Collect()
    per: dict[str, dict[str, Any]] = {suffix: {} for suffix in known}
    for k, v in s.items():
        having = {suffix: options[k] for suffix, options in known.items() if k in options}
        if not having:
            check(_fail, key + (k,), f"unknown option {k!r} for {shown} output; allowed: {allowed}")
            continue
        extra = _SAVE.get(k)
        if extra is not None:
            value = check(extra, key + (k,), v, default=_FAILED)
            values = {suffix: value for suffix in having} if value is not _FAILED else {}
        else:
            values = check(_typed_each, key + (k,), v, having, default={})
        for suffix, value in values.items():
            per[suffix][k] = value
    check.raise_all()
    ignored = [
        (key + (k,), i)
        for i, suffix in enumerate(suffixes)
        for k in s
        if k not in known[suffix.lower()]
    ]
    return _SaveOutputs([dict(per[suffix.lower()]) for suffix in suffixes], ignored)


def _typed_each(key: Key, v: Any, defaults: dict[str, Any]) -> dict[str, Any]:
    """``v`` checked against the default of each backend (by suffix) that takes it."""
    return {suffix: _typed(key, v, default) for suffix, default in defaults.items()}
