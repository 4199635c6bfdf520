"""Strokes: the samples cut into runs of equal visibility and occlusion
depth, one :class:`~lgraph.Stroke` a run (the renderer's last stage before
the labels)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..output.bezier import CurveRef, unwrapped
from ..output.drawing import Stroke
from ..scene.style import Style
from .sampling import Samples

if TYPE_CHECKING:
    from ._protocols import RenderNode

__all__ = ["run_strokes"]


def run_strokes(
    s: Samples,
    nodes: tuple[RenderNode, ...],
    hidden_lines: bool,
    rule: Callable[[str, int], Style | None],
    min_extent: list[float],
    depth: np.ndarray,
) -> list[list[Stroke]]:
    """Split samples into runs of equal visibility and occlusion depth
    (``depth``, per sample), one stroke per run; the strokes of each view.
    Hidden runs are styled by ``rule(family, depth)`` and dropped where it
    gives None.

    The last run of a closed curve joins its first when both have one state.
    Runs whose projection is smaller than ``min_extent`` of their view
    (degenerate curves such as a parameter circle through a cone's vertex)
    are dropped."""
    n = len(s.t)
    brk = np.flatnonzero((s.cid[1:] != s.cid[:-1]) | (depth[1:] != depth[:-1])) + 1
    starts = np.concatenate([[0], brk])
    ends = np.concatenate([brk, [n]])
    # projected extent of every run at once
    # (column by column: numpy reduces an (n, 2) array along an axis slowly)
    x, y = s.xy[:, 0], s.xy[:, 1]
    extent = np.maximum(
        np.maximum.reduceat(x, starts) - np.minimum.reduceat(x, starts),
        np.maximum.reduceat(y, starts) - np.minimum.reduceat(y, starts),
    )
    run_cid, run_depth = s.cid[starts], depth[starts]
    run_hidden = run_depth > 0
    new_curve = run_cid[1:] != run_cid[:-1]
    first = np.flatnonzero(np.concatenate([[True], new_curve]))  # first run of each curve
    last = np.flatnonzero(np.concatenate([new_curve, [True]]))
    join = (last != first) & s.closed[run_cid[first]]
    join &= run_depth[first] == run_depth[last]
    partner = np.full(len(starts), -1)  # last run of a closed curve -> its first run
    partner[last[join]] = first[join]
    keep = np.ones(len(starts), dtype=bool)
    keep[first[join]] = False  # drawn with the curve's last run
    if not hidden_lines:
        keep &= ~run_hidden
    joined = partner >= 0
    size = np.where(joined, np.maximum(extent, extent[partner]), extent)
    run_view = s.view[run_cid]
    keep &= (size > np.asarray(min_extent)[run_view]) & (joined | (ends - starts >= 2))
    rows = np.flatnonzero(keep)
    # every kept run's samples (a joined run: then its curve's first run, less
    # the shared sample) gathered in one go, then cut into strokes
    a, b = starts[rows], ends[rows]
    pr = partner[rows]
    fa = np.where(pr >= 0, starts[pr] + 1, 0)
    fb = np.where(pr >= 0, ends[pr], 0)
    seg_start = np.column_stack([a, fa]).ravel()
    seg_len = np.column_stack([b - a, fb - fa]).ravel()
    total = np.cumsum(seg_len)
    n_idx = int(total[-1]) if len(total) else 0
    idx = np.repeat(seg_start - (total - seg_len), seg_len) + np.arange(n_idx)
    ends_k = total[1::2].tolist()  # where each stroke's samples end
    bounds = list(zip([0, *ends_k[:-1]], ends_k))
    xy, xyz, uv = (
        [g[i:j] for i, j in bounds] for g in (np.take(a, idx, axis=0) for a in (s.xy, s.xyz, s.uv))
    )
    lens = seg_len.reshape(-1, 2).sum(axis=1)  # the strokes' parameters, increasing:
    tu = unwrapped(s.t[idx], lens, (s.t1 - s.t0)[run_cid[rows]])
    # a style depends on the batch's own style, the node and the family: the
    # same for a batch (or a node's contour) in every view
    styles: dict[tuple[int, int, str], Style] = {}
    hidden_styles: dict[tuple[str, int], Style | None] = {}
    # what every stroke of a part shares: batch, node, first curve id, curve
    # names, surface (its node's own), transform, parameters drawn or not
    shared: dict[int, tuple] = {}
    out: list[list[Stroke]] = [[] for _ in min_extent]
    projectors = s.views.projectors
    crow = run_cid[rows]
    tus = [tu[i:j] for i, j in bounds]
    for k, (c, p, dep, v, t0, t1, closed) in enumerate(
        zip(
            crow.tolist(),
            s.part[crow].tolist(),
            run_depth[rows].tolist(),
            run_view[rows].tolist(),
            s.t0[crow].tolist(),
            s.t1[crow].tolist(),
            s.closed[crow].tolist(),
        )
    ):
        part = shared.get(p)
        if part is None:
            batch, node, transform, first_id = s.parts[p]
            surface = _own_surface(batch.surface, nodes[node])
            part = shared[p] = (
                batch,
                node,
                first_id,
                batch.curve_family,
                surface,
                transform,
                s.group[p] in s.no_uv,
            )
        batch, node, first_id, names, surface, transform, no_uv = part
        family = batch.family if names is None else names[c - first_id]
        if family == "contour":  # an arrow's outline is drawn as family "arrow"
            family = getattr(surface, "outline_family", "contour")
        if dep:
            if (family, dep) not in hidden_styles:
                hidden_styles[family, dep] = rule(family, dep)
            style = hidden_styles[family, dep]
            if style is None:  # the rule draws no such hidden stroke
                continue
        else:
            key = (id(batch.style), node, family)
            style = styles.get(key)
            if style is None:
                style = styles[key] = batch.style or nodes[node].style_for(family)
        # the exact curve of the stroke (lgraph.output.bezier: curves="bezier" output)
        curve = CurveRef(batch, c - first_id, transform, projectors[v], tus[k], t0, t1, closed)
        stroke = Stroke(
            xy[k], xyz[k], None if no_uv else uv[k], not dep, family, surface, style, dep,
            curve=curve,
        )  # fmt: skip
        out[v].append(stroke)
    return out


def _own_surface(surface: Any, node: RenderNode) -> Any:
    """The node's own surface object for a batch's ``surface``: a cached
    batch is shared by equal surfaces of several nodes
    (:mod:`lgraph.families.cache`), and holds the first of them."""
    own = node.surface
    if surface is None or own is None or surface is own:
        return surface
    return own if type(own) is type(surface) and bool(own == surface) else surface
