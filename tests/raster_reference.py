"""The straightforward raster frame, for tests and benchmarks: how
``lgraph.output.backends.png.render_image`` and the GIF frames of
``lgraph.animation.writers`` drew and encoded a frame before they were made
cheaper (whole supersampled canvas, each run transformed and handed to pillow
on its own as Python floats, the whole canvas box-reduced; the whole frame
inverted through a copy and encoded; lines 2 px wide with the L-shaped pen
of ``lgraph.output.backends._pen`` drawn line by line).  The fast code
must give the same pixels.
"""

from __future__ import annotations

import io
import math

import numpy as np
from PIL import Image, ImageDraw

from lgraph.output.backends._common import background_rgb, page_runs
from lgraph.output.backends.png import (
    MAX_SUPERSAMPLED_PIXELS,
    _disc_vertices,
    _image_size,
    _is_gray,
)
from lgraph.output.dashes import dash_polyline

_INVERT = [255 - g for g in range(256)]
_DESCENDING_GREYS = bytes(c for g in range(255, -1, -1) for c in (g, g, g))


def draw_polyline(draw, px, ink, lw):
    if lw == 2:  # the L-shaped pen, line by line: the points, back through them moved in x,
        p = np.trunc(px)  # then segment by segment moved down (falling) or up (rising)
        draw.line(p.ravel().tolist(), fill=ink, width=1)
        draw.line((p + (1, 0))[::-1].ravel().tolist(), fill=ink, width=1)
        for j in range(len(p) - 1):  # level and upright segments count as falling
            (dx, dy) = p[j + 1] - p[j]
            move = -1 if dx * dy < 0 else 1
            draw.line((p[j : j + 2] + (0, move)).ravel().tolist(), fill=ink, width=1)
        return
    draw.line(px.ravel().tolist(), fill=ink, width=lw)
    if lw < 3:
        return
    r = (lw - 1) / 2.0
    for x, y in px[_disc_vertices(px, lw / 2.0)].tolist():
        draw.ellipse((x - r, y - r, x + r, y + r), fill=ink)


def render_image(drawing, *, dpi=150, size=None, supersample=3, gray=False):
    """The image ``render_image`` gave before (without the warnings)."""
    pw, ph = drawing.page_size()
    w, h, sx, sy, centre = _image_size(pw, ph, dpi, size)
    ss = max(1, min(int(supersample), math.isqrt(MAX_SUPERSAMPLED_PIXELS // (w * h))))
    bg = background_rgb(drawing)
    if bg is None:
        mode, fill = "RGBA", (0, 0, 0, 0)
    elif gray and _is_gray(drawing, bg):
        mode, fill = "L", round(bg[0] * 255)
    else:
        mode, fill = "RGB", tuple(round(c * 255) for c in bg)
    img = Image.new(mode, (w * ss, h * ss), fill)
    draw = ImageDraw.Draw(img)
    ox = centre * (w - pw * sx) / 2.0
    oy = centre * (h - ph * sy) / 2.0
    mat = np.array([[sx * ss, 0.0], [0.0, -sy * ss]])
    off = np.array([ox * ss - 0.5, (oy + ph * sy) * ss - 0.5])
    unit = math.sqrt(sx * sy) * ss
    diag = math.hypot(w * ss, h * ss)
    for pts, stroke in page_runs(drawing):
        style = stroke.style
        ink = tuple(round(c * 255) for c in style.color)
        if mode == "RGBA":
            ink = (*ink, 255)
        elif mode == "L":
            ink = ink[0]
        if style.width * unit >= 2 * diag:
            draw.rectangle((0, 0, w * ss, h * ss), fill=ink)
            continue
        lw = max(1, round(style.width * unit))
        px = pts @ mat + off
        if style.dash and min(style.dash) * unit >= ss:
            for piece in dash_polyline(px, tuple(x * unit for x in style.dash)):
                draw_polyline(draw, piece, ink, lw)
            continue
        draw_polyline(draw, px, ink, lw)
    if getattr(drawing, "labels", ()):
        from lgraph.output.backends._labels import png_labels

        png_labels(img, drawing, mat, off, mode == "RGBA")
    if ss > 1:
        img = img.reduce(ss)
    return img, 72.0 * math.sqrt(sx * sy)


def gif_frame(im):
    """A grey ("L") frame as the GIF encoding of the whole frame (pillow's
    output, parsed no further)."""
    pal = Image.frombytes("P", im.size, im.point(_INVERT).tobytes())
    pal.putpalette(_DESCENDING_GREYS)
    buf = io.BytesIO()
    pal.save(buf, "GIF", optimize=False)
    return buf.getvalue()
