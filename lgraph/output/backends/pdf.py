"""PDF backend (reportlab): one stroked path per stroke, vector and compact.

Each stroke's path is formatted as PDF operators in one pass and injected with
``Canvas.addLiteral``; reportlab's per-point path API costs about 10 us per
point, the single formatting pass about 0.1 us.  Coordinates are written as
integers in units of ``10**-precision`` pt under a scaling matrix (``cm``),
which formats about three times faster than decimals.  The page stream is
deflated with our own filter (chosen zlib level, no ASCII85 layer).

>>> import numpy as np, tempfile, os
>>> from lgraph.output.drawing import Drawing, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [1.0, 1.0]]), xyz=np.zeros((2, 3)))
>>> with tempfile.TemporaryDirectory() as tmp:
...     path = os.path.join(tmp, "a.pdf")
...     write_pdf(Drawing(strokes=(s,)), path)
...     open(path, "rb").read(5)
b'%PDF-'
"""

from __future__ import annotations

import os
import zlib
from typing import Any

import numpy as np

from ._common import background_rgb, check_options, curve_options, fmt_num, page_run_points

__all__ = ["write_pdf", "new_canvas", "draw_page"]

_WHITE = (1.0, 1.0, 1.0)

#: zlib level of ``compress=True``: on line-drawing streams (integer
#: coordinates) level 1 is twice as fast as level 4 and four times as fast as
#: zlib's default 6, for a file about 5 % (7 %) larger.
_DEFAULT_LEVEL = 1

#: integer coordinates stay below this (the integer limit of PDF readers)
_INT_LIMIT = 2.0**31 - 1


class _Flate:
    """A Flate stream filter with a chosen zlib level and no ASCII85 layer.

    reportlab's own page compression always uses zlib level 6 and, with its
    default ``useA85``, ASCII85-encodes the result (25 % larger, and slow).
    """

    pdfname = "FlateDecode"

    def __init__(self, level: int) -> None:
        self.level = level

    def encode(self, text: str | bytes) -> bytes:
        if isinstance(text, str):
            text = text.encode("utf-8")
        return zlib.compress(text, self.level)

    def decode(self, encoded: bytes) -> bytes:
        return zlib.decompress(encoded)


def _compress_level(compress: Any) -> int:
    if isinstance(compress, bool):
        return _DEFAULT_LEVEL if compress else 0
    if isinstance(compress, int) and 0 <= compress <= 9:
        return compress
    raise ValueError(
        f"write_pdf: compress must be True, False or a zlib level 0..9, got {compress!r}"
    )


def _dash_op(dash: tuple[float, ...] | None, unit: float) -> str:
    if not dash:
        return "[] 0 d"
    return "[" + " ".join(fmt_num(x * unit) for x in dash) + "] 0 d"


def write_pdf(
    drawing: Any,
    path: str | os.PathLike[str],
    *,
    compress: bool | int = True,
    precision: int | str = 3,
    title: str = "lgraph",
    curves: str = "polyline",
    text: str = "outlines",
    **options: Any,
) -> None:
    """Write ``drawing`` as a one-page vector PDF.

    Parameters
    ----------
    drawing : Drawing
        The display list; only ``page_size()``, ``page_strokes()`` (or
        ``page_points()``, where it has one) and ``background`` are used.
    path : path-like
        File to write (whatever its suffix).
    compress : bool or int, default True
        Deflate-compress the page content stream: True is zlib level 1 (a
        good speed/size balance for coordinate text), an int 1..9 picks the
        level, False or 0 writes it uncompressed.
    precision : int or length, default 3
        Decimals of the coordinates in points (3 is 1/72000 inch); the
        coordinates are written as integers in units of ``10**-precision``
        pt under a ``cm`` scaling matrix, and line widths and dash lengths
        scaled to match.  With ``curves="bezier"`` a length (``"0.01mm"``,
        the default) is the largest deviation from the exact curves.
    title : str, default "lgraph"
        Document title in the PDF metadata (the creator is always "lgraph").
    curves : "polyline" (default) or "bezier"
        ``"bezier"`` writes the strokes that know their exact curve (those a
        render makes) as cubic Bézier segments within ``precision`` of it
        (:mod:`lgraph.output.bezier`), at any page size; others stay polylines.
    text : "outlines" (default) or "text"
        Labels as filled glyph outlines (the same look in every format) or
        as real text that ``pdftotext`` finds and readers copy: the base
        fonts Times and Symbol, mathematics laid out by mathtext (STIX
        metrics); a label with a character those fonts lack stays outlines.

    Notes
    -----
    The page is ``drawing.page_size()`` points.  Strokes have round caps and
    joins; colour, width and dash come from each stroke's style and are set
    only when they change.  A background other than white (the paper) is
    painted as a full-page rectangle; None and white leave the page
    unpainted.  Runs of non-finite points split a stroke.

    Raises
    ------
    TypeError
        For an option this writer does not know.
    ValueError
        For a bad ``precision`` or ``compress``.
    """
    check_options("write_pdf", options, ("compress", "precision", "title", "curves", "text"))
    from ._labels import check_text_mode

    text = check_text_mode("write_pdf", text)
    precision, deviation = curve_options("write_pdf", curves, precision)
    level = _compress_level(compress)

    pw, ph = drawing.page_size()
    canvas = new_canvas(path, (pw, ph), level, title)
    draw_page(canvas, drawing, precision, deviation, text)
    canvas.showPage()
    canvas.save()


