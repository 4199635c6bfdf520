"""lgraph-hpgl: an example lgraph backend plugin writing HPGL for pen plotters.

Registered through the entry point group ``lgraph.backends`` (see
``pyproject.toml``), so after ``pip install lgraph-hpgl``::

    drawing.save("figure.hpgl")

HPGL units are 1/40 mm (1016 per inch, 14.111 per pt); the page origin is
the lower left corner, as in lgraph's page coordinates.  Each colour gets a
pen (``SP1`` for the first colour met, ``SP2`` for the next, ... up to
``pens``, then the pens are reused); dashed strokes are split into their
dashes, since plotters draw them best as separate pen-down moves.

>>> import numpy as np, tempfile, os
>>> from lgraph import Drawing, Page, Stroke
>>> s = Stroke(xy=np.array([[0.0, 0.0], [72.0, 36.0]]), xyz=np.zeros((2, 3)))
>>> d = Drawing(strokes=(s,), page=Page(margin=0, extent=72))
>>> with tempfile.TemporaryDirectory() as tmp:
...     write_hpgl(d, os.path.join(tmp, "a.hpgl"))
...     text = open(os.path.join(tmp, "a.hpgl")).read()
>>> print(text, end="")
IN;SP1;
PU0,0;PD1016,508;
PU;SP0;
"""

from __future__ import annotations

import os
import warnings
from typing import Any

import numpy as np

from lgraph.output.drawing import dash_polyline

__all__ = ["write_hpgl", "UNITS_PER_PT"]
__version__ = "0.1.0"

#: HPGL plotter units per PostScript point (1016 units per inch, 72 pt per inch)
UNITS_PER_PT = 1016.0 / 72.0


def _finite_runs(points: np.ndarray) -> list[np.ndarray]:
    ok = np.isfinite(points).all(axis=1)
    edges = np.diff(np.concatenate([[False], ok, [False]]).astype(np.int8))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    return [points[a:b] for a, b in zip(starts, stops) if b - a >= 2]


#: a character's cap height, as a fraction of the font size, in the plotter's stroke font
_CAP = 0.7
_CM_PER_PT = 2.54 / 72.0


def _labels(drawing: Any, colours: dict[tuple[float, ...], int], pens: int) -> list[str]:
    r"""Plain labels in the plotter's stroke font (``LB``); labels with TeX
    mathematics are skipped with a warning (a stroke font cannot set them).

    >>> import lgraph as lg
    >>> scene = lg.Scene()
    >>> _ = scene.add(lg.Label("P", at=(0, 0, 0)))
    >>> d = scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    >>> _labels(d, {}, 8)[0].startswith("PU;SP1;SI")
    True
    """
    out: list[str] = []
    skipped = []
    for origin, lab in drawing.page_labels() if getattr(drawing, "labels", ()) else ():
        if "$" in lab.text:
            skipped.append(lab.text)
            continue
        pen = colours.setdefault(tuple(lab.style.color), len(colours) % pens + 1)
        h = _CAP * lab.size * _CM_PER_PT
        x, y = np.rint(np.asarray(origin) * UNITS_PER_PT).astype(np.int64).tolist()
        # no control character reaches the plotter stream (ESC would start a
        # device command, ETX ends the label): a drawing built by hand may
        # hold any text, so they are dropped here as well
        text = "".join(c for c in lab.text if c.isprintable())
        text = text.encode("ascii", "replace").decode("ascii")
        out.append(f"PU;SP{pen};SI{0.6 * h:.3f},{h:.3f};PU{x},{y};LB{text}\x03\n")
    if skipped:
        warnings.warn(
            f"write_hpgl: {len(skipped)} label(s) with TeX mathematics left out "
            f"({', '.join(map(repr, skipped[:3]))}): the plotter's stroke font cannot set them",
            stacklevel=3,
        )
    return out


def write_hpgl(drawing: Any, path: str | os.PathLike[str], *, pens: int = 8) -> None:
    """Write ``drawing`` as HPGL.

    Parameters
    ----------
    drawing : lgraph.Drawing
        The display list (only ``page_strokes()`` is used).
    path : path-like
        File to write.
    pens : int, default 8
        Number of pens in the plotter's carousel (1 to 256).

    Raises
    ------
    ValueError
        For a bad ``pens``.
    """
    if isinstance(pens, bool) or not isinstance(pens, int) or not 1 <= pens <= 256:
        raise ValueError(f"write_hpgl: pens must be an integer from 1 to 256, got {pens!r}")
    colours: dict[tuple[float, ...], int] = {}
    out = ["IN;"]
    current = None
    for pts, stroke in drawing.page_strokes():
        style = stroke.style
        pen = colours.setdefault(tuple(style.color), len(colours) % pens + 1)
        if pen != current:
            out.append(f"SP{pen};\n" if current is None else f"PU;SP{pen};\n")
            current = pen
        for run in _finite_runs(np.asarray(pts, float)):
            pieces = dash_polyline(run, style.dash) if style.dash else [run]
            for piece in pieces:
                q = np.rint(piece * UNITS_PER_PT).astype(np.int64)
                keep = np.concatenate([[True], np.any(q[1:] != q[:-1], axis=1)])
                q = q[keep]
                if len(q) < 2:
                    q = np.vstack([q, q[-1:]])  # a dot: pen down where it is
                body = ",".join(map(str, q[1:].ravel().tolist()))
                out.append(f"PU{q[0, 0]},{q[0, 1]};PD{body};\n")
    labels = _labels(drawing, colours, pens)
    out.extend(labels)
    if current is None and not labels:
        out.append("\n")
    out.append("PU;SP0;\n")
    text = "".join(out)
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write(text)
