"""SVG backend: plain XML, one ``<polyline>`` per stroke, no dependencies.

User units are points (the ``viewBox`` is the page in pt), y points down as
SVG wants; the ``width`` and ``height`` attributes are in mm (``save("x.svg",
width="200mm")`` gives the page that width, see :meth:`Drawing.sized`; line
widths stay in pt).  By default the
polylines are grouped in Inkscape layers, ``<g inkscape:groupmode="layer"
inkscape:label="1 contour" id="layer1">``, one per family (hidden parts in
their own layer) or per surface (:mod:`lgraph.output.layers`), each carrying the one
stroke colour and width of its layer: pen-plotter tools (vpype, AxiDraw) read
them as one pen each.  Each polyline carries ``data-family`` and
``data-visible`` attributes, which renderers and plotter tools ignore.

>>> import numpy as np, tempfile, os
>>> import xml.etree.ElementTree as ET
>>> from lgraph.output.drawing import Drawing, Page, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)), family="u1")
>>> d = Drawing(strokes=(s,), page=Page(margin=0, extent=72))
>>> with tempfile.TemporaryDirectory() as tmp:
...     path = os.path.join(tmp, "a.svg")
...     write_svg(d.sized(width="50.8mm"), path, precision=1)
...     root = ET.parse(path).getroot()
>>> root.get("width"), root.get("height"), root.get("viewBox")  # the ink, round caps too
('50.8mm', '25.4882mm', '0 0 144 72.25')
>>> layer = root.find("{http://www.w3.org/2000/svg}g")
>>> layer.get("{http://www.inkscape.org/namespaces/inkscape}label"), layer.get("stroke-width")
('1 u1', '0.5')
>>> layer.find("{http://www.w3.org/2000/svg}polyline").get("points")
'0.2,72.0 143.8,0.2'
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from ..layers import check_layer_mode, drawing_layers
from ..units import to_unit
from ._common import (
    background_rgb,
    check_options,
    curve_options,
    fmt_num,
    format_points,
    hex_color,
    page_runs,
    xml_attr,
    xml_text,
)

__all__ = ["write_svg", "INKSCAPE_NS", "xml_attr", "xml_text"]

#: The Inkscape namespace of the layer attributes.
INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"

_WHITE = (1.0, 1.0, 1.0)


def _polyline(pts: np.ndarray, stroke: Any, precision: int, style_attrs: str) -> str:
    coords = format_points(pts, "{},{} ", precision)[:-1]
    return (
        f"<polyline{style_attrs} data-family={xml_attr(stroke.family)} "
        f'data-visible="{"true" if stroke.visible else "false"}" points="{coords}"/>\n'
    )


def _path(pts: np.ndarray, stroke: Any, precision: int, style_attrs: str) -> str:
    """A run of Bézier control points (``3k + 1``) as one ``<path>``."""
    f = f"%.{precision}f"
    pair = f"{f},{f}"
    k = (len(pts) - 1) // 3
    d = ("M" + pair + (" C" + " ".join([pair] * 3)) * k) % tuple(pts.ravel().tolist())
    return (
        f"<path{style_attrs} data-family={xml_attr(stroke.family)} "
        f'data-visible="{"true" if stroke.visible else "false"}" d="{d}"/>\n'
    )


def _element(run: tuple[Any, ...], a: np.ndarray, b: np.ndarray, precision: int, attrs_: str):
    pts, s = run[0] * a + b, run[1]
    if len(run) > 2 and run[2]:
        return _path(pts, s, precision, attrs_)
    return _polyline(pts, s, precision, attrs_)


def _style_attrs(style: Any) -> str:
    dash = ""
    if style.dash:
        dash = ' stroke-dasharray="' + " ".join(fmt_num(x) for x in style.dash) + '"'
    return (
        f' fill="none" stroke="{hex_color(style.color)}" '
        f'stroke-width="{fmt_num(style.width)}" stroke-linecap="round" '
        f'stroke-linejoin="round"{dash}'
    )


def write_svg(
    drawing: Any,
    path: str | os.PathLike[str],
    *,
    precision: int | str = 3,
    layers: str | None = "family",
    curves: str = "polyline",
    text: str = "outlines",
    **options: Any,
) -> None:
    """Write ``drawing`` as an SVG file.

    Parameters
    ----------
    drawing : Drawing
        The display list.
    path : path-like
        File to write (whatever its suffix).
    precision : int or length, default 3
        Decimals of the point coordinates (in pt); with ``curves="bezier"``
        a length (``"0.01mm"``, the default) is the largest deviation from
        the exact curves.
    layers : "family" (default), "surface", "occlusion" or None
        One Inkscape layer per family (hidden parts in a layer ``hidden``), per
        surface, or no groups at all (every polyline styled on its own).
    curves : "polyline" (default) or "bezier"
        ``"bezier"``: the strokes that know their exact curve become
        ``<path d="M ... C ...">`` of cubic Bézier segments within
        ``precision`` of it (:mod:`lgraph.output.bezier`; vpype and Inkscape read
        them), the others stay polylines.
    text : "outlines" (default) or "text"
        Labels as filled glyph outlines or as ``<text>`` (a ``<tspan>`` a
        glyph, mathtext's layout in the STIX fonts): editable and searchable.

    Notes
    -----
    Every stroke becomes one ``<polyline>`` (inside its layer's ``<g>``, which
    holds the colour, width, round caps/joins and, when dashed,
    ``stroke-dasharray``); a stroke containing non-finite points (breaks)
    becomes one polyline per finite run.  A background other than white (the
    paper) is a full-page ``<rect>`` first; None and white add nothing, so
    plotter tools see only the strokes.  Labels (glyph outlines) come last, in
    a layer ``labels`` of their own when there are layers.

    Raises
    ------
    TypeError
        For an option this writer does not know.
    ValueError
        For a bad ``precision`` or ``layers`` (before anything is written).
    """
    check_options("write_svg", options, ("precision", "layers", "curves", "text"))
    from ._labels import check_text_mode

    text = check_text_mode("write_svg", text)
    precision, deviation = curve_options("write_svg", curves, precision)
    mode = check_layer_mode(layers, "write_svg")
    pw, ph = drawing.page_size()
    w, h = fmt_num(pw), fmt_num(ph)
    out = ['<?xml version="1.0" encoding="UTF-8"?>\n']
    out.append(
        f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="{INKSCAPE_NS}" '
        f'version="1.1" width="{fmt_num(to_unit(pw, "mm"))}mm" '
        f'height="{fmt_num(to_unit(ph, "mm"))}mm" viewBox="0 0 {w} {h}">\n'
    )
    bg = background_rgb(drawing)
    if bg is not None and bg != _WHITE:
        out.append(f'<rect x="0" y="0" width="{w}" height="{h}" fill="{hex_color(bg)}"/>\n')
    # page points (y up) to SVG user units (y down)
    a, b = np.array([1.0, -1.0]), np.array([0.0, ph])
    if deviation is None:
        runs: list[tuple[Any, ...]] = list(page_runs(drawing))
    else:
        from ..bezier import page_curve_runs

        runs = page_curve_runs(drawing, deviation)
    if mode is None:
        for run in runs:
            out.append(_element(run, a, b, precision, _style_attrs(run[1].style)))
    groups = drawing_layers(drawing, mode, runs) if mode else []
    for layer in groups:
        out.append(
            f'<g inkscape:groupmode="layer" inkscape:label={xml_attr(layer.label)} '
            f'id="layer{layer.number}"{_style_attrs(layer.style)}>\n'
        )
        out.extend(_element(run, a, b, precision, "") for run in layer.runs)
        out.append("</g>\n")
    if getattr(drawing, "labels", ()):
        from ._labels import svg_labels

        labels = svg_labels(drawing, ph, precision, text)
        if mode is not None:  # one more layer, so plotter tools see one group for them all
            number = len(groups) + 1
            labels = [
                f'<g inkscape:groupmode="layer" inkscape:label="{number} labels" '
                f'id="layer{number}">\n',
                *labels,
                "</g>\n",
            ]
        out.extend(labels)
    out.append("</svg>\n")
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("".join(out))
