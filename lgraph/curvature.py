"""Fundamental forms, principal curvatures and directions, and the paper's
equation (3.3) for lines of curvature.

>>> import numpy as np
>>> import lgraph as lg
>>> k1, k2 = principal_curvatures(lg.Sphere(2.0), np.array([0.3]), np.array([1.0]))
>>> np.allclose(np.abs([k1[0], k2[0]]), 0.5)
True
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = [
    "fundamental_forms",
    "principal_curvatures",
    "principal_directions",
    "curvature_equation_angle",
]


def fundamental_forms(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, ...]:
    """``(g11, g12, g22, L11, L12, L22)`` at ``(u1, u2)``."""
    g11, g12, g22 = surface.first_fundamental_form(u1, u2)
    L11, L12, L22 = surface.second_fundamental_form(u1, u2)
    return g11, g12, g22, L11, L12, L22


def principal_curvatures(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    """Principal curvatures ``k1 <= k2`` from the fundamental forms."""
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    g = g11 * g22 - g12 * g12
    H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
    K = (L11 * L22 - L12 * L12) / g
    root = np.sqrt(np.maximum(H * H - K, 0.0))
    return H - root, H + root


def _direction_for(k, g11, g12, g22, L11, L12, L22):  # noqa: ANN001, ANN202
    """Parameter direction ``(du1, du2)`` solving ``(L - k G) du = 0``."""
    a11, a12, a22 = L11 - k * g11, L12 - k * g12, L22 - k * g22
    v1 = np.stack([a12, -a11], axis=-1)  # kernel from the first row
    v2 = np.stack([a22, -a12], axis=-1)  # kernel from the second row
    n1 = np.linalg.norm(v1, axis=-1)
    n2 = np.linalg.norm(v2, axis=-1)
    return np.where((n1 >= n2)[..., None], v1, v2)


def principal_directions(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    """Unit 3-D principal directions ``(e1, e2)`` for ``k1 <= k2``.

    At umbilics the directions are arbitrary (returned as NaN-free vectors of
    the parameter directions).
    """
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    k1, k2 = principal_curvatures(surface, u1, u2)
    x1, x2 = surface.derivatives(u1, u2)
    out = []
    for k, fallback in ((k1, x1), (k2, x2)):
        du = _direction_for(k, g11, g12, g22, L11, L12, L22)
        e = du[..., :1] * x1 + du[..., 1:] * x2
        n = np.linalg.norm(e, axis=-1, keepdims=True)
        bad = n[..., 0] <= 1e-300
        e = np.where(bad[..., None], fallback, e)
        n = np.linalg.norm(e, axis=-1, keepdims=True)
        out.append(e / n)
    return out[0], out[1]


def curvature_equation_angle(surface: Any, uv: np.ndarray, duv: np.ndarray) -> np.ndarray:
    """Angle (radians) between the 3-D direction ``x1 du1 + x2 du2`` and the
    nearest principal direction, computed from equation (3.3) of the paper.

    Equation (3.3): ``det [[L11 du1 + L12 du2, g11 du1 + g12 du2],
    [L21 du1 + L22 du2, g21 du1 + g22 du2]] = 0`` holds exactly along lines of
    curvature.  Rather than the raw determinant (whose scale depends on the
    parametrization) this returns the angle to the closer principal direction,
    with both principal directions obtained from (3.3) as a quadratic in
    ``du1 : du2``.
    """
    uv = np.asarray(uv, float)
    duv = np.asarray(duv, float)
    u1, u2 = uv[:, 0], uv[:, 1]
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    x1, x2 = surface.derivatives(u1, u2)
    # (3.3) expanded:  A du1^2 + B du1 du2 + C du2^2 = 0
    A = L11 * g12 - L12 * g11
    B = L11 * g22 - L22 * g11
    C = L12 * g22 - L22 * g12
    t = duv[:, :1] * x1 + duv[:, 1:] * x2
    t /= np.linalg.norm(t, axis=-1, keepdims=True)
    # the two roots as directions (du1, du2); robust to A or C = 0
    disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0.0))
    s = np.where(B >= 0, 1.0, -1.0)
    q = -0.5 * (B + s * disc)
    # roots of A r^2 + B r + C = 0 with r = du1/du2:  r1 = q/A, r2 = C/q
    # use homogeneous forms to avoid dividing: (du1, du2) = (q, A) and (C, q)
    d1 = np.stack([q, A], axis=-1)
    d2 = np.stack([C, q], axis=-1)
    angles = []
    for d in (d1, d2):
        e = d[:, :1] * x1 + d[:, 1:] * x2
        n = np.linalg.norm(e, axis=-1)
        with np.errstate(invalid="ignore", divide="ignore"):
            c = np.abs(np.einsum("ij,ij->i", e, t)) / n
        angles.append(np.where(n > 0, np.arccos(np.clip(c, 0.0, 1.0)), np.pi / 2))
    return np.minimum(angles[0], angles[1])
