"""The exact contour of a quadric: a plane section, parametrized in closed form.

For ``F(x) = x^T A x + b.x + d`` the contour is where the view vector is
tangent, ``grad F(x) . w = 0``:

* parallel view (``w`` fixed): ``2 w^T A x + b.w = 0`` -- a plane;
* central view (``w = e - x``, eye ``e``): ``grad F(x).(e - x) = 0`` and, using
  ``F(x) = 0`` (so ``x^T A x = -b.x - d``), ``(2 A e + b).x + b.e + 2 d = 0``
  -- the polar plane of the eye.

Both cut the quadric in a conic.  With an orthonormal basis ``f1, f2`` of the
plane diagonalizing the restricted form, ``x = p0 + y1 f1 + y2 f2`` and
``F = w1 y1^2 + w2 y2^2 + 2 g.y + k``; completing squares gives an ellipse
``(cos t, sin t)``, hyperbola branches ``(+-cosh t, sinh t)``, a parabola
``(t, t^2)`` or line pairs, each exact.  Pieces are then cut to the drawn
patch.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...curves import CurveBatch
from .._patch import clip_intervals

__all__ = ["contour_plane", "plane_section"]


def contour_plane(surface: Any, projector: Any) -> tuple[np.ndarray, float]:
    """``(n, h)`` with the contour lying in the plane ``n . x = h``."""
    from ...scene.projectors import CentralProjector

    A, b, d = surface.coefficients
    if isinstance(projector, CentralProjector):
        e = np.asarray(projector.eye, float)
        return 2 * A @ e + b, -float(b @ e + 2 * d)
    w = np.asarray(projector.frame[2], float)
    return 2 * A @ w, -float(b @ w)


def _basis(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    helper = np.eye(3)[int(np.argmin(np.abs(n)))]
    e1 = np.cross(n, helper)
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(n, e1)


def _pieces(surface: Any, n: np.ndarray, h: float) -> tuple[str, list[tuple], float] | None:
    """The conic ``{F = 0} & {n.x = h}`` as (kind, [(C, U, V), ...], tmax)."""
    A, b, d = surface.coefficients
    nn = float(np.linalg.norm(n))
    lo, hi = surface.bounds()
    R = float(np.max(np.linalg.norm(np.array([lo, hi]), axis=1))) * np.sqrt(3.0) + 1.0
    normA = float(np.max(np.abs(A))) + 1e-300
    if nn <= 1e-13 * (normA * R + float(np.linalg.norm(b))):
        return None  # every point is on the contour (view along a ruling): nothing exact
    nu = n / nn
    p0 = nu * (h / nn)
    if np.linalg.norm(p0) > R:
        return None
    e1, e2 = _basis(nu)
    E = np.stack([e1, e2], axis=1)
    M = E.T @ A @ E
    g = E.T @ (A @ p0 + b / 2)
    k = float(p0 @ A @ p0 + b @ p0 + d)
    w, Rot = np.linalg.eigh(M)
    f = (E @ Rot).T  # f[0], f[1]: principal directions in the plane
    gp = Rot.T @ g
    tol_w = 1e-10 * normA
    R2 = R + float(np.linalg.norm(p0))
    zero = np.abs(w) <= tol_w
    if not zero.any():
        c = -gp / w
        centre = p0 + c[0] * f[0] + c[1] * f[1]
        K = k - float(w @ c**2)
        tol_k = 1e-12 * (abs(k) + float(np.abs(w) @ c**2) + normA * R * R)
        if w[0] * w[1] > 0:
            r1, r2 = -K / w[0], -K / w[1]
            if not (r1 > 0 and r2 > 0) or abs(K) <= tol_k:
                return None
            return "ellipse", [(centre, np.sqrt(r1) * f[0], np.sqrt(r2) * f[1])], 0.0
        i, j = (0, 1) if w[0] > 0 else (1, 0)
        wp, wm = w[i], -w[j]
        if abs(K) <= tol_k:  # a line pair through the centre
            pieces = []
            for sgn in (1.0, -1.0):
                u = np.sqrt(wm) * f[i] + sgn * np.sqrt(wp) * f[j]
                pieces.append((centre, u / np.linalg.norm(u), np.zeros(3)))
            return "line", pieces, R2 + float(np.linalg.norm(centre))
        if K < 0:  # wp y_i^2 - wm y_j^2 = -K > 0: branches along f[i]
            al, be, fa, fb = np.sqrt(-K / wp), np.sqrt(-K / wm), f[i], f[j]
        else:
            al, be, fa, fb = np.sqrt(K / wm), np.sqrt(K / wp), f[j], f[i]
        cm = (R2 + float(np.linalg.norm(centre))) / min(al, be)
        tmax = float(np.arccosh(max(1.0, cm))) + 1e-3
        return "hyperbola", [(centre, al * fa, be * fb), (centre, -al * fa, be * fb)], tmax
    if zero.all():
        gn = float(np.linalg.norm(gp))
        if gn <= 1e-12 * (normA * R + float(np.linalg.norm(b))):
            return None
        y = -k * gp / (2 * gn * gn)
        q = p0 + y[0] * f[0] + y[1] * f[1]
        u = (-gp[1] * f[0] + gp[0] * f[1]) / gn
        return "line", [(q, u, np.zeros(3))], R2 + float(np.linalg.norm(q))
    i, j = (1, 0) if zero[0] else (0, 1)  # w[i] != 0, w[j] == 0
    if abs(gp[j]) > 1e-10 * (normA * R + float(np.linalg.norm(b))):
        # y_j = -(w_i t^2 + 2 g_i t + k) / (2 g_j), y_i = t
        al, be, ga = -w[i] / (2 * gp[j]), -gp[i] / gp[j], -k / (2 * gp[j])
        C = p0 + ga * f[j]
        return "parabola", [(C, f[i] + be * f[j], al * f[j])], R2
    disc = gp[i] ** 2 - w[i] * k
    if disc < 0:
        return None
    roots = {(-gp[i] + s * np.sqrt(disc)) / w[i] for s in (1.0, -1.0)}
    pieces = [(p0 + r * f[i], f[j], np.zeros(3)) for r in roots]
    return "line", pieces, R2


def _shape(kind: str, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    if kind == "ellipse":
        return np.cos(t), np.sin(t)
    if kind == "hyperbola":
        return np.cosh(t), np.sinh(t)
    if kind == "parabola":
        return t, t * t
    return t, np.zeros_like(t)


def plane_section(surface: Any, n: np.ndarray, h: float, family: str = "contour") -> list:
    """Curve batches of the conic ``{F = 0} & {n.x = h}`` on the drawn patch.

    Only the contour's own conic (``family="contour"``) is marked as lying on
    the contour; every other section (level lines) lies on the surface and is
    hidden by it like any curve on it.
    """
    from ..._own import CONTOUR, ON

    found = _pieces(surface, np.asarray(n, float), float(h))
    if found is None:
        return []
    kind, pieces, tmax = found
    C = np.array([p[0] for p in pieces])
    U = np.array([p[1] for p in pieces])
    V = np.array([p[2] for p in pieces])
    m = len(pieces)
    if kind == "ellipse":
        t0, t1, closed = np.zeros(m), np.full(m, 2 * np.pi), np.ones(m, bool)
    else:
        t0, t1, closed = np.full(m, -tmax), np.full(m, tmax), np.zeros(m, bool)

    def xyz(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
        s1, s2 = _shape(kind, t)
        return C[idx] + s1[:, None] * U[idx] + s2[:, None] * V[idx]

    if not getattr(surface, "closed", True):
        cid, t0, t1, closed = clip_intervals(
            lambda idx, t: surface.patch_margin(xyz(idx, t)), t0, t1, closed
        )
        C, U, V = C[cid], U[cid], V[cid]
        if not len(cid):
            return []

    def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x = xyz(idx, np.asarray(t, float))
        return x, surface.uv_of(x)

    return [
        CurveBatch(
            family,
            t0,
            t1,
            evaluate,
            closed=closed,
            surface=surface,
            own=CONTOUR if family == "contour" else ON,
        )
    ]
