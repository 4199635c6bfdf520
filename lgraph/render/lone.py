"""One ellipsoid alone, drawn by exact ellipses: visibility in closed form,
without a ray test (the paper's figures of a single quadric).

When the only surface that hides is an ellipsoid and every curve is an exact
ellipse on it (its parameter lines, plane sections) or its contour, nothing
but the ellipsoid itself can hide a point, and on its own surface a point
``x`` is hidden exactly when the gradient of ``F`` points away from the
viewer: ``g(x) = (2 A x + b) . w < 0`` (``w`` toward the viewer).  On the
ellipsoid ``g`` is linear in ``x`` (``F(x) = 0`` removes the square), so on
an ellipse ``x = c + p cos t + q sin t`` it is ``P + Q cos t + R sin t`` and
vanishes at two angles at most, in closed form
(:func:`~lgraph.render.flips.contour_crossings`).  Those are all of the
curve's flips: they are inserted before refinement (both sides, within
``BISECTION_RTOL`` of the span, as :func:`~lgraph.render.flips.locate_flips`
leaves them), so a visible piece between two hidden samples is found
however short, and a hidden point lies behind exactly one sheet (the near
half of the ellipsoid): its occlusion depth is 1.

The general pipeline gives the same strokes (``tests/test_lone_ellipsoid.py``
compares them); this path skips its fixed cost (the ray-test grid, the net's
crossings, locating flips), which is most of a small figure's time.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import _tolerance as tol
from ..scene.projectors import CentralProjector
from ..surfaces._base import CONTOUR, ON
from ..surfaces.quadrics._ray import quadric_coefficients_world
from ..surfaces.quadrics.quadric import Quadric
from .flips import contour_crossings
from .sampling import Samples, merge, refine

if TYPE_CHECKING:
    from ._protocols import RenderNode

__all__ = ["lone_ellipsoid", "lone_visibility"]


def lone_ellipsoid(nodes: tuple[RenderNode, ...], s: Samples) -> int | None:
    """The node of the scene's one ellipsoid when it is the only node that
    hides and every curve is an exact ellipse on it or its contour; else None
    (the general pipeline then decides)."""
    hiding = [j for j, n in enumerate(nodes) if n.surface is not None and n.hides]
    if len(hiding) != 1 or s.ellipses is None:
        return None
    j = hiding[0]
    surface = nodes[j].surface
    if not (isinstance(surface, Quadric) and surface.closed):
        return None
    if not np.all(np.linalg.eigvalsh(surface.coefficients[0]) > 0):
        return None
    on = (s.kind == ON) | (s.kind == CONTOUR)
    if not np.all((s.owner == j) & on & np.isfinite(s.ellipses[:, 0, 0])):
        return None
    return j


def lone_visibility(
    s: Samples,
    node: RenderNode,
    abs_tol: float | np.ndarray,
    hidden_lines: bool,
) -> np.ndarray:
    """Classify, seed and refine the samples of a :func:`lone_ellipsoid`
    scene (``node`` its ellipsoid's node); returns every sample's occlusion
    depth (0 or 1)."""
    surface = node.surface
    lo, hi = surface.bounds()
    centre = node.transform.apply((0.5 * (np.asarray(lo) + np.asarray(hi)))[None])[0]
    inv = node.transform.inverse()
    A, b, d = quadric_coefficients_world(
        *surface.coefficients, inv.matrix, inv.offset + inv.matrix @ centre
    )
    # per view: g(x) = k . (x - centre) + k0
    linear = []
    for p in s.views.projectors:
        if isinstance(p, CentralProjector):
            eye = np.asarray(p.eye, float) - centre
            linear.append((2 * A @ eye + b, float(b @ eye + 2 * d)))
        else:
            v = np.asarray(p.frame[2], float)
            linear.append((2 * A @ v, float(b @ v)))

    def hidden(cid: np.ndarray, xyz: np.ndarray) -> np.ndarray:
        """Which points ``xyz`` of curves ``cid`` lie on the far side."""
        out = np.zeros(len(cid), dtype=bool)
        on = s.kind[cid] == ON
        for k, sel in s.views.groups(s.view[cid]):
            kv, k0 = linear[k]
            out[sel] = on[sel] & ((xyz[sel] - centre) @ kv + k0 < 0)
        return out

    s.hidden = hidden(s.cid, s.xyz)
    cid, t = _crossings(s, A, b, d, centre)
    settled = None
    if not hidden_lines:  # chords between two hidden samples stay, unless crossed
        settled = s.hidden.copy()
        j = s.after(cid, t)
        settled[j], settled[np.minimum(j + 1, len(settled) - 1)] = False, False
    refine(s, abs_tol, settled)
    fresh = np.flatnonzero(s.fresh)
    s.hidden[fresh] = hidden(s.cid[fresh], np.take(s.xyz, fresh, axis=0))
    s.fresh[:] = False
    if len(t):  # both sides of every crossing, after refinement (as flips are)
        xyz, uv, xy = s.evaluate(cid, t, True)
        merge(s, s.after(cid, t), cid, t, xyz, uv, xy, hidden(cid, xyz))
    return s.hidden.astype(np.int64)


def _crossings(
    s: Samples, A: np.ndarray, b: np.ndarray, d: float, centre: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Both sides of every crossing of an ellipse on the ellipsoid (world
    coefficients ``A, b, d`` about ``centre``) with its contour: curve ids
    and parameters, in (curve, t) order."""
    c = np.flatnonzero(s.kind == ON)
    root = np.empty((len(c), 2))
    for k, rows in s.views.groups(s.view[c]):
        m = len(c[rows])
        root[rows] = contour_crossings(
            s.ellipses[c[rows]],
            np.broadcast_to(A, (m, 3, 3)),
            np.broadcast_to(b, (m, 3)),
            np.full(m, d),
            s.views.projectors[k],
            centre,
        )
    t0, span = s.t0[c][:, None], (s.t1 - s.t0)[c][:, None]
    root = t0 + np.mod(root - t0, 2 * np.pi)  # the first turn from t0 on (spans <= 2 pi)
    inside = np.isfinite(root) & (root <= t0 + span)
    cid, t = np.repeat(c, 2)[inside.ravel()], root[inside]
    step = 0.25 * tol.BISECTION_RTOL * np.maximum((s.t1 - s.t0)[cid], np.abs(t))
    cid, t = np.repeat(cid, 2), (t[:, None] + step[:, None] * np.array([-1.0, 1.0])).ravel()
    keep = (t >= s.t0[cid]) & (t <= s.t1[cid])  # a crossing at an end: its inner side
    cid, t = cid[keep], t[keep]
    order = np.lexsort((t, cid))
    return cid[order], t[order]
