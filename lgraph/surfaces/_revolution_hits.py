"""Ray test of a surface of revolution, reduced to one root problem in ``t`` per ray.

A line ``o + lam v`` (``|v| = 1``) has height ``h = o_a + c lam`` along the axis
(``c = v . a``) and squared distance ``r^2 = d^2 + k^2 (lam - s*)^2`` from it
(``k^2 = 1 - c^2``, ``d`` its distance from the axis, reached at ``lam = s*``,
height ``h*``).  It meets the parallel ``t`` exactly where

    F(t) = c^2 (rho(t)^2 - d^2) - k^2 (z(t) - h*)^2 = 0,

the meridian section of the hyperboloid of revolution the line sweeps; there
``lam = s* + (z - h*) / c`` (or, for lines nearly perpendicular to the axis,
``lam = s* +- sqrt(rho^2 - d^2) / k``, the one consistent with the height).

``F`` and ``F'`` are evaluated on the profile grid for all candidate rays at
once.  Roots are taken from (1) grid nodes where ``|F|`` is at rounding level,
(2) sign changes between nodes, refined by Illinois to machine precision, and
(3) every cell where ``F`` turns back toward zero (``F'`` changes sign the
right way): its extremum is located (a root of ``F'``) and either splits the
cell into two sign changes or is itself a double root.  So a grazing ray
whose two roots fall into one cell is never missed, provided a cell holds at
most one extremum of ``F`` (the profile grid resolves the profile's turns).
Rays that miss the surface's bounding cylinder are rejected first.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .._own import CONTOUR, ON
from .._tolerance import SELF_HIT_RTOL

if TYPE_CHECKING:
    from .revolution import SurfaceOfRevolution

__all__ = ["hits"]

#: |F| below this (times size^2) is a root: rounding level of F, about 100 ulp
GRAZE_FTOL = 1e-14
#: rays from contour points: roots this close (times size) are the point's own tangency
CONTOUR_SELF_RTOL = 1e-6
#: lines with |v . a| below this take their roots' ray parameter from the radius
FLAT_C = 1e-3
#: a root's ray parameter from the radius must agree with its height to this (times size)
FLAT_RTOL = 1e-7
#: (rays x grid nodes) per chunk of the scan
CHUNK = 1 << 20


def hits(
    surface: SurfaceOfRevolution,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray | None = None,
) -> np.ndarray:
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    v = np.asarray(directions, dtype=float).reshape(-1, 3)
    n = len(o)
    out = np.zeros(n, bool)
    if not n:
        return out
    smax = np.broadcast_to(np.asarray(smax, dtype=float), (n,))
    own = np.zeros(n, np.int8) if own is None else np.asarray(own)
    g = surface._grid
    size = g["size"]
    speed = np.linalg.norm(v, axis=1)
    vh = v / speed[:, None]
    a = g["frame"][2]
    oa, c = o @ a, vh @ a
    op = o - oa[:, None] * a
    vp = vh - c[:, None] * a
    k2 = np.einsum("ij,ij->i", vp, vp)
    with np.errstate(invalid="ignore", divide="ignore"):
        sstar = np.where(k2 > 1e-300, -np.einsum("ij,ij->i", op, vp) / k2, 0.0)
    q = op + sstar[:, None] * vp
    d2 = np.einsum("ij,ij->i", q, q)
    hstar = oa + c * sstar
    lam_max = smax * speed
    flat = np.abs(c) < FLAT_C
    rtol = np.where(own == CONTOUR, CONTOUR_SELF_RTOL, SELF_HIT_RTOL)
    rtol = np.where((own == ON) & flat, FLAT_RTOL, rtol)
    eps = rtol * size
    # bounding cylinder: the part of the ray inside the slab of heights, nearest the axis
    rho, z = g["rho"], g["z"]
    pad = 0.02 * size
    zlo, zhi, rmax = z.min() - pad, z.max() + pad, rho.max() + pad
    with np.errstate(invalid="ignore", divide="ignore"):
        l1, l2 = (zlo - oa) / c, (zhi - oa) / c
    inslab = (oa >= zlo) & (oa <= zhi)
    lo = np.where(flat & (c == 0), np.where(inslab, -np.inf, np.inf), np.minimum(l1, l2))
    hi = np.where(flat & (c == 0), np.where(inslab, np.inf, -np.inf), np.maximum(l1, l2))
    lo, hi = np.maximum(lo, 0.0), np.minimum(hi, lam_max)
    near = np.clip(sstar, lo, hi)
    with np.errstate(invalid="ignore"):
        r2min = d2 + k2 * (near - sstar) ** 2
    cand = np.nonzero((hi >= lo) & (r2min <= rmax * rmax))[0]
    if not len(cand):
        return out
    m = len(g["t"])
    step = max(1, CHUNK // m)
    for start in range(0, len(cand), step):
        r = cand[start : start + step]
        out[r] = _scan(surface, c[r], k2[r], d2[r], hstar[r], sstar[r], eps[r], lam_max[r])
    return out


def _scan(
    surface: SurfaceOfRevolution,
    c: np.ndarray,
    k2: np.ndarray,
    d2: np.ndarray,
    hs: np.ndarray,
    ss: np.ndarray,
    eps: np.ndarray,
    lam_max: np.ndarray,
) -> np.ndarray:
    """Whether each line has a root with ``eps < lam < lam_max``."""
    from .ruled import _illinois

    g = surface._grid
    t, rho, z, drho, dz = g["t"], g["rho"], g["z"], g["drho"], g["dz"]
    size = g["size"]
    ftol = GRAZE_FTOL * size * size
    span = t[-1] - t[0]
    c2 = c * c
    C2, K2, D2, H = c2[:, None], k2[:, None], d2[:, None], hs[:, None]
    dzh = z - H
    F = C2 * (rho * rho - D2) - K2 * dzh * dzh
    dF = 2 * (C2 * rho * drho - K2 * dzh * dz)
    pos = F > 0
    small = np.abs(F) <= ftol
    root_ray = [np.nonzero(small)[0]]
    root_t = [np.broadcast_to(t, F.shape)[small]]
    bi, bj = np.nonzero(pos[:, :-1] != pos[:, 1:])
    br_ray, br_a, br_b = [bi], [t[bj]], [t[bj + 1]]
    br_fa, br_fb = [F[bi, bj]], [F[bi, bj + 1]]
    F0, F1, G0, G1 = F[:, :-1], F[:, 1:], dF[:, :-1], dF[:, 1:]
    turn = (
        (pos[:, :-1] == pos[:, 1:])
        & ~small[:, :-1]
        & ~small[:, 1:]
        & (((F0 > 0) & (G0 < 0) & (G1 > 0)) | ((F0 < 0) & (G0 > 0) & (G1 < 0)))
    )
    ei, ej = np.nonzero(turn)

    def f_at(x: np.ndarray, ray: np.ndarray) -> np.ndarray:
        rr, zz = surface.rz(x)
        h = zz - hs[ray]
        return c2[ray] * (rr * rr - d2[ray]) - k2[ray] * h * h

    if len(ei):

        def df_at(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
            ray = ei[sel]
            rr, zz = surface.rz(x)
            dr, dzz = surface.drz(x)
            return 2 * (c2[ray] * rr * dr - k2[ray] * (zz - hs[ray]) * dzz)

        te = _illinois(df_at, t[ej], t[ej + 1], G0[ei, ej], G1[ei, ej], 4e-16 * span)
        fe = f_at(te, ei)
        flip = (fe > 0) != (F0[ei, ej] > 0)
        touch = ~flip & (np.abs(fe) <= ftol)
        root_ray.append(ei[touch])
        root_t.append(te[touch])
        fi, fj, tf, ff = ei[flip], ej[flip], te[flip], fe[flip]
        br_ray += [fi, fi]
        br_a += [t[fj], tf]
        br_b += [tf, t[fj + 1]]
        br_fa += [F0[fi, fj], ff]
        br_fb += [ff, F1[fi, fj]]
    ray = np.concatenate(br_ray)
    if len(ray):
        a, b = np.concatenate(br_a), np.concatenate(br_b)
        fa, fb = np.concatenate(br_fa), np.concatenate(br_fb)
        x = _illinois(lambda x, sel: f_at(x, ray[sel]), a, b, fa, fb, 4e-16 * span)
        root_ray.append(ray)
        root_t.append(x)
    rr, tt = np.concatenate(root_ray), np.concatenate(root_t)
    hit = np.zeros(len(c), bool)
    if not len(rr):
        return hit
    rho_r, z_r = surface.rz(tt)
    h = z_r - hs[rr]
    cr, k = c[rr], np.sqrt(k2[rr])
    with np.errstate(invalid="ignore", divide="ignore"):
        steep = np.abs(cr) >= FLAT_C
        lam = [np.where(steep, ss[rr] + h / np.where(steep, cr, 1.0), np.nan)]
        half = np.sqrt(np.maximum(rho_r * rho_r - d2[rr], 0.0)) / np.where(k > 0, k, 1.0)
        # the parallel must reach the line (rho >= d) and the height must agree
        reach = np.sqrt(d2[rr]) - rho_r <= FLAT_RTOL * size
        for sign in (1.0, -1.0):
            ok = ~steep & reach & (np.abs(cr * sign * half - h) <= FLAT_RTOL * size)
            lam.append(np.where(ok, ss[rr] + sign * half, np.nan))
    for lm in lam:
        good = (lm > eps[rr]) & (lm < lam_max[rr])
        hit[rr[good]] = True
    return hit
