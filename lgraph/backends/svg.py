"""SVG backend: plain XML, one ``<polyline>`` per stroke, no dependencies.

User units are points (``viewBox`` equals the page size in pt), y points
down as SVG wants.  Each polyline carries ``data-family`` and
``data-visible`` attributes; renderers and pen-plotter tools (vpype) ignore
unknown attributes.

>>> import numpy as np, tempfile, os
>>> import xml.etree.ElementTree as ET
>>> from lgraph.drawing import Drawing, Page, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)))
>>> d = Drawing(strokes=(s,), page=Page(margin=0, extent=100))
>>> with tempfile.TemporaryDirectory() as tmp:
...     path = os.path.join(tmp, "a.svg")
...     write_svg(d, path, precision=1)
...     root = ET.parse(path).getroot()
>>> root.get("viewBox")
'0 0 100 50'
>>> line = root.find("{http://www.w3.org/2000/svg}polyline")
>>> line.get("points"), line.get("stroke-width"), line.get("data-family")
('0.0,50.0 100.0,0.0', '0.5', 'curve')
"""

from __future__ import annotations

import os
from typing import Any
from xml.sax.saxutils import quoteattr

from ._common import (
    background_rgb,
    check_options,
    check_precision,
    fmt_num,
    format_points,
    hex_color,
    page_runs,
)

__all__ = ["write_svg"]

_WHITE = (1.0, 1.0, 1.0)


def write_svg(
    drawing: Any,
    path: str | os.PathLike[str],
    *,
    precision: int = 3,
    **options: Any,
) -> None:
    """Write ``drawing`` as an SVG file.

    Parameters
    ----------
    drawing : Drawing
        The display list.
    path : path-like
        File to write (whatever its suffix).
    precision : int, default 3
        Decimals of the point coordinates (in pt).

    Notes
    -----
    Every stroke becomes one ``<polyline fill="none">`` with its colour,
    width, round caps/joins and, when dashed, ``stroke-dasharray``; a stroke
    containing non-finite points (breaks) becomes one polyline per finite
    run.  A background other than white (the paper) is a full-page ``<rect>``
    first; None and white add nothing, so plotter tools see only the strokes.

    Raises
    ------
    TypeError
        For an option this writer does not know.
    ValueError
        For a bad ``precision``.
    """
    check_options("write_svg", options, ("precision",))
    precision = check_precision("write_svg", precision)

    pw, ph = drawing.page_size()
    w, h = fmt_num(pw), fmt_num(ph)
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n')
        f.write(
            f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" '
            f'width="{w}pt" height="{h}pt" viewBox="0 0 {w} {h}">\n'
        )
        bg = background_rgb(drawing)
        if bg is not None and bg != _WHITE:
            f.write(f'<rect x="0" y="0" width="{w}" height="{h}" fill="{hex_color(bg)}"/>\n')
        for pts, stroke in page_runs(drawing):
            style = stroke.style
            flipped = pts * (1.0, -1.0) + (0.0, ph)
            coords = format_points(flipped, "{},{} ", precision)[:-1]
            dash = ""
            if style.dash:
                dash = ' stroke-dasharray="' + " ".join(fmt_num(x) for x in style.dash) + '"'
            f.write(
                f'<polyline fill="none" stroke="{hex_color(style.color)}" '
                f'stroke-width="{fmt_num(style.width)}" stroke-linecap="round" '
                f'stroke-linejoin="round"{dash} data-family={quoteattr(str(stroke.family))} '
                f'data-visible="{"true" if stroke.visible else "false"}" points="{coords}"/>\n'
            )
        if getattr(drawing, "labels", ()):
            from ._labels import svg_labels

            f.writelines(svg_labels(drawing, ph, precision))
        f.write("</svg>\n")
