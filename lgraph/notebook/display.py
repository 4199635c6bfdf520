"""Drawings in notebooks and other programs: file objects, inline reprs, matplotlib.

* :func:`~lgraph.notebook.display.save_to_fileobj` -- ``drawing.save(fileobj, format="pdf")``
  for any binary file object (``io.BytesIO``, a socket's file, an open file);
* :func:`~lgraph.notebook.display.to_bytes` -- the bytes of a drawing in any backend's format
  (what ``_repr_png_`` and ``to_svg`` use);
* :func:`~lgraph.notebook.display.plot` -- the strokes as matplotlib line collections
  (``drawing.plot(ax)``); matplotlib is optional and imported only here;
* :func:`~lgraph.notebook.display.scene_drawing` -- the drawing a :class:`~lgraph.Scene` shows of
  itself in a notebook (:data:`DEFAULT_VIEW`).

IPython finds ``_repr_svg_`` and ``_repr_png_`` on :class:`~lgraph.Drawing`
and :class:`~lgraph.Scene` by name; lgraph never imports IPython.

>>> import io
>>> import lgraph as lg
>>> scene = lg.Scene()
>>> _ = scene.add(lg.Sphere(1), lg.ParameterLines(4, 8))
>>> d = scene.render(lg.ParallelProjector(direction=(1, 1, 1)))
>>> buf = io.BytesIO()
>>> _ = d.save(buf, format="pdf")
>>> buf.getvalue()[:5]
b'%PDF-'
>>> d._repr_png_()[:8]
b'\\x89PNG\\r\\n\\x1a\\n'
>>> d.to_svg().startswith('<?xml')
True
"""

from __future__ import annotations

import os
import tempfile
import weakref
from collections.abc import Sequence
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any, Protocol, TypeVar

import numpy as np

if TYPE_CHECKING:
    from ..scene.projectors import Projector
    from ..scene.style import Style

__all__ = [
    "save_to_fileobj",
    "to_bytes",
    "plot",
    "scene_drawing",
    "default_view",
    "DEFAULT_VIEW",
    "REPR_PNG_DPI",
]


# -- what this module needs of a drawing and a scene -------------------------------
# (lgraph.output.drawing.Drawing and lgraph.Scene, which call this module: typed by
# protocols, the imports go one way)
class _PlottedStroke(Protocol):
    """A stroke as :func:`plot` draws it (:class:`~lgraph.output.drawing.Stroke`)."""

    @property
    def xy(self) -> np.ndarray: ...

    @property
    def visible(self) -> bool: ...

    @property
    def family(self) -> str: ...

    @property
    def style(self) -> Style: ...


class _PlottedLabel(Protocol):
    """A placed label as :func:`plot` writes it (:class:`~lgraph.PlacedLabel`)."""

    @property
    def text(self) -> str: ...

    @property
    def xy(self) -> np.ndarray: ...

    @property
    def visible(self) -> bool: ...

    @property
    def anchor(self) -> str: ...

    @property
    def offset(self) -> tuple[float, float]: ...

    @property
    def size(self) -> float: ...

    @property
    def style(self) -> Style: ...


class Shown(Protocol):
    """A drawing as this module shows it (:class:`~lgraph.output.drawing.Drawing`):
    its strokes, labels and bounds; the backends that :func:`to_bytes` runs get it whole."""

    @property
    def strokes(self) -> Sequence[_PlottedStroke]: ...

    @property
    def labels(self) -> Sequence[_PlottedLabel]: ...

    def bounds(self) -> tuple[float, float, float, float]: ...


#: what a scene renders to (its drawing)
D_co = TypeVar("D_co", covariant=True)


class Showable(Protocol[D_co]):
    """A scene as :func:`scene_drawing` shows it (:class:`~lgraph.Scene`): its
    nodes (compared by identity) and its drawing in a view."""

    @property
    def nodes(self) -> tuple[object, ...]: ...

    def render(self, projector: Projector) -> D_co: ...


