r"""lgraph-tikz: an lgraph backend plugin writing TikZ/PGF for LaTeX.

Registered through the entry point group ``lgraph.backends`` (see
``pyproject.toml``), so after ``pip install lgraph-tikz``::

    drawing.save("figure.tex")                       # \input{figure.tex} in a document
    drawing.save("figure.tex", width="8.5cm")        # scaled to 8.5 cm wide
    drawing.save("figure.tex", standalone=True)      # a complete document of its own
    drawing.save("figure.tex", curves="bezier")      # exact curves (lgraph.output.bezier)

or ``lgraph render fig.toml -o fig.tex``.  Coordinates are in cm.  Every
layer of the drawing (:mod:`lgraph.output.layers`: one per family, hidden parts in
their own) is a named TikZ style, ``lgraph/contour``, ``lgraph/hidden``,
``lgraph/u1``, ...; the file declares each one only if the document has not
(and only inside the picture), so a document restyles all its figures from the
preamble::

    \tikzset{lgraph/hidden/.style={draw=gray!60, line width=0.2pt, densely dotted}}

Labels (``drawing.labels``) become ``\node[anchor=...]`` with their raw TeX,
set in the document's fonts, styled ``lgraph/label`` (``lgraph/hidden-label``).  Line
widths and dashes are in PostScript points (``bp``) and never scaled.

Label text is untrusted (scene files) and TeX runs it, so every label is
checked again here, also those of drawings built by hand: no control
characters, no ``^^`` and no command that reaches files or the shell,
defines commands or changes how TeX reads text (``\input``, ``\write18``,
``\catcode``, ``\def``, ``\csname``, ...: ``lgraph.output._text.check_tex``, which
:class:`lgraph.Label` applies when it is made), balanced braces and no ``%``
(either would end the ``\node`` early).  Document macros (``$\vx_1$``) pass.
Layer names keep letters, digits and ``._+-`` (others become ``-``).

>>> import numpy as np, tempfile, os
>>> from lgraph import Drawing, Page, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)), family="u1")
>>> d = Drawing(strokes=(s,), page=Page(margin=0, extent=72))
>>> with tempfile.TemporaryDirectory() as tmp:  # the ink, round caps included, is 5.08 cm wide
...     write_tikz(d, os.path.join(tmp, "a.tex"), width="5.08cm")
...     text = open(os.path.join(tmp, "a.tex")).read()
>>> print(text, end="")
% lgraph figure, 5.08 x 2.5488 cm; restyle with \tikzset{lgraph/<layer>/.style={...}}
% layers: u1
\providecommand\lgraphstyle[2]{\pgfkeysifdefined{/tikz/lgraph/#1/.@cmd}{}{\tikzset{lgraph/#1/.style={#2}}}}%
\begin{tikzpicture}[x=1cm, y=1cm, line cap=round, line join=round]
\lgraphstyle{u1}{draw={rgb,255:red,0;green,0;blue,0}, line width=0.5bp}
\useasboundingbox (0,0) rectangle (5.08,2.5488);
\draw[lgraph/u1] (0.009,0.009) -- (5.071,2.540);
\end{tikzpicture}%
"""

from __future__ import annotations

import math
import os
import re
from typing import Any

import numpy as np

from lgraph.output._text import check_tex, quote
from lgraph.output.layers import drawing_layers
from lgraph.output.units import UNITS, length_pt

__all__ = ["write_tikz", "ANCHORS"]
__version__ = "0.2.0"

_CM = UNITS["cm"]  # pt per cm

#: lgraph label anchors -> TikZ anchors
ANCHORS = {
    "center": "center",
    "n": "north",
    "s": "south",
    "e": "east",
    "w": "west",
    "ne": "north east",
    "nw": "north west",
    "se": "south east",
    "sw": "south west",
}


#: TeX tokens that matter to a node's text: control words and symbols (skipped:
#: ``\{``, ``\%`` are characters), braces and comments.
_TEX_TOKEN = re.compile(r"\\(?:[A-Za-z@]+|.)|[{}%]", re.S)

#: Characters of a layer name kept in a TikZ style name (``lgraph/<name>``).
_NOT_NAME = re.compile(r"[^\w.+-]")


