"""Helpers shared by the built-in backends: options, colours, numbers, point runs.

>>> hex_color((1.0, 0.5, 0.0))
'#ff8000'
>>> fmt_num(0.30000000000000004), fmt_num(500.0), fmt_num(-0.0)
('0.3', '500', '0')
"""

from __future__ import annotations

import numbers
import re
from collections.abc import Iterator, Mapping
from typing import Any
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from ..._validate import positive_finite  # noqa: F401 - the backends' check (re-exported)

__all__ = [
    "check_options",
    "check_precision",
    "curve_options",
    "BEZIER_PRECISION",
    "background_rgb",
    "hex_color",
    "fmt_num",
    "format_points",
    "finite_runs",
    "page_runs",
    "page_run_points",
    "positive_finite",
]


def check_options(writer: str, options: Mapping[str, Any], known: tuple[str, ...]) -> None:
    """Raise TypeError naming the first option ``writer`` does not accept.

    >>> check_options("write_svg", {"dpi": 72}, ("precision",))
    Traceback (most recent call last):
    ...
    TypeError: write_svg: unknown option 'dpi'; known options: precision
    """
    if options:
        name = next(iter(options))
        known_list = ", ".join(known) if known else "(none)"
        raise TypeError(f"{writer}: unknown option {name!r}; known options: {known_list}")


def check_precision(writer: str, precision: Any) -> int:
    """Validate the number of decimals used for coordinates (an int in 0..6)."""
    if (
        not isinstance(precision, numbers.Integral)
        or isinstance(precision, bool)
        or not 0 <= precision <= 6
    ):
        raise ValueError(f"{writer}: precision must be an integer in 0..6, got {precision!r}")
    return int(precision)


#: the deviation of ``curves="bezier"`` from the exact curves when
#: ``precision`` gives no length: 0.01 mm on the page
BEZIER_PRECISION = "0.01mm"


def curve_options(writer: str, curves: Any, precision: Any) -> tuple[int, float | None]:
    """``curves=`` and ``precision=`` of a vector writer checked: the number
    of decimals of the coordinates and, for ``curves="bezier"``, the largest
    deviation from the exact curves in pt (None: polylines).

    ``precision`` is a number of decimals (an int in 0..6) or, for Bézier
    curves, a length on the page (``"0.01mm"``; default
    :data:`BEZIER_PRECISION`), which also sets the decimals (to a tenth of it).

    >>> d, tol = curve_options("write_svg", "bezier", "0.01mm")
    >>> d, round(tol, 6)
    (3, 0.028346)
    >>> curve_options("write_svg", "polyline", 2)
    (2, None)
    >>> curve_options("write_svg", "splines", 3)
    Traceback (most recent call last):
    ...
    ValueError: write_svg: curves must be 'polyline' or 'bezier', got 'splines'
    """
    import math

    from ..units import length_pt

    if curves not in ("polyline", "bezier"):
        raise ValueError(f"{writer}: curves must be 'polyline' or 'bezier', got {curves!r}")
    if isinstance(precision, str):
        if curves != "bezier":
            raise ValueError(
                f"{writer}: precision must be an integer in 0..6 (decimals) with polylines; "
                f"a length is the deviation of curves='bezier', got {precision!r}"
            )
        tol = length_pt(precision, f"{writer}: precision")
        decimals = min(6, max(1, math.ceil(-math.log10(tol / 10))))
        return decimals, tol
    decimals = check_precision(writer, precision)
    if curves == "bezier":
        return decimals, length_pt(BEZIER_PRECISION)
    return decimals, None


def background_rgb(drawing: Any) -> tuple[float, float, float] | None:
    """The drawing's background as an RGB triple in [0, 1], or None (transparent)."""
    bg = getattr(drawing, "background", None)
    if bg is None:
        return None
    from ...scene.style import _color

    return _color(bg)


def hex_color(rgb: tuple[float, float, float]) -> str:
    """``#rrggbb`` for an RGB triple in [0, 1]."""
    r, g, b = (min(255, max(0, round(c * 255))) for c in rgb)
    return f"#{r:02x}{g:02x}{b:02x}"


def fmt_num(x: float, digits: int = 4) -> str:
    """A short decimal for a scalar attribute (width, dash, page size).

    Rounds to ``digits`` decimals and drops trailing zeros; never uses an
    exponent (neither PDF nor SVG attributes want one).
    """
    s = f"{float(x):.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("", "-0") else s


def format_points(points: np.ndarray, template: str, precision: int) -> str:
    """Format all points in one pass with ``template`` repeated per point.

    ``template`` contains two ``{}`` placeholders that become ``%.<precision>f``.

    >>> format_points(np.array([[1.0, 2.0], [3.25, 4.0]]), "{} {} l\\n", 1)
    '1.0 2.0 l\\n3.2 4.0 l\\n'
    """
    f = f"%.{precision}f"
    pts = np.asarray(points, dtype=float)
    return (template.format(f, f) * len(pts)) % tuple(pts.ravel().tolist())


