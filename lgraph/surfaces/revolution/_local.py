"""Local analysis of a surface of revolution at a point on it.

Near a point ``x`` with unit normal ``N`` the surface lies at ``II(xi, xi) / 2``
above its tangent plane; a ray ``x + lam v`` lies at ``lam N . v``.  So the
ray meets the surface again at ``lam2 = 2 N . v / II(v, v)`` to leading order:
the second root that the ray test cannot separate from the point's own when
the point is near its contour (docs/mathematics.rst, "Surfaces of
revolution").  A point's parameter ``t`` comes from
:func:`~lgraph.surfaces.revolution._convex.t_of_points`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._convex import meridian_coordinates, t_of_points

if TYPE_CHECKING:
    from ._protocol import Revolved

__all__ = ["near_own_hits", "normal_component", "own_second_root", "point_parameters"]


def normal_component(surface: Revolved, o: np.ndarray, v: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``N . v / |v|`` at points ``o`` with parameter ``t`` (``N = (z' r - rho' a)
    / |P'|``, ``r`` the radial unit vector; any unit vector at the axis, where
    ``z' = 0``)."""
    _, _, rv = meridian_coordinates(surface, o, v)
    dr, dz = surface.drz(t)
    with np.errstate(invalid="ignore", divide="ignore"):
        return (dz * rv - dr * (v @ surface.frame[2])) / (
            np.hypot(dr, dz) * np.sqrt(np.einsum("ij,ij->i", v, v))
        )


def near_own_hits(
    surface: Revolved, o: np.ndarray, vh: np.ndarray, eps: float
) -> tuple[np.ndarray, np.ndarray]:
    """The first two outputs of :func:`own_second_root`."""
    hit, decided, _, _ = own_second_root(surface, o, vh, eps)
    return hit, decided


def own_second_root(
    surface: Revolved, o: np.ndarray, vh: np.ndarray, eps: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Rays from points ``o`` on the surface (unit directions ``vh``) that meet
    it again at ``0 < lam <= eps``, where the ray test cannot tell the second
    root from the point's own (near the contour the two roots of the ray
    function merge, and a near-double root is found to about the square root
    of the rounding level only), which points were decided (the second
    output), ``N . v / |v|`` there and their parameters ``t`` (NaN where not
    decided): near the point the surface lies at
    ``II(xi, xi) / 2`` above the tangent plane and the ray at ``lam N . v``, so
    the second root is ``lam2 = 2 N . v / II(v, v)`` with
    ``II(v, v) = k_m (v . e_m)^2 + k_p (v . e_p)^2`` (meridian and parallel
    curvatures ``k_m = (z' rho'' - rho' z'') / |P'|^3``, ``k_p = -z' / (rho |P'|)``
    for ``N = (z' r - rho' a) / |P'|``).  With it a flip at the point's own
    contour lies exactly where ``N . v = 0``.  Profiles whose heights are not
    monotone on the grid, and points whose parameter is not recovered to
    ``1e-9`` of the size, are left to the ray test (not decided)."""
    out = np.zeros(len(o), bool)
    g = surface._grid
    dzs = np.diff(g["z"])
    if not len(o) or not (np.all(dzs > 0) or np.all(dzs < 0)):
        return out, out.copy(), np.full(len(o), np.nan), np.full(len(o), np.nan)
    a = surface.frame[2]
    h, r, _ = meridian_coordinates(surface, o)
    radial = o - h[:, None] * a
    t, rho, found = _recovered(surface, h, r)
    dr, dz = surface.drz(t)
    ddr, ddz = surface.ddrz(t)
    speed = np.hypot(dr, dz)
    with np.errstate(invalid="ignore", divide="ignore"):
        rhat = radial / r[:, None]
        va = vh @ a
        vr = np.einsum("ij,ij->i", rhat, vh)
        vp = np.einsum("ij,ij->i", np.cross(a, rhat), vh)
        nv = (dz * vr - dr * va) / speed
        vm = (dr * vr + dz * va) / speed
        k_m = (dz * ddr - dr * ddz) / speed**3
        k_p = -dz / (rho * speed)
        lam2 = 2 * nv / (k_m * vm * vm + k_p * vp * vp)
    found &= r > 0
    hit = found & (lam2 > 0) & (lam2 <= eps)
    return hit, found, np.where(found, nv, np.nan), np.where(found, t, np.nan)


def point_parameters(surface: Revolved, o: np.ndarray) -> np.ndarray:
    """The parameter ``t`` of points ``o`` on the surface (NaN where it is not
    recovered to ``1e-9`` of the size; profiles with monotone heights)."""
    h, r, _ = meridian_coordinates(surface, o)
    t, _, found = _recovered(surface, h, r)
    return np.where(found, t, np.nan)


def _recovered(
    surface: Revolved, h: np.ndarray, r: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``t`` of the meridian points ``(r, h)``, ``rho(t)``, and whether the
    point lies on the profile there to ``1e-9`` of the size."""
    t = t_of_points(surface, h, r)
    rho, z = surface.rz(t)
    return t, rho, np.hypot(rho - r, z - h) <= 1e-9 * surface.size
