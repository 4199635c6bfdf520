"""PNG backend (pillow): anti-aliased raster by supersampling.

The drawing is rendered at ``supersample`` times the output resolution and
box-reduced (``Image.reduce``), which anti-aliases without the ringing of a
Lanczos filter.  Lines 2 supersampled pixels wide are drawn with an
L-shaped pen (:mod:`lgraph.output.backends._pen`): unlike pillow's own, their
weight does not change with their direction.  Round caps and joins of
wider lines are drawn as discs: pillow's own ``joint="curve"`` loops over
every vertex in Python and gives no caps, so discs go only where they show
(stroke ends, dash ends and vertices whose turning angle opens a visible
gap), found with one vectorized test.

Animation frames make this path hot, so it does no more work than the pixels
need, without changing one of them: all points are mapped at once and handed
to pillow as the integers it would truncate them to (one float32 array), only
the box of the supersampled canvas that the strokes can reach is box-reduced
(and pasted onto the background), and a grey frame's canvas is kept for the
next frame of the same size, with only that box cleared.

>>> import numpy as np, tempfile, os
>>> from PIL import Image
>>> from lgraph.output.drawing import Drawing, Page, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)))
>>> d = Drawing(strokes=(s,), page=Page(margin=0, extent=100))
>>> with tempfile.TemporaryDirectory() as tmp:
...     path = os.path.join(tmp, "a.png")
...     write_png(d, path, dpi=144)
...     Image.open(path).size
(200, 100)
"""

from __future__ import annotations

import functools
import math
import numbers
import os
import threading
import warnings
from typing import Any

import numpy as np

from ..dashes import dash_polyline
from ._common import background_rgb, check_options, page_run_points, positive_finite
from ._pen import Pen

__all__ = ["write_png", "render_image", "MAX_SIDE"]

#: Largest allowed output image side in pixels.
MAX_SIDE = 20000

#: Largest supersampled canvas in pixels; ``supersample`` is lowered to fit.
MAX_SUPERSAMPLED_PIXELS = 2**28

#: A round join is drawn where the gap it fills would exceed this (in
#: supersampled pixels).
_JOIN_GAP_PX = 0.25


def _image_size(pw: float, ph: float, dpi: Any, size: Any) -> tuple[int, int, float, float, float]:
    """Pixel size, scale (px per pt) and offset for the page ``pw`` x ``ph`` pt."""
    if size is None:
        dpi = positive_finite("write_png", "dpi", dpi)
        scale = dpi / 72.0
        w, h = max(1, round(pw * scale)), max(1, round(ph * scale))
        if max(w, h) > MAX_SIDE:
            raise ValueError(
                f"write_png: dpi={dpi:g} gives a {w} x {h} px image; the limit is "
                f"{MAX_SIDE} px per side (lower dpi or give size)"
            )
        # Map the page exactly onto the rounded pixel grid.
        return w, h, w / pw, h / ph, 0.0
    if isinstance(size, numbers.Integral) and not isinstance(size, bool):
        n = _check_side(size, "size")
        scale = n / max(pw, ph)
        w, h = max(1, round(pw * scale)), max(1, round(ph * scale))
        return w, h, w / pw, h / ph, 0.0
    try:
        w, h = size
    except (TypeError, ValueError):
        raise ValueError(
            f"write_png: size must be an int (longer side in px) or (width, height) "
            f"in px, got {size!r}"
        ) from None
    w, h = _check_side(w, "size[0]"), _check_side(h, "size[1]")
    # Keep the aspect ratio: fit the page inside (w, h) and centre it.
    scale = min(w / pw, h / ph)
    return w, h, scale, scale, 1.0


def _check_side(value: Any, name: str) -> int:
    if not isinstance(value, numbers.Integral) or isinstance(value, bool) or value < 1:
        raise ValueError(f"write_png: {name} must be a positive integer, got {value!r}")
    if value > MAX_SIDE:
        raise ValueError(f"write_png: {name} = {value} px exceeds the limit of {MAX_SIDE} px")
    return int(value)


