r"""lgraph-tikz: an example lgraph backend plugin writing TikZ/PGF for LaTeX.

Registered through the entry point group ``lgraph.backends`` (see
``pyproject.toml``), so after ``pip install lgraph-tikz``::

    drawing.save("figure.tex")                     # \input{figure.tex} in a document
    drawing.save("figure.tex", standalone=True)    # a complete standalone document

Coordinates are in pt (``x=1pt, y=1pt``), so the picture has the page size
lgraph computed; every stroke becomes one ``\draw`` with its colour, width
and dash pattern.  Every label becomes a ``\node`` holding its raw text
(``$...$`` is typeset by TeX) with no font set, so the document's fonts
apply; its anchor is lgraph's anchor (``"sw"`` -> ``south west``).

>>> import numpy as np, tempfile, os
>>> from lgraph import Drawing, Page, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)))
>>> d = Drawing(strokes=(s,), page=Page(margin=0, extent=100))
>>> with tempfile.TemporaryDirectory() as tmp:
...     write_tikz(d, os.path.join(tmp, "a.tex"), precision=1)
...     text = open(os.path.join(tmp, "a.tex")).read()
>>> print(text, end="")
% lgraph figure, 100 x 50 pt
\begin{tikzpicture}[x=1pt, y=1pt, line cap=round, line join=round]
\definecolor{lgc0}{rgb}{0,0,0}
\useasboundingbox (0,0) rectangle (100,50);
\draw[color=lgc0, line width=0.5pt] (0.0,0.0) -- (100.0,50.0);
\end{tikzpicture}
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

__all__ = ["write_tikz"]
__version__ = "0.1.0"


def _num(x: float) -> str:
    s = f"{float(x):.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("", "-0") else s


def _finite_runs(points: np.ndarray) -> list[np.ndarray]:
    ok = np.isfinite(points).all(axis=1)
    edges = np.diff(np.concatenate([[False], ok, [False]]).astype(np.int8))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    return [points[a:b] for a, b in zip(starts, stops) if b - a >= 2]


_ANCHORS = {
    "center": "center",
    "n": "north",
    "ne": "north east",
    "e": "east",
    "se": "south east",
    "s": "south",
    "sw": "south west",
    "w": "west",
    "nw": "north west",
}


def _label_nodes(drawing: Any, colours: dict[tuple[float, ...], str]) -> list[str]:
    r"""One ``\node`` per label of ``drawing`` (none for an older lgraph).

    >>> import lgraph as lg
    >>> scene = lg.Scene()
    >>> _ = scene.add(lg.Label("$\\kappa_1$", at=(0, 0, 0), anchor="sw"))
    >>> d = scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    >>> _label_nodes(d, {})
    ['\\node[anchor=south west, text=lgc0] at (18,18) {$\\kappa_1$};\n']
    """
    labels = getattr(drawing, "labels", ())
    if not labels:
        return []
    out = []
    for (x, y), lab in zip(drawing.label_positions().tolist(), labels):
        name = colours.setdefault(tuple(float(c) for c in lab.style.color), f"lgc{len(colours)}")
        opts = f"anchor={_ANCHORS[lab.anchor]}, text={name}"
        out.append(f"\\node[{opts}] at ({_num(x)},{_num(y)}) {{{lab.text}}};\n")
    return out


def write_tikz(
    drawing: Any,
    path: str | os.PathLike[str],
    *,
    precision: int = 2,
    standalone: bool = False,
) -> None:
    r"""Write ``drawing`` as a ``tikzpicture``.

    Parameters
    ----------
    drawing : lgraph.Drawing
        The display list (``page_size()`` and ``page_strokes()`` are used).
    path : path-like
        File to write.
    precision : int, default 2
        Decimals of the coordinates in pt (0 to 6).
    standalone : bool, default False
        Wrap the picture in a ``standalone`` document that compiles on its own.

    Raises
    ------
    ValueError
        For a bad ``precision``.
    """
    if isinstance(precision, bool) or not isinstance(precision, int) or not 0 <= precision <= 6:
        raise ValueError(f"write_tikz: precision must be an integer from 0 to 6, got {precision!r}")
    w, h = drawing.page_size()
    colours: dict[tuple[float, ...], str] = {}
    body: list[str] = []
    fmt = f"(%.{precision}f,%.{precision}f)"
    for pts, stroke in drawing.page_strokes():
        style = stroke.style
        rgb = tuple(float(c) for c in style.color)
        name = colours.setdefault(rgb, f"lgc{len(colours)}")
        opts = [f"color={name}", f"line width={_num(style.width)}pt"]
        if style.dash:
            pattern = " ".join(
                f"{'on' if k % 2 == 0 else 'off'} {_num(x)}pt" for k, x in enumerate(style.dash)
            )
            opts.append(f"dash pattern={pattern}")
        for run in _finite_runs(np.asarray(pts, float)):
            coords = " -- ".join([fmt] * len(run)) % tuple(run.ravel().tolist())
            body.append(f"\\draw[{', '.join(opts)}] {coords};\n")
    body.extend(_label_nodes(drawing, colours))
    head = [f"% lgraph figure, {_num(w)} x {_num(h)} pt\n"]
    if standalone:
        head.append("\\documentclass{standalone}\n\\usepackage{tikz}\n\\begin{document}\n")
    head.append("\\begin{tikzpicture}[x=1pt, y=1pt, line cap=round, line join=round]\n")
    for rgb, name in colours.items():
        head.append(f"\\definecolor{{{name}}}{{rgb}}{{{','.join(_num(c) for c in rgb)}}}\n")
    head.append(f"\\useasboundingbox (0,0) rectangle ({_num(w)},{_num(h)});\n")
    tail = ["\\end{tikzpicture}\n"]
    if standalone:
        tail.append("\\end{document}\n")
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("".join(head + body + tail))
