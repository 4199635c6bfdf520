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
from .surfaces._base import CONTOUR, OFF
from .surfaces._quadric_ray import quadric_coefficients_world, quadric_ray_hits
from .surfaces.quadrics import Quadric

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
    cause: np.ndarray | None = None  # grouped quadric hiding each sample, or -1


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


def _merge(s: _Samples, after: np.ndarray, cid, t, xyz, uv, xy, hidden=None) -> np.ndarray:  # noqa: ANN001
    """Insert new samples into ``s``, each right after sample ``after[i]``
    (``after`` sorted; equal entries keep their given order).  Returns a mask of
    the new points in the merged arrays."""
    pos = np.asarray(after) + 1
    s.cid = np.insert(s.cid, pos, cid)
    s.t = np.insert(s.t, pos, t)
    s.xyz = np.insert(s.xyz, pos, xyz, axis=0)
    s.xy = np.insert(s.xy, pos, xy, axis=0)
    if s.uv is not None:
        s.uv = np.insert(s.uv, pos, uv, axis=0)
    if hidden is not None:
        s.hidden = np.insert(s.hidden, pos, hidden)
    new = np.zeros(len(s.t), dtype=bool)
    new[pos + np.arange(len(pos))] = True
    return new


def _refine(s: _Samples, projector: Projector, abs_tol: float) -> None:
    """Refine until every chord's midpoint is within ``abs_tol`` of the curve.

    A chord whose midpoint deviates by ``dev`` is split into
    ``m = ceil(sqrt(dev / abs_tol))`` equal parts at once (the deviation of a
    smooth curve shrinks with the square of the chord), so a pass or two
    usually suffices; the new chords are tested again.
    """
    span = s.batch.t1 - s.batch.t0
    need = np.ones(len(s.t) - 1, dtype=bool)
    for _ in range(tol.MAX_REFINE_PASSES):
        seg = need & (s.cid[1:] == s.cid[:-1])
        seg &= (s.t[1:] - s.t[:-1]) > 1e-12 * span[s.cid[:-1]]
        idx = np.nonzero(seg)[0]
        if not len(idx):
            return
        tm = 0.5 * (s.t[idx] + s.t[idx + 1])
        _, _, xy = _evaluate(s.batch, s.transform, projector, s.cid[idx], tm)
        dev = _seg_distance(xy, s.xy[idx], s.xy[idx + 1])
        split = ~(dev <= abs_tol)  # also splits where dev is NaN
        if not split.any():
            return
        idx, dev = idx[split], dev[split]
        with np.errstate(invalid="ignore"):
            m = np.ceil(1.05 * np.sqrt(dev / abs_tol))
        m = np.clip(np.nan_to_num(m, nan=2.0), 2, tol.MAX_SPLIT).astype(np.int64)
        after = np.repeat(idx, m - 1)
        j = np.arange(len(after)) - np.repeat(np.cumsum(m - 1) - (m - 1), m - 1) + 1
        frac = j / np.repeat(m, m - 1)
        t = s.t[after] + frac * (s.t[after + 1] - s.t[after])
        c = s.cid[after]
        xyz, uv, xy = _evaluate(s.batch, s.transform, projector, c, t)
        new = _merge(s, after, c, t, xyz, uv, xy)
        need = new[:-1] | new[1:]
        if len(s.t) > tol.MAX_POINTS:
            raise ValueError(
                f"render: more than {tol.MAX_POINTS} points needed; lower the number of "
                "lines or raise the tolerance"
            )