def _disc_vertices(px: np.ndarray, radius: float) -> np.ndarray:
    """Indices of the vertices of ``px`` that need a disc for a round cap/join."""
    n = len(px)
    ends = np.array([0, n - 1])
    if n < 3:
        return ends
    d1 = px[1:-1] - px[:-2]
    d2 = px[2:] - px[1:-1]
    l1 = np.hypot(d1[:, 0], d1[:, 1])
    l2 = np.hypot(d2[:, 0], d2[:, 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        cos_t = np.einsum("ij,ij->i", d1, d2) / (l1 * l2)
    cos_t = np.where(np.isfinite(cos_t), np.clip(cos_t, -1.0, 1.0), 1.0)
    # Gap between a butt-joined corner and the round join: r (1 - cos(theta/2)).
    gap = radius * (1.0 - np.sqrt((1.0 + cos_t) / 2.0))
    inner = np.flatnonzero(gap > _JOIN_GAP_PX) + 1
    return np.concatenate([ends, inner])


#: Below this, pixel coordinates truncated to integers are exact in float32.
_F32_EXACT = 2.0**24

#: Grey supersampled canvases up to this many pixels (4 MB) are kept, one per
#: thread, for the next frame of the same size.
_REUSE_MAX_PIXELS = 2**22
_reused = threading.local()


def _pillow_xy(px: np.ndarray, small: bool) -> Any:
    """Pixel coordinates ``px`` as pillow takes them.

    Pillow truncates every coordinate of a line or an ellipse to an integer
    (toward zero) and rasterizes from those integers; so when the points are
    ``small`` (within ``2**24`` px) they go as those integers in a float32
    array (exact; pillow reads its buffer, with no Python float per
    coordinate).  Otherwise as the list of floats.
    """
    return np.trunc(px).astype(np.float32) if small else px.ravel().tolist()


def _draw_polyline(
    draw: Any, px: np.ndarray, ink: tuple[int, ...] | int, lw: int, small: bool
) -> None:
    """Draw one polyline in supersampled pixel coordinates with round caps/joins
    (2 pixels wide: with the L-shaped pen)."""
    if lw == 2:
        Pen(_pillow_xy, px, small).draw(draw, 0, len(px), ink)
        return
    draw.line(_pillow_xy(px, small), fill=ink, width=lw)
    _draw_discs(draw, px, ink, lw, small)


def _draw_discs(
    draw: Any, px: np.ndarray, ink: tuple[int, ...] | int, lw: int, small: bool
) -> None:
    """The round caps and joins of the polyline ``px`` (none below 3 px wide)."""
    if lw < 3:
        return
    r = (lw - 1) / 2.0
    c = px[_disc_vertices(px, lw / 2.0)]
    corners = np.stack([c - r, c + r], axis=1).reshape(-1, 2)  # (x - r, y - r), (x + r, y + r)
    boxes = np.asarray(_pillow_xy(corners, small), dtype=float).reshape(-1, 4)
    for box in boxes.tolist():
        draw.ellipse(box, fill=ink)


def _ink_box(
    bounds: tuple[float, float, float, float], lw_max: int, ss: int, size: tuple[int, int]
) -> tuple[int, int, int, int]:
    """A box ``(left, top, right, bottom)`` of the supersampled canvas of
    ``size`` px, on multiples of ``ss`` and within the canvas, that holds every
    pixel of the strokes through points within ``bounds`` (``xmin, xmax, ymin,
    ymax``), at most ``lw_max`` px wide: only this box needs the background
    and the box filter.

    A stroke reaches at most ``lw_max / 2 + 2`` px beyond its points (pillow
    truncates coordinates to integers, rounds polygon corners up and draws a
    disc within its integer box); the margin is ``lw_max + 3``.
    """
    x0, x1, y0, y1 = bounds
    W, H = size
    margin = lw_max + 3
    left = min(W, max(0, math.floor((x0 - margin) / ss) * ss))
    top = min(H, max(0, math.floor((y0 - margin) / ss) * ss))
    right = max(left, min(W, math.ceil((x1 + margin) / ss) * ss))
    bottom = max(top, min(H, math.ceil((y1 + margin) / ss) * ss))
    return left, top, right, bottom


def _canvas(mode: str, size: tuple[int, int], fill: Any, box: tuple[int, int, int, int]) -> Any:
    """A supersampled canvas of ``size`` px with the background ``fill`` in
    ``box`` (the only part drawn on and read): grey ones up to
    ``_REUSE_MAX_PIXELS`` are this thread's canvas of the last frame of that
    size, with just the box cleared (no new memory to fault in and fill).
    Pillow draws by overwriting pixels and no stroke reaches outside the box
    (:func:`_ink_box`), so the box comes out as on a new canvas."""
    from PIL import Image

    if mode != "L" or size[0] * size[1] > _REUSE_MAX_PIXELS:
        return Image.new(mode, size, fill)
    img = getattr(_reused, "canvas", None)
    if img is None or img.size != size:
        img = _reused.canvas = None  # the old one freed first
        img = _reused.canvas = Image.new(mode, size, fill)
    else:
        img.paste(fill, box)
    return img


@functools.lru_cache(maxsize=16)
def _reduced_fill(mode: str, fill: Any, ss: int) -> Any:
    """The background ``fill`` as the box filter of ``ss`` gives it (a
    constant, kept: every frame of an animation asks for it)."""
    from PIL import Image

    return Image.new(mode, (ss, ss), fill).reduce(ss).getpixel((0, 0)) if ss > 1 else fill


def _onto_page(
    canvas: Any,
    mode: str,
    box: tuple[int, int, int, int],
    ss: int,
    size: tuple[int, int],
    fill: Any,
) -> Any:
    """The page of ``size`` px: the ``box`` of the supersampled ``canvas``
    (None if the box is empty) reduced by ``ss``, on the background elsewhere."""
    from PIL import Image

    left, top = box[:2]
    page = Image.new(mode, size, _reduced_fill(mode, fill, ss))
    if canvas is not None:
        part = canvas.reduce(ss, box=box) if ss > 1 else canvas.crop(box)
        page.paste(part, (left // ss, top // ss))
    return page


def write_png(
    drawing: Any,
    path: str | os.PathLike[str],
    *,
    dpi: float = 150,
    size: int | tuple[int, int] | None = None,
    supersample: int = 3,
    **options: Any,
) -> None:
    """Write ``drawing`` as an anti-aliased PNG.

    Parameters
    ----------
    drawing : Drawing
        The display list.
    path : path-like
        File to write (whatever its suffix).
    dpi : float, default 150
        Pixels per inch of the page (a page point is 1/72 inch).
    size : int or (int, int), optional
        Overrides ``dpi``: an int is the longer side in pixels; ``(width,
        height)`` is the exact image size, with the page fitted inside and
        centred (aspect ratio kept).
    supersample : int, default 3
        Render at this many times the resolution, then box-reduce.  Lowered
        automatically when the supersampled canvas would exceed
        ``MAX_SUPERSAMPLED_PIXELS``.

    Notes
    -----
    Line widths scale with the resolution (at least 1 supersampled pixel); a
    stroke wider than twice the image's diagonal covers the whole image (drawn
    as one fill, with a warning).  Dashes are split with
    :func:`lgraph.output.drawing.dash_polyline`; a dash pattern with a dash or gap
    shorter than one output pixel is drawn solid, with a warning.  The background
    is ``drawing.background`` (an RGB image); None gives a transparent RGBA
    image.  The effective dpi is written into the PNG metadata.

    Raises
    ------
    TypeError
        For an option this writer does not know.
    ValueError
        For a bad ``dpi``, ``size`` or ``supersample``, or an image larger than
        ``MAX_SIDE`` pixels per side.
    """
    vector_only = sorted({"curves", "text"} & set(options))
    if vector_only:
        raise TypeError(
            f"write_png: {' and '.join(f'{k}=' for k in vector_only)} belong to the vector "
            "formats (PDF, SVG, TikZ); a PNG is pixels: for smooth curves in a very large "
            "PNG render with a smaller tolerance (Scene.render(..., tolerance=...))"
        )
    check_options("write_png", options, ("dpi", "size", "supersample"))
    if (
        not isinstance(supersample, numbers.Integral)
        or isinstance(supersample, bool)
        or not 1 <= supersample <= 8
    ):
        raise ValueError(f"write_png: supersample must be an integer in 1..8, got {supersample!r}")

    from PIL.PngImagePlugin import PngInfo

    img, eff_dpi = render_image(drawing, dpi=dpi, size=size, supersample=supersample)
    info = PngInfo()
    info.add_text("Software", "lgraph")
    img.save(path, format="PNG", dpi=(eff_dpi, eff_dpi), pnginfo=info)


def _is_gray(drawing: Any, bg: tuple[float, float, float] | None) -> bool:
    """Whether ``drawing`` can be drawn in one grey channel with the same
    pixels: an opaque grey background, grey strokes and no labels."""
    if bg is None or getattr(drawing, "labels", ()):
        return False
    colors = {bg, *(s.style.color for s in drawing.strokes)}
    return all(r == g == b for r, g, b in (tuple(round(c * 255) for c in rgb) for rgb in colors))


def _plan(
    drawing: Any,
    mode: str,
    mat: np.ndarray,
    off: np.ndarray,
    unit: float,
    ss: int,
    max_width: float,
) -> tuple[list[tuple[Any, ...]], np.ndarray, set[float], set[tuple[float, ...]]]:
    """What to draw: for each run of points, ``(first point, end, ink, width in
    px, dash pattern in px or None)`` (width 0: a stroke at least ``max_width``
    px wide, which covers the page); all the runs' points in supersampled
    pixels, mapped at once; the too wide widths and the dash patterns drawn
    solid (shorter than a pixel), both in pt; ``unit`` is px per pt."""
    solid_dashes: set[tuple[float, ...]] = set()
    too_wide: set[float] = set()
    pts, bounds, strokes = page_run_points(drawing)
    how: dict[int, tuple[Any, int, tuple[float, ...] | None]] = {}  # id(style) -> ink, width, dash
    plan = []
    for (a, b), stroke in zip(bounds, strokes):
        style = stroke.style
        ink_lw_dash = how.get(id(style))
        if ink_lw_dash is None:
            ink = tuple(round(c * 255) for c in style.color)
            ink = (*ink, 255) if mode == "RGBA" else ink[0] if mode == "L" else ink
            pattern = None
            if style.width * unit >= max_width:
                # a stroke this wide covers every pixel of the page: one fill, not
                # thousands of page-sized polygons
                too_wide.add(style.width)
                lw = 0
            else:
                lw = max(1, round(style.width * unit))
                if style.dash and min(style.dash) * unit < ss:
                    solid_dashes.add(tuple(style.dash))  # shorter than a pixel: drawn solid
                elif style.dash:
                    pattern = tuple(x * unit for x in style.dash)
            ink_lw_dash = how[id(style)] = (ink, lw, pattern)
        ink, lw, pattern = ink_lw_dash
        plan.append((a, b, ink, lw, pattern) if lw else (0, 0, ink, 0, None))
    # mat is diagonal, so this is bit for bit ``pts @ mat + off`` run by run
    # (x * a + y * 0 rounds once, with or without a fused multiply-add)
    px = pts * mat.diagonal() + off
    return plan, px, too_wide, solid_dashes


def render_image(
    drawing: Any,
    *,
    dpi: float = 150,
    size: int | tuple[int, int] | None = None,
    supersample: int = 3,
    gray: bool = False,
) -> tuple[Any, float]:
    """The drawing as a pillow image (options as for :func:`write_png`, already
    checked) and its effective dpi; :func:`write_png` saves it.

    With ``gray`` a drawing in shades of grey on an opaque background (and
    without labels) comes as a one-channel ``"L"`` image: the same pixels as
    the RGB image's channels, drawn and box-reduced in a third of the memory
    (animation frames use it; a GIF takes it without a palette search).
    """
    from PIL import ImageDraw

    pw, ph = drawing.page_size()
    w, h, sx, sy, centre = _image_size(pw, ph, dpi, size)
    ss = int(supersample)
    ss = max(1, min(ss, math.isqrt(MAX_SUPERSAMPLED_PIXELS // (w * h))))

    bg = background_rgb(drawing)
    one_channel = gray and _is_gray(drawing, bg)
    if bg is None:
        mode, fill = "RGBA", (0, 0, 0, 0)
    elif one_channel:
        mode, fill = "L", round(bg[0] * 255)
    else:
        mode, fill = "RGB", tuple(round(c * 255) for c in bg)
    # Page pt (y up) -> supersampled pixel coordinates (y down, pixel centres
    # at integer + 0.5 in continuous coordinates).
    ox = centre * (w - pw * sx) / 2.0
    oy = centre * (h - ph * sy) / 2.0
    mat = np.array([[sx * ss, 0.0], [0.0, -sy * ss]])
    off = np.array([ox * ss - 0.5, (oy + ph * sy) * ss - 0.5])
    unit = math.sqrt(sx * sy) * ss  # supersampled px per pt for widths and dashes
    diag = math.hypot(w * ss, h * ss)  # canvas diagonal in supersampled px
    plan, px, too_wide, solid_dashes = _plan(drawing, mode, mat, off, unit, ss, 2 * diag)

    full = (0, 0, w * ss, h * ss)
    box, small = full, False
    if len(px):
        xs, ys = px[:, 0], px[:, 1]  # (a reduction along axis 0 of px is slow)
        bounds = (xs.min(), xs.max(), ys.min(), ys.max())
        small = bool(-_F32_EXACT < min(bounds) and max(bounds) < _F32_EXACT)
    labels = getattr(drawing, "labels", ())
    if not too_wide and not labels:
        if small:
            box = _ink_box(bounds, max(p[3] for p in plan), ss, full[2:])
        elif not len(px):
            box = (0, 0, 0, 0)  # nothing to draw
    img = None
    if box[2] > box[0] and box[3] > box[1]:  # else no stroke reaches the page
        img = _canvas(mode, full[2:], fill, box)
        draw = ImageDraw.Draw(img)
        xy = _pillow_xy(px, small)  # all points at once
        two = any(p[3] == 2 and not p[4] for p in plan)
        pen = Pen(_pillow_xy, px, small) if two else None
        k = 1 if small else 2  # rows or list items a point
        for start, stop, ink, lw, pattern in plan:
            if not lw:
                draw.rectangle((0, 0, w * ss, h * ss), fill=ink)
            elif pattern:
                for piece in dash_polyline(px[start:stop], pattern):
                    _draw_polyline(draw, piece, ink, lw, small)
            elif lw == 2:
                pen.draw(draw, start, stop, ink)
            else:
                draw.line(xy[k * start : k * stop], fill=ink, width=lw)
                _draw_discs(draw, px[start:stop], ink, lw, small)
    if too_wide:
        warnings.warn(
            f"write_png: stroke widths {sorted(too_wide)} pt exceed twice the image's "
            "diagonal; such a stroke covers the whole image",
            stacklevel=2,
        )
    if solid_dashes:
        warnings.warn(
            f"write_png: dash patterns {sorted(solid_dashes)} (pt) have dashes or gaps "
            f"shorter than a pixel at {72 * math.sqrt(sx * sy):.4g} dpi; drawn solid",
            stacklevel=2,
        )

    if labels:
        from ._labels import png_labels

        png_labels(img, drawing, mat, off, mode == "RGBA")
    if box == full and ss > 1:
        img = img.reduce(ss)
    elif box != full or img is getattr(_reused, "canvas", None):  # not the kept canvas
        img = _onto_page(img, mode, box, ss, (w, h), fill)
    return img, 72.0 * math.sqrt(sx * sy)