def new_canvas(path: Any, pagesize: tuple[float, float], level: int, title: str) -> Any:
    """A reportlab canvas for ``path`` (or a binary file object) with our stream
    filter at zlib ``level``."""
    from reportlab.pdfgen.canvas import Canvas

    target = path if hasattr(path, "write") else os.fspath(path)
    canvas = Canvas(target, pagesize=pagesize, pageCompression=0)
    if level:
        doc = getattr(canvas, "_doc", None)
        if hasattr(doc, "defaultStreamFilters"):
            # Streams without their own filters (the page) get the document's.
            doc.defaultStreamFilters = [_Flate(level)]
        else:  # pragma: no cover - other reportlab internals
            canvas.setPageCompression(1)
    canvas.setTitle(str(title))
    canvas.setCreator("lgraph")
    canvas.setSubject("line drawing")
    return canvas


def draw_page(
    canvas: Any,
    drawing: Any,
    precision: int,
    deviation: float | None = None,
    text: str = "outlines",
) -> None:
    """Draw ``drawing``'s strokes (and background) onto the canvas's current page
    (as Bézier curves within ``deviation`` pt of the exact curves, when given)."""
    pw, ph = drawing.page_size()
    bg = background_rgb(drawing)
    if bg is not None and bg != _WHITE:
        rgb = " ".join(fmt_num(c) for c in bg)
        canvas.addLiteral(f"{rgb} rg 0 0 {fmt_num(pw)} {fmt_num(ph)} re f")
    canvas.addLiteral("1 J 1 j")  # round caps and joins

    # One template for the whole page, formatted with all coordinates in one
    # pass: per stroke "x y m", "x y l" for the rest, "S"; style operators
    # (which contain no '%') only where the style changes.
    canvas.addLiteral("q")  # the strokes' scaling matrix ends before the labels
    if deviation is None:
        # the runs lie in one array, in order: its values are the page's
        flat, bounds, owners = page_run_points(drawing)
        runs = [(flat[a:b], s, False) for (a, b), s in zip(bounds, owners)]
        values = flat.ravel() if runs else np.empty(0)
    else:
        from ..bezier import page_curve_runs

        runs = page_curve_runs(drawing, deviation)
        values = np.concatenate([pts.ravel() for pts, _, _ in runs]) if runs else np.empty(0)
    unit = 10.0**precision
    if len(values) and np.abs(values).max() * unit >= _INT_LIMIT:  # a huge page
        unit, f = 1.0, f"%.{precision}f"
    else:
        # integers in units of 10**-precision pt under a scaling matrix: about
        # three times faster to format than decimals, and shorter
        values, f = np.rint(values * unit).astype(np.int64), "%d"
        if unit != 1.0:
            k = fmt_num(1 / unit, precision)
            canvas.addLiteral(f"{k} 0 0 {k} 0 0 cm")
    move, line = f"{f} {f} m\n", f"{f} {f} l\n"
    curve = f"{f} {f} {f} {f} {f} {f} c\n"
    color = width = dash = None
    template: list[str] = []
    for pts, stroke, bezier in runs:
        style = stroke.style
        if style.color != color:
            color = style.color
            template.append(" ".join(fmt_num(c) for c in color) + " RG\n")
        if style.width != width:
            width = style.width
            template.append(f"{fmt_num(width * unit)} w\n")
        if style.dash != dash:
            dash = style.dash
            template.append(_dash_op(dash, unit) + "\n")
        body = curve * ((len(pts) - 1) // 3) if bezier else line * (len(pts) - 1)
        template.append(move + body + "S\n")
    if runs:
        canvas.addLiteral("".join(template) % tuple(values.tolist()))
    canvas.addLiteral("Q")
    if getattr(drawing, "labels", ()):
        from ._labels import pdf_labels

        pdf_labels(drawing, canvas, text)