def _node_text(text: str) -> str:
    r"""``text`` as the body of a ``\node``: refused (ValueError) when it is
    not safe TeX (``lgraph.output._text.check_tex``) or would end the node early
    (unbalanced braces, ``%``).

    >>> _node_text(r"$\vx_1 = \{u\}$ 50\%")
    '$\\vx_1 = \\{u\\}$ 50\\%'
    >>> _node_text("x}; \\draw (0,0) -- (1,1); {")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: write_tikz: label text must have balanced braces ..., got a } at position 1 ...
    """
    if not isinstance(text, str):
        raise TypeError(f"write_tikz: label text must be a string, got {type(text).__name__}")
    check_tex("write_tikz: label", text)
    depth = 0
    for m in _TEX_TOKEN.finditer(text):
        tok = m.group()
        if tok == "%":
            raise ValueError(
                "write_tikz: label text must not contain % (TeX would skip the rest of the "
                f"line, the end of the \\node with it; write \\% for a percent sign), found "
                f"at position {m.start()} of {quote(text)}"
            )
        if tok == "{":
            depth += 1
        elif tok == "}":
            depth -= 1
            if depth < 0:
                raise ValueError(
                    "write_tikz: label text must have balanced braces (it is the body of a "
                    f"\\node), got a }} at position {m.start()} of {quote(text)} that closes "
                    "nothing"
                )
    if depth:
        raise ValueError(
            "write_tikz: label text must have balanced braces (it is the body of a \\node), "
            f"got {depth} unclosed {{ in {quote(text)}"
        )
    return text


def _style_name(name: str) -> str:
    """A layer name as a TikZ style name: characters other than letters,
    digits and ``._+-`` become ``-`` (a brace or backslash would be TeX)."""
    return _NOT_NAME.sub("-", str(name)) or "layer"


def _num(x: float) -> str:
    s = f"{float(x):.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("", "-0") else s


def _style(style: Any) -> str:
    r, g, b = (min(255, max(0, round(c * 255))) for c in style.color)
    opts = [f"draw={{rgb,255:red,{r};green,{g};blue,{b}}}", f"line width={_num(style.width)}bp"]
    if style.dash:
        pattern = " ".join(
            f"{'on' if k % 2 == 0 else 'off'} {_num(x)}bp" for k, x in enumerate(style.dash)
        )
        opts.append(f"dash pattern={pattern}")
    return ", ".join(opts)


def _page_document(width_bp: float, height_bp: float) -> str:
    """A LaTeX preamble whose page is exactly the picture (only latex-base and tikz needed)."""
    return (
        "\\documentclass{article}\n\\usepackage{tikz}\n\\pagestyle{empty}\n"
        f"\\setlength{{\\paperwidth}}{{{_num(width_bp)}bp}}"
        f"\\setlength{{\\paperheight}}{{{_num(height_bp)}bp}}\n"
        "\\ifdefined\\pdfpagewidth\\setlength{\\pdfpagewidth}{\\paperwidth}"
        "\\setlength{\\pdfpageheight}{\\paperheight}\\fi\n"
        "\\ifdefined\\pagewidth\\setlength{\\pagewidth}{\\paperwidth}"
        "\\setlength{\\pageheight}{\\paperheight}\\fi\n"
        "\\setlength{\\hoffset}{-1in}\\setlength{\\voffset}{-1in}"
        "\\setlength{\\oddsidemargin}{0pt}\\setlength{\\evensidemargin}{0pt}\n"
        "\\setlength{\\topmargin}{0pt}\\setlength{\\headheight}{0pt}"
        "\\setlength{\\headsep}{0pt}\\setlength{\\footskip}{0pt}\\setlength{\\topskip}{0pt}\n"
        "\\setlength{\\textwidth}{\\paperwidth}\\setlength{\\textheight}{2\\paperheight}"
        "\\setlength{\\parindent}{0pt}\n"
        "\\begin{document}%\n"
    )


def _labels(drawing: Any, fmt: str) -> list[str]:
    """One ``\\node`` per label of ``drawing`` (none for a drawing without labels):
    its raw TeX at the anchor point of its box (offset applied), in its colour,
    then the style ``lgraph/label`` (``lgraph/hidden-label`` for hidden ones),
    so a document can restyle them."""
    labels = getattr(drawing, "labels", ())
    if not labels:
        return []
    out = []
    for xy, lab in zip(np.asarray(drawing.label_positions(), float), labels):
        text = _node_text(lab.text)
        if not np.isfinite(xy).all():
            continue
        anchor = ANCHORS.get(str(lab.anchor).lower(), "center")
        r, g, b = (min(255, max(0, round(c * 255))) for c in lab.style.color)
        at = fmt % tuple((xy / _CM).tolist())
        style = "lgraph/label" if lab.visible else "lgraph/hidden-label"
        out.append(
            f"\\node[anchor={anchor}, text={{rgb,255:red,{r};green,{g};blue,{b}}}, {style}] "
            f"at {at} {{{text}}};\n"
        )
    return out


