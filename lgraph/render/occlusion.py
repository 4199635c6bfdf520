"""Which points are hidden: every sample against every surface of the scene."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import _tolerance as tol
from ..geometry.vectors import box_corners, dot
from ..scene.projectors import CentralProjector, Projector
from ..surfaces._base import CONTOUR, OFF
from ..surfaces.quadrics._ray import quadric_coefficients_world, quadric_outlines, quadric_ray_hits
from ..surfaces.quadrics.quadric import Quadric
from .boxes import BoxGrid
from .twins import lies_on, twin_groups
from .views import Views, as_views

if TYPE_CHECKING:
    from ._protocols import RenderNode

__all__ = ["NotBatchable", "Occlusion"]


class NotBatchable(Exception):
    """Raised when views cannot be rendered together (the caller renders them
    one by one): a closed quadric whose projected box exists in some of them
    only (an eye inside its bounding box)."""


def _box(projector: Projector, corners: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Projected bounding box of world ``corners``; None when some lie at or
    behind a central projector's eye."""
    if isinstance(projector, CentralProjector) and not np.all(projector.depth(corners) > 0):
        return None
    pc = projector.project(corners)
    return pc.min(axis=0), pc.max(axis=0)


def _padded(boxes: list) -> np.ndarray:
    """Boxes ``((x0, y0), (x1, y1))`` or None (unbounded), one a view, as an
    array ``(views, 4)`` grown by 1e-9 of their size (ties go inside)."""
    lim = np.array(
        [(-np.inf, -np.inf, np.inf, np.inf) if b is None else (*b[0], *b[1]) for b in boxes]
    )
    pad = 1e-9 * (np.maximum(lim[:, 2] - lim[:, 0], lim[:, 3] - lim[:, 1]) + 1.0)
    pad = np.where(np.isfinite(pad), pad, 0.0)
    return lim + np.column_stack([-pad, -pad, pad, pad])


def _inside(xy: np.ndarray, boxes: np.ndarray, view: np.ndarray) -> np.ndarray:
    """Which points ``xy`` lie in the box ``boxes[view]`` of their view (the
    box's sides gathered column by column: a row gather is much slower)."""
    x, y = xy[:, 0], xy[:, 1]
    inside = (x >= boxes[:, 0][view]) & (x <= boxes[:, 2][view])
    inside &= (y >= boxes[:, 1][view]) & (y <= boxes[:, 3][view])
    return inside