#: The view a scene shows of itself in a notebook: parallel projection from
#: azimuth -60 degrees, elevation 30 degrees (as ``ParallelProjector.from_angles``).
DEFAULT_VIEW = (-60.0, 30.0)

#: Resolution of ``_repr_png_`` (a figure's longer side is then about 750 px).
REPR_PNG_DPI = 100


def _format_suffix(format: Any) -> str:
    if not isinstance(format, str) or not format.strip(". "):
        raise ValueError(
            "Drawing.save: writing to a file object needs format= 'pdf', 'png', 'svg' or "
            f"another backend's suffix, got {format!r}"
        )
    return "." + format.strip().lstrip(".").lower()


def to_bytes(drawing: Shown, format: str, **options: Any) -> bytes:
    """The file ``drawing.save(path.<format>, **options)`` would write, as bytes.

    The backend writes into a private temporary folder (backends write paths,
    and reportlab and pillow decide how to open them), read back and removed.
    """
    from ..output.backends import get_backend

    suffix = _format_suffix(format)
    writer = get_backend(suffix)
    with tempfile.TemporaryDirectory(prefix="lgraph-") as tmp:
        path = Path(tmp) / f"drawing{suffix}"
        writer(drawing, path, **options)
        return path.read_bytes()


def save_to_fileobj(drawing: Shown, fileobj: IO[bytes], format: Any, **options: Any) -> IO[bytes]:
    """Write ``drawing`` into the binary file object ``fileobj`` (at its position).

    The whole file is produced first, so a failing backend writes nothing into
    ``fileobj``.  Returns ``fileobj``.
    """
    if format is None:
        name = getattr(fileobj, "name", None)
        format = Path(os.fspath(name)).suffix if isinstance(name, (str, os.PathLike)) else None
    data = to_bytes(drawing, format, **options)
    try:
        fileobj.write(data)
    except TypeError:
        raise TypeError(
            "Drawing.save: the file object must be opened in binary mode ('wb'), "
            f"got {type(fileobj).__name__}"
        ) from None
    return fileobj


# -- notebooks ------------------------------------------------------------------
def default_view() -> Projector:
    """The projector of :data:`DEFAULT_VIEW`."""
    from ..scene.projectors import ParallelProjector

    return ParallelProjector.from_angles(*DEFAULT_VIEW)


_SHOWN: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def scene_drawing(scene: Showable[D_co]) -> D_co:
    """The scene rendered from :data:`DEFAULT_VIEW` (remembered until a node is
    added: IPython asks for the SVG and the PNG of the same scene)."""
    nodes = scene.nodes
    memo = _SHOWN.get(scene)
    if memo is not None and len(memo[0]) == len(nodes):
        if all(a is b for a, b in zip(memo[0], nodes)):
            return memo[1]
    drawing = scene.render(default_view())
    _SHOWN[scene] = (nodes, drawing)
    return drawing


# -- matplotlib ------------------------------------------------------------------
def _matplotlib() -> Any:
    try:
        import matplotlib
        from matplotlib.collections import LineCollection
    except ImportError:
        raise ImportError(
            "Drawing.plot needs matplotlib, which is not installed; install it with "
            "`pip install matplotlib` (or `pip install lgraph[matplotlib]`)"
        ) from None
    return matplotlib, LineCollection


