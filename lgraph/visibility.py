"""Sampling, visibility and exact transitions: the render pipeline.

1. every node's families give curve batches (in the node's local frame);
2. all curves are sampled adaptively until each chord deviates from the true
   projected curve by at most ``tolerance`` times the figure's diagonal;
3. every sample is tested against every surface in the scene (vectorized,
   with a projected bounding-box cull);
4. where visibility flips between two samples, the flip is located by
   bisection on the curve parameter to near machine precision;
5. runs of equal visibility become strokes.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from . import _tolerance as tol
from .drawing import HIDDEN_STYLE, Drawing, Page, Stroke, Style
from .geometry.transforms import Transform
from .projectors import CentralProjector, ParallelProjector, Projector
from .surfaces._base import OFF

if TYPE_CHECKING:
    from .curves import CurveBatch
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


@attrs.define
class _Samples:
    """Samples of one batch: flat arrays sorted by (curve index, t)."""

    entry: int
    batch: CurveBatch
    node: int
    transform: Transform
    cid: np.ndarray
    t: np.ndarray
    xyz: np.ndarray  # world
    uv: np.ndarray | None
    xy: np.ndarray
    hidden: np.ndarray | None = None


def _evaluate(
    batch: CurveBatch, transform: Transform, projector: Projector, cid: np.ndarray, t: np.ndarray
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    xyz, uv = batch.evaluate(cid, t)
    xyz = np.asarray(xyz, dtype=float).reshape(-1, 3)
    if not transform.is_identity:
        xyz = transform.apply(xyz)
    return (
        xyz,
        (None if uv is None else np.asarray(uv, float).reshape(-1, 2)),
        projector.project(xyz),
    )


def _seg_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points ``p`` to segments ``ab`` (all (n, 2))."""
    ab = b - a
    ap = p - a
    den = np.einsum("ij,ij->i", ab, ab)
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(den > 0, np.einsum("ij,ij->i", ap, ab) / den, 0.0)
    s = np.clip(s, 0.0, 1.0)
    return np.linalg.norm(ap - s[:, None] * ab, axis=1)


def _initial(
    entry: int, batch: CurveBatch, node: int, transform: Transform, projector: Projector
) -> _Samples:
    m = len(batch)
    k = tol.INITIAL_SAMPLES
    frac = np.linspace(0.0, 1.0, k)
    cid = np.repeat(np.arange(m), k)
    t = (batch.t0[:, None] + (batch.t1 - batch.t0)[:, None] * frac).ravel()
    xyz, uv, xy = _evaluate(batch, transform, projector, cid, t)
    return _Samples(entry, batch, node, transform, cid, t, xyz, uv, xy)


def _merge(s: _Samples, cid, t, xyz, uv, xy, hidden=None) -> np.ndarray:  # noqa: ANN001
    """Insert new samples into ``s`` (keeping the order); returns a new-point mask."""
    n_old = len(s.t)
    s.cid = np.concatenate([s.cid, cid])
    s.t = np.concatenate([s.t, t])
    order = np.lexsort((s.t, s.cid))
    s.cid, s.t = s.cid[order], s.t[order]
    s.xyz = np.concatenate([s.xyz, xyz])[order]
    s.xy = np.concatenate([s.xy, xy])[order]
    if s.uv is not None:
        s.uv = np.concatenate([s.uv, uv])[order]
    if hidden is not None:
        s.hidden = np.concatenate([s.hidden, hidden])[order]
    return order >= n_old