def write_tikz(
    drawing: Any,
    path: str | os.PathLike[str],
    *,
    precision: int = 3,
    standalone: bool = False,
    width: float | str | None = None,
    layers: str = "family",
    curves: str = "polyline",
) -> None:
    r"""Write ``drawing`` as a ``tikzpicture`` (see the module docstring).

    Parameters
    ----------
    drawing : lgraph.Drawing
        The display list.
    path : path-like
        File to write.
    precision : int or length, default 3
        Decimals of the coordinates in cm (0 to 6; 3 is 0.01 mm); with
        ``curves="bezier"`` a length (``"0.01mm"``, the default) is the
        largest deviation from the exact curves.
    standalone : bool, default False
        Write a complete LaTeX document whose page is exactly the picture
        (it needs only LaTeX's base classes and TikZ).
    width : length, optional
        The picture's width (``"8.5cm"``, ``"3in"``, ``"80mm"`` or pt), as
        ``Drawing.save(width=...)`` gives it (which handles ``width`` and
        ``height`` before calling any writer); default: the page size lgraph
        computed.  Line widths and labels are not scaled.
    layers : "family" (default) or "surface"
        What the named styles are: one per family of curves or per surface
        (hidden parts always ``lgraph/hidden``).
    curves : "polyline" (default) or "bezier"
        ``"bezier"``: the strokes that know their exact curve are drawn as
        ``.. controls (a) and (b) ..`` cubic segments within ``precision``
        of it (:mod:`lgraph.output.bezier`); the others stay polylines.

    Raises
    ------
    ValueError
        For a bad option or a label whose text is not safe TeX (see the module
        docstring), before anything is written.
    """
    deviation = None
    if curves not in ("polyline", "bezier"):
        raise ValueError(f"write_tikz: curves must be 'polyline' or 'bezier', got {curves!r}")
    if curves == "bezier":
        deviation = length_pt("0.01mm")
        if isinstance(precision, str):
            deviation = length_pt(precision, "write_tikz: precision")
            precision = min(6, max(3, math.ceil(-math.log10(deviation / _CM / 10))))
    if isinstance(precision, bool) or not isinstance(precision, int) or not 0 <= precision <= 6:
        raise ValueError(f"write_tikz: precision must be an integer from 0 to 6, got {precision!r}")
    if not isinstance(standalone, bool):
        raise ValueError(f"write_tikz: standalone must be True or False, got {standalone!r}")
    if layers not in ("family", "surface"):
        raise ValueError(f"write_tikz: layers must be 'family' or 'surface', got {layers!r}")
    if width is not None:  # as Drawing.save(width=...): the page gets that width
        length_pt(width, "write_tikz: width")
        drawing = drawing.sized(width=width)
    fmt = f"(%.{precision}f,%.{precision}f)"
    labels = _labels(drawing, fmt)  # checked before anything is written
    pw, ph = drawing.page_size()
    runs = None
    if deviation is not None:
        from lgraph.output.bezier import page_curve_runs

        runs = page_curve_runs(drawing, deviation)
    groups = drawing_layers(drawing, layers, runs)
    names = [_style_name(g.name) for g in groups]
    w_cm, h_cm = pw / _CM, ph / _CM
    head = [
        f"% lgraph figure, {_num(w_cm)} x {_num(h_cm)} cm; "
        "restyle with \\tikzset{lgraph/<layer>/.style={...}}\n",
        f"% layers: {', '.join(names)}\n",
    ]
    if standalone:
        head.append(_page_document(pw, ph))
    head.append(
        "\\providecommand\\lgraphstyle[2]{\\pgfkeysifdefined{/tikz/lgraph/#1/.@cmd}{}"
        "{\\tikzset{lgraph/#1/.style={#2}}}}%\n"
    )
    head.append("\\begin{tikzpicture}[x=1cm, y=1cm, line cap=round, line join=round]\n")
    head.extend(f"\\lgraphstyle{{{name}}}{{{_style(g.style)}}}\n" for name, g in zip(names, groups))
    if getattr(drawing, "labels", ()):
        head.append("\\lgraphstyle{label}{}\n\\lgraphstyle{hidden-label}{}\n")
    head.append(f"\\useasboundingbox (0,0) rectangle ({_num(w_cm)},{_num(h_cm)});\n")
    body = []
    for name, g in zip(names, groups):
        for item in g.runs:
            run = np.asarray(item[0], float) / _CM
            if len(item) > 2 and item[2]:  # Bézier control points, 3k + 1
                k = (len(run) - 1) // 3
                pattern = fmt + f" .. controls {fmt} and {fmt} .. {fmt}" * k
            else:
                pattern = " -- ".join([fmt] * len(run))
            coords = pattern % tuple(run.ravel().tolist())
            body.append(f"\\draw[lgraph/{name}] {coords};\n")
    body.extend(labels)
    tail = ["\\end{tikzpicture}%\n"]
    if standalone:
        tail.append("\\end{document}\n")
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("".join(head + body + tail))
