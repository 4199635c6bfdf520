"""The backend-neutral display list: strokes, styles and page geometry.

A :class:`Drawing` is plain data.  Backends (``lgraph.backends``) turn it into
files; they know nothing about surfaces.

>>> import numpy as np
>>> s = Stroke(xy=np.array([[0.0, 0.0], [1.0, 2.0]]), xyz=np.zeros((2, 3)))
>>> d = Drawing(strokes=(s,))
>>> d.bounds()
(0.0, 0.0, 1.0, 2.0)
>>> w, h = d.page_size()
>>> round(w, 1), round(h, 1)
(286.0, 536.0)
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import IO, Any

import attrs
import numpy as np

from ._atomic import publish, removed_on_signals, temporary_beside
from ._validate import finite_positive, nonnegative_finite
from .style import ANCHORS, HIDDEN_STYLE, OUTLINE, Style, _color, _dash  # noqa: F401 - re-exported

__all__ = ["Style", "Stroke", "PlacedLabel", "Page", "Drawing", "HIDDEN_STYLE"]


def _array_or_none(value: Any) -> np.ndarray | None:
    return None if value is None else np.asarray(value, dtype=float)


@attrs.frozen(eq=False)
class Stroke:
    """One polyline of the drawing.

    Attributes
    ----------
    xy : (n, 2) array
        Projected coordinates (projection plane, arbitrary units).
    xyz : (n, 3) array
        World coordinates of the same points.
    uv : (n, 2) array or None
        Parameters of the points on :attr:`!surface`; None for free curves.
    visible : bool
        False only for hidden parts (present when rendering with ``hidden_lines=True``).
    family : str
        ``"contour"``, ``"u1"``, ``"u2"``, ``"curvature"``, ``"curve"``, ...
    surface : Surface or None
        The surface the stroke lies on.
    style : Style
        Colour, width and dash pattern.
    """

    xy: np.ndarray = attrs.field(converter=np.asarray)
    xyz: np.ndarray = attrs.field(converter=np.asarray)
    uv: np.ndarray | None = attrs.field(default=None, converter=_array_or_none)
    visible: bool = True
    family: str = "curve"
    surface: Any = None
    style: Style = Style()

    def __len__(self) -> int:
        return len(self.xy)


@attrs.frozen(eq=False)
class PlacedLabel:
    """A label as placed by the renderer (``drawing.labels``).

    Attributes
    ----------
    text : str
        The text (``$...$`` is TeX mathematics).
    xy : (2,) array
        Projected coordinates of the anchor (the space of :attr:`!Stroke.xy`).
    xyz : (3,) array
        World coordinates of the anchor.
    visible : bool
        False for a hidden label (present when rendering with ``hidden_lines=True``).
    anchor : str
        Which point of the text box sits at the anchor (``"sw"``, ...; never ``"auto"``).
    offset : (dx, dy)
        Shift of the text from the anchor in pt.
    size : float
        Font size in pt.
    style : Style
        Its colour (hidden labels get the hidden style's colour).
    """

    text: str
    xy: np.ndarray = attrs.field(converter=lambda v: np.asarray(v, dtype=float))
    xyz: np.ndarray = attrs.field(converter=lambda v: np.asarray(v, dtype=float))
    visible: bool = True
    anchor: str = "center"
    offset: tuple[float, float] = (0.0, 0.0)
    size: float = 10.0
    style: Style = Style()

    def box(self) -> tuple[float, float, float, float]:
        """The text's ink box relative to the anchor's page position, in pt
        (offset and anchor applied)."""
        from ._text import text_shape

        bx0, by0, bx1, by1 = text_shape(self.text, self.size).box
        ox, oy = self.origin()
        return (bx0 + ox, by0 + oy, bx1 + ox, by1 + oy)

    def origin(self) -> tuple[float, float]:
        """Where the text's baseline starts, relative to the anchor's page position (pt)."""
        from ._text import text_shape

        bx0, by0, bx1, by1 = text_shape(self.text, self.size).box
        pad = LABEL_PAD * self.size
        fx, fy = ANCHORS[self.anchor]
        # the anchor point of the padded box goes to the offset anchor
        ax = bx0 - pad + fx * (bx1 - bx0 + 2 * pad)
        ay = by0 - pad + fy * (by1 - by0 + 2 * pad)
        return (self.offset[0] - ax, self.offset[1] - ay)


#: space between a label's ink box and its anchor point, in units of its size
#: (TikZ's inner sep is about 0.33 em)
LABEL_PAD = 0.25


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


def _window(value: Any) -> tuple[float, float, float, float] | None:
    if value is None:
        return None
    try:
        x0, y0, x1, y1 = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(
            f"Drawing: window must be (xmin, ymin, xmax, ymax) or None, got {value!r}"
        ) from None
    if not (math.isfinite(x0 + y0 + x1 + y1) and x0 < x1 and y0 < y1):
        raise ValueError(
            f"Drawing: window must be finite with xmin < xmax and ymin < ymax, got {value!r}"
        )
    return (x0, y0, x1, y1)


@attrs.frozen(eq=False, repr=False)
class Drawing:
    """Strokes plus page geometry; ``save`` writes PDF, PNG or SVG by suffix."""

    strokes: tuple[Stroke, ...] = attrs.field(converter=tuple)
    page: Page = attrs.field(default=None, converter=_page)
    background: tuple[float, float, float] | None = attrs.field(default=(1.0, 1.0, 1.0))
    labels: tuple[PlacedLabel, ...] = attrs.field(default=(), converter=tuple, kw_only=True)
    #: ``(xmin, ymin, xmax, ymax)`` in projection coordinates that the page
    #: shows; None (default): the strokes' :meth:`bounds`.  Animations give
    #: every frame the same window, so the figure keeps its place and scale.
    window: tuple[float, float, float, float] | None = attrs.field(
        default=None, kw_only=True, converter=_window
    )
    _cache: dict = attrs.field(factory=dict, init=False, repr=False)

    # -- geometry ---------------------------------------------------------
    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of all strokes and label anchors in
        projection coordinates."""
        pts = [s.xy for s in self.strokes if len(s.xy)]
        pts += [lab.xy.reshape(1, 2) for lab in self.labels]
        if not pts:
            return (0.0, 0.0, 1.0, 1.0)
        allp = np.concatenate(pts)
        x, y = allp[:, 0], allp[:, 1]  # by column: reductions along axis 0 of (n, 2) are slow
        ok = np.isfinite(x) & np.isfinite(y)
        if not ok.all():  # NaN points break a stroke
            x, y = x[ok], y[ok]
        if not len(x):
            return (0.0, 0.0, 1.0, 1.0)
        return (float(x.min()), float(y.min()), float(x.max()), float(y.max()))

    def _layout(self) -> tuple[float, np.ndarray, float, float]:
        """Scale, offset and page size mapping projection coords to page points
        (computed once: a drawing never changes)."""
        if "layout" not in self._cache:
            self._cache["layout"] = self._compute_layout()
        return self._cache["layout"]

    def _compute_layout(self) -> tuple[float, np.ndarray, float, float]:
        x0, y0, x1, y1 = self.bounds() if self.window is None else self.window
        w, h = max(x1 - x0, 1e-300), max(y1 - y0, 1e-300)
        if max(w, h) <= 1e-12 * max(abs(x0), abs(y0), abs(x1), abs(y1), 1.0):
            w = h = 1.0  # a single point (one label): the extent's units
        if w <= 1e-12 * max(h, 1.0):
            w = h
        if h <= 1e-12 * max(w, 1.0):
            h = w
        page = self.page
        m = page.margin
        if self.labels:
            return _layout_with_boxes(self, (x0, y0, x1, y1), w, h)
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

    def page_size(self) -> tuple[float, float]:
        """Width and height of the page in points."""
        _, _, pw, ph = self._layout()
        return pw, ph

    def page_labels(self) -> Iterator[tuple[np.ndarray, PlacedLabel]]:
        """Yield ``(origin, label)``: where each label's text baseline starts on
        the page (pt, y upwards); hidden labels first."""
        scale, offset, _, _ = self._layout()
        for lab in sorted(self.labels, key=lambda lab: lab.visible):
            ox, oy = lab.origin()
            yield lab.xy * scale + offset + (ox, oy), lab

    def label_positions(self) -> np.ndarray:
        """``(n, 2)``: where the anchor point of each label's box goes on the page
        (pt, y up): the projected anchor plus the offset.  For backends that
        typeset the text themselves (TikZ nodes)."""
        scale, offset, _, _ = self._layout()
        out = np.empty((len(self.labels), 2))
        for i, lab in enumerate(self.labels):
            out[i] = lab.xy * scale + offset + lab.offset
        return out

    def label_boxes(self) -> np.ndarray:
        """``(n, 4)`` ink boxes ``x0, y0, x1, y1`` of :attr:`!labels` on the page (pt, y up)."""
        scale, offset, _, _ = self._layout()
        out = np.empty((len(self.labels), 4))
        for i, lab in enumerate(self.labels):
            out[i] = np.array(lab.box()) + np.tile(lab.xy * scale + offset, 2)
        return out

    def page_strokes(self) -> Iterator[tuple[np.ndarray, Stroke]]:
        """Yield ``(points, stroke)`` with points in page units (pt, y upwards).

        Strokes come in drawing order: hidden parts first, then visible ones.
        """
        scale, offset, _, _ = self._layout()
        order = sorted(range(len(self.strokes)), key=lambda i: self.strokes[i].visible)
        strokes = [self.strokes[i] for i in order if len(self.strokes[i].xy) >= 2]
        if not strokes:
            return
        # one affine map for all points, then views per stroke
        pts = np.concatenate([s.xy for s in strokes]) * scale + offset
        cuts = np.cumsum([len(s.xy) for s in strokes[:-1]]).tolist()
        yield from zip(np.split(pts, cuts), strokes)

    # -- selection --------------------------------------------------------
    def select(self, *, family: str | None = None, visible: bool | None = None) -> Drawing:
        """A drawing with only the strokes matching the given family/visibility."""
        keep = tuple(
            s
            for s in self.strokes
            if (family is None or s.family == family) and (visible is None or s.visible == visible)
        )
        return attrs.evolve(self, strokes=keep)

    def sized(self, width: Any = None, height: Any = None) -> Drawing:
        """This drawing on a page cropped to the figure, scaled to a physical size.

        ``width`` and ``height`` are lengths (``"8.5cm"``, ``"60mm"``,
        ``"3in"``, ``"200pt"`` or a number of pt, see :func:`!lgraph.units.length_pt`).
        With one of them the page has exactly that width (height); with both the
        figure keeps its aspect and fits inside ``width`` x ``height``.  Line
        widths and label sizes stay in pt.

        >>> import numpy as np
        >>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)))
        >>> [round(v, 3) for v in Drawing(strokes=(s,)).sized(width="8.5cm").page_size()]
        [240.945, 138.472]
        """
        from .units import length_pt

        if width is None and height is None:
            return self
        fw = None if width is None else length_pt(width, "Drawing.save: width")
        fh = None if height is None else length_pt(height, "Drawing.save: height")
        m = self.page.margin
        for name, v in (("width", fw), ("height", fh)):
            if v is not None and v <= 2 * m:
                raise ValueError(
                    f"Drawing.save: {name} must exceed twice the page margin ({2 * m:g} pt), "
                    f"got {v:g} pt"
                )
        page = Page(margin=m, extent=self.page.extent, fit_width=fw, fit_height=fh)
        return attrs.evolve(self, page=page)

    def __len__(self) -> int:
        return len(self.strokes)

    @property
    def n_points(self) -> int:
        """Total number of points over all strokes."""
        return int(sum(len(s.xy) for s in self.strokes))

    # -- pen plotters -----------------------------------------------------
    def for_plotter(
        self,
        merge: float | str = "0.1mm",
        min_length: float | str = "0.3mm",
        sort: bool = True,
        *,
        layers: str | None = "family",
        width: float | str | None = None,
    ) -> Drawing:
        """A copy cleaned for a pen plotter: merged paths, no duplicates or
        fragments, short pen-up travel (see :func:`lgraph.plotter.for_plotter`).

        >>> import numpy as np
        >>> xy = np.array([[0.0, 0.0], [1.0, 0.0]])
        >>> d = Drawing(strokes=[Stroke(xy=xy, xyz=np.zeros((2, 3)))] * 2)
        >>> len(d.for_plotter().strokes)
        1
        """
        from .plotter import for_plotter

        return for_plotter(self, merge, min_length, sort, layers=layers, width=width)

    def pen_up_length(self, unit: str = "pt", *, layers: str | None = "family") -> float:
        """Pen-up travel on the page between consecutive paths of each layer
        (see :func:`lgraph.plotter.pen_up_length`); ``unit``: pt, mm, cm, in."""
        from .plotter import pen_up_length

        return pen_up_length(self, unit, layers=layers)

    # -- output -----------------------------------------------------------
    def save(
        self,
        path: str | os.PathLike[str] | IO[bytes],
        *,
        width: str | float | None = None,
        height: str | float | None = None,
        format: str | None = None,
        **options: Any,
    ) -> Any:
        """Write the drawing to ``path``; the format follows the suffix.

        ``width`` / ``height`` (optional) give the figure a physical size
        (``"8.5cm"``, ``"85mm"``, ``"3.3in"``, ``"240pt"``; see :meth:`sized`),
        for every format; line widths and label sizes stay in pt.

        ``.pdf`` (reportlab, vector), ``.png`` (pillow, anti-aliased; options
        ``dpi`` or ``size``), ``.svg`` (plain XML polylines) and any suffix a
        backend plugin registers.  The file is written atomically: on any error
        nothing is left behind.

        ``path`` may also be a binary file object (``io.BytesIO``, an open
        file); then ``format`` (``"pdf"``, ``"png"``, ``"svg"``, ...) names
        the format, and the object is returned.  ``format`` given with a path
        overrides its suffix.

        Returns the path written.
        """
        from .backends import get_backend

        drawing = self.sized(width, height)
        if hasattr(path, "write"):
            from .display import save_to_fileobj

            return save_to_fileobj(drawing, path, format, **options)  # type: ignore[arg-type]
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(
                "Drawing.save: path must be a file name (str or path) or a binary file "
                f"object, got {type(path).__name__}"
            )
        path = Path(path)
        if format is not None:
            from .display import _format_suffix

            writer = get_backend(_format_suffix(format))
        else:
            writer = get_backend(path.suffix)
        tmp = temporary_beside(path, "Drawing.save")
        try:
            with removed_on_signals(tmp):
                writer(drawing, Path(tmp), **options)
                publish(tmp, path)
        except BaseException as exc:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            if isinstance(exc, OSError) and exc.filename in (tmp, Path(tmp)):
                # name the file the user asked for, not the temporary one
                raise type(exc)(exc.errno, exc.strerror, str(path)) from None
            raise
        return path

    # -- notebooks and other programs ---------------------------------------
    def to_svg(self, **options: Any) -> str:
        """The SVG document as a string (options as for ``save(".svg")``)."""
        from .display import to_bytes

        return to_bytes(self, "svg", **options).decode("utf-8")

    def _repr_svg_(self) -> str:
        """Inline display in Jupyter (IPython calls it; lgraph never imports IPython)."""
        return self.to_svg()

    def _repr_png_(self) -> bytes:
        """Inline PNG for front ends that prefer raster images."""
        from .display import REPR_PNG_DPI, to_bytes

        return to_bytes(self, "png", dpi=REPR_PNG_DPI)

    def plot(self, ax: Any = None, *, axis: bool = False) -> Any:
        """Draw the strokes into a matplotlib ``Axes`` (needs matplotlib) and return it.

        See :func:`lgraph.display.plot`: line collections with the strokes'
        colours, widths and dashes in pt, equal aspect, hidden parts below.
        """
        from .display import plot

        return plot(self, ax, axis=axis)

    def __repr__(self) -> str:
        w, h = self.page_size()
        return (
            f"<Drawing: {len(self.strokes)} strokes, {self.n_points} points, "
            f"page {w:.0f} x {h:.0f} pt>"
        )


#: Most dashes :func:`dash_polyline` makes of one polyline (memory budget).
MAX_DASHES = 1_000_000


def dash_polyline(points: np.ndarray, pattern: Sequence[float]) -> list[np.ndarray]:
    """Split a polyline into its dashes (for backends without native dashes).

    ``pattern`` is a sequence of on/off lengths (in the units of ``points``)
    repeated along the arc length from the first point.  Each dash is an
    ``(m, 2)`` array: its interpolated start, the polyline's vertices inside
    it, and its interpolated end.  Fully vectorized: no Python loop over
    points or dashes.

    >>> pts = np.array([[0.0, 0.0], [10.0, 0.0]])
    >>> [d[:, 0].tolist() for d in dash_polyline(pts, (2, 3))]
    [[0.0, 2.0], [5.0, 7.0]]
    >>> [d.tolist() for d in dash_polyline([[0, 0], [2, 0], [2, 2]], (3, 0.5))]
    [[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0]], [[2.0, 1.5], [2.0, 2.0]]]
    """
    pts = np.asarray(points, float)
    pat = np.asarray(pattern, float)
    if len(pts) < 2 or len(pat) < 2:
        return []
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    total = arc[-1]
    period = float(pat.sum())
    if not (total > 0 and period > 0):
        return []
    # Start of every "on" interval: period index times period plus the offset
    # of that interval inside the pattern.
    on = pat[0::2]
    offsets = np.concatenate([[0.0], np.cumsum(pat)[1:-1:2]])
    n_periods = int(np.ceil(total / period)) + 1
    if n_periods * len(on) > MAX_DASHES:
        raise ValueError(
            f"dash_polyline: pattern {tuple(pat.tolist())} gives {n_periods * len(on)} dashes "
            f"along a polyline of length {total:g}; the limit is {MAX_DASHES} "
            "(lengthen the pattern)"
        )
    starts = (np.arange(n_periods)[:, None] * period + offsets[None, :]).ravel()
    ends = starts + np.tile(on, n_periods)
    keep = starts < total
    starts, ends = starts[keep], np.minimum(ends[keep], total)
    # Vertices strictly inside each dash: indices lo .. hi-1.
    lo = np.searchsorted(arc, starts, side="right")
    hi = np.searchsorted(arc, ends, side="left")
    counts = hi - lo + 2
    first = np.concatenate([[0], np.cumsum(counts)[:-1]])
    local = np.arange(counts.sum()) - np.repeat(first, counts)
    idx = np.clip(np.repeat(lo - 1, counts) + local, 0, len(pts) - 1)
    out = pts[idx]
    ends_t = np.column_stack([starts, ends])
    for axis in (0, 1):
        interp = np.interp(ends_t, arc, pts[:, axis])
        out[first, axis] = interp[:, 0]
        out[first + counts - 1, axis] = interp[:, 1]
    return np.split(out, first[1:])


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


def _layout_with_boxes(
    drawing: Drawing, bounds: tuple[float, float, float, float], w: float, h: float
) -> tuple[float, np.ndarray, float, float]:
    """The layout when labels are present: their text boxes (in pt, not scaled)
    must fit on the page as well as the strokes."""
    x0, y0, x1, y1 = bounds
    labels = drawing.labels
    a = np.array([[x0, y0], [x1, y1]] + [lab.xy.tolist() for lab in labels])
    boxes = np.array([lab.box() for lab in labels]).reshape(-1, 4)
    lo = np.vstack([np.zeros((2, 2)), boxes[:, :2]])
    hi = np.vstack([np.zeros((2, 2)), boxes[:, 2:]])
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
