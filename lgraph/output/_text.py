r"""Label text: validation, and text turned into glyph outlines for the backends.

Text between ``$...$`` is TeX mathematics, typeset by matplotlib's
``mathtext`` (Computer Modern, ``mathtext.fontset = "cm"``) and turned into
glyph outlines (:class:`matplotlib.textpath.TextPath`), so PDF, SVG and PNG
show identical vector shapes without a LaTeX installation.  Text outside
``$`` is set in DejaVu Serif (shipped with matplotlib).  matplotlib is
imported only here, and only when a label is checked or laid out.

Without matplotlib, plain text (no ``$``) still works: its box comes from
reportlab's metrics of Times-Roman and the backends draw it as native text
(a PDF base font, an SVG ``<text>``, a pillow font); text with ``$`` then
raises an ImportError naming the ``lgraph[labels]`` extra.

Coordinates are points with y upwards, relative to the start of the text's
baseline.

>>> s = text_shape("$x_1$", 10.0)
>>> x0, y0, x1, y1 = s.box
>>> 0 <= x0 < x1 < 20 and y0 < 0 < y1 < 10
True
>>> check_text("Label", "$\\foo$")
Traceback (most recent call last):
...
ValueError: Label '$\\foo$': unknown TeX in the text: Unknown symbol: \foo

Label text is untrusted input (scene files): before anything parses it,
:func:`check_text` refuses text longer than :data:`MAX_LABEL_LENGTH`,
control characters, groups nested deeper than :data:`MAX_LABEL_DEPTH` and
the TeX commands that reach files or the shell, define commands or change
how TeX reads its input (:func:`check_tex`; the TikZ backend passes label
text to TeX as it is).  Messages quote the text with :func:`quote`: escaped
and cut to a readable length.

>>> check_text("Label", "bell\x07")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
ValueError: Label: text must not contain control characters (...), got '\x07' at position 4 ...
>>> check_text("Label", "$\\input{/etc/passwd}$")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
ValueError: Label: text must not use the TeX command \input (it reads or writes files), ...
"""

from __future__ import annotations

import functools
import re
from typing import Any

import attrs
import numpy as np

from .._tolerance import MAX_LABEL_DEPTH, MAX_LABEL_LENGTH
from ._tex_check import QUOTE_LENGTH, _check_size, check_tex, quote  # noqa: F401 - re-exported

__all__ = [
    "TextShape",
    "TextGlyphs",
    "text_glyphs",
    "check_text",
    "check_tex",
    "quote",
    "text_shape",
    "text_box",
    "has_math",
    "EXTRA_HINT",
    "MAX_LABEL_LENGTH",
    "MAX_LABEL_DEPTH",
]

#: how to get the optional dependency
EXTRA_HINT = "pip install 'lgraph[labels]' (or pip install matplotlib)"

#: font of the text outside ``$...$`` (outlines) ...
_FAMILY = "DejaVu Serif"
#: ... and of plain text when matplotlib is missing (a PDF base font)
FALLBACK_FONT = "Times-Roman"

#: path codes (those of matplotlib.path.Path)
MOVETO, LINETO, CURVE3, CURVE4, CLOSEPOLY = 1, 2, 3, 4, 79

_DOLLAR = re.compile(r"(?<!\\)\$")


class _TypesetError(ValueError):
    """mathtext failed for a reason other than the text's TeX (its recursion or memory)."""


def has_math(text: str) -> bool:
    """Whether ``text`` contains an unescaped ``$`` (TeX mathematics)."""
    return bool(_DOLLAR.search(text))


def _matplotlib(text: str) -> Any:
    try:
        import matplotlib  # noqa: F401
        from matplotlib import textpath
    except ImportError:
        raise ImportError(
            f"Label {text!r}: TeX mathematics ($...$) in labels needs matplotlib; {EXTRA_HINT}"
        ) from None
    return textpath


