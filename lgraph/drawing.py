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
import tempfile
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from ._validate import finite_positive, nonnegative_finite

__all__ = ["Style", "Stroke", "Page", "Drawing", "HIDDEN_STYLE"]


def _color(value: Any) -> tuple[float, float, float]:
    """Convert a colour to an RGB triple in [0, 1].

    Accepts ``(r, g, b)`` floats in [0, 1], ``"#rrggbb"`` or a few names.
    """
    names = {
        "black": (0.0, 0.0, 0.0),
        "white": (1.0, 1.0, 1.0),
        "red": (0.8, 0.0, 0.0),
        "green": (0.0, 0.5, 0.0),
        "blue": (0.0, 0.2, 0.8),
        "gray": (0.5, 0.5, 0.5),
        "grey": (0.5, 0.5, 0.5),
    }
    if isinstance(value, str):
        v = value.strip().lower()
        if v in names:
            return names[v]
        if v.startswith("#") and len(v) == 7:
            try:
                return tuple(int(v[i : i + 2], 16) / 255.0 for i in (1, 3, 5))  # type: ignore[return-value]
            except ValueError:
                pass
        raise ValueError(
            f"Style: color must be '#rrggbb', one of {sorted(names)} or an (r, g, b) "
            f"triple in [0, 1], got {value!r}"
        )
    try:
        rgb = tuple(float(c) for c in value)
    except TypeError:
        raise ValueError(
            f"Style: color must be '#rrggbb' or an (r, g, b) triple in [0, 1], got {value!r}"
        ) from None
    if len(rgb) != 3 or not all(0.0 <= c <= 1.0 for c in rgb):
        raise ValueError(f"Style: color must be an (r, g, b) triple in [0, 1], got {value!r}")
    return rgb  # type: ignore[return-value]


def _dash(value: Any) -> tuple[float, ...] | None:
    if value is None:
        return None
    try:
        d = tuple(float(x) for x in value)
    except TypeError:
        raise ValueError(
            f"Style: dash must be None or a sequence of on/off lengths in pt, got {value!r}"
        ) from None
    if not d or len(d) % 2 or not all(math.isfinite(x) and x > 0 for x in d):
        raise ValueError(
            "Style: dash must be an even-length sequence of positive finite lengths in pt, "
            f"got {value!r}"
        )
    return d


@attrs.frozen
class Style:
    """How a stroke looks: colour, line width (pt) and dash pattern (pt).

    >>> Style(width=1.0).width
    1.0
    >>> Style(color="#ff0000").color
    (1.0, 0.0, 0.0)
    >>> Style(width=0)
    Traceback (most recent call last):
    ...
    ValueError: Style: width must be a positive finite number, got 0
    """

    color: tuple[float, float, float] = attrs.field(default=(0.0, 0.0, 0.0), converter=_color)
    width: float = attrs.field(default=0.5, validator=finite_positive("Style"))
    dash: tuple[float, ...] | None = attrs.field(default=None, converter=_dash)

    def evolve(self, **changes: Any) -> Style:
        """A copy with some fields changed."""
        return attrs.evolve(self, **changes)


#: Default look of hidden parts (``hidden_lines=True``): thin and dashed.
HIDDEN_STYLE = Style(color=(0.35, 0.35, 0.35), width=0.3, dash=(2.0, 1.5))


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
        Parameters of the points on :attr:`surface`; None for free curves.
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

    @width.validator
    @height.validator
    def _check_size(self, attribute: attrs.Attribute, value: float | None) -> None:
        if value is not None:
            finite_positive("Page")(self, attribute, value)

    def __attrs_post_init__(self) -> None:
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


@attrs.frozen(eq=False)
class Drawing:
    """Strokes plus page geometry; ``save`` writes PDF, PNG or SVG by suffix."""

    strokes: tuple[Stroke, ...] = attrs.field(converter=tuple)
    page: Page = attrs.field(default=None, converter=_page)
    background: tuple[float, float, float] | None = attrs.field(default=(1.0, 1.0, 1.0))
    _cache: dict = attrs.field(factory=dict, init=False, repr=False)

    # -- geometry ---------------------------------------------------------
    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` of all strokes in projection coordinates."""
        pts = [s.xy for s in self.strokes if len(s.xy)]
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
        x0, y0, x1, y1 = self.bounds()
        w, h = max(x1 - x0, 1e-300), max(y1 - y0, 1e-300)
        if w <= 1e-12 * max(h, 1.0):
            w = h
        if h <= 1e-12 * max(w, 1.0):
            h = w
        m = self.page.margin
        if self.page.width is None:
            scale = self.page.extent / max(w, h)
            pw, ph = w * scale + 2 * m, h * scale + 2 * m
        else:
            pw, ph = self.page.width, self.page.height
            scale = min((pw - 2 * m) / w, (ph - 2 * m) / h)
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        offset = np.array([pw / 2 - scale * cx, ph / 2 - scale * cy])
        return scale, offset, pw, ph

    def page_size(self) -> tuple[float, float]:
        """Width and height of the page in points."""
        _, _, pw, ph = self._layout()
        return pw, ph

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

    def __len__(self) -> int:
        return len(self.strokes)

    @property
    def n_points(self) -> int:
        """Total number of points over all strokes."""
        return int(sum(len(s.xy) for s in self.strokes))

    # -- output -----------------------------------------------------------
    def save(self, path: str | os.PathLike[str], **options: Any) -> Path:
        """Write the drawing to ``path``; the format follows the suffix.

        ``.pdf`` (reportlab, vector), ``.png`` (pillow, anti-aliased; options
        ``dpi`` or ``size``), ``.svg`` (plain XML polylines) and any suffix a
        backend plugin registers.  The file is written atomically: on any error
        nothing is left behind.

        Returns the path written.
        """
        from .backends import get_backend

        path = Path(path)
        writer = get_backend(path.suffix)
        parent = path.parent if str(path.parent) else Path(".")
        if not parent.is_dir():
            raise FileNotFoundError(f"Drawing.save: folder {str(parent)!r} does not exist")
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=parent)
        os.close(fd)
        try:
            writer(self, Path(tmp), **options)
            os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600 files
            os.replace(tmp, path)
        except BaseException:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            raise
        return path


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


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
