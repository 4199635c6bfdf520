"""Ray tests against quadrics, vectorized over rays *and* quadrics.

Used by :meth:`Quadric.hits` (one quadric, many rays) and by the renderer's
grouped path (many quadric nodes at once, coefficients gathered per ray).

For a ray ``o + s v`` the quadric ``x^T A x + b . x + d`` becomes
``qa s^2 + qb s + qc``.  A point on the quadric itself has ``qc = 0``: its own
root is ``s = 0`` and the other one exactly ``s = -qb/qa`` (no discriminant,
which is ill-conditioned for grazing rays near the contour).  Other points use
the numerically stable pair ``q / qa``, ``qc / q`` with
``q = -(qb + sign(qb) sqrt(disc)) / 2``.

>>> import numpy as np
>>> A = np.eye(3); b = np.zeros(3)
>>> o = np.array([[0.0, 0.0, 1.0], [3.0, 0.0, 0.0]])     # on the unit sphere / outside
>>> v = np.array([[0.0, 0.0, -1.0], [1.0, 0.0, 0.0]])
>>> quadric_ray_hits(o, v, np.inf, np.array([1, 0]), A, b, -1.0, 1e-9).tolist()
[True, False]
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..._own import CONTOUR, ON
from ...geometry.vectors import dot as _dot

__all__ = ["quadric_ray_hits", "quadric_coefficients_world", "quadric_outlines"]


def quadric_ray_hits(
    o: np.ndarray,
    v: np.ndarray,
    smax: np.ndarray | float,
    own: np.ndarray,
    A: np.ndarray,
    b: np.ndarray,
    d: np.ndarray | float,
    eps: np.ndarray | float,
    in_patch: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
    count: bool = False,
    qc: np.ndarray | None = None,
) -> np.ndarray:
    """Whether rays meet the quadric(s) at some ``s`` with ``eps < s < smax``
    (with ``count``: how many times, 0, 1 or 2).

    ``A`` is ``(3, 3)`` or ``(n, 3, 3)``, ``b`` ``(3,)`` or ``(n, 3)``, ``d``
    scalar or ``(n,)``.  ``own`` codes: ON (origin on this quadric: only the
    second root counts), CONTOUR (grazing: never hidden by its own quadric),
    otherwise a foreign origin.  ``in_patch(points, index)`` (optional) says
    whether the hit points (rows ``index`` of the rays) lie on the drawn patch.
    ``qc`` (optional): the quadrics' values ``o.A.o + b.o + d`` at the origins,
    computed already (as here).
    """
    smax = np.broadcast_to(np.asarray(smax, dtype=float), o.shape[:-1])
    Av = np.einsum("...ij,...j->...i", A, v) if A.ndim == 3 else v @ A
    qa = _dot(v, Av)
    qb = 2 * _dot(o, Av) + _dot(v, b)
    hits = np.zeros(o.shape[:-1], dtype=np.int8)

    def accept(s: np.ndarray, mask: np.ndarray, lower: np.ndarray | float) -> np.ndarray:
        ok = mask & np.isfinite(s) & (s > lower) & (s < smax)
        if in_patch is not None and ok.any():
            idx = np.nonzero(ok)[0]
            ok[idx] = in_patch(o[idx] + s[idx, None] * v[idx], idx)
        return ok

    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        on = own == ON
        if on.any():
            hits += accept(-qb / qa, on, 0.0)
        # contour points: the view ray is tangent (double root at s = 0); it
        # meets the quadric elsewhere only if it lies on it (a ruling), and
        # then it does not hide its own contour either.
        off = (own != ON) & (own != CONTOUR)
        if off.any():
            if qc is None:
                Ao = np.einsum("...ij,...j->...i", A, o) if A.ndim == 3 else o @ A
                qc = _dot(o, Ao) + _dot(o, b) + d
            disc = qb * qb - 4 * qa * qc
            real = off & (disc >= 0)
            sq = np.sqrt(np.where(real, disc, 0.0))
            q = -0.5 * (qb + np.copysign(sq, qb))
            lin = real & (np.abs(qa) <= 1e-14 * (np.abs(qb) + np.abs(qc)) + 1e-300)
            r1 = np.where(lin, -qc / qb, q / qa)
            r2 = np.where(lin, np.nan, qc / q)
            hits += accept(r1, real, eps)
            hits += accept(r2, real, eps)
    return hits if count else hits > 0


def quadric_coefficients_world(
    A: np.ndarray, b: np.ndarray, d: float, inverse_matrix: np.ndarray, inverse_offset: np.ndarray
) -> tuple[np.ndarray, np.ndarray, float]:
    """Coefficients of the same quadric in world coordinates.

    With ``x_local = R x + c`` (``R, c`` the inverse transform):
    ``A_w = R^T A R``, ``b_w = R^T (2 A c + b)``, ``d_w = c^T A c + b . c + d``.
    """
    R, c = inverse_matrix, inverse_offset
    return R.T @ A @ R, R.T @ (2 * A @ c + b), float(c @ A @ c + b @ c + d)


def quadric_outlines(
    A: np.ndarray, b: np.ndarray, d: np.ndarray, camera: np.ndarray, ellipsoid: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The outlines (apparent contours in the image) of quadrics
    ``x^T A x + b . x + d = 0`` (``A`` ``(n, 3, 3)``, ``b`` ``(n, 3)``, ``d``
    ``(n,)``) seen through the 3 x 4 ``camera`` (homogeneous image point of
    a homogeneous point): conics ``C`` ``(n, 3, 3)`` and their tight boxes
    ``(n, 4)`` ``(x0, y0, x1, y1)``, for the rows flagged ``ellipsoid`` (NaN
    elsewhere).  ``[x, y, 1] C [x, y, 1]^T`` is positive exactly inside the
    outline (the image of the solid) and zero on it.

    With ``Q = [[A, b/2], [b^T/2, d]]`` the outline's dual conic is
    ``C* = M Q^-1 M^T``; the outline is its inverse, signed by the image of
    the ellipsoid's centre (inside).  The tangent lines ``x = c`` of the
    outline are the roots of ``l C* l = 0`` for ``l = (1, 0, -c)``.

    >>> M = np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]])  # seen along z
    >>> sphere = np.eye(3)[None], np.zeros((1, 3)), np.array([-4.0])  # radius 2
    >>> C, box = quadric_outlines(*sphere, M, np.array([True]))
    >>> [round(float(p @ C[0] @ p), 6) for p in np.array([[2.0, 0, 1], [0, 0, 1], [3, 0, 1]])]
    [0.0, 0.942809, -1.178511]
    >>> box.round(6).tolist()
    [[-2.0, -2.0, 2.0, 2.0]]
    """
    n = len(A)
    Q = np.empty((n, 4, 4))
    Q[:, :3, :3] = A
    Q[:, :3, 3] = Q[:, 3, :3] = 0.5 * b
    Q[:, 3, 3] = d
    conic = np.full((n, 3, 3), np.nan)
    box = np.full((n, 4), np.nan)
    pd = np.flatnonzero(ellipsoid)
    if not len(pd):
        return conic, box
    M = camera
    with np.errstate(all="ignore"):
        dual = M @ np.linalg.inv(Q[pd]) @ M.T
        C = np.linalg.inv(dual)
        C /= np.linalg.norm(C, axis=(1, 2))[:, None, None]
        centre = np.linalg.solve(A[pd], -0.5 * b[pd][:, :, None])[:, :, 0]
        c = np.column_stack([centre, np.ones(len(pd))]) @ M.T
        conic[pd] = C * np.sign(np.einsum("ni,nij,nj->n", c, C, c))[:, None, None]
        for axis in (0, 1):  # the tangent lines x = c, then y = c
            a, h, w = dual[:, axis, axis], dual[:, axis, 2], dual[:, 2, 2]
            root = np.sqrt(np.maximum(h * h - a * w, 0.0))
            ends = np.sort(np.column_stack([(h - root) / w, (h + root) / w]), axis=1)
            box[pd, axis], box[pd, axis + 2] = ends[:, 0], ends[:, 1]
    pad = 1e-9 * (box[:, 2] - box[:, 0] + box[:, 3] - box[:, 1])[:, None]
    return conic, box + pad * np.array([-1, -1, 1, 1])