def _refine(s: _Samples, projector: Projector, abs_tol: float) -> None:
    span = s.batch.t1 - s.batch.t0
    need = np.ones(len(s.t) - 1, dtype=bool)
    for _ in range(tol.MAX_REFINE_PASSES):
        seg = need & (s.cid[1:] == s.cid[:-1])
        seg &= (s.t[1:] - s.t[:-1]) > 1e-12 * span[s.cid[:-1]]
        idx = np.nonzero(seg)[0]
        if not len(idx):
            return
        tm = 0.5 * (s.t[idx] + s.t[idx + 1])
        cm = s.cid[idx]
        xyz, uv, xy = _evaluate(s.batch, s.transform, projector, cm, tm)
        dev = _seg_distance(xy, s.xy[idx], s.xy[idx + 1])
        split = ~(dev <= abs_tol)  # also splits where dev is NaN
        if not split.any():
            return
        new = _merge(
            s, cm[split], tm[split], xyz[split], None if uv is None else uv[split], xy[split]
        )
        need = new[:-1] | new[1:]
        if len(s.t) > tol.MAX_POINTS:
            raise ValueError(
                f"render: more than {tol.MAX_POINTS} points needed; lower the number of "
                "lines or raise the tolerance"
            )


class _Visibility:
    """Tests world points against every hiding surface of the scene."""

    def __init__(self, nodes: tuple[Node, ...], projector: Projector) -> None:
        self.projector = projector
        self.items = []
        for j, node in enumerate(nodes):
            surf = node.surface
            if surf is None or not node.hides:
                continue
            inv = node.transform.inverse()
            lo, hi = surf.bounds()
            corners = np.array(
                [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
            )
            wc = node.transform.apply(corners)
            box = None
            if not isinstance(projector, CentralProjector) or np.all(projector.depth(wc) > 0):
                pc = projector.project(wc)
                box = (pc.min(axis=0), pc.max(axis=0))
            self.items.append((j, surf, inv, box))

    def hidden(
        self, xyz: np.ndarray, xy: np.ndarray, owner: np.ndarray, kind: np.ndarray
    ) -> np.ndarray:
        dirs, smax = self.projector.rays(xyz)
        out = np.zeros(len(xyz), dtype=bool)
        for j, surf, inv, box in self.items:
            cand = ~out
            if box is not None:
                pad = 1e-9 * float(np.max(box[1] - box[0]) + 1.0)
                cand &= np.all((xy >= box[0] - pad) & (xy <= box[1] + pad), axis=1)
            idx = np.nonzero(cand)[0]
            if not len(idx):
                continue
            own = np.where(owner[idx] == j, kind[idx], OFF).astype(np.int8)
            o = inv.apply(xyz[idx])
            v = inv.apply_vector(dirs[idx])
            out[idx] = surf.hits(o, v, smax[idx], own)
        return out


def _owner_arrays(s: _Samples, n: int) -> tuple[np.ndarray, np.ndarray]:
    if s.batch.surface is None:
        return np.full(n, -1), np.full(n, OFF, np.int8)
    return np.full(n, s.node), np.full(n, s.batch.own, np.int8)


def _bisect(all_s: list[_Samples], vis: _Visibility, projector: Projector) -> None:
    """Locate every visibility flip to near machine precision; insert both sides."""
    flips = []
    for s in all_s:
        f = np.nonzero((s.cid[1:] == s.cid[:-1]) & (s.hidden[1:] != s.hidden[:-1]))[0]
        flips.append(f)
    lo = [s.t[f] for s, f in zip(all_s, flips)]
    hi = [s.t[f + 1] for s, f in zip(all_s, flips)]
    hlo = [s.hidden[f] for s, f in zip(all_s, flips)]
    cids = [s.cid[f] for s, f in zip(all_s, flips)]
    active = [k for k, f in enumerate(flips) if len(f)]
    for _ in range(tol.BISECTION_MAX_STEPS):
        mids, evals = [], []
        for k in active:
            s = all_s[k]
            span = (s.batch.t1 - s.batch.t0)[cids[k]]
            go = (hi[k] - lo[k]) > tol.BISECTION_RTOL * np.maximum(span, np.abs(lo[k]))
            if not go.any():
                continue
            idx = np.nonzero(go)[0]
            tm = 0.5 * (lo[k][idx] + hi[k][idx])
            xyz, _, xy = _evaluate(s.batch, s.transform, projector, cids[k][idx], tm)
            owner, kind = _owner_arrays(s, len(idx))
            mids.append((k, idx, tm))
            evals.append((xyz, xy, owner, kind))
        if not mids:
            break
        h = vis.hidden(
            np.concatenate([e[0] for e in evals]),
            np.concatenate([e[1] for e in evals]),
            np.concatenate([e[2] for e in evals]),
            np.concatenate([e[3] for e in evals]),
        )
        pos = 0
        for k, idx, tm in mids:
            hk = h[pos : pos + len(idx)]
            pos += len(idx)
            same = hk == hlo[k][idx]
            lo[k][idx[same]] = tm[same]
            hi[k][idx[~same]] = tm[~same]
    for k in active:
        s = all_s[k]
        t = np.concatenate([lo[k], hi[k]])
        c = np.concatenate([cids[k], cids[k]])
        xyz, uv, xy = _evaluate(s.batch, s.transform, projector, c, t)
        _merge(s, c, t, xyz, uv, xy, np.concatenate([hlo[k], ~hlo[k]]))


def _strokes(s: _Samples, node: Node, hidden_lines: bool, hidden_style: Style) -> list[Stroke]:
    """Split samples into runs of equal visibility, one stroke per run."""
    n = len(s.t)
    brk = np.nonzero((s.cid[1:] != s.cid[:-1]) | (s.hidden[1:] != s.hidden[:-1]))[0] + 1
    starts = np.concatenate([[0], brk])
    ends = np.concatenate([brk, [n]])
    runs = list(zip(starts.tolist(), ends.tolist()))
    # closed curves: join the last run with the first when both have one state
    first_of = {}
    last_of = {}
    for r, (a, _b) in enumerate(runs):
        c = int(s.cid[a])
        first_of.setdefault(c, r)
        last_of[c] = r
    joined: dict[int, tuple[int, int]] = {}
    for c, rf in first_of.items():
        rl = last_of[c]
        if rl != rf and s.batch.closed[c] and s.hidden[runs[rf][0]] == s.hidden[runs[rl][0]]:
            joined[rl] = runs[rf]
    skip = set(first_of[c] for c in first_of if last_of[c] in joined)
    family = s.batch.family
    style = s.batch.style or node.style_for(family)
    surface = s.batch.surface
    out = []
    for r, (a, b) in enumerate(runs):
        if r in skip:
            continue
        vis = not bool(s.hidden[a])
        if not vis and not hidden_lines:
            continue
        if r in joined:
            fa, fb = joined[r]
            sel = np.concatenate([np.arange(a, b), np.arange(fa + 1, fb)])
        else:
            sel = slice(a, b)
        xy = s.xy[sel]
        if len(xy) < 2:
            continue
        out.append(
            Stroke(
                xy=xy,
                xyz=s.xyz[sel],
                uv=None if s.uv is None else s.uv[sel],
                visible=vis,
                family=family,
                surface=surface,
                style=style if vis else hidden_style,
            )
        )
    return out


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
    samples: list[_Samples] = []
    for ni, node in enumerate(nodes):
        local = local_projector(projector, node.transform)
        for b in scene.batches(node, local):
            if len(b):
                samples.append(_initial(len(samples), b, ni, node.transform, projector))
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
    for s in samples:
        _refine(s, projector, abs_tol)
    vis = _Visibility(nodes, projector)
    for s in samples:
        owner, kind = _owner_arrays(s, len(s.t))
        s.hidden = vis.hidden(s.xyz, s.xy, owner, kind)
    _bisect(samples, vis, projector)
    strokes: list[Stroke] = []
    for s in samples:
        strokes.extend(_strokes(s, nodes[s.node], hidden_lines, hidden_style))
    return Drawing(strokes=strokes, page=page)


def classify(scene: Scene, projector: Projector, points: Any) -> np.ndarray:
    """Hidden flags of arbitrary world points (not on any surface) in ``scene``."""
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    vis = _Visibility(scene.nodes, projector)
    return vis.hidden(p, projector.project(p), np.full(len(p), -1), np.zeros(len(p), np.int8))