class Occlusion:
    """Tests world points against every hiding surface of the scene.

    Closed quadrics (ellipsoids, spheres, ...) are tested all at once: their
    coefficients are moved to world coordinates and gathered per (point,
    quadric) pair found by a uniform grid over their projected bounding boxes,
    so the cost does not grow with the number of nodes.  Every other surface
    is asked through its own ``hits`` for the points inside its box.

    The grouped quadrics are tested in coordinates centred on the scene
    (``centre``, the middle of the hiding surfaces' bounding box): a scene far
    from the origin gives the same results as the same scene at the origin
    (the quadratic terms would otherwise cancel catastrophically).

    Tie rule for coincident surfaces: a point that lies on another grouped
    quadric (residual within ``COINCIDENT_RTOL`` of the equation's scale,
    i.e. within about ``COINCIDENT_RTOL`` times the quadric's size) is tested
    against that quadric as if it were its own (same ownership code): the
    same sphere added twice hides exactly what one of them hides, never a
    random half of the points by round-off.  Points known to lie on two
    surfaces (intersection curves) carry an owner ``len(nodes) + k`` that
    stands for both nodes of ``shared[k]``: they are their own points on
    both, whatever the round-off (a scene far from the origin).
    """

    def __init__(
        self,
        nodes: tuple[RenderNode, ...],
        projector: Projector | Views,
        shared: Sequence[tuple[int, int]] = (),
    ) -> None:
        self.views = views = as_views(projector)
        # owners of points on two surfaces (intersection curves): owner
        # ``len(nodes) + k`` lies on both nodes of ``shared[k]``
        pairs = np.asarray(shared, dtype=np.int64).reshape(-1, 2)
        n = len(nodes)
        self._on_first = np.concatenate([[-1], np.arange(n), pairs[:, 0]])
        self._on_second = np.concatenate([[-1], np.full(n, -1), pairs[:, 1]])
        self.items = []  # (node index, surface, inverse transform, boxes) asked one by one
        quads = []  # (node index, boxes, A_w, b_w, d_w, eps) tested together
        hiding = [(j, n) for j, n in enumerate(nodes) if n.surface is not None and n.hides]
        world = {}
        for j, node in hiding:
            lo, hi = node.surface.bounds()
            corners = box_corners(lo, hi)
            world[j] = node.transform.apply(corners)
        allc = np.concatenate(list(world.values())) if world else np.zeros((1, 3))
        allc = allc[np.isfinite(allc).all(axis=1)]
        #: the origin of the coordinates the grouped quadrics are tested in
        self.centre = 0.5 * (allc.min(axis=0) + allc.max(axis=0)) if len(allc) else np.zeros(3)
        for j, node in hiding:
            surf = node.surface
            inv = node.transform.inverse()
            wc = world[j]
            boxes = [_box(p, wc) for p in views.projectors]  # per view; None: none
            grouped = [box is not None for box in boxes]
            if isinstance(surf, Quadric) and surf.closed and any(grouped) and not all(grouped):
                raise NotBatchable("a closed quadric has a box in some views only")
            if isinstance(surf, Quadric) and surf.closed and all(grouped):
                A, b, d = quadric_coefficients_world(
                    *surf.coefficients, inv.matrix, inv.offset + inv.matrix @ self.centre
                )
                size = float(np.linalg.norm(wc.max(axis=0) - wc.min(axis=0)))
                quads.append((j, boxes, A, b, d, tol.SELF_HIT_RTOL * size))
            else:
                self.items.append((j, surf, inv, boxes))
        #: per asked surface, the nodes holding the same surface in the same place
        #: (their points are its own points: the tie rule for surfaces that have
        #: no implicit equation, such as a ParametricSurface added twice)
        first = self.first = twin_groups(nodes)
        self.twins = {j: np.flatnonzero(first == first[j]) for j, _, _, _ in self.items}
        self._setup_grid(quads)
        #: per node (index + 1; 0 for no node): its grouped quadric, or -1
        self._q_of_node = np.full(len(nodes) + 1, -1)
        if self.nq:
            self._q_of_node[self.q_node + 1] = np.arange(self.nq)
        #: per asked surface, its padded box ``(x0, y0, x1, y1)`` in every view
        #: (unbounded where it has none)
        self._item_boxes = {j: _padded(boxes) for j, _, _, boxes in self.items}
        #: relative cost of testing one point (1: the grouped quadric test)
        self.cost_per_point = 1.0 + sum(it[1].hit_cost for it in self.items)
        #: fixed cost of one visibility test call
        self.cost_per_call = tol.STEP_COST + sum(it[1].hit_call_cost for it in self.items)

    def _setup_grid(self, quads: list) -> None:
        self.nq = len(quads)
        self._outline_cache: dict[int, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}
        if not quads:
            return
        self.q_node = np.array([q[0] for q in quads])
        self.q_A = np.array([q[2] for q in quads])
        self.q_b = np.array([q[3] for q in quads])
        self.q_d = np.array([q[4] for q in quads])
        self.q_eps = np.array([q[5] for q in quads])
        # ellipsoids (A positive definite): a continuous hiding margin exists
        self.q_pd = np.all(np.linalg.eigvalsh(self.q_A) > 0, axis=1)
        #: per view, the quadrics' projected boxes (those of the ellipsoids'
        #: outlines where tighter) and the grid over them
        self.grids = []
        for k in range(self.views.k):
            box = np.array([[*q[1][k][0], *q[1][k][1]] for q in quads])
            tight = self.outline_boxes(k)
            ok = np.isfinite(tight).all(axis=1)
            box[ok, :2] = np.maximum(box[ok, :2], tight[ok, :2])
            box[ok, 2:] = np.minimum(box[ok, 2:], tight[ok, 2:])
            self.grids.append(BoxGrid(box))
        #: one quadric: its (padded) box in every view, ``(views, 4)``
        self._quadric_boxes = np.array([g.box[0] for g in self.grids])

    def outlines(self, k: int) -> np.ndarray:
        """The projected outlines of the grouped ellipsoids in view ``k``:
        one conic ``(nq, 3, 3)`` each, ``[x, y, 1] C [x, y, 1]^T`` positive
        exactly inside the outline (the image of the ellipsoid), zero on it
        (the image of its contour); NaN for quadrics that are not
        ellipsoids (:func:`~lgraph.surfaces.quadrics._ray.quadric_outlines`).
        Image coordinates relative to :meth:`image_origin` (a scene far
        from the origin keeps its digits)."""
        if k not in self._outline_cache:
            p = self.views.projectors[k]
            e1, e2, e3 = p.frame
            # the 3 x 4 camera of the centred coordinates
            if isinstance(p, CentralProjector):
                rows = np.array([p.distance * e1, p.distance * e2, -e3])
                M = np.column_stack([rows, -rows @ (p.eye - self.centre)])
            else:
                M = np.zeros((3, 4))
                M[:2, :3] = e1, e2
                M[:2, 3] = np.array([e1, e2]) @ self.centre
                M[2, 3] = 1.0
            origin = p.project(self.centre[None])[0]
            shift = np.array([[1.0, 0.0, -origin[0]], [0.0, 1.0, -origin[1]], [0.0, 0.0, 1.0]])
            conic, box = quadric_outlines(self.q_A, self.q_b, self.q_d, shift @ M, self.q_pd)
            self._outline_cache[k] = (conic, box + np.tile(origin, 2), origin)
        return self._outline_cache[k][0]

    def outline_boxes(self, k: int) -> np.ndarray:
        """Tight boxes ``(nq, 4)`` ``(x0, y0, x1, y1)`` of the grouped
        ellipsoids' outlines in view ``k`` (NaN for other quadrics)."""
        self.outlines(k)
        return self._outline_cache[k][1]

    def image_origin(self, k: int) -> np.ndarray:
        """The image of the scene's centre in view ``k``: the origin of the
        coordinates of :meth:`outlines`."""
        self.outlines(k)
        return self._outline_cache[k][2]

    def _quadric_pairs(
        self, xy: np.ndarray, view: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(point, quadric) index pairs whose projected box (in the point's
        view) contains the point."""
        if self.views.k == 1 or view is None:
            return self.grids[0].pairs(xy)
        if self.nq == 1:  # one box a view: each point against its view's box
            pt = np.flatnonzero(_inside(xy, self._quadric_boxes, view))
            return pt, np.zeros(len(pt), dtype=np.int64)
        pts, qs = [], []
        for k, rows in self.views.groups(view):
            pt, q = self.grids[k].pairs(xy[rows])
            pts.append(np.arange(len(xy))[rows][pt])
            qs.append(q)
        pt, q = np.concatenate(pts), np.concatenate(qs)
        order = np.argsort(pt, kind="stable")  # by point, as for one view
        return pt[order], q[order]

    def hidden(
        self,
        xyz: np.ndarray,
        xy: np.ndarray,
        owner: np.ndarray,
        kind: np.ndarray,
        cause: np.ndarray | None = None,
        view: np.ndarray | None = None,
    ) -> np.ndarray:
        """Hidden flags of points ``xyz`` (projected to ``xy``, each in its
        ``view``); ``cause`` (optional output) receives, for points hidden
        by a grouped quadric, that quadric's index (else -1)."""
        return self._test(xyz, xy, owner, kind, cause, view, False)

    def sheets(
        self,
        xyz: np.ndarray,
        xy: np.ndarray,
        owner: np.ndarray,
        kind: np.ndarray,
        view: np.ndarray | None = None,
    ) -> np.ndarray:
        """How many surface sheets lie between each point and the eye: the
        crossings of its ray with every hiding surface (the grouped
        ellipsoids' roots in closed form, the others' ``hit_count``)."""
        return self._test(xyz, xy, owner, kind, None, view, True)

    def _test(
        self,
        xyz: np.ndarray,
        xy: np.ndarray,
        owner: np.ndarray,
        kind: np.ndarray,
        cause: np.ndarray | None,
        view: np.ndarray | None,
        count: bool,
    ) -> np.ndarray:
        """:meth:`hidden` (flags) or :meth:`sheets` (counts, with ``count``)."""
        if isinstance(view, (int, np.integer)):
            view = None if self.views.k == 1 else np.full(len(xyz), view)
        dirs, smax = self.views.rays(xyz, view)
        out = np.zeros(len(xyz), dtype=np.int64 if count else bool)
        if cause is not None:
            cause[:] = -1
        if self.nq:
            pt, q = self._quadric_pairs(xy, view)
            if len(pt) == len(xyz) and self.nq == 1:  # one quadric, every point in its box
                o, v, sm, ow, kd = xyz - self.centre, dirs, smax, owner, kind
            else:
                # np.take: row gathers several times faster than fancy indexing
                o, v = np.take(xyz, pt, axis=0) - self.centre, np.take(dirs, pt, axis=0)
                sm = smax[pt]
                ow, kd = owner[pt], kind[pt]
            coef = self._coefficients(q)
            own, qc = self._owned(o, q, ow, kd, coef, values=True)
            own = np.where(own, kd, OFF).astype(np.int8)
            h = quadric_ray_hits(o, v, sm, own, *coef, count=count, qc=qc)
            if count:
                np.add.at(out, pt, h)
            else:
                out[pt[h]] = True
                if cause is not None:
                    cause[pt[h]] = q[h]
        if not self.items:
            return out
        for j, surf, inv, idx in self._in_boxes(xy, view):
            if not len(idx):
                continue
            mine = self._on(owner[idx], self.twins[j])
            own = np.where(mine, kind[idx], OFF).astype(np.int8)
            o = inv.apply(np.take(xyz, idx, axis=0))  # rows: np.take is faster
            tie = np.flatnonzero(~mine & (kind[idx] != OFF))
            if len(tie):  # the tie rule: points lying on this surface count as its own
                on = tie[lies_on(surf, o[tie])]
                own[on] = kind[idx[on]]
            v = inv.apply_vector(np.take(dirs, idx, axis=0))
            if count:
                out[idx] += np.asarray(surf.hit_count(o, v, smax[idx], own), dtype=np.int64)
            else:
                out[idx] |= surf.hits(o, v, smax[idx], own)
        return out

    def _in_boxes(self, xy: np.ndarray, view: np.ndarray | None) -> Iterator[tuple]:
        """``(node, surface, inverse transform, rows)`` of every surface asked
        one by one, with the rows of the points inside its projected box (in
        their view)."""
        if self.views.k == 1 or view is None:
            # points sorted by x: each box selects a contiguous slab, then filtered by y
            order = np.argsort(xy[:, 0], kind="stable")
            xs = xy[order, 0]
            for j, surf, inv, (box,) in self.items:
                if box is None:
                    yield j, surf, inv, np.arange(len(xy))
                    continue
                x0, y0, x1, y1 = self._item_boxes[j][0]
                a, b = np.searchsorted(xs, [x0, x1])
                idx = order[a:b]
                y = xy[idx, 1]
                yield j, surf, inv, idx[(y >= y0) & (y <= y1)]
            return
        for j, surf, inv, _ in self.items:
            yield j, surf, inv, np.flatnonzero(_inside(xy, self._item_boxes[j], view))

    def own_margins(
        self,
        xyz: np.ndarray,
        owner: np.ndarray,
        kind: np.ndarray,
        uv: np.ndarray | None = None,
        which: int | None = None,
        view: np.ndarray | None = None,
    ) -> np.ndarray:
        """For points on a surface asked one by one, that surface's transition
        functions (:meth:`~lgraph.Surface.visibility_margins`), ``(k,
        n)`` padded with NaN; ``k = 0`` when no surface has any.  They speak
        for the point's own surface only, not for the rest of the scene.
        ``uv``: the points' parameters on their own surface, when known;
        ``which``: only that function of each surface (one row); ``view``: the
        points' views."""
        parts = []
        if len(xyz) and self.items:
            dirs, smax = self.views.rays(xyz, view)
            for j, surf, inv, _ in self.items:
                idx = np.flatnonzero(self._on(owner, self.twins[j]) & (kind != OFF))
                if not len(idx):
                    continue
                m = surf.visibility_margins(
                    inv.apply(xyz[idx]),
                    inv.apply_vector(dirs[idx]),
                    smax[idx],
                    kind[idx],
                    None if uv is None else uv[idx],
                    which,
                )
                if m is not None:
                    parts.append((idx, np.asarray(m, float).reshape(-1, len(idx))))
        out = np.full((max((len(m) for _, m in parts), default=0), len(xyz)), np.nan)
        for idx, m in parts:
            out[: len(m), idx] = m
        return out

    def own_cosines(
        self,
        xyz: np.ndarray,
        owner: np.ndarray,
        view: np.ndarray | None = None,
        uv: np.ndarray | None = None,
    ) -> np.ndarray:
        """``N . ray`` at points on their own surfaces (``(n, 2)``: the
        owner's surface, and for an intersection curve on a grouped
        ellipsoid its second one; NaN where unknown), continuous along a
        curve and zero where it crosses its own contour.  For grouped
        ellipsoids ``N`` is ``grad F``; for the other surfaces the unit
        normal at the points' parameters ``uv`` (their own surface's).
        Where its sign changes between two samples, the curve has crossed its
        own contour, where its image only touches the image of the contour
        (no 2-D crossing)."""
        out = np.full((len(xyz), 2), np.nan)
        if not len(xyz):
            return out
        dirs, _ = self.views.rays(xyz, view)
        for col, nodes in enumerate((self._on_first, self._on_second)):
            if not self.nq:
                break
            q = self._q_of_node[nodes[owner + 1] + 1]
            rows = np.flatnonzero(q >= 0)
            if not len(rows):
                continue
            x = xyz[rows] - self.centre
            A, b, _, _ = self._coefficients(q[rows])
            g = 2 * (np.einsum("nij,nj->ni", A, x) if A.ndim == 3 else x @ A) + b
            out[rows, col] = np.einsum("ni,ni->n", g, dirs[rows])
        if uv is None:
            return out
        first = self._on_first[owner + 1]
        for j, surf, inv, _ in self.items:
            rows = np.flatnonzero((first == j) & np.isfinite(uv[:, 0]))
            if not len(rows):
                continue
            with np.errstate(all="ignore"):
                n = surf.normal(uv[rows, 0], uv[rows, 1])
                out[rows, 0] = np.einsum("ni,ni->n", n, inv.apply_vector(dirs[rows]))
        return out

    def _on(self, owner: np.ndarray, nodes: np.ndarray) -> np.ndarray:
        """Which points of owners ``owner`` lie on one of ``nodes``."""
        first, second = self._on_first[owner + 1], self._on_second[owner + 1]
        return np.isin(first, nodes) | np.isin(second, nodes)

    def _owned(
        self,
        o: np.ndarray,
        q: np.ndarray,
        owner: np.ndarray,
        kind: np.ndarray,
        coef: tuple,
        values: bool = False,
    ) -> Any:
        """Which (centred point, quadric) pairs count as the point's own surface:
        its own node's, or one it lies on (the tie rule for coincident surfaces).
        With ``values``, also the ray test's ``qc`` (the same einsums: the same
        bits) when the tie rule computes it for all pairs (one quadric a pair)."""
        node = self.q_node[q]
        own = (self._on_first[owner + 1] == node) | (self._on_second[owner + 1] == node)
        tie = ~own & (kind != OFF)
        if not tie.any():
            return (own, None) if values else own
        A, b, d, _ = coef
        i = np.flatnonzero(tie)
        qc = None
        if values and A.ndim == 3:
            xAx, bx = dot(o, np.einsum("...ij,...j->...i", A, o)), dot(o, b)
            qc = xAx + bx + d
            xAx, bx = xAx[i], bx[i]
        else:
            oi = np.take(o, i, axis=0)  # rows: np.take is several times faster
            Ai = np.take(A, i, axis=0) if A.ndim == 3 else A
            Ax = np.einsum("...ij,...j->...i", Ai, oi) if Ai.ndim == 3 else oi @ Ai
            xAx = np.einsum("ij,ij->i", oi, Ax)
            bi = np.take(b, i, axis=0) if b.ndim == 2 else np.broadcast_to(b, oi.shape)
            bx = np.einsum("ij,ij->i", oi, bi)
        di = d[i] if np.ndim(d) else d
        scale = np.abs(xAx) + np.abs(bx) + np.abs(di)
        own[i] = np.abs(xAx + bx + di) <= tol.COINCIDENT_RTOL * scale
        return (own, qc) if values else own

    def _coefficients(self, q: np.ndarray) -> tuple:
        """``(A, b, d, eps)`` of quadrics ``q``: gathered per point, or the single
        quadric's own arrays when all points belong to one (faster products)."""
        if len(q) and (self.nq == 1 or np.all(q == q[0])):
            k = int(q[0])
            return self.q_A[k], self.q_b[k], self.q_d[k], self.q_eps[k]
        return (
            np.take(self.q_A, q, axis=0),
            np.take(self.q_b, q, axis=0),
            self.q_d[q],
            self.q_eps[q],
        )

    def margin(
        self,
        xyz: np.ndarray,
        q: np.ndarray,
        owner: np.ndarray,
        kind: np.ndarray,
        view: np.ndarray | None = None,
    ) -> np.ndarray:
        """Continuous function, positive exactly where ellipsoid ``q`` hides the point.

        With ``qa s^2 + qb s + qc`` the ray's quadratic (``qa > 0``): a point on
        the ellipsoid is hidden by it iff ``s2 = -qb/qa > 0``; any other point
        iff it is inside (``qc < 0``) or the ray meets the ellipsoid ahead
        (``disc >= 0`` and ``qb < 0``).  Used to locate flips by root finding.
        """
        dirs, _ = self.views.rays(xyz, view)
        xyz = xyz - self.centre
        coef = self._coefficients(q)  # per point, or one quadric's (broadcast)
        A, b, d, _ = coef
        Av = np.einsum("...ij,...j->...i", A, dirs) if A.ndim == 3 else dirs @ A
        qa = np.einsum("...i,...i", dirs, Av)
        qb = 2 * np.einsum("...i,...i", xyz, Av) + np.einsum("...i,...i", dirs, b)
        s_sum = -qb / qa  # r1 + r2
        own = self._owned(xyz, q, owner, kind, coef)
        out = np.where(kind == CONTOUR, -1.0, s_sum)
        if own.all():
            return out
        Ax = np.einsum("...ij,...j->...i", A, xyz) if A.ndim == 3 else xyz @ A
        qc = np.einsum("...i,...i", xyz, Ax) + np.einsum("...i,...i", xyz, b) + d
        foreign = np.maximum(-qc / qa, np.minimum((qb * qb - 4 * qa * qc) / (4 * qa * qa), s_sum))
        return np.where(own, out, foreign)
