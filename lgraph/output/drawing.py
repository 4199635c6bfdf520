"""The backend-neutral display list: strokes, placed labels and the drawing.

A :class:`Drawing` is plain data: :class:`Stroke` polylines and
:class:`PlacedLabel` texts in projection coordinates, plus a page.  Backends
(``lgraph.backends``) turn it into files; they know nothing about surfaces.
The page geometry (:class:`~lgraph.Page` and the map onto it) is in
:mod:`lgraph.output.page`, dash patterns for backends in :mod:`lgraph.output.dashes`; both
are importable from here as before.  No formula of docs/mathematics.rst.

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
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

import attrs
import numpy as np

from ..scene.style import ANCHORS, HIDDEN_STYLE, LABEL_PAD, OUTLINE, Style, _color, _dash  # noqa: F401
from ._atomic import publish, removed_on_signals, temporary_beside
from .dashes import MAX_DASHES, dash_polyline  # noqa: F401 - re-exported (plugins use it)
from .page import Page, _page, page_layout

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
    occlusion : int
        0 for a visible stroke; for a hidden one, the number of surface
        sheets between it and the eye (its ray's crossings with the
        surfaces: 1 behind the near side of a sphere, 2 behind a whole
        sphere).  Hidden strokes are split where it changes.  Exact where
        the surfaces count their crossings (quadrics, planes, tori and
        cyclides, parametric surfaces with the numeric ray test: their
        ``hit_count``); a class with a ray test of its own but no count
        (ruled surfaces, surfaces of revolution, ...) counts once.
    """

    xy: np.ndarray = attrs.field(converter=np.asarray)
    xyz: np.ndarray = attrs.field(converter=np.asarray)
    uv: np.ndarray | None = attrs.field(default=None, converter=_array_or_none)
    visible: bool = True
    family: str = "curve"
    surface: Any = None
    style: Style = Style()
    occlusion: int = 0
    #: the gap in pt of a point mark's halo (the lines are cut around it,
    #: :mod:`lgraph.output.halos`); None: no halo
    halo: float | None = attrs.field(default=None, kw_only=True)
    #: the exact curve the samples lie on (:class:`lgraph.output.bezier.CurveRef`,
    #: set by the renderer), for ``save(..., curves="bezier")``; None: none
    curve: Any = attrs.field(default=None, kw_only=True, repr=False)

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
    halo : float or None
        The gap in pt around its ink box within which the strokes are cut
        (:mod:`lgraph.output.halos`); None: no halo.
    """

    text: str
    xy: np.ndarray = attrs.field(converter=lambda v: np.asarray(v, dtype=float))
    xyz: np.ndarray = attrs.field(converter=lambda v: np.asarray(v, dtype=float))
    visible: bool = True
    anchor: str = "center"
    offset: tuple[float, float] = (0.0, 0.0)
    size: float = 10.0
    style: Style = Style()
    halo: float | None = attrs.field(default=None, kw_only=True)

    def box(self) -> tuple[float, float, float, float]:
        """The text's ink box relative to the anchor's page position, in pt
        (offset and anchor applied)."""
        from ._text import text_box

        bx0, by0, bx1, by1 = text_box(self.text, self.size)
        ox, oy = self.origin()
        return (bx0 + ox, by0 + oy, bx1 + ox, by1 + oy)

    def origin(self) -> tuple[float, float]:
        """Where the text's baseline starts, relative to the anchor's page position (pt)."""
        from ._text import text_box

        bx0, by0, bx1, by1 = text_box(self.text, self.size)
        pad = LABEL_PAD * self.size
        fx, fy = ANCHORS[self.anchor]
        # the anchor point of the padded box goes to the offset anchor
        ax = bx0 - pad + fx * (bx1 - bx0 + 2 * pad)
        ay = by0 - pad + fy * (by1 - by0 + 2 * pad)
        return (self.offset[0] - ax, self.offset[1] - ay)


#: ``save(background=...)`` not given: the drawing's own
_KEEP: Any = object()


def _background(value: Any) -> tuple[float, float, float] | None:
    """A page background: a colour, or None (transparent)."""
    if value is None or (
        isinstance(value, str) and value.strip().lower() in ("none", "transparent")
    ):
        return None
    try:
        return _color(value)
    except ValueError as exc:
        raise ValueError(
            "Drawing.save: background must be a colour or None (transparent); "
            + str(exc).removeprefix("Style: ")
        ) from None


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
            self._cache["layout"] = page_layout(self)
        return self._cache["layout"]

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

    def page_points(self) -> tuple[np.ndarray, list[int], list[Stroke]]:
        """The strokes of two or more points in drawing order (hidden parts
        first, then visible ones), with all their points in page units (pt, y
        upwards) in one array: stroke ``k``'s are ``points[ends[k - 1]:ends[k]]``
        (from 0 for the first).  Backends draw from it without a list of
        arrays (:meth:`page_strokes` gives one).

        >>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)))
        >>> points, ends, strokes = Drawing(strokes=(s, s)).page_points()
        >>> points.shape, ends, len(strokes)
        ((4, 2), [2, 4], 2)
        """
        scale, offset, _, _ = self._layout()
        order = sorted(range(len(self.strokes)), key=lambda i: self.strokes[i].visible)
        strokes = [self.strokes[i] for i in order if len(self.strokes[i].xy) >= 2]
        if not strokes:
            return np.empty((0, 2)), [], []
        # one affine map for all points
        pts = np.concatenate([s.xy for s in strokes]) * scale + offset
        ends = np.cumsum([len(s.xy) for s in strokes]).tolist()
        if any(x.halo is not None for x in (*self.labels, *self.strokes)):
            from .halos import cut_strokes  # labels' halos cut the strokes on the page

            pts, ends, strokes = cut_strokes(self, pts, ends, strokes)
        return pts, ends, strokes

    def halo_regions(self) -> tuple[np.ndarray, np.ndarray]:
        """The regions cut out of the strokes on the page (pt, y up): boxes
        ``(k, 4)`` ``x0, y0, x1, y1`` (labels' ink boxes grown by their
        halos) and discs ``(m, 3)`` ``cx, cy, r`` (point marks with halos)."""
        from .halos import halo_regions

        return halo_regions(self)

    def page_strokes(self) -> Iterator[tuple[np.ndarray, Stroke]]:
        """Yield ``(points, stroke)`` with points in page units (pt, y upwards).

        Strokes come in drawing order: hidden parts first, then visible ones.
        """
        pts, ends, strokes = self.page_points()
        yield from ((pts[a:b], s) for a, b, s in zip([0, *ends], ends, strokes))

    # -- selection --------------------------------------------------------
    def select(self, *, family: str | None = None, visible: bool | None = None) -> Drawing:
        """A drawing with only the strokes matching the given family/visibility."""
        keep = tuple(
            s
            for s in self.strokes
            if (family is None or s.family == family) and (visible is None or s.visible == visible)
        )
        return attrs.evolve(self, strokes=keep)

    def sized(self, width: Any = None, height: Any = None, margin: Any = None) -> Drawing:
        r"""This drawing on a page cropped to the figure, scaled to a physical size.

        ``width`` and ``height`` are lengths (``"8.5cm"``, ``"60mm"``,
        ``"3in"``, ``"200pt"`` or a number of pt, see :func:`!lgraph.output.units.length_pt`).
        With one of them the page has exactly that width (height); with both the
        figure keeps its aspect and fits inside ``width`` x ``height``.  The
        figure's ink -- strokes with their line widths and round caps, and
        labels -- spans the page less ``margin`` on each side: 0 by default
        when a size is given, so that ``\includegraphics`` places exactly the
        figure; ``margin`` is a length too (``"2mm"``, a number of pt).
        Without a size, ``margin`` replaces the page's margin.  Line widths and
        label sizes stay in pt.

        >>> import numpy as np
        >>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)))
        >>> [round(v, 3) for v in Drawing(strokes=(s,)).sized(width="8.5cm").page_size()]
        [240.945, 120.722]
        >>> [round(v, 3) for v in Drawing(strokes=(s,)).sized(width=100, margin="2mm").page_size()]
        [100.0, 55.919]
        """
        from .units import length_pt

        m = None if margin is None else length_pt(margin, "Drawing.save: margin", zero=True)
        if width is None and height is None:
            return self if m is None else attrs.evolve(self, page=attrs.evolve(self.page, margin=m))
        fw = None if width is None else length_pt(width, "Drawing.save: width")
        fh = None if height is None else length_pt(height, "Drawing.save: height")
        m = 0.0 if m is None else m
        for name, v in (("width", fw), ("height", fh)):
            if v is not None and v <= 2 * m:
                raise ValueError(
                    f"Drawing.save: {name} must exceed twice the margin ({2 * m:g} pt), "
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
        fragments, short pen-up travel (see :func:`lgraph.output.plotter.for_plotter`).

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
        (see :func:`lgraph.output.plotter.pen_up_length`); ``unit``: pt, mm, cm, in."""
        from .plotter import pen_up_length

        return pen_up_length(self, unit, layers=layers)

    # -- output -----------------------------------------------------------
    def save(
        self,
        path: str | os.PathLike[str] | IO[bytes],
        *,
        width: str | float | None = None,
        height: str | float | None = None,
        margin: str | float | None = None,
        background: Any = _KEEP,
        format: str | None = None,
        **options: Any,
    ) -> Any:
        """Write the drawing to ``path``; the format follows the suffix.

        ``width`` / ``height`` (optional) give the figure a physical size
        (``"8.5cm"``, ``"85mm"``, ``"3.3in"``, ``"240pt"``; see :meth:`sized`),
        for every format: the figure's ink (strokes with their widths, and
        labels) is that size, plus ``margin`` (a length, default 0) on each
        side; line widths and label sizes stay in pt.

        ``background`` (optional) replaces the drawing's: a colour (any
        ``color=`` value, ``"tab:blue"``, ``"#f4f4f4"``) painted over the
        whole page in PNG, PDF and SVG, or None (also ``"none"``,
        ``"transparent"``): a transparent PNG (RGBA) and nothing painted in
        PDF and SVG.  White paints nothing in PDF and SVG either (the paper).

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

        drawing = self.sized(width, height, margin)
        if background is not _KEEP:
            drawing = attrs.evolve(drawing, background=_background(background))
        if hasattr(path, "write"):
            from ..notebook.display import save_to_fileobj

            return save_to_fileobj(drawing, path, format, **options)  # type: ignore[arg-type]
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(
                "Drawing.save: path must be a file name (str or path) or a binary file "
                f"object, got {type(path).__name__}"
            )
        path = Path(path)
        if format is not None:
            from ..notebook.display import _format_suffix

            writer = get_backend(_format_suffix(format))
        else:
            writer = get_backend(path.suffix)
        tmp = temporary_beside(path, "Drawing.save")
        try:
            with removed_on_signals(tmp):
                writer(drawing, Path(tmp), **options)
                path = publish(tmp, path)  # normalized: "a/../x.svg" is "x.svg"
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
        from ..notebook.display import to_bytes

        return to_bytes(self, "svg", **options).decode("utf-8")

    def _repr_svg_(self) -> str:
        """Inline display in Jupyter (IPython calls it; lgraph never imports IPython)."""
        return self.to_svg()

    def _repr_png_(self) -> bytes:
        """Inline PNG for front ends that prefer raster images."""
        from ..notebook.display import REPR_PNG_DPI, to_bytes

        return to_bytes(self, "png", dpi=REPR_PNG_DPI)

    def plot(self, ax: Any = None, *, axis: bool = False, legend: bool = False) -> Any:
        """Draw the drawing into a matplotlib ``Axes`` (needs matplotlib) and return it.

        See :func:`lgraph.notebook.display.plot`: line collections by family with the
        strokes' colours, widths and dashes in pt, hidden parts below, point
        marks, labels as text (mathtext), ``legend=True`` for a legend by family.
        """
        from ..notebook.display import plot

        return plot(self, ax, axis=axis, legend=legend)

    def __repr__(self) -> str:
        w, h = self.page_size()
        return (
            f"<Drawing: {len(self.strokes)} strokes, {self.n_points} points, "
            f"page {w:.0f} x {h:.0f} pt>"
        )