class _Visibility:
    """Tests world points against every hiding surface of the scene.

    Closed quadrics (ellipsoids, spheres, ...) are tested all at once: their
    coefficients are moved to world coordinates and gathered per (point,
    quadric) pair found by a uniform grid over their projected bounding boxes,
    so the cost does not grow with the number of nodes.  Every other surface
    is asked through its own ``hits`` for the points inside its box.
    """

    def __init__(self, nodes: tuple[Node, ...], projector: Projector) -> None:
        self.projector = projector
        self.items = []  # (node index, surface, inverse transform, box) asked one by one
        quads = []  # (node index, box, A_w, b_w, d_w, eps) tested together
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
            if isinstance(surf, Quadric) and surf.closed and box is not None:
                A, b, d = quadric_coefficients_world(*surf.coefficients, inv.matrix, inv.offset)
                size = float(np.linalg.norm(wc.max(axis=0) - wc.min(axis=0)))
                quads.append((j, box, A, b, d, tol.SELF_HIT_RTOL * size))
            else:
                self.items.append((j, surf, inv, box))
        self._setup_grid(quads)
        #: relative cost of testing one point (1: the grouped quadric test)
        self.cost_per_point = 1.0 + sum(it[1].hit_cost for it in self.items)
        #: fixed cost of one visibility test call
        self.cost_per_call = tol.STEP_COST + sum(it[1].hit_call_cost for it in self.items)

    def _setup_grid(self, quads: list) -> None:
        self.nq = len(quads)
        if not quads:
            return
        self.q_node = np.array([q[0] for q in quads])
        self.q_box = np.array([[*q[1][0], *q[1][1]] for q in quads])  # x0 y0 x1 y1
        self.q_A = np.array([q[2] for q in quads])
        self.q_b = np.array([q[3] for q in quads])
        self.q_d = np.array([q[4] for q in quads])
        self.q_eps = np.array([q[5] for q in quads])
        # ellipsoids (A positive definite): a continuous hiding margin exists
        self.q_pd = np.all(np.linalg.eigvalsh(self.q_A) > 0, axis=1)
        pad = 1e-9 * (np.ptp(self.q_box[:, [0, 2]]) + np.ptp(self.q_box[:, [1, 3]]) + 1.0)
        self.q_box += np.array([-pad, -pad, pad, pad])
        g = max(1, int(2 * np.sqrt(self.nq)))
        x0, y0 = self.q_box[:, 0].min(), self.q_box[:, 1].min()
        x1, y1 = self.q_box[:, 2].max(), self.q_box[:, 3].max()
        self.grid = (g, x0, y0, max(x1 - x0, 1e-300) / g, max(y1 - y0, 1e-300) / g)
        cells: list[list[int]] = [[] for _ in range(g * g)]
        for i, (bx0, by0, bx1, by1) in enumerate(self.q_box):
            cx = self._cell(np.array([bx0, bx1]), 1)
            cy = self._cell(np.array([by0, by1]), 2)
            for yy in range(cy[0], cy[1] + 1):
                for xx in range(cx[0], cx[1] + 1):
                    cells[yy * g + xx].append(i)
        counts = np.array([len(c) for c in cells])
        self.cell_start = np.concatenate([[0], np.cumsum(counts)[:-1]])
        self.cell_count = counts
        self.cell_items = np.array([i for c in cells for i in c], dtype=np.int64)

    def _cell(self, values: np.ndarray, axis: int) -> np.ndarray:
        g, origin, size = self.grid[0], self.grid[axis], self.grid[axis + 2]
        return np.clip(((values - origin) / size).astype(np.int64), 0, g - 1)

    def _quadric_pairs(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(point, quadric) index pairs whose projected box contains the point."""
        g = self.grid[0]
        cell = self._cell(xy[:, 1], 2) * g + self._cell(xy[:, 0], 1)
        counts = self.cell_count[cell]
        pt = np.repeat(np.arange(len(xy)), counts)
        first = np.repeat(self.cell_start[cell] + counts - np.cumsum(counts), counts)
        q = self.cell_items[first + np.arange(len(pt))]
        box = self.q_box[q]
        p = xy[pt]
        inside = (p[:, 0] >= box[:, 0]) & (p[:, 0] <= box[:, 2])
        inside &= (p[:, 1] >= box[:, 1]) & (p[:, 1] <= box[:, 3])
        return pt[inside], q[inside]

    def hidden(
        self,
        xyz: np.ndarray,
        xy: np.ndarray,
        owner: np.ndarray,
        kind: np.ndarray,
        cause: np.ndarray | None = None,
    ) -> np.ndarray:
        """Hidden flags; ``cause`` (optional output) receives, for points hidden
        by a grouped quadric, that quadric's index (else -1)."""
        dirs, smax = self.projector.rays(xyz)
        out = np.zeros(len(xyz), dtype=bool)
        if cause is not None:
            cause[:] = -1
        if self.nq:
            pt, q = self._quadric_pairs(xy)
            own = np.where(owner[pt] == self.q_node[q], kind[pt], OFF).astype(np.int8)
            h = quadric_ray_hits(
                xyz[pt], dirs[pt], smax[pt], own,
                self.q_A[q], self.q_b[q], self.q_d[q], self.q_eps[q],
            )  # fmt: skip
            out[pt[h]] = True
            if cause is not None:
                cause[pt[h]] = q[h]
        if not self.items:
            return out
        # other surfaces: cull by the projected bounding box; points sorted by
        # x, so each box selects a contiguous slab that is then filtered by y
        order = np.argsort(xy[:, 0], kind="stable")
        xs = xy[order, 0]
        for j, surf, inv, box in self.items:
            if box is None:
                idx = np.arange(len(xyz))
            else:
                (x0, y0), (x1, y1) = box
                pad = 1e-9 * (max(x1 - x0, y1 - y0) + 1.0)
                a, b = np.searchsorted(xs, [x0 - pad, x1 + pad])
                idx = order[a:b]
                y = xy[idx, 1]
                idx = idx[(y >= y0 - pad) & (y <= y1 + pad)]
            if not len(idx):
                continue
            own = np.where(owner[idx] == j, kind[idx], OFF).astype(np.int8)
            o = inv.apply(xyz[idx])
            v = inv.apply_vector(dirs[idx])
            out[idx] |= surf.hits(o, v, smax[idx], own)
        return out

    def margin(
        self, xyz: np.ndarray, q: np.ndarray, owner: np.ndarray, kind: np.ndarray
    ) -> np.ndarray:
        """Continuous function, positive exactly where ellipsoid ``q`` hides the point.

        With ``qa s^2 + qb s + qc`` the ray's quadratic (``qa > 0``): a point on
        the ellipsoid is hidden by it iff ``s2 = -qb/qa > 0``; any other point
        iff it is inside (``qc < 0``) or the ray meets the ellipsoid ahead
        (``disc >= 0`` and ``qb < 0``).  Used to find flips by regula falsi.
        """
        dirs, _ = self.projector.rays(xyz)
        A, b, d = self.q_A[q], self.q_b[q], self.q_d[q]
        Av = np.einsum("nij,nj->ni", A, dirs)
        qa = np.einsum("ni,ni->n", dirs, Av)
        qb = 2 * np.einsum("ni,ni->n", xyz, Av) + np.einsum("ni,ni->n", dirs, b)
        qc = np.einsum("ni,nij,nj->n", xyz, A, xyz) + np.einsum("ni,ni->n", xyz, b) + d
        s_sum = -qb / qa  # r1 + r2
        foreign = np.maximum(-qc / qa, np.minimum((qb * qb - 4 * qa * qc) / (4 * qa * qa), s_sum))
        own = owner == self.q_node[q]
        return np.where(own, np.where(kind == CONTOUR, -1.0, s_sum), foreign)


def _owner_arrays(s: _Samples, n: int) -> tuple[np.ndarray, np.ndarray]:
    if s.batch.surface is None:
        return np.full(n, -1), np.full(n, OFF, np.int8)
    return np.full(n, s.node), np.full(n, s.batch.own, np.int8)


@attrs.define
class _Flips:
    """All visibility flips of the scene in flat arrays (one entry per flip).

    Flip ``i`` lies on curve ``cid[i]`` of sample set ``k[i]``, between samples
    ``f[i]`` and ``f[i] + 1``; ``lo < hi`` bracket it and ``hlo`` is the hidden
    state at ``lo``.
    """

    k: np.ndarray
    f: np.ndarray
    cid: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    hlo: np.ndarray
    span: np.ndarray
    owner: np.ndarray
    kind: np.ndarray

    @classmethod
    def find(cls, all_s: list[_Samples]) -> _Flips:
        parts = []
        for k, s in enumerate(all_s):
            f = np.nonzero((s.cid[1:] == s.cid[:-1]) & (s.hidden[1:] != s.hidden[:-1]))[0]
            if len(f):
                owner, kind = _owner_arrays(s, len(f))
                span = (s.batch.t1 - s.batch.t0)[s.cid[f]]
                parts.append((np.full(len(f), k), f, s.cid[f], s.t[f], s.t[f + 1],
                              s.hidden[f], span, owner, kind))  # fmt: skip
        if not parts:
            z = np.empty(0)
            return cls(*(z.astype(int), z.astype(int), z.astype(int), z, z, z.astype(bool), z,
                         z.astype(int), z.astype(np.int8)))  # fmt: skip
        return cls(*(np.concatenate(col) for col in zip(*parts)))

    def __len__(self) -> int:
        return len(self.k)

    def open(
        self,
        idx: np.ndarray | None = None,
        lo: np.ndarray | None = None,
        hi: np.ndarray | None = None,
    ) -> np.ndarray:
        """Mask of brackets (all, or those at ``idx``) still wider than
        ``BISECTION_RTOL`` of the span; ``lo, hi`` replace the stored ends."""
        sel = slice(None) if idx is None else idx
        lo = self.lo[sel] if lo is None else lo
        hi = self.hi[sel] if hi is None else hi
        return (hi - lo) > tol.BISECTION_RTOL * np.maximum(self.span[sel], np.abs(lo))


def _points(all_s: list[_Samples], projector: Projector, k: np.ndarray, cid: np.ndarray,
            t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """World points and projections of parameters ``t`` on curves ``(k, cid)``;
    one ``evaluate`` call per sample set involved."""
    xyz = np.empty((len(t), 3))
    xy = np.empty((len(t), 2))
    order = np.argsort(k, kind="stable")
    ks = k[order]
    cuts = np.nonzero(np.diff(ks))[0] + 1
    for sel in np.split(order, cuts):
        if len(sel):
            s = all_s[k[sel[0]]]
            xyz[sel], _, xy[sel] = _evaluate(s.batch, s.transform, projector, cid[sel], t[sel])
    return xyz, xy


def _regula_falsi(all_s: list[_Samples], fl: _Flips, vis: _Visibility,
                  projector: Projector) -> None:  # fmt: skip
    """Flips caused by an ellipsoid: regula falsi (Illinois) on its continuous
    hiding margin, a handful of steps instead of dozens.  Each step evaluates
    the estimate and points just past it on either side, so that near the root
    the bracket collapses at once.  Results are verified with the full
    visibility test; brackets that fail stay for :func:`_k_section`."""
    if not vis.nq or not len(fl):
        return
    hid_end = np.where(fl.hlo, fl.f, fl.f + 1)
    vis_end = np.where(fl.hlo, fl.f + 1, fl.f)
    # flat views over all sample sets: sample i of set k is row offset[k] + i
    offset = np.concatenate([[0], np.cumsum([len(s.t) for s in all_s])[:-1]])
    cause = np.concatenate([s.cause for s in all_s])
    q = cause[offset[fl.k] + hid_end]
    ok = q >= 0
    ok[ok] = vis.q_pd[q[ok]]
    idx = np.nonzero(ok)[0]
    if not len(idx):
        return
    xyz_all = np.concatenate([s.xyz for s in all_s])
    xyz_a = xyz_all[offset[fl.k[idx]] + vis_end[idx]]
    xyz_b = xyz_all[offset[fl.k[idx]] + hid_end[idx]]
    fa = vis.margin(xyz_a, q[idx], fl.owner[idx], fl.kind[idx])
    fb = vis.margin(xyz_b, q[idx], fl.owner[idx], fl.kind[idx])
    good = (fa <= 0) & (fb > 0)
    idx, fa, fb, q = idx[good], fa[good], fb[good], q[idx][good]
    a = np.where(fl.hlo[idx], fl.hi[idx], fl.lo[idx])  # visible end
    b = np.where(fl.hlo[idx], fl.lo[idx], fl.hi[idx])  # hidden end
    kept = np.zeros(len(idx), np.int8)
    span = fl.span[idx]
    rows3 = np.array([-1.0, 0.0, 1.0])
    for _ in range(tol.BISECTION_MAX_STEPS):
        g = np.nonzero(fl.open(idx, np.minimum(a, b), np.maximum(a, b)))[0]
        if not len(g):
            break
        w = b[g] - a[g]  # signed: from the visible end to the hidden end
        with np.errstate(divide="ignore", invalid="ignore"):
            u = -fa[g] / (fb[g] - fa[g])  # position of the secant root in the bracket
        u = np.where((u > 0) & (u < 1), u, 0.5)
        step = 0.5 * tol.BISECTION_RTOL * np.maximum(span[g], np.abs(a[g])) / np.abs(w)
        tt = a[g, None] + np.clip(u[:, None] + rows3 * step[:, None], 0.0, 1.0) * w[:, None]
        ig = idx[g]
        xyz, _ = _points(all_s, projector, np.repeat(fl.k[ig], 3), np.repeat(fl.cid[ig], 3),
                         tt.ravel())  # fmt: skip
        m = vis.margin(xyz, np.repeat(q[g], 3), np.repeat(fl.owner[ig], 3),
                       np.repeat(fl.kind[ig], 3)).reshape(-1, 3)  # fmt: skip
        hid = m > 0
        first = np.where(hid.any(axis=1), hid.argmax(axis=1), 3)  # first hidden point
        rows = np.arange(len(g))
        new_b, new_a = first < 3, first > 0
        b[g[new_b]], fb[g[new_b]] = tt[rows[new_b], first[new_b]], m[rows[new_b], first[new_b]]
        ia = first[new_a] - 1
        a[g[new_a]], fa[g[new_a]] = tt[rows[new_a], ia], m[rows[new_a], ia]
        # Illinois: an end kept twice in a row has its value halved
        only_a, only_b = new_a & ~new_b, new_b & ~new_a
        fb[g[only_a & (kept[g] == 2)]] *= 0.5
        fa[g[only_b & (kept[g] == 1)]] *= 0.5
        kept[g] = np.where(only_a, 2, np.where(only_b, 1, 0))
    # verify with the full test; accepted brackets replace the originals
    kk, cc = np.tile(fl.k[idx], 2), np.tile(fl.cid[idx], 2)
    xyz, xy = _points(all_s, projector, kk, cc, np.concatenate([a, b]))
    h = vis.hidden(xyz, xy, np.tile(fl.owner[idx], 2), np.tile(fl.kind[idx], 2))
    n = len(idx)
    ok = ~h[:n] & h[n:] & ~fl.open(idx, np.minimum(a, b), np.maximum(a, b))
    sel, hl = idx[ok], fl.hlo[idx[ok]]
    fl.lo[sel] = np.where(hl, b[ok], a[ok])
    fl.hi[sel] = np.where(hl, a[ok], b[ok])


def _k_section(all_s: list[_Samples], fl: _Flips, vis: _Visibility,
               projector: Projector) -> None:  # fmt: skip
    """Remaining flips: each step splits every bracket into ``K`` parts at once
    (the exactness of bisection in ``1/log2(K)`` of the steps), keeping the
    first sub-bracket whose ends differ.  ``K`` trades the fixed cost of a
    step against the number and cost of the tests: large for a few flips on
    cheap surfaces, 2 (bisection) for many flips on costly ones."""
    n_open = int(fl.open().sum())
    # cost of a step: a fixed part plus the sub-points times the cost of a test;
    # pick the K with the least cost per bit gained (deterministic: no timing)
    ks = 2 ** np.arange(1, int(np.log2(tol.SECTIONS)) + 1)
    per_bit = (vis.cost_per_call + n_open * (ks - 1) * vis.cost_per_point) / np.log2(ks)
    K = int(ks[np.argmin(per_bit)])
    frac = np.arange(1, K) / K
    for _ in range(tol.BISECTION_MAX_STEPS):
        idx = np.nonzero(fl.open())[0]
        if not len(idx):
            break
        tm = fl.lo[idx, None] + (fl.hi[idx] - fl.lo[idx])[:, None] * frac
        rep = np.repeat(idx, K - 1)
        xyz, xy = _points(all_s, projector, fl.k[rep], fl.cid[rep], tm.ravel())
        h = vis.hidden(xyz, xy, fl.owner[rep], fl.kind[rep]).reshape(tm.shape)
        differs = h != fl.hlo[idx, None]
        # first sub-point whose state differs from lo's; none: flip in the last part
        first = np.where(differs.any(axis=1), differs.argmax(axis=1), K - 1)
        rows = np.arange(len(idx))
        has_lo, has_hi = first > 0, first < K - 1
        fl.lo[idx[has_lo]] = tm[rows[has_lo], first[has_lo] - 1]
        fl.hi[idx[has_hi]] = tm[rows[has_hi], first[has_hi]]


def _locate_flips(all_s: list[_Samples], vis: _Visibility, projector: Projector) -> None:
    """Locate every visibility flip between two samples to near machine
    precision (``BISECTION_RTOL`` of the parameter span) and insert both sides."""
    fl = _Flips.find(all_s)
    _regula_falsi(all_s, fl, vis, projector)
    _k_section(all_s, fl, vis, projector)
    order = np.argsort(fl.k, kind="stable")
    for sel in np.split(order, np.nonzero(np.diff(fl.k[order]))[0] + 1):
        if not len(sel):
            continue
        s = all_s[fl.k[sel[0]]]
        # both ends of each bracket, in order, right after the flip's first sample
        t = np.column_stack([fl.lo[sel], fl.hi[sel]]).ravel()
        c = np.repeat(fl.cid[sel], 2)
        xyz, uv, xy = _evaluate(s.batch, s.transform, projector, c, t)
        hidden = np.column_stack([fl.hlo[sel], ~fl.hlo[sel]]).ravel()
        _merge(s, np.repeat(fl.f[sel], 2), c, t, xyz, uv, xy, hidden)


def _strokes(
    s: _Samples, node: Node, hidden_lines: bool, hidden_style: Style, min_extent: float
) -> list[Stroke]:
    """Split samples into runs of equal visibility, one stroke per run.

    Runs whose projection is smaller than ``min_extent`` (degenerate curves such
    as a parameter circle through a cone's vertex) are dropped."""
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
        if len(xy) < 2 or np.ptp(xy, axis=0).max() <= min_extent:
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
    owners = [_owner_arrays(s, len(s.t)) for s in samples]
    cause = np.empty(sum(len(s.t) for s in samples), dtype=np.int64)
    hidden = vis.hidden(
        np.concatenate([s.xyz for s in samples]),
        np.concatenate([s.xy for s in samples]),
        np.concatenate([o for o, _ in owners]),
        np.concatenate([k for _, k in owners]),
        cause,
    )
    cuts = np.cumsum([len(s.t) for s in samples])[:-1]
    for s, h, c in zip(samples, np.split(hidden, cuts), np.split(cause, cuts)):
        s.hidden, s.cause = h, c
    _locate_flips(samples, vis, projector)
    strokes: list[Stroke] = []
    for s in samples:
        strokes.extend(_strokes(s, nodes[s.node], hidden_lines, hidden_style, 1e-12 * diag))
    return Drawing(strokes=strokes, page=page)


def classify(scene: Scene, projector: Projector, points: Any) -> np.ndarray:
    """Hidden flags of arbitrary world points (not on any surface) in ``scene``."""
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    vis = _Visibility(scene.nodes, projector)
    return vis.hidden(p, projector.project(p), np.full(len(p), -1), np.zeros(len(p), np.int8))
