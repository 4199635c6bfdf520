"""Labels in the built-in backends: glyph outlines as PDF paths, SVG paths and
filled PNG polygons (the same shapes everywhere, :mod:`lgraph.output._text`), or
native text for plain labels when matplotlib is missing.

Labels are drawn after the strokes, each in its colour; they never change
the strokes.

>>> import numpy as np
>>> from lgraph.output._text import text_shape
>>> ops = path_ops(text_shape("$x$", 10.0), np.zeros(2), "{} {} ", "m", "l", "c", "h", 2)
>>> ops.startswith(("0.", "1.", "2.", "3.")) and ops.rstrip().endswith("h")
True
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._text import CLOSEPOLY, CURVE4, FALLBACK_FONT, LINETO, MOVETO, cubic_segments, polygons
from .._text import text_shape as _shape
from ._common import fmt_num, hex_color, xml_attr, xml_text

__all__ = ["path_ops", "pdf_labels", "svg_labels", "png_labels", "TEXT_MODES", "check_text_mode"]

#: ``text=`` of the PDF and SVG writers: glyph outlines (the same look
#: everywhere, the default) or real text (searchable, copyable, editable)
TEXT_MODES = ("outlines", "text")

#: PDF base fonts of real text, by glyph style; characters outside their
#: encoding come from Symbol (Greek, math operators)
_PDF_FONTS = {"roman": "Times-Roman", "italic": "Times-Italic", "bold": "Times-Bold"}


def check_text_mode(writer: str, text: Any) -> str:
    """Validate ``text=``: ``"outlines"`` or ``"text"``.

    >>> check_text_mode("write_pdf", "glyphs")
    Traceback (most recent call last):
    ...
    ValueError: write_pdf: text must be 'outlines' or 'text', got 'glyphs'
    """
    if text not in TEXT_MODES:
        raise ValueError(f"{writer}: text must be 'outlines' or 'text', got {text!r}")
    return text


def _pdf_font(char: str, style: str) -> str | None:
    """The base font that can show ``char`` (None: none of them can)."""
    import reportlab.pdfbase.rl_codecs  # noqa: F401 - registers the codecs

    for font, codec in ((_PDF_FONTS[style], "winansi"), ("Symbol", "symbol")):
        try:
            char.encode(codec)
        except (UnicodeError, LookupError):
            continue
        return font
    return None


def _pdf_text(canvas: Any, origin: np.ndarray, lab: Any) -> bool:
    """Draw ``lab`` as real text (base fonts); False if a character has no
    base font (the label is then drawn as outlines)."""
    from .._text import text_glyphs

    layout = text_glyphs(lab.text, lab.size)
    fonts = [_pdf_font(c, st) if c.strip() else "Times-Roman" for _, _, c, st, _ in layout.glyphs]
    if None in fonts:  # (plain text is one run: all of it in one font, or outlines)
        return False
    canvas.setFillColorRGB(*lab.style.color)
    x0, y0 = float(origin[0]), float(origin[1])
    for (x, y, c, _, size), font in zip(layout.glyphs, fonts):
        canvas.setFont(font, size)
        canvas.drawString(x0 + x, y0 + y, c)
    for x, y, w, h in layout.rects:
        canvas.rect(x0 + x, y0 + y, w, h, stroke=0, fill=1)
    return True


def path_ops(
    shape: Any,
    origin: np.ndarray,
    pair: str,
    move: str,
    line: str,
    curve: str,
    close: str,
    precision: int,
    flip_height: float | None = None,
) -> str:
    """The outline of ``shape`` at ``origin`` as path operators, formatted in one pass.

    ``pair`` formats one point (two ``{}``); ``move``/``line``/``curve``/
    ``close`` are the operator names.  Without ``flip_height`` (PDF) each
    operator follows its numbers; with it (SVG) it precedes them and y
    becomes ``flip_height - y``.
    """
    kind, pts, _ = cubic_segments(shape.codes, shape.vertices)
    if not len(kind):
        return ""
    pts = pts + origin
    if flip_height is not None:
        pts = pts * (1.0, -1.0) + (0.0, flip_height)
    f = f"%.{precision}f"
    p = pair.format(f, f)
    svg = flip_height is not None
    templ = {
        MOVETO: f"{move} {p}" if svg else f"{p}{move}\n",
        LINETO: f"{line} {p}" if svg else f"{p}{line}\n",
        CURVE4: f"{curve} {p}{p}{p}" if svg else f"{p}{p}{p}{curve}\n",
        CLOSEPOLY: f"{close} " if svg else f"{close}\n",
    }
    take = np.zeros((len(kind), 6), bool)
    take[(kind == MOVETO) | (kind == LINETO), 4:] = True
    take[kind == CURVE4] = True
    values = pts.reshape(-1, 6)[take]
    template = "".join(templ[k] for k in kind.tolist())
    return template % tuple(values.tolist())


def pdf_labels(drawing: Any, canvas: Any, text: str = "outlines") -> None:
    """Append the labels to a reportlab canvas (outlines filled, or base-font
    text: always with ``text="text"``, else where matplotlib is missing)."""
    for origin, lab in drawing.page_labels():
        if text == "text" and _pdf_text(canvas, origin, lab):
            continue
        shape = _shape(lab.text, lab.size)
        rgb = " ".join(fmt_num(c) for c in lab.style.color)
        if shape.string is not None:
            canvas.setFillColorRGB(*lab.style.color)
            canvas.setFont(FALLBACK_FONT, lab.size)
            canvas.drawString(float(origin[0]), float(origin[1]), shape.string)
            continue
        ops = path_ops(shape, origin, "{} {} ", "m", "l", "c", "h", 3)
        if ops:
            canvas.addLiteral(f"{rgb} rg\n{ops}f")


def _svg_text(origin: np.ndarray, lab: Any, height: float, color: str) -> str:
    """``lab`` as one ``<text>``, a ``<tspan>`` a glyph (mathtext's layout),
    and ``<rect>`` fraction bars."""
    from .._text import text_glyphs

    layout = text_glyphs(lab.text, lab.size)
    spans = []
    for x, y, c, style, size in layout.glyphs:
        look = {"italic": ' font-style="italic"', "bold": ' font-weight="bold"'}.get(style, "")
        spans.append(
            f'<tspan x="{fmt_num(origin[0] + x)}" y="{fmt_num(height - origin[1] - y)}" '
            f'font-size="{fmt_num(size)}"{look}>{xml_text(c)}</tspan>'
        )
    rects = "".join(
        f'<rect x="{fmt_num(origin[0] + x)}" y="{fmt_num(height - origin[1] - y - h)}" '
        f'width="{fmt_num(w)}" height="{fmt_num(h)}" fill="{color}"/>'
        for x, y, w, h in layout.rects
    )
    return (
        f'<text font-family="STIXGeneral, Times New Roman, Times, serif" fill="{color}" '
        f'xml:space="preserve">{"".join(spans)}</text>{rects}'
    )


def svg_labels(drawing: Any, height: float, precision: int, text: str = "outlines") -> list[str]:
    """One ``<g>`` per label: a filled ``<path>`` of its outline, or a
    ``<text>`` (``text="text"``, or plain text where matplotlib is missing)."""
    out = []
    for origin, lab in drawing.page_labels():
        shape = _shape(lab.text, lab.size)
        color = hex_color(lab.style.color)
        head = (
            f'<g class="label" data-text={xml_attr(lab.text)} '
            f'data-visible="{"true" if lab.visible else "false"}">'
        )
        if text == "text":
            body = _svg_text(origin, lab, height, color)
        elif shape.string is not None:
            x, y = fmt_num(origin[0]), fmt_num(height - origin[1])
            body = (
                f'<text x="{x}" y="{y}" font-family="Times New Roman, Times, serif" '
                f'font-size="{fmt_num(lab.size)}" fill="{color}">{xml_text(shape.string)}</text>'
            )
        else:
            d = path_ops(shape, origin, "{},{} ", "M", "L", "C", "Z", precision, height)
            body = f'<path fill="{color}" stroke="none" d="{d.strip()}"/>'
        out.append(f"{head}{body}</g>\n")
    return out


def _pil_font(px: float) -> Any:
    from PIL import ImageFont

    size = max(1, round(px))
    for name in ("DejaVuSerif.ttf", "LiberationSerif-Regular.ttf", "Times New Roman.ttf"):
        try:
            return ImageFont.truetype(name, size)
        except OSError:
            continue
    return ImageFont.load_default(size=size)


def png_labels(img: Any, drawing: Any, mat: np.ndarray, off: np.ndarray, rgba: bool) -> None:
    """Fill the labels' outlines into the supersampled image ``img``.

    ``mat`` and ``off`` map page pt to pixels (as for the strokes).  Each
    label's contours are combined even-odd in a mask (a glyph's holes stay
    open), then its colour is pasted through the mask.
    """
    from PIL import Image, ImageChops, ImageDraw

    unit = math.sqrt(abs(np.linalg.det(mat)))
    for origin, lab in drawing.page_labels():
        shape = _shape(lab.text, lab.size)
        ink = tuple(round(c * 255) for c in lab.style.color)
        if rgba:
            ink = (*ink, 255)
        if shape.string is not None:
            x, y = (np.asarray(origin) @ mat + off).tolist()
            ImageDraw.Draw(img).text(
                (x, y), shape.string, fill=ink, font=_pil_font(lab.size * unit), anchor="ls"
            )
            continue
        polys = [(p + origin) @ mat + off for p in polygons(shape.codes, shape.vertices)]
        if not polys:
            continue
        allp = np.concatenate(polys)
        x0, y0 = np.floor(allp.min(axis=0)).astype(int) - 1
        x1, y1 = np.ceil(allp.max(axis=0)).astype(int) + 2
        size = (int(x1 - x0), int(y1 - y0))
        mask = Image.new("1", size, 0)
        for p in polys:
            one = Image.new("1", size, 0)
            ImageDraw.Draw(one).polygon((p - (x0, y0)).ravel().tolist(), fill=1)
            mask = ImageChops.logical_xor(mask, one)
        img.paste(ink, (int(x0), int(y0), int(x1), int(y1)), mask)