def plot(drawing: Shown, ax: Any = None, *, axis: bool = False, legend: bool = False) -> Any:
    """Draw the drawing into a matplotlib ``Axes`` (a new figure when None).

    One ``LineCollection`` per family, visibility and style (hidden parts
    first, below the visible ones, dashed as the style says), labelled with
    the family (``"u1"``, ``"contour"``; hidden ones ``"u1 (hidden)"``), in
    projection coordinates with equal aspect; line widths and dash lengths
    in pt as in the PDF (matplotlib's widths are pt; its dash scaling by the
    line width is undone).  Point marks are round markers of their size in
    pt (label ``"point"``); labels are matplotlib text at their anchors,
    offset and aligned as in the files (mathtext with Computer Modern for
    ``$...$``), in their size and colour.  ``legend=True`` adds a legend
    with one entry per family (and one for hidden parts of each).
    ``axis=False`` hides the axes' frame and ticks, which mean nothing for
    a projection.  Halos are not cut here (the scale of pt to data is known
    only when matplotlib draws): a label with a halo gets a knock-out box in
    the axes' background colour, its gap wide.  Returns the Axes.
    """
    from ..output.backends._common import finite_runs

    matplotlib, LineCollection = _matplotlib()
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    scale_dashes = bool(matplotlib.rcParams.get("lines.scale_dashes", True))
    groups: dict[tuple, list[np.ndarray]] = {}
    dots: dict[tuple, list[np.ndarray]] = {}
    for s in sorted(drawing.strokes, key=lambda s: s.visible):
        st = s.style
        if s.family == "point" and len(s.xy):
            dots.setdefault((s.visible, st.color, st.width), []).append(s.xy[0])
            continue
        runs = finite_runs(s.xy)
        if runs:
            groups.setdefault((s.family, s.visible, st.color, st.width, st.dash), []).extend(runs)
    handles: dict[str, Any] = {}
    for (family, visible, color, width, dash), segments in groups.items():
        style: Any = "solid"
        if dash:
            k = width if scale_dashes else 1.0
            style = (0.0, tuple(x / k for x in dash))
        name = family if visible else f"{family} (hidden)"
        lc = LineCollection(
            segments,
            colors=[color],
            linewidths=width,
            linestyles=[style],
            capstyle="round",
            joinstyle="round",
            zorder=2.0 if visible else 1.5,
            label=name,
        )
        ax.add_collection(lc)
        handles.setdefault(name, lc)
    for (visible, color, size), at in dots.items():
        xy = np.array(at)
        name = "point" if visible else "point (hidden)"
        z = 2.5 if visible else 1.6
        (line,) = ax.plot(*xy.T, "o", ms=size, mew=0, color=color, zorder=z, label=name)
        handles.setdefault(line.get_label(), line)
    _plot_labels(drawing, ax)
    x0, y0, x1, y1 = drawing.bounds()
    pad = 0.02 * max(x1 - x0, y1 - y0, 1e-12)
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - pad, y1 + pad)
    ax.set_aspect("equal")
    if legend and handles:
        ax.legend(list(handles.values()), list(handles), loc="best", fontsize="small")
    if not axis:
        ax.set_axis_off()
    return ax


def _plot_labels(drawing: Shown, ax: Any) -> None:
    """The labels as matplotlib text: the anchor point of the text's padded
    box at the offset anchor, as :meth:`lgraph.PlacedLabel.origin` places it."""
    from matplotlib.transforms import offset_copy

    from ..scene.style import ANCHORS, LABEL_PAD

    for lab in drawing.labels:
        fx, fy = ANCHORS[lab.anchor]
        pad = LABEL_PAD * lab.size
        dx = lab.offset[0] + pad * (1 - 2 * fx)
        dy = lab.offset[1] + pad * (1 - 2 * fy)
        where = offset_copy(ax.transData, fig=ax.figure, x=dx, y=dy, units="points")
        ha = {0.0: "left", 0.5: "center", 1.0: "right"}[fx]
        va = {0.0: "bottom", 0.5: "center", 1.0: "top"}[fy]  # "bottom": of the ink
        halo = getattr(lab, "halo", None)
        box = None
        if halo is not None:  # a knock-out behind the text (pad: in font sizes)
            box = {
                "boxstyle": f"square,pad={max(float(halo), 0.0) / lab.size:g}",
                "facecolor": ax.get_facecolor(),
                "edgecolor": "none",
            }
        ax.text(
            float(lab.xy[0]),
            float(lab.xy[1]),
            lab.text,
            transform=where,
            ha=ha,
            va=va,
            fontsize=lab.size,
            color=lab.style.color,
            family="DejaVu Serif",
            math_fontfamily="cm",
            zorder=3.0 if lab.visible else 1.7,
            bbox=box,
        )
