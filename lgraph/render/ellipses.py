"""Exact ellipses (the parameter lines and plane sections of quadrics,
``Samples.ellipses``) against the contour of the ellipsoid they lie on, in
closed form: where they cross it (``contour_crossings``), and samples
put on both sides of crossings that fall between two samples of one state
(``seed_crossings``).  Used by ``lgraph.render.flips`` and
``lgraph.render.lone``."""

from __future__ import annotations

import numpy as np

from .. import _tolerance as tol
from ..scene.projectors import CentralProjector, Projector
from ..surfaces._base import ON
from .occlusion import Occlusion
from .sampling import Samples, merge

__all__ = ["contour_crossings", "ellipse_crossings", "seed_crossings"]


def contour_crossings(
    e: np.ndarray,
    A: np.ndarray,
    bq: np.ndarray,
    d: np.ndarray,
    projector: Projector,
    centre: np.ndarray,
) -> np.ndarray:
    """Where exact ellipses ``x = c + p cos t + r sin t`` (rows of ``e``)
    cross the contour of the ellipsoids ``x.A x + bq.x + d = 0`` they lie on
    (coefficients in coordinates centred on ``centre``, see
    :class:`~lgraph.render.occlusion.Occlusion`): ``(n, 2)`` angles ``t`` (defined
    modulo 2 pi; NaN: no crossing).

    On its quadric a point is hidden by it exactly when ``(2 A x + bq) . w <
    0`` (``w`` toward the viewer), and there that function is linear in
    ``x``: ``x . (2 A o + bq) + bq . o + 2 d`` for an eye ``o``,
    ``x . 2 A v + bq . v`` for a parallel view ``v``.  On the ellipse it is
    ``P + Q cos t + R sin t``, zero at ``atan2(R, Q) -+ acos(-P / hypot(Q, R))``.
    """
    e = e.copy()
    e[:, 0] -= centre
    if isinstance(projector, CentralProjector):
        eye = projector.eye - centre
        k = 2 * A @ eye + bq
        k0 = bq @ eye + 2 * d
    else:
        v = projector.frame[2]
        k = 2 * A @ v
        k0 = bq @ v
    P = np.einsum("ni,ni->n", k, e[:, 0]) + k0
    Q = np.einsum("ni,ni->n", k, e[:, 1])
    R = np.einsum("ni,ni->n", k, e[:, 2])
    with np.errstate(divide="ignore", invalid="ignore"):
        half = np.arccos(-P / np.hypot(Q, R))  # NaN: no crossing at all
    return np.arctan2(R, Q)[:, None] + half[:, None] * np.array([-1.0, 1.0])


def ellipse_crossings(s: Samples, c: np.ndarray, q: np.ndarray, vis: Occlusion) -> np.ndarray:
    """:func:`contour_crossings` of the exact ellipses of curves ``c`` on
    grouped quadrics ``q``, each curve in its view."""
    out = np.empty((len(c), 2))
    for k, rows in s.views.groups(s.view[c]):
        cr, qr = c[rows], q[rows]
        out[rows] = contour_crossings(
            s.ellipses[cr], vis.q_A[qr], vis.q_b[qr], vis.q_d[qr], s.views.projectors[k], vis.centre
        )
    return out


def seed_crossings(s: Samples, vis: Occlusion) -> None:
    """Insert samples on both sides of every contour crossing of an exact
    ellipse on its own ellipsoid that lies in a chord without a flip.

    Such a chord holds two crossings (both crossings of the curve: it meets
    the contour twice at most), i.e. a piece visible or hidden between two
    samples of the other state, which sampling alone would miss however
    fine.  The new samples are fresh (tested later); usually there are none.
    """
    if s.ellipses is None or not vis.nq:
        return
    q_of_node = np.full(int(max(s.owner.max(), vis.q_node.max())) + 1, -1)
    q_of_node[vis.q_node] = np.arange(vis.nq)
    c = np.flatnonzero(np.isfinite(s.ellipses[:, 0, 0]) & (s.kind == ON) & (s.owner >= 0))
    q = q_of_node[s.owner[c]]
    c, q = c[q >= 0], q[q >= 0]
    c, q = c[vis.q_pd[q]], q[vis.q_pd[q]]
    if not len(c):
        return
    root = ellipse_crossings(s, c, q, vis)
    t0, span = s.t0[c][:, None], (s.t1 - s.t0)[c][:, None]
    root = t0 + np.mod(root - t0, 2 * np.pi)  # the first turn from t0 on (spans <= 2 pi)
    inside = np.isfinite(root) & (root < t0 + span)
    cid, t = np.repeat(c, 2)[inside.ravel()], root[inside]
    own_q = np.repeat(q, 2)[inside.ravel()]
    if not len(t):
        return
    # the chord holding each crossing: samples ``j - 1`` and ``j``
    j = s.after(cid, t) + 1
    ok = (j > 0) & (j < len(s.t))
    j, cid, t, own_q = j[ok], cid[ok], t[ok], own_q[ok]
    quiet = (s.cid[j - 1] == cid) & (s.cid[j] == cid) & (s.hidden[j - 1] == s.hidden[j])
    # ... and both ends visible, or both hidden by this ellipsoid (ends hidden
    # by another surface are refined anyway, and there the crossing may not
    # show at all)
    quiet &= ~s.hidden[j] | ((s.cause[j - 1] == own_q) & (s.cause[j] == own_q))
    j, cid, t = j[quiet], cid[quiet], t[quiet]
    if not len(t):
        return
    # both sides of each crossing, strictly inside the chord and in order
    room = np.minimum(t - s.t[j - 1], s.t[j] - t)
    step = np.minimum(1e-7 * (s.t1 - s.t0)[cid], 0.5 * room)
    ok = step > tol.BISECTION_RTOL * (s.t1 - s.t0)[cid]  # not on a sample already
    j, cid, t, step = j[ok], cid[ok], t[ok], step[ok]
    order = np.lexsort((t, j))
    j, cid, t, step = j[order], cid[order], t[order], step[order]
    tt = np.column_stack([t - step, t + step]).ravel()
    cc = np.repeat(cid, 2)
    xyz, uv, xy = s.evaluate(cc, tt, True)
    merge(s, np.repeat(j - 1, 2), cc, tt, xyz, uv, xy)