def _finite_bounds(points: np.ndarray) -> list[tuple[int, int]]:
    """``(start, stop)`` of the runs of two or more finite points of ``points``."""
    pts = np.asarray(points, dtype=float)
    ok = np.isfinite(pts).all(axis=1)
    if ok.all():
        return [(0, len(pts))] if len(pts) >= 2 else []
    edges = np.diff(np.concatenate([[False], ok, [False]]).astype(np.int8))
    starts = np.flatnonzero(edges == 1).tolist()
    stops = np.flatnonzero(edges == -1).tolist()
    return [(a, b) for a, b in zip(starts, stops) if b - a >= 2]


def finite_runs(points: np.ndarray) -> list[np.ndarray]:
    """Split a polyline at non-finite points; keep the runs of two or more points.

    >>> p = np.array([[0, 0], [1, 0], [np.nan, 0], [2, 0], [3, 1], [4, 1]], float)
    >>> [len(r) for r in finite_runs(p)]
    [2, 3]
    """
    pts = np.asarray(points, dtype=float)
    return [pts[a:b] for a, b in _finite_bounds(pts)]


def page_run_points(drawing: Any) -> tuple[np.ndarray, list[tuple[int, int]], list[Any]]:
    """Every finite run of every stroke (:func:`page_runs`) at once: the runs'
    points in page points in one array, ``(start, stop)`` of each run in it,
    and each run's stroke.  From ``drawing.page_points()``, or from
    ``drawing.page_strokes()`` for a drawing-like object without it.

    >>> from lgraph.output.drawing import Drawing, Stroke
    >>> xy = np.array([[0, 0], [1, 0], [np.nan, 0], [2, 0], [3, 1], [4, 1]], float)
    >>> pts, bounds, strokes = page_run_points(Drawing((Stroke(xy, np.zeros((6, 3))),)))
    >>> len(pts), bounds
    (5, [(0, 2), (2, 5)])
    """
    flat = getattr(drawing, "page_points", None)
    if flat is not None:
        pts, ends, strokes = flat()
    else:  # a drawing-like object with only page_strokes() (the documented minimum)
        items = [(p, s) for p, s in drawing.page_strokes() if len(p) >= 2]
        pts = np.concatenate([p for p, _ in items]) if items else np.empty((0, 2))
        ends = np.cumsum([len(p) for p, _ in items]).tolist()
        strokes = [s for _, s in items]
    x, y = pts[:, 0], pts[:, 1]  # by column: reductions along axis 0 of (n, 2) are slow
    if np.isfinite(x).all() and np.isfinite(y).all():
        # the common case: every stroke is one run (checked at once)
        return pts, list(zip([0, *ends], ends)), strokes
    keep, bounds, owners, n = [], [], [], 0
    for a, b, stroke in zip([0, *ends], ends, strokes):
        for r0, r1 in _finite_bounds(pts[a:b]):
            keep.append(pts[a + r0 : a + r1])
            bounds.append((n, n + r1 - r0))
            owners.append(stroke)
            n += r1 - r0
    return (np.concatenate(keep) if keep else np.empty((0, 2))), bounds, owners


def page_runs(drawing: Any) -> Iterator[tuple[np.ndarray, Any]]:
    """Yield ``(points, stroke)`` in page points for every finite run of every stroke.

    A stroke whose points are all finite gives exactly one run; NaN or inf
    points (breaks) split it.
    """
    pts, bounds, strokes = page_run_points(drawing)
    yield from ((pts[a:b], s) for (a, b), s in zip(bounds, strokes))


#: Characters XML 1.0 cannot hold, not even as ``&#...;``: C0 controls but tab
#: and line breaks, lone surrogates, U+FFFE and U+FFFF.
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def xml_attr(value: Any) -> str:
    r"""``value`` as a quoted XML attribute value, whatever its characters.

    ``&``, ``<``, ``>``, ``"`` and whitespace are escaped; characters XML
    cannot hold become U+FFFD, so the file stays well-formed.  Every string of
    the SVG that does not come from lgraph itself goes through this or
    :func:`xml_text` (labels refuse such characters already; this covers
    drawings built by hand and family names).

    >>> xml_attr("a<b\x07") == '"a&lt;b\ufffd"'
    True
    """
    return quoteattr(_NOT_XML.sub("\ufffd", str(value)))


def xml_text(value: Any) -> str:
    r"""``value`` as XML character data (see :func:`xml_attr`); ``\r`` kept as ``&#13;``."""
    return escape(_NOT_XML.sub("\ufffd", str(value)), {"\r": "&#13;"})