def _mpl_available() -> bool:
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def check_text(owner: str, text: Any, typeset: bool = True) -> str:
    """Validate label text; raises ValueError naming the label and the problem.

    Checks, in this order and each before anything parses the text: a
    string, at most :data:`MAX_LABEL_LENGTH` characters, no control
    characters (C0, DEL, C1, lone surrogates, U+FFFE, U+FFFF: a label is one
    line) and no TeX that reaches files or the shell (both :func:`check_tex`),
    not empty, groups nested at most :data:`MAX_LABEL_DEPTH` deep,
    balanced ``$``; then, with ``typeset`` (and matplotlib installed), that
    mathtext knows every TeX command.  :class:`lgraph.Label` does not
    typeset: the TikZ backend hands the text to TeX, where the document's
    macros are defined; lgraph typesets a label where it draws its glyphs
    (:func:`text_shape`).
    """
    if not isinstance(text, str):
        raise TypeError(f"{owner}: text must be a string, got {type(text).__name__}")
    if len(text) > MAX_LABEL_LENGTH:
        _check_size(owner, text)
    check_tex(owner, text)
    if not text.strip():
        raise ValueError(f"{owner}: text must not be empty, got {quote(text)}")
    _check_size(owner, text)
    if len(_DOLLAR.findall(text)) % 2:
        raise ValueError(
            f"{owner} {quote(text)}: unbalanced $ (mathematics goes between a pair of $...$)"
        )
    if typeset and has_math(text) and _mpl_available():
        _typeset(owner, text, 10.0)
    return text


def _typeset(owner: str, text: str, size: float) -> tuple[np.ndarray, np.ndarray]:
    """mathtext's outline of ``text``, its errors as one ValueError naming the label."""
    try:
        return _outline(text, size)
    except _TypesetError as exc:
        raise ValueError(f"{owner}: {str(exc).partition(': ')[2]}") from None
    except ValueError as exc:
        lines = [ln.strip() for ln in str(exc).splitlines() if ln.strip()]
        why = next((ln for ln in lines if "Exception:" in ln or "Error" in ln), lines[-1:])
        why = why if isinstance(why, str) else (why[0] if why else "cannot parse")
        why = re.sub(r"^\w*(Exception|Error):\s*", "", why)
        why = re.sub(r",\s*found .*$", "", why)
        raise ValueError(f"{owner} {quote(text)}: unknown TeX in the text: {why}") from None


@attrs.frozen(eq=False)
class TextShape:
    """A laid-out text: its ink box and either glyph outlines or a native string.

    ``codes``/``vertices`` are the outline (matplotlib path codes: 1 move, 2
    line, 3 quadratic, 4 cubic control points, 79 close) in pt; ``string`` is
    set instead when the text is drawn as native text (no matplotlib).
    """

    box: tuple[float, float, float, float]
    size: float
    codes: np.ndarray | None = None
    vertices: np.ndarray | None = None
    string: str | None = None


@functools.lru_cache(maxsize=512)
def _outline(text: str, size: float) -> tuple[np.ndarray, np.ndarray]:
    textpath = _matplotlib(text)
    import matplotlib as mpl
    from matplotlib.font_manager import FontProperties

    _check_size("Label", text)  # also for text that did not come through check_text
    try:
        with mpl.rc_context({"mathtext.fontset": "cm"}):
            prop = FontProperties(family=_FAMILY)  # its math font is the fontset here
            try:
                tp = textpath.TextPath((0, 0), text, size=size, prop=prop)
            except AttributeError:
                # matplotlib fails on text that draws nothing (a zero-width
                # space, a soft hyphen): an empty outline
                if len(textpath.text_to_path.get_text_path(prop, text, ismath=has_math(text))[0]):
                    raise
                return np.empty(0, np.int64), np.empty((0, 2))
    except RecursionError:
        raise _TypesetError(
            f"Label: text nests too deeply for mathtext to typeset (it ran out of recursion; "
            f"groups count, and so do chains of accents): {quote(text)}"
        ) from None
    except MemoryError:
        raise _TypesetError(
            f"Label: text needs more memory than mathtext has to typeset it: {quote(text)}"
        ) from None
    codes = np.asarray(tp.codes, dtype=np.int64)
    vertices = np.asarray(tp.vertices, dtype=float)
    return codes, vertices


