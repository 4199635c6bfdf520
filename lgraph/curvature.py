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

from ._budget import check_parameters
from ._tolerance import ASYMPTOTIC_RTOL, FIELD_RTOL, PARABOLIC_STOP, UMBILIC_STOP

__all__ = [
    "fundamental_forms",
    "principal_curvatures",
    "principal_directions",
    "curvature_equation_angle",
    "principal_field",
    "asymptotic_field",
]


def fundamental_forms(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, ...]:
    """``(g11, g12, g22, L11, L12, L22)`` at ``(u1, u2)``."""
    g11, g12, g22 = surface.first_fundamental_form(u1, u2)
    L11, L12, L22 = surface.second_fundamental_form(u1, u2)
    return g11, g12, g22, L11, L12, L22


def principal_curvatures(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    """Principal curvatures ``k1 <= k2`` from the fundamental forms."""
    check_parameters("principal_curvatures", surface, u1, u2)
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    g = g11 * g22 - g12 * g12
    H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
    K = (L11 * L22 - L12 * L12) / g
    root = np.sqrt(np.maximum(H * H - K, 0.0))
    return H - root, H + root


def _direction_for(k, g11, g12, g22, L11, L12, L22):  # noqa: ANN001, ANN202
    """Parameter direction ``(du1, du2)`` solving ``(L - k G) du = 0``."""
    a11, a12, a22 = L11 - k * g11, L12 - k * g12, L22 - k * g22
    # the kernel from the longer row: (a12, -a11) from the first, (a22, -a12)
    # from the second; |first|^2 - |second|^2 = a11^2 - a22^2
    first = np.abs(a11) >= np.abs(a22)
    out = np.empty(np.shape(a11) + (2,))
    out[..., 0] = np.where(first, a12, a22)
    out[..., 1] = -np.where(first, a11, a12)
    return out


def principal_directions(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    """Unit 3-D principal directions ``(e1, e2)`` for ``k1 <= k2``.

    At umbilics the directions are arbitrary (returned as NaN-free vectors of
    the parameter directions).
    """
    check_parameters("principal_directions", surface, u1, u2)
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


# ---------------------------------------------------------------------------
# line fields: the two principal directions, the two asymptotic directions
# ---------------------------------------------------------------------------
def _frame(surface: Any, uv: np.ndarray) -> tuple[np.ndarray, ...]:
    """``x1, x2, (g11, g12, g22), (L11, L12, L22)`` at rows of ``uv`` (one call each
    of ``derivatives`` and ``second_derivatives``)."""
    u1, u2 = uv[:, 0], uv[:, 1]
    x1, x2 = surface.derivatives(u1, u2)
    g11 = np.einsum("ij,ij->i", x1, x1)
    g12 = np.einsum("ij,ij->i", x1, x2)
    g22 = np.einsum("ij,ij->i", x2, x2)
    n = np.empty_like(x1)  # x1 x x2 (np.cross costs ~30 us on small arrays)
    n[:, 0] = x1[:, 1] * x2[:, 2] - x1[:, 2] * x2[:, 1]
    n[:, 1] = x1[:, 2] * x2[:, 0] - x1[:, 0] * x2[:, 2]
    n[:, 2] = x1[:, 0] * x2[:, 1] - x1[:, 1] * x2[:, 0]
    with np.errstate(invalid="ignore", divide="ignore"):
        n /= np.sqrt(np.einsum("ij,ij->i", n, n))[:, None]
    x11, x12, x22 = surface.second_derivatives(u1, u2)
    L = (np.einsum("ij,ij->i", n, x11), np.einsum("ij,ij->i", n, x12),
         np.einsum("ij,ij->i", n, x22))  # fmt: skip
    return x1, x2, (g11, g12, g22), L


def _unit(du: np.ndarray, g11: np.ndarray, g12: np.ndarray, g22: np.ndarray) -> np.ndarray:
    """Parameter directions ``(n, 2)`` scaled to unit 3-D length (metric ``g``)."""
    a, b = du[:, 0], du[:, 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        return du / np.sqrt(g11 * a * a + 2 * g12 * a * b + g22 * b * b)[:, None]


def principal_field(surface: Any, uv: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The line field of the principal directions at rows of ``uv`` ``(n, 2)``.

    Returns ``(D, strength, G)``: ``D[:, b]`` is the parameter direction
    ``(du1, du2)`` of unit 3-D length belonging to ``k1`` (``b = 0``) and ``k2``
    (``b = 1``), ``strength = (k2 - k1) / (|k1| + |k2|)`` (0 at umbilics, NaN at
    a flat umbilic or a singular point) and ``G = (g11, g12, g22)`` columns.

    >>> import numpy as np
    >>> import lgraph as lg
    >>> D, s, G = principal_field(lg.Torus(3, 1), np.array([[0.3, 0.2]]))
    >>> bool(np.allclose(np.abs(D[0]) @ [1, 1] > 0, True)), bool(s[0] > 0.5)
    (True, True)
    """
    _x1, _x2, (g11, g12, g22), (L11, L12, L22) = _frame(surface, uv)
    with np.errstate(invalid="ignore", divide="ignore"):
        g = g11 * g22 - g12 * g12
        H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
        K = (L11 * L22 - L12 * L12) / g
        root = np.sqrt(np.maximum(H * H - K, 0.0))
        strength = 2 * root / (np.abs(H - root) + np.abs(H + root))
    D = np.empty((len(uv), 2, 2))
    for b, k in enumerate((H - root, H + root)):
        D[:, b] = _unit(_direction_for(k, g11, g12, g22, L11, L12, L22), g11, g12, g22)
    return D, strength, np.stack([g11, g12, g22], axis=1)


def asymptotic_field(surface: Any, uv: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The line field of the asymptotic directions (``II(du) = 0``) at rows of
    ``uv``: ``(D, strength, G)`` as for :func:`principal_field`, with
    ``strength = -K / (H^2 + |K|)`` (positive where ``K < 0``; the two branches
    merge where it reaches 0, on the parabolic lines).

    >>> import numpy as np
    >>> import lgraph as lg
    >>> D, s, G = asymptotic_field(lg.Helicoid(), np.array([[0.5, 0.3]]))
    >>> bool(s[0] > 0)
    True
    """
    _x1, _x2, (g11, g12, g22), (L11, L12, L22) = _frame(surface, uv)
    with np.errstate(invalid="ignore", divide="ignore"):
        g = g11 * g22 - g12 * g12
        K = (L11 * L22 - L12 * L12) / g
        H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
        strength = -K / (H * H + np.abs(K))
    disc = np.sqrt(np.maximum(L12 * L12 - L11 * L22, 0.0))
    D = np.empty((len(uv), 2, 2))
    for b, sgn in enumerate((1.0, -1.0)):
        # L11 a^2 + 2 L12 a b + L22 b^2 = 0: (a, b) = (-L12 +- disc, L11) or (L22, -L12 -+ disc)
        va = np.stack([-L12 + sgn * disc, L11], axis=1)
        vb = np.stack([L22, -L12 - sgn * disc], axis=1)
        use_a = np.einsum("ij,ij->i", va, va) >= np.einsum("ij,ij->i", vb, vb)
        D[:, b] = _unit(np.where(use_a[:, None], va, vb), g11, g12, g22)
    return D, strength, np.stack([g11, g12, g22], axis=1)


# how lines of each field end and how tightly they are integrated (lgraph.families.fieldlines)
principal_field.stop = UMBILIC_STOP  # type: ignore[attr-defined]
principal_field.rtol = FIELD_RTOL  # type: ignore[attr-defined]
asymptotic_field.stop = PARABOLIC_STOP  # type: ignore[attr-defined]
asymptotic_field.rtol = ASYMPTOTIC_RTOL  # type: ignore[attr-defined]
