"""Transition functions of a surface of revolution for the renderer's flip search.

Along a curve on the surface, the surface starts or stops hiding the curve's
point ``x`` (ray ``x + s v`` toward the viewer) where

* ``x`` crosses the surface's own contour: ``N(x) . v = 0``; on a certified
  convex closed surface this is the only way, and ``-N . v`` is positive
  exactly where the point is hidden (:mod:`lgraph.surfaces.revolution._convex`);
* the ray passes through a rim, the boundary parallel ``t_e`` (not a pole):
  the line meets that circle exactly when
  ``F_e = c^2 (rho_e^2 - d^2) - k^2 (z_e - h*)^2 = 0`` (``c = v . a``,
  ``k^2 = 1 - c^2``, ``d`` the line's distance from the axis and ``h*`` the
  height where it comes closest; the ray function of
  :mod:`lgraph.surfaces.revolution._hits` at ``t_e``), smooth in ``x``;
* the ray grazes the surface elsewhere: two roots of ``F`` merge at an
  extremum (:func:`~lgraph.surfaces.revolution._hits.grazing`).

For a profile with monotone heights grazing rays (and rims again) are covered
by one function, the far margin of :mod:`lgraph.surfaces.revolution._fast`
(positive exactly where the ray test hits past the point's own cell, and
continuous also where a pair of extrema of ``F`` is born), and contour
points get ``F''`` at the point, which vanishes at the cusps of the apparent
contour.

:meth:`SurfaceOfRevolution.visibility_margins` returns these functions; the
renderer root-finds the one that changes sign across a flip and verifies the
result with the full ray test (docs/mathematics.rst, "Surfaces of
revolution").
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..._own import CONTOUR, OFF
from ..._tolerance import SELF_HIT_RTOL
from ._convex import convex_sign, margin
from ._fast import cusp_function, far_margin, monotone_tables, own_sign
from ._hits import CONTOUR_SELF_RTOL, FLAT_C, GRAZE_FTOL, _blocks, grazing, ray_terms
from ._local import normal_component, point_parameters

if TYPE_CHECKING:
    from ._protocol import Revolved

__all__ = ["far_rows", "margins", "rim_function"]


def rim_function(surface: Revolved, o: np.ndarray, v: np.ndarray, t_e: float) -> np.ndarray:
    """``F_e / size^2`` (module docstring): zero where the line ``o + s v``
    meets the parallel ``t_e``."""
    _, _, _, c, k2, d2, hstar, _ = ray_terms(surface, o, v)
    rho_e, z_e = (float(x[0]) for x in surface.rz(np.array([t_e])))
    f = c * c * (rho_e * rho_e - d2) - k2 * (z_e - hstar) ** 2
    return f / surface.size**2


def margins(
    surface: Revolved,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray,
    uv: np.ndarray | None = None,
    which: int | None = None,
) -> np.ndarray:
    """The transition functions, ``(k, n)`` (only row ``which`` when given): on
    a certified convex surface its exact hiding margin alone; otherwise
    ``N . v / |v|`` (NaN where ``uv`` is unknown and on contour curves), one
    rim function per boundary parallel that is not a pole (cheap and smooth:
    tried before the rest), then for a profile with monotone heights the
    cusp function of contour points and the far margin (:func:`far_rows`),
    for other profiles the grazing function
    (:func:`~lgraph.surfaces.revolution._hits.grazing`)."""
    o = np.asarray(origins, float).reshape(-1, 3)
    v = np.asarray(directions, float).reshape(-1, 3)
    own = np.asarray(own)
    if convex_sign(surface):
        return margin(surface, o, v, smax, own, uv)[None]
    t = np.full(len(o), np.nan) if uv is None else np.asarray(uv, float).reshape(-1, 2)[:, 0]
    tab = monotone_tables(surface, _blocks(surface)["cellpad"])
    rims = [] if surface.profile_closed else [
        end for end, pole in zip(surface.t_range, surface.poles) if not pole
    ]  # fmt: skip
    n_rows = len(rims) + (3 if tab is not None else 2)

    def row(k: int) -> np.ndarray:
        if k == 0:
            nv = np.full(len(o), np.nan)
            on = np.flatnonzero((own != OFF) & (own != CONTOUR) & np.isfinite(t))
            if len(on):
                nv[on] = normal_component(surface, o[on], v[on], t[on])
            return nv
        if k <= len(rims):
            return rim_function(surface, o, v, rims[k - 1])
        if tab is not None:
            return far_rows(surface, tab, o, v, smax, own, t, k - len(rims))
        return grazing(surface, o, v, smax, own)

    if which is not None:
        return row(which)[None]
    return np.stack([row(k) for k in range(n_rows)])


def far_rows(
    surface: Revolved,
    tab: dict,
    o: np.ndarray,
    v: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray,
    t: np.ndarray,
    k: int,
) -> np.ndarray:
    """Row 1: on contour curves, ``F''`` at the point
    (:func:`~lgraph.surfaces.revolution._fast.cusp_function`: zero at a
    cusp of the apparent contour, where the contour starts or stops hiding
    behind the surface next to it); row 2: the far margin
    (:func:`~lgraph.surfaces.revolution._fast.far_margin`: positive exactly
    where the ray test finds a hit past the point's own cell, continuous
    where it changes, so it locates grazing rays, rays past a rim and rays
    past a cusp alike).  Steep rays only (NaN elsewhere).  ``t``: the
    points' parameters (NaN: found from the points)."""
    n = len(o)
    out = np.full(n, np.nan)
    g = surface._grid
    size = g["size"]
    speed, vh, oa, c, k2, d2, hs, _ = ray_terms(surface, o, v)
    pick = (own != OFF) & (np.abs(c) >= FLAT_C) & ((own == CONTOUR) if k == 1 else True)
    idx = np.flatnonzero(pick)
    if not len(idx):
        return out
    t = t[idx].copy()
    lost = np.flatnonzero(~np.isfinite(t))
    if len(lost):
        t[lost] = point_parameters(surface, o[idx[lost]])
    contour = own[idx] == CONTOUR
    lam_max = np.broadcast_to(np.asarray(smax, float), (n,))[idx] * speed[idx]
    eps = np.where(contour, CONTOUR_SELF_RTOL, SELF_HIT_RTOL) * size
    ray = (c[idx], k2[idx], d2[idx], hs[idx], oa[idx], eps, lam_max)
    if k == 1:
        out[idx] = cusp_function(surface, ray, np.arange(len(idx)), t)
        return out
    nv = np.full(len(idx), np.nan)
    axial = o[idx] - oa[idx, None] * surface.frame[2]
    on = np.flatnonzero(~contour & np.isfinite(t) & (np.einsum("ij,ij->i", axial, axial) > 0))
    if len(on):
        nv[on] = normal_component(surface, o[idx[on]], vh[idx[on]], t[on])
        # rays decided by the local analysis (the ray test's eps there)
        eps[on] = CONTOUR_SELF_RTOL * size
    s0 = own_sign(surface, tab, ray, contour, t, nv)
    out[idx] = far_margin(surface, tab, ray, s0, GRAZE_FTOL * size * size) / size**2
    return out
