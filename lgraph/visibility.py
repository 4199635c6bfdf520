"""The render pipeline: sampling, visibility and exact transitions.

1. every node's families give curve batches (in the node's local frame);
2. the initial samples are tested against every surface in the scene
   (vectorized, with a projected bounding-box cull; :mod:`lgraph._occlusion`);
3. all curves are sampled adaptively until each chord deviates from the true
   projected curve by at most ``tolerance`` times the figure's diagonal
   (:mod:`lgraph._sampling`) -- except, without hidden lines, chords on the
   far side of their own ellipsoid -- and the new samples are tested;
4. where visibility flips between two samples, the flip is located to near
   machine precision on the curve parameter (:mod:`lgraph._flips`);
5. runs of equal visibility become strokes.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from . import _tolerance as tol
from ._flips import locate_flips
from ._occlusion import Occlusion
from ._sampling import Samples, initial_samples, owner_arrays, refine
from .drawing import HIDDEN_STYLE, Drawing, Page, Stroke, Style
from .geometry.transforms import Transform
from .projectors import CentralProjector, ParallelProjector, Projector

if TYPE_CHECKING:
    from .scene import Node, Scene

__all__ = ["render", "local_projector"]


def local_projector(projector: Projector, transform: Transform) -> Projector:
    """The projector expressed in the local frame of a node with ``transform``.

    Only its view geometry (rays, view vectors, contour) is meaningful.
    """
    if transform.is_identity:
        return projector
    inv = transform.inverse()
    if isinstance(projector, CentralProjector):
        up = inv.apply_vector(projector.up)
        return CentralProjector(
            eye=inv.apply(projector.eye),
            target=inv.apply(projector.target),
            up=up if np.any(up) else (0, 0, 1),
        )
    d = inv.apply_vector(projector.frame[2])
    up = inv.apply_vector(projector.frame[1])
    return ParallelProjector(direction=d, up=up)


def _strokes(
    s: Samples, node: Node, hidden_lines: bool, hidden_style: Style, min_extent: float
) -> list[Stroke]:
    """Split samples into runs of equal visibility, one stroke per run.

    The last run of a closed curve joins its first when both have one state.
    Runs whose projection is smaller than ``min_extent`` (degenerate curves
    such as a parameter circle through a cone's vertex) are dropped."""
    n = len(s.t)
    brk = np.flatnonzero((s.cid[1:] != s.cid[:-1]) | (s.hidden[1:] != s.hidden[:-1])) + 1
    starts = np.concatenate([[0], brk])
    ends = np.concatenate([brk, [n]])
    # projected extent of every run at once
    extent = np.max(np.maximum.reduceat(s.xy, starts) - np.minimum.reduceat(s.xy, starts), axis=1)
    run_cid, run_hidden = s.cid[starts], s.hidden[starts]
    new_curve = run_cid[1:] != run_cid[:-1]
    first = np.flatnonzero(np.concatenate([[True], new_curve]))  # first run of each curve
    last = np.flatnonzero(np.concatenate([new_curve, [True]]))
    join = (last != first) & s.batch.closed[run_cid[first]]
    join &= run_hidden[first] == run_hidden[last]
    partner = np.full(len(starts), -1)  # last run of a closed curve -> its first run
    partner[last[join]] = first[join]
    keep = np.ones(len(starts), dtype=bool)
    keep[first[join]] = False  # drawn with the curve's last run
    if not hidden_lines:
        keep &= ~run_hidden
    joined = partner >= 0
    size = np.where(joined, np.maximum(extent, extent[partner]), extent)
    keep &= (size > min_extent) & (joined | (ends - starts >= 2))
    names = s.batch.curve_family
    surface = s.batch.surface
    styles: dict[str, Style] = {}
    out = []
    for r in np.flatnonzero(keep).tolist():
        a, b, c = int(starts[r]), int(ends[r]), int(run_cid[r])
        family = s.batch.family if names is None else names[c]
        if family not in styles:
            styles[family] = s.batch.style or node.style_for(family)
        vis = not run_hidden[r]
        if joined[r]:
            fa, fb = int(starts[partner[r]]), int(ends[partner[r]])
            sel = np.concatenate([np.arange(a, b), np.arange(fa + 1, fb)])
        else:
            sel = slice(a, b)
        out.append(
            Stroke(
                xy=s.xy[sel],
                xyz=s.xyz[sel],
                uv=None if s.uv is None else s.uv[sel],
                visible=vis,
                family=family,
                surface=surface,
                style=styles[family] if vis else hidden_style,
            )
        )
    return out


def _classify(samples: list[Samples], vis: Occlusion) -> None:
    """Test the fresh samples of every set against the scene, in one call."""
    fresh = [np.flatnonzero(s.fresh) for s in samples]
    n = sum(len(f) for f in fresh)
    if not n:
        return
    owners = [owner_arrays(s, len(f)) for s, f in zip(samples, fresh)]
    cause = np.empty(n, dtype=np.int64)
    hidden = vis.hidden(
        np.concatenate([s.xyz[f] for s, f in zip(samples, fresh)]),
        np.concatenate([s.xy[f] for s, f in zip(samples, fresh)]),
        np.concatenate([o for o, _ in owners]),
        np.concatenate([k for _, k in owners]),
        cause,
    )
    start = 0
    for s, f in zip(samples, fresh):
        s.hidden[f] = hidden[start : start + len(f)]
        s.cause[f] = cause[start : start + len(f)]
        s.fresh[f] = False
        start += len(f)


def _self_hidden(s: Samples, vis: Occlusion) -> np.ndarray | None:
    """Samples hidden by their own closed quadric (on its far side).

    When hidden lines are not drawn, a chord between two of them is not
    refined.  A visible piece inside such a chord would have to cross the
    contour twice within it; for a plane section (parameter lines of
    ellipsoids) those are its only two contour crossings, so the piece is a
    near-tangency shorter than the chord.  Chords hidden by *other*
    surfaces are refined as usual, so that visible pieces peeking out
    between hidden samples keep being found.
    """
    if not vis.nq:
        return None
    q = s.cause
    return (q >= 0) & (vis.q_node[np.maximum(q, 0)] == s.node)


def render(
    scene: Scene,
    projector: Projector,
    *,
    hidden_lines: bool = False,
    tolerance: float = tol.CHORD_TOLERANCE,
    page: Page | tuple[float, float] | None = None,
    hidden_style: Style | None = None,
) -> Drawing:
    """Render ``scene`` as seen by ``projector`` (see :meth:`Scene.render`)."""
    if not isinstance(projector, Projector):
        raise TypeError(
            "Scene.render: projector must be a ParallelProjector or CentralProjector, "
            f"got {type(projector).__name__}"
        )
    if not (
        isinstance(tolerance, (int, float)) and math.isfinite(tolerance) and 0 < tolerance <= 0.1
    ):
        raise ValueError(f"Scene.render: tolerance must be a number in (0, 0.1], got {tolerance!r}")
    hidden_style = HIDDEN_STYLE if hidden_style is None else hidden_style
    nodes = scene.nodes
    batches = [
        (ni, b)
        for ni, node in enumerate(nodes)
        for b in scene.batches(node, local_projector(projector, node.transform))
        if len(b)
    ]
    n_initial = tol.INITIAL_SAMPLES * sum(len(b) for _, b in batches)
    if n_initial > tol.MAX_POINTS:
        raise ValueError(
            f"Scene.render: {sum(len(b) for _, b in batches)} curves need more than "
            f"{tol.MAX_POINTS} sample points; draw fewer lines"
        )
    samples: list[Samples] = []
    for ni, b in batches:
        samples.append(initial_samples(len(samples), b, ni, nodes[ni].transform, projector))
    if not samples:
        return Drawing(strokes=(), page=page)
    if isinstance(projector, CentralProjector):
        for s in samples:
            if not np.all(projector.depth(s.xyz) > 0):
                raise ValueError(
                    f"CentralProjector: part of node {s.node} ({nodes[s.node].item!r}) lies at or "
                    "behind the eye; move the eye farther away"
                )
    allxy = np.concatenate([s.xy for s in samples])
    finite = np.isfinite(allxy).all(axis=1)
    if not finite.all():
        bad = next(s for s in samples if not np.isfinite(s.xy).all())
        raise ValueError(
            f"render: node {bad.node} ({nodes[bad.node].item!r}) produced non-finite points "
            f"in family {bad.batch.family!r}"
        )
    diag = float(np.linalg.norm(allxy.max(axis=0) - allxy.min(axis=0)))
    abs_tol = tolerance * (diag if diag > 0 else 1.0)
    vis = Occlusion(nodes, projector)
    _classify(samples, vis)
    for s in samples:
        refine(s, projector, abs_tol, None if hidden_lines else _self_hidden(s, vis))
    _classify(samples, vis)
    locate_flips(samples, vis, projector)
    strokes: list[Stroke] = []
    for s in samples:
        strokes.extend(_strokes(s, nodes[s.node], hidden_lines, hidden_style, 1e-12 * diag))
    return Drawing(strokes=strokes, page=page)