@functools.lru_cache(maxsize=512)
def text_shape(text: str, size: float) -> TextShape:
    """The shape of ``text`` at ``size`` pt (cached)."""
    if not has_math(text) and not _mpl_available():
        from reportlab.pdfbase.pdfmetrics import getAscentDescent, stringWidth

        ascent, descent = getAscentDescent(FALLBACK_FONT, size)
        width = stringWidth(text, FALLBACK_FONT, size)
        return TextShape((0.0, float(descent), float(width), float(ascent)), size, string=text)
    try:
        codes, vertices = _typeset("Label", text, size)
    except ValueError as exc:
        raise ValueError(
            f"{exc}; lgraph draws this label's glyphs itself here (PDF, SVG, PNG), with "
            "mathtext, which knows no document macros: the TikZ backend (.tex) hands the "
            "text to TeX as written"
        ) from None
    drawn = vertices[codes != CLOSEPOLY]
    if len(drawn):
        box = (*drawn.min(axis=0).tolist(), *drawn.max(axis=0).tolist())
    else:  # only spaces
        box = (0.0, 0.0, 0.0, 0.0)
    return TextShape(tuple(box), size, codes=codes, vertices=vertices)


def segments(codes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Split path codes into drawing commands, vectorized.

    Returns ``(kind, end)``: the code of each command and the index of its
    last vertex (a quadratic uses two vertices, a cubic three).

    >>> k, e = segments(np.array([1, 2, 3, 3, 3, 3, 79]))
    >>> k.tolist(), e.tolist()
    ([1, 2, 3, 3, 79], [0, 1, 3, 5, 6])
    """
    codes = np.asarray(codes)
    n = len(codes)
    if not n:
        return codes, np.empty(0, np.int64)
    idx = np.arange(n)
    new_run = np.concatenate([[True], codes[1:] != codes[:-1]])
    run_start = np.maximum.accumulate(np.where(new_run, idx, 0))
    pos = idx - run_start
    per = np.select([codes == CURVE3, codes == CURVE4], [2, 3], 1)
    last = pos % per == per - 1
    return codes[last], idx[last]


def cubic_segments(
    codes: np.ndarray, vertices: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Commands with quadratics raised to cubics: ``(kind, points, start)``.

    ``kind`` is 1 (move), 2 (line), 4 (cubic) or 79 (close); ``points`` is
    ``(m, 3, 2)``: for a cubic its two control points and end point, for a
    move or line the point in the last slot.  ``start`` (m, 2) is the current
    point before each command.
    """
    kind, end = segments(codes)
    if not len(kind):  # text that draws nothing
        return kind, np.empty((0, 3, 2)), np.empty((0, 2))
    v = np.asarray(vertices, float)
    pts = np.repeat(v[end][:, None, :], 3, axis=1)
    prev = np.where(end > 0, end - 1, 0)
    q3 = kind == CURVE3
    q4 = kind == CURVE4
    # the current point before a command: the previous command's end vertex
    start = np.zeros((len(kind), 2))
    start[1:] = v[end[:-1]]
    # after a close, the current point is the subpath's start (the last move)
    moves = np.where(kind == MOVETO, np.arange(len(kind)), 0)
    last_move = np.maximum.accumulate(moves)
    after_close = np.concatenate([[False], kind[:-1] == CLOSEPOLY])
    start[after_close] = v[end[last_move[after_close]]]
    if q3.any():
        c = v[prev[q3]]
        p0, p2 = start[q3], v[end[q3]]
        pts[q3, 0] = p0 + 2.0 / 3.0 * (c - p0)
        pts[q3, 1] = p2 + 2.0 / 3.0 * (c - p2)
    if q4.any():
        pts[q4, 0] = v[end[q4] - 2]
        pts[q4, 1] = v[end[q4] - 1]
    kind = np.where(q3, CURVE4, kind)
    return kind, pts, start


def polygons(codes: np.ndarray, vertices: np.ndarray, steps: int = 8) -> list[np.ndarray]:
    """The outline flattened to closed polygons (curves at ``steps`` points each)."""
    kind, pts, start = cubic_segments(codes, vertices)
    if not len(kind):
        return []
    t = np.linspace(0.0, 1.0, steps + 1)[1:, None, None]
    p0, c1, c2, p3 = start[None], pts[None, :, 0], pts[None, :, 1], pts[None, :, 2]
    u = 1.0 - t
    curve = u**3 * p0 + 3 * u * u * t * c1 + 3 * u * t * t * c2 + t**3 * p3  # (steps, m, 2)
    counts = np.where(kind == CURVE4, steps, np.where(kind == CLOSEPOLY, 0, 1))
    chunks = np.where(
        (kind == CURVE4)[None, :, None], curve, np.broadcast_to(pts[None, :, 2], curve.shape)
    )
    flat = np.transpose(chunks, (1, 0, 2))  # (m, steps, 2)
    take = np.arange(steps)[None, :] >= (steps - counts)[:, None]
    points = flat[take]
    owner = np.repeat(np.arange(len(kind)), counts)
    poly_id = np.cumsum(kind == MOVETO)[owner]
    cuts = np.flatnonzero(np.diff(poly_id)) + 1
    return [p for p in np.split(points, cuts) if len(p) >= 3]


def text_box(text: str, size: float) -> tuple[float, float, float, float]:
    r"""The ink box of ``text`` for the page layout: :func:`text_shape`'s, or,
    where lgraph cannot typeset it (document macros, or mathematics without
    matplotlib: TikZ output, where TeX typesets it), an estimate: half an em
    a character, control words one character, commands and braces none.

    >>> text_box("$\\vx_1$", 10.0)
    (0.0, -2.5, 10.0, 7.5)
    """
    try:
        return text_shape(text, size).box
    except (ValueError, ImportError):
        body = re.sub(r"\\[A-Za-z]+", "x", text)
        n = len(re.sub(r"[${}^_\\]", "", body)) or 1
        return (0.0, -0.25 * size, 0.5 * size * n, 0.75 * size)


@attrs.frozen(eq=False)
class TextGlyphs:
    """A label laid out for real text (``save(..., text="text")``): glyphs
    ``(x, y, char, style, size)`` (pt, y up, from the start of the baseline;
    ``style`` ``"roman"``, ``"italic"`` or ``"bold"``) and filled rectangles
    ``(x, y, w, h)`` (fraction bars, roots)."""

    glyphs: tuple[tuple[float, float, str, str, float], ...]
    rects: tuple[tuple[float, float, float, float], ...]


#: mathtext lays real text out at this size, then scales (as matplotlib's
#: TextPath does: its positions are rounded to whole units of this size)
_TEXT_SCALE = 100.0


@functools.lru_cache(maxsize=512)
def text_glyphs(text: str, size: float) -> TextGlyphs:
    """``text`` at ``size`` pt as glyphs of real text: plain text is one
    glyph run; ``$...$`` mathematics is laid out by mathtext with the STIX
    fonts (Times-like, with Unicode character codes), each glyph with its
    character, position, style and size.

    >>> g = text_glyphs("$x_1$", 10.0)
    >>> [(c, s, round(z, 1)) for _, _, c, s, z in g.glyphs]
    [('x', 'italic', 10.0), ('1', 'roman', 7.0)]
    """
    if not has_math(text) or not _mpl_available():
        return TextGlyphs(((0.0, 0.0, text, "roman", float(size)),), ())
    import matplotlib as mpl
    from matplotlib.font_manager import FontProperties
    from matplotlib.mathtext import MathTextParser

    _check_size("Label", text)
    k = size / _TEXT_SCALE
    with mpl.rc_context({"mathtext.fontset": "stix"}):
        prop = FontProperties(family="STIXGeneral", size=_TEXT_SCALE)
        parsed = MathTextParser("path").parse(text, dpi=72, prop=prop)
    glyphs = []
    # (font, size, character code, [glyph index: matplotlib >= 3.11], x, y)
    for font, fontsize, code, *_, ox, oy in parsed.glyphs:
        name = str(getattr(font, "fname", "")).lower()  # STIXGeneralBol, STIXGeneralItalic
        style = "bold" if "bol" in name else "italic" if "ital" in name else "roman"
        glyphs.append((float(ox) * k, float(oy) * k, chr(code), style, float(fontsize) * k))
    rects = tuple(tuple(float(v) * k for v in r) for r in parsed.rects)
    return TextGlyphs(tuple(glyphs), rects)  # type: ignore[arg-type]
