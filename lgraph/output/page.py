"""Page geometry: the :class:`Page` and the map from projection coordinates to it.

A drawing's strokes live in projection coordinates; :func:`page_layout` finds
the scale and offset that put them on the page (in pt, y up): cropped to the
figure or fitted inside a given page, and with labels, so that their text
boxes (whose size in pt does not scale with the figure) fit as well.  No
formula of docs/mathematics.rst: the layout is a one-dimensional fit per
axis (``_fit_scale`` bisects a convex condition).

>>> Page(100, 100, margin=60)
Traceback (most recent call last):
...
ValueError: Page: width and height must exceed twice the margin (120 pt), got 100 x 100
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Protocol

import attrs
import numpy as np

from .._validate import finite_positive, nonnegative_finite

if TYPE_CHECKING:
    from ..scene.style import Style

__all__ = ["Page", "page_layout", "stroke_ink"]


class _Inked(Protocol):
    """What the layout needs of a stroke (:class:`~lgraph.output.drawing.Stroke`)."""

    @property
    def xy(self) -> np.ndarray: ...

    @property
    def style(self) -> Style: ...


class _Boxed(Protocol):
    """What the layout needs of a placed label (:class:`~lgraph.output.drawing.PlacedLabel`)."""

    @property
    def xy(self) -> np.ndarray: ...

    def box(self) -> tuple[float, float, float, float]: ...


class Laid(Protocol):
    """What the layout needs of a drawing (:class:`~lgraph.output.drawing.Drawing`,
    which imports this module: typing by this protocol keeps the import one-way)."""

    @property
    def strokes(self) -> Sequence[_Inked]: ...

    @property
    def labels(self) -> Sequence[_Boxed]: ...

    @property
    def page(self) -> Page: ...

    @property
    def window(self) -> tuple[float, float, float, float] | None: ...

    def bounds(self) -> tuple[float, float, float, float]: ...


@attrs.frozen
class Page:
    """Page geometry in points (1/72 inch).

    With ``width`` and ``height`` both None (the default) the page is cropped
    to the figure: its longer side is ``extent`` points, plus ``margin`` on each
    side.  With both given, the figure is fitted inside the margins and centred,
    keeping its aspect ratio.
    """

    width: float | None = attrs.field(default=None)
    height: float | None = attrs.field(default=None)
    margin: float = attrs.field(default=18.0, validator=nonnegative_finite("Page"))
    extent: float = attrs.field(default=500.0, validator=finite_positive("Page"))
    #: crop to the figure, scaled so that the page is this wide (pt) ...
    fit_width: float | None = attrs.field(default=None, kw_only=True)
    #: ... and/or at most this high (pt); set by ``Drawing.save(width=, height=)``
    fit_height: float | None = attrs.field(default=None, kw_only=True)

    @width.validator
    @height.validator
    @fit_width.validator
    @fit_height.validator
    def _check_size(self, attribute: attrs.Attribute, value: float | None) -> None:
        if value is not None:
            finite_positive("Page")(self, attribute, value)

    def __attrs_post_init__(self) -> None:
        fit = self.fit_width is not None or self.fit_height is not None
        if fit and self.width is not None:
            raise ValueError("Page: fit_width/fit_height crop the page; give no width and height")
        if (self.width is None) != (self.height is None):
            raise ValueError("Page: give both width and height, or neither (crop to figure)")
        if self.width is not None and min(self.width, self.height) <= 2 * self.margin:
            raise ValueError(
                f"Page: width and height must exceed twice the margin ({2 * self.margin} pt), "
                f"got {self.width} x {self.height}"
            )

    @classmethod
    def a4(cls, landscape: bool = False, margin: float = 36.0) -> Page:
        """An A4 page (595.28 x 841.89 pt)."""
        w, h = 595.2756, 841.8898
        return cls(h, w, margin) if landscape else cls(w, h, margin)


def _page(value: Any) -> Page:
    if isinstance(value, Page):
        return value
    if value is None:
        return Page()
    try:
        w, h = value
    except (TypeError, ValueError):
        raise ValueError(
            f"Drawing: page must be a Page or (width, height) in pt, got {value!r}"
        ) from None
    return Page(float(w), float(h))


def page_layout(drawing: Laid) -> tuple[float, np.ndarray, float, float]:
    """Scale, offset and page size that map ``drawing``'s projection coordinates
    to page points (pt, y up): the window (default: the strokes' bounds) fitted to
    the page, or with labels, the window and the labels' text boxes."""
    x0, y0, x1, y1 = drawing.bounds() if drawing.window is None else drawing.window
    w, h = max(x1 - x0, 1e-300), max(y1 - y0, 1e-300)
    if max(w, h) <= 1e-12 * max(abs(x0), abs(y0), abs(x1), abs(y1), 1.0):
        w = h = 1.0  # a single point (one label): the extent's units
    if w <= 1e-12 * max(h, 1.0):
        w = h
    if h <= 1e-12 * max(w, 1.0):
        h = w
    page = drawing.page
    m = page.margin
    fit = page.fit_width is not None or page.fit_height is not None
    if drawing.labels or fit:
        return _layout_with_boxes(drawing, (x0, y0, x1, y1), w, h, ink=fit)
    if page.width is None:
        scale = page.extent / max(w, h)
        fits = [(page.fit_width, w), (page.fit_height, h)]
        fitted = [(size - 2 * m) / ext for size, ext in fits if size is not None]
        if fitted:
            scale = min(fitted)
            if min(fitted) <= 0:
                raise ValueError(
                    f"Drawing: the page size must exceed twice the margin ({2 * m} pt)"
                )
        pw, ph = w * scale + 2 * m, h * scale + 2 * m
    else:
        pw, ph = page.width, page.height
        scale = min((pw - 2 * m) / w, (ph - 2 * m) / h)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    offset = np.array([pw / 2 - scale * cx, ph / 2 - scale * cy])
    return scale, offset, pw, ph


def _fit_scale(a: np.ndarray, lo: np.ndarray, hi: np.ndarray, avail: float) -> float:
    """Largest scale ``s`` with ``max(a s + hi) - min(a s + lo) <= avail``.

    The left side is convex in ``s`` and at ``s = 0`` is the widest text box,
    so the scales that fit form an interval starting at 0; bisect its end.
    """
    span = float(a.max() - a.min())
    if span <= 0:
        return math.inf
    if float(hi.max() - lo.min()) >= avail:
        raise ValueError(
            f"Drawing: the labels need more than the {avail:g} pt available; "
            "make the page larger or the labels smaller"
        )
    s_lo, s_hi = 0.0, avail / span
    while (a * s_hi + hi).max() - (a * s_hi + lo).min() <= avail:
        s_lo, s_hi = s_hi, 2 * s_hi
    for _ in range(80):
        mid = 0.5 * (s_lo + s_hi)
        if (a * mid + hi).max() - (a * mid + lo).min() <= avail:
            s_lo = mid
        else:
            s_hi = mid
    return s_lo


def stroke_ink(drawing: Laid) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each stroke's lower left and upper right points (projection
    coordinates, ``(k, 2)`` each) and half its line width (pt, ``(k,)``): the
    ink of a stroke with round caps reaches that far beyond its points.

    >>> from lgraph.output.drawing import Drawing, Stroke
    >>> s = Stroke(xy=np.array([[0.0, 1.0], [2.0, np.nan], [3.0, -1.0]]), xyz=np.zeros((3, 3)))
    >>> lo, hi, half = stroke_ink(Drawing((s,)))
    >>> lo.tolist(), hi.tolist(), half.tolist()
    ([[0.0, -1.0]], [[3.0, 1.0]], [0.25])
    """
    strokes = [s for s in drawing.strokes if len(s.xy)]
    if not strokes:
        return np.empty((0, 2)), np.empty((0, 2)), np.empty(0)
    pts = np.concatenate([np.asarray(s.xy, float).reshape(-1, 2) for s in strokes])
    starts = np.cumsum([0] + [len(s.xy) for s in strokes[:-1]])
    with np.errstate(invalid="ignore"):
        lo = np.fmin.reduceat(pts, starts, axis=0)  # fmin: NaN points (breaks) ignored
        hi = np.fmax.reduceat(pts, starts, axis=0)
    half = np.array([s.style.width / 2 for s in strokes])
    ok = np.isfinite(lo).all(axis=1) & np.isfinite(hi).all(axis=1)
    return lo[ok], hi[ok], half[ok]


def _layout_with_boxes(
    drawing: Laid,
    bounds: tuple[float, float, float, float],
    w: float,
    h: float,
    ink: bool = False,
) -> tuple[float, np.ndarray, float, float]:
    """The layout when labels are present: their text boxes (in pt, not scaled)
    must fit on the page as well as the strokes; with ``ink`` (a page of a
    physical size) the strokes' half line widths too, so that the ink of the
    figure spans the page less its margins."""
    x0, y0, x1, y1 = bounds
    labels = drawing.labels
    a = np.array([[x0, y0], [x1, y1]] + [lab.xy.tolist() for lab in labels])
    boxes = np.array([lab.box() for lab in labels]).reshape(-1, 4)
    lo = np.vstack([np.zeros((2, 2)), boxes[:, :2]])
    hi = np.vstack([np.zeros((2, 2)), boxes[:, 2:]])
    if ink and drawing.window is None:
        s_lo, s_hi, half = stroke_ink(drawing)
        pad = np.repeat(half[:, None], 2, axis=1)
        a = np.vstack([a, s_lo, s_hi])
        lo = np.vstack([lo, -pad, -pad])
        hi = np.vstack([hi, pad, pad])
    page = drawing.page
    m = page.margin
    if page.width is None:
        fits = [
            _fit_scale(a[:, k], lo[:, k], hi[:, k], size - 2 * m) if size is not None else math.inf
            for k, size in enumerate((page.fit_width, page.fit_height))
        ]
        scale = min(fits) if any(f < math.inf for f in fits) else page.extent / max(w, h)
        if not math.isfinite(scale):
            scale = page.extent / max(w, h)
        low = (a * scale + lo).min(axis=0)
        high = (a * scale + hi).max(axis=0)
        pw, ph = (high - low + 2 * m).tolist()
        if page.fit_width is not None and scale == fits[0] < math.inf:
            pw = page.fit_width  # exact (the bisection is within rounding)
        if page.fit_height is not None and scale == fits[1] < math.inf:
            ph = page.fit_height
        offset = m - low
    else:
        pw, ph = page.width, page.height
        scale = min(_fit_scale(a[:, k], lo[:, k], hi[:, k], size - 2 * m) for k, size in
                    enumerate((pw, ph)))  # fmt: skip
        if not math.isfinite(scale):
            scale = min((pw - 2 * m) / w, (ph - 2 * m) / h)
        low = (a * scale + lo).min(axis=0)
        high = (a * scale + hi).max(axis=0)
        offset = np.array([pw, ph]) / 2 - (low + high) / 2
    return float(scale), offset, float(pw), float(ph)
