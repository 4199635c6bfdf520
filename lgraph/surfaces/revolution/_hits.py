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

Broad phase: the profile grid is cut into blocks of ``BLOCK`` cells, each
bounded by a ring (``rho`` and ``z`` ranges padded by a bound on the profile's
bulge between nodes); a ray is scanned only on the blocks whose rings it
enters.  Narrow phase: a cell whose ray-parameter range (from its padded
heights) lies inside ``(eps, lam_max)`` decides a sign change at once; only
cells straddling those limits are refined (safeguarded Newton on ``F``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..._own import CONTOUR, OFF, ON
from ..._tolerance import SELF_HIT_RTOL
from ._fast import monotone_tables, newton, own_sign, scan
from ._local import own_second_root, point_parameters

if TYPE_CHECKING:
    from ._protocol import Revolved

__all__ = ["grazing", "hits", "ray_terms"]

#: |F| below this (times size^2) is a root: rounding level of F, about 100 ulp
GRAZE_FTOL = 1e-14
#: rays from contour points: roots this close (times size) are the point's own tangency
CONTOUR_SELF_RTOL = 1e-6
#: lines with |v . a| below this take their roots' ray parameter from the radius
FLAT_C = 1e-3
#: a root's ray parameter from the radius must agree with its height to this (times size)
FLAT_RTOL = 1e-7
#: Newton stops where |F| is below this (times size^2): its rounding level
NEWTON_FTOL = 1e-16
#: grid cells per block of the broad phase
BLOCK = 16
#: (rays x blocks) per chunk of the broad phase
CHUNK = 1 << 20


def _blocks(surface: Revolved) -> dict:
    """Ring bounds of blocks of ``BLOCK`` grid cells (cached on the surface)."""
    g = surface._grid
    if "blocks" in g:
        return g["blocks"]
    t, rho, z = g["t"], g["rho"], g["z"]
    m = len(t) - 1
    # bulge of the profile off each cell's chord: (dt^2 / 8) max |P''|, with |P''|
    # from second differences of the nodes (doubled for safety)
    dt = np.diff(t)
    d2 = np.zeros(m + 1)
    d2[1:-1] = np.hypot(np.diff(rho, 2), np.diff(z, 2)) / (dt[1:] * dt[:-1])
    d2[0], d2[-1] = d2[1], d2[-2]
    cellpad = 0.25 * dt * dt * np.maximum(d2[:-1], d2[1:]) + 1e-9 * g["size"]
    nb = -(-m // BLOCK)
    j0 = np.arange(nb) * BLOCK
    j1 = np.minimum(j0 + BLOCK, m)
    rlo = np.array([rho[a : b + 1].min() for a, b in zip(j0, j1)])
    rhi = np.array([rho[a : b + 1].max() for a, b in zip(j0, j1)])
    zlo = np.array([z[a : b + 1].min() for a, b in zip(j0, j1)])
    zhi = np.array([z[a : b + 1].max() for a, b in zip(j0, j1)])
    bpad = np.array([cellpad[a:b].max() for a, b in zip(j0, j1)])
    out = {
        "j0": j0, "rlo": np.maximum(rlo - bpad, 0.0), "rhi": rhi + bpad,
        "zlo": zlo - bpad, "zhi": zhi + bpad, "cellpad": cellpad,
    }  # fmt: skip
    g["blocks"] = out
    return out


def ray_terms(surface: Revolved, o: np.ndarray, v: np.ndarray) -> tuple:
    """``(|v|, v / |v|, o . a, c, k^2, d^2, h*, s*)`` of the lines ``o + s v``
    (module docstring; ``s*`` where they come closest to the axis)."""
    speed = np.sqrt(np.einsum("ij,ij->i", v, v))
    vh = v / speed[:, None]
    a = surface.frame[2]
    oa, c = o @ a, vh @ a
    op = o - oa[:, None] * a
    vp = vh - c[:, None] * a
    k2 = np.einsum("ij,ij->i", vp, vp)
    with np.errstate(invalid="ignore", divide="ignore"):
        sstar = np.where(k2 > 1e-300, -np.einsum("ij,ij->i", op, vp) / k2, 0.0)
    q = op + sstar[:, None] * vp
    d2 = np.einsum("ij,ij->i", q, q)
    return speed, vh, oa, c, k2, d2, oa + c * sstar, sstar


def ray_derivatives(
    surface: Revolved, c2: np.ndarray, k2: np.ndarray, hs: np.ndarray
) -> Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """``(F', F'')`` at ``t = x`` of the rays ``rows`` (per-ray ``c^2``,
    ``k^2`` and ``h*``; ``F = c^2 (rho^2 - d^2) - k^2 (z - h*)^2``)."""

    def d_dd(x: np.ndarray, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        rr, zz = surface.rz(x)
        dr, dzz = surface.drz(x)
        ddr, ddz = surface.ddrz(x)
        cc, kk, h = c2[rows], k2[rows], zz - hs[rows]
        return (
            2 * (cc * rr * dr - kk * h * dzz),
            2 * (cc * (dr * dr + rr * ddr) - kk * (dzz * dzz + h * ddz)),
        )

    return d_dd


def grazing(
    surface: Revolved,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray,
) -> np.ndarray:
    """``-sign(F''(t*)) F(t*) / size^2 + GRAZE_FTOL`` at the extremum ``t*`` of
    each ray's function ``F`` that is nearest to zero among those inside the
    ray's range (NaN: none, or a line nearly perpendicular to the axis).
    Where the ray starts or stops grazing the surface away from its point,
    two roots of ``F`` merge at such an extremum: this value changes sign
    there, smoothly along a curve, exactly where :func:`hits` (which counts
    ``|F(t*)| <= GRAZE_FTOL size^2`` as touching) changes its answer."""
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    v = np.asarray(directions, dtype=float).reshape(-1, 3)
    n = len(o)
    out = np.full(n, np.nan)
    if not n:
        return out
    g = surface._grid
    size, t = g["size"], g["t"]
    span = t[-1] - t[0]
    speed, _, _, c, k2, d2, hs, ss = ray_terms(surface, o, v)
    lam_max = np.broadcast_to(np.asarray(smax, dtype=float), (n,)) * speed
    cut = np.where(np.asarray(own) == OFF, SELF_HIT_RTOL, CONTOUR_SELF_RTOL) * size
    C2, K2 = (c * c)[:, None], k2[:, None]
    dzh = g["z"] - hs[:, None]
    dF = 2 * (C2 * g["rho"] * g["drho"] - K2 * dzh * g["dz"])
    ri, cj = np.nonzero((dF[:, :-1] > 0) != (dF[:, 1:] > 0))
    if not len(ri):
        return out

    derivatives = ray_derivatives(surface, c * c, k2, hs)

    def d_dd(x: np.ndarray, sel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return derivatives(x, ri[sel])

    # F is flat at its extremum: t to 1e-9 gives F there to rounding level
    te = newton(d_dd, t[cj], t[cj + 1], dF[ri, cj], dF[ri, cj + 1], 1e-9 * span, 0.0)
    rr, zz = surface.rz(te)
    h = zz - hs[ri]
    fe = (c * c)[ri] * (rr * rr - d2[ri]) - k2[ri] * h * h
    curv = d_dd(te, np.arange(len(te)))[1]
    steep = np.abs(c[ri]) >= FLAT_C
    with np.errstate(invalid="ignore", divide="ignore"):
        lam = ss[ri] + h / np.where(steep, c[ri], 1.0)
    ok = steep & (lam > cut[ri]) & (lam < lam_max[ri])
    ri, fe, curv = ri[ok], fe[ok], curv[ok]
    order = np.lexsort((np.abs(fe), ri))  # by ray, then |F|
    ri, fe, curv = ri[order], fe[order], curv[order]
    first = np.concatenate([[True], ri[1:] != ri[:-1]]) if len(ri) else np.zeros(0, bool)
    # oriented to be positive where the two roots exist (below a minimum, above
    # a maximum), shifted by the band where the ray test counts a touching
    out[ri[first]] = -np.sign(curv[first]) * fe[first] / size**2 + GRAZE_FTOL
    return out


def hits(
    surface: Revolved,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray | None = None,
    *,
    general: bool = False,
) -> np.ndarray:
    """Which rays ``origins + s directions``, ``0 < s < smax``, meet the surface
    (``own``: where the origins lie, see :mod:`lgraph._own`).  Rays of a
    profile with monotone heights go through
    :func:`~lgraph.surfaces.revolution._fast.scan`, the others (and all, with ``general=True``: the
    reference for tests) through the scan of ring-bounded blocks."""
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
    speed, vh, oa, c, k2, d2, hstar, sstar = ray_terms(surface, o, v)
    lam_max = smax * speed
    flat = np.abs(c) < FLAT_C
    rtol = np.where(own == CONTOUR, CONTOUR_SELF_RTOL, SELF_HIT_RTOL)
    rtol = np.where((own == ON) & flat, FLAT_RTOL, rtol)
    eps = rtol * size
    on = np.flatnonzero(own == ON)
    nv, t_own = np.full(n, np.nan), np.full(n, np.nan)
    if len(on):  # second roots near the point's own (at its contour): local analysis
        cut = CONTOUR_SELF_RTOL * size
        out[on], decided, nv[on], t_own[on] = own_second_root(surface, o[on], vh[on], cut)
        eps[on[decided]] = np.maximum(eps[on[decided]], cut)
    rest = np.flatnonzero(~out)
    blk = _blocks(surface)
    tab = None if general else monotone_tables(surface, blk["cellpad"])
    if tab is not None:  # monotone heights: one run of cells per steep ray
        fast = rest[~flat[rest]]
        con = fast[own[fast] == CONTOUR]
        if len(con):
            t_own[con] = point_parameters(surface, o[con])
        ray = (c[fast], k2[fast], d2[fast], hstar[fast], oa[fast], eps[fast], lam_max[fast])
        s0 = own_sign(surface, tab, ray, own[fast] == CONTOUR, t_own[fast], nv[fast])
        sub = np.zeros(len(fast), bool)
        done = scan(surface, tab, ray, own[fast] != OFF, s0, GRAZE_FTOL * size * size, sub)
        out[fast] = sub
        keep = np.ones(n, bool)
        keep[fast[done]] = False
        rest = rest[keep[rest]]
    if not len(rest):
        return out
    if len(rest) < n:  # the general test on the rest
        sub = out[rest]
        _general(surface, blk, rest, oa, c, k2, d2, hstar, sstar, eps, lam_max, sub)
        out[rest] = sub
    else:
        _general(surface, blk, slice(None), oa, c, k2, d2, hstar, sstar, eps, lam_max, out)
    return out


def _general(surface, blk, sel, oa, c, k2, d2, hstar, sstar, eps, lam_max, out) -> None:  # noqa: ANN001
    """The scan on ring-bounded blocks of the grid for the rays ``sel``."""
    oa, c, k2, d2, hstar, sstar, eps, lam_max = (
        x[sel] for x in (oa, c, k2, d2, hstar, sstar, eps, lam_max)
    )
    n = len(c)
    nb = len(blk["j0"])
    step = max(1, CHUNK // nb)
    pairs_r, pairs_b = [], []
    for start in range(0, n, step):
        sl = slice(start, start + step)
        r, b = _broad(blk, oa[sl], c[sl], k2[sl], d2[sl], sstar[sl], eps[sl], lam_max[sl])
        pairs_r.append(r + start)
        pairs_b.append(b)
    pr, pb = np.concatenate(pairs_r), np.concatenate(pairs_b)
    if not len(pr):
        return
    ray = (c, k2, d2, hstar, sstar, eps, lam_max)
    _narrow(surface, blk, pr, pb, ray, out)


def _broad(blk: dict, oa, c, k2, d2, ss, eps, lam_max) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001
    """(ray, block) pairs whose ring the ray segment ``eps < lam < lam_max`` enters."""
    C = c[:, None]
    with np.errstate(invalid="ignore", divide="ignore"):
        l1 = (blk["zlo"] - oa[:, None]) / C
        l2 = (blk["zhi"] - oa[:, None]) / C
    zero = C == 0
    inslab = (oa[:, None] >= blk["zlo"]) & (oa[:, None] <= blk["zhi"])
    lo = np.where(zero, np.where(inslab, -np.inf, np.inf), np.minimum(l1, l2))
    hi = np.where(zero, np.where(inslab, np.inf, -np.inf), np.maximum(l1, l2))
    lo = np.maximum(lo, eps[:, None])
    hi = np.minimum(hi, lam_max[:, None])
    S, K2, D2 = ss[:, None], k2[:, None], d2[:, None]
    near = np.clip(S, lo, hi)
    with np.errstate(invalid="ignore"):
        rmin2 = D2 + K2 * (near - S) ** 2
        far = np.maximum(np.abs(lo - S), np.abs(hi - S))
        rmax2 = D2 + K2 * far * far
    ok = (hi >= lo) & (rmin2 <= blk["rhi"] ** 2) & (rmax2 >= blk["rlo"] ** 2)
    return np.nonzero(ok)


def _trimmed(surface: Revolved, ray, pr, p, a, b, za, zb, dza, span):  # noqa: ANN001, ANN202
    """Cells ``[a, b]`` (pairs ``p``, ``z`` monotone) cut to ``eps < lam < lam_max``,
    ``lam = (z - o_a) / c``: the cell tuple of :func:`_narrow` (all inside the range)."""
    c, k2, d2, hs, ss, eps, lam_max = ray
    r = pr[p]
    oa = hs[r] - c[r] * ss[r]
    lam_a, lam_b = (za - oa) / c[r], (zb - oa) / c[r]
    lo_t, hi_t = a.copy(), b.copy()
    keep = np.ones(len(a), bool)
    for limit, above in ((eps[r], True), (lam_max[r], False)):
        fin = np.isfinite(limit)
        za_ = np.where(fin, oa + c[r] * np.where(fin, limit, 0.0), 0.0)
        ina = (lam_a > limit) == above
        inb = (lam_b > limit) == above
        keep &= ina | inb
        cut = fin & (ina != inb) & keep
        if cut.any():
            k = np.flatnonzero(cut)
            zt = za_[k]

            def f_df(x: np.ndarray, sel: np.ndarray, zt: np.ndarray = zt, k: np.ndarray = k) -> Any:
                return surface.rz(x)[1] - zt[sel], surface.drz(x)[1]

            tc = newton(f_df, lo_t[k], hi_t[k], za[k] - zt, zb[k] - zt, 4e-16 * span, 0.0)
            # the end outside the range moves to the cut
            lo_t[k] = np.where(ina[k], lo_t[k], tc)
            hi_t[k] = np.where(ina[k], tc, hi_t[k])
    p, lo_t, hi_t = p[keep], lo_t[keep], hi_t[keep]
    r = pr[p]
    both = np.concatenate([lo_t, hi_t])
    rr, zz = surface.rz(both)
    dr, dzz = surface.drz(both)
    rp = np.concatenate([r, r])
    cc, kk, h = (c * c)[rp], k2[rp], zz - hs[rp]
    f = cc * (rr * rr - d2[rp]) - kk * h * h
    df = 2 * (cc * rr * dr - kk * h * dzz)
    n = len(p)
    return (p, lo_t, hi_t, f[:n], f[n:], df[:n], df[n:], np.ones(n, bool))


def _narrow(surface: Revolved, blk: dict, pr, pb, ray, out) -> None:  # noqa: ANN001
    """Scan the (ray, block) pairs on the fine grid; set ``out[ray]`` for hits."""
    c, k2, d2, hs, ss, eps, lam_max = ray
    g = surface._grid
    size = g["size"]
    ftol = GRAZE_FTOL * size * size
    t_all = g["t"]
    m = len(t_all) - 1
    span = t_all[-1] - t_all[0]
    # nodes of each pair's block (blocks at the end may be shorter: clamp, and mask)
    j = blk["j0"][pb][:, None] + np.arange(BLOCK + 1)
    valid_cell = j[:, 1:] <= m
    j = np.minimum(j, m)
    t, rho, z = t_all[j], g["rho"][j], g["z"][j]
    drho, dz = g["drho"][j], g["dz"][j]
    C2 = (c * c)[pr][:, None]
    K2, D2, H = k2[pr][:, None], d2[pr][:, None], hs[pr][:, None]
    dzh = z - H
    F = C2 * (rho * rho - D2) - K2 * dzh * dzh
    dF = 2 * (C2 * rho * drho - K2 * dzh * dz)
    # each cell's range of the ray parameter (steep rays; flat rays: unknown)
    cp = blk["cellpad"][np.minimum(j[:, :-1], m - 1)]
    zc_lo = np.minimum(z[:, :-1], z[:, 1:]) - cp
    zc_hi = np.maximum(z[:, :-1], z[:, 1:]) + cp
    cr = c[pr][:, None]
    steep = np.abs(cr) >= FLAT_C
    with np.errstate(invalid="ignore", divide="ignore"):
        l1 = ss[pr][:, None] + (zc_lo - H) / cr
        l2 = ss[pr][:, None] + (zc_hi - H) / cr
    llo = np.where(steep, np.minimum(l1, l2), -np.inf)
    lhi = np.where(steep, np.maximum(l1, l2), np.inf)
    E, LM = eps[pr][:, None], lam_max[pr][:, None]
    outside = (lhi <= E) | (llo >= LM) | ~valid_cell
    inside = (llo > E) & (lhi < LM)
    pos = F > 0
    # cells of steep rays straddling lam = eps or lam = lam_max where z is monotone:
    # cut to the part with eps < lam < lam_max (lam = (z - o_a) / c along a steep
    # line), so a ray's own root (lam = 0) is never refined
    dz0, dz1 = dz[:, :-1], dz[:, 1:]
    trim = steep & ~outside & ~inside & (dz0 * dz1 > 0)
    outside = outside | trim
    change = (pos[:, :-1] != pos[:, 1:]) & ~outside
    # sure hits: a sign change inside the ray's range
    sure = change & inside
    out[pr[sure.any(axis=1)]] = True
    F0, F1, G0, G1 = F[:, :-1], F[:, 1:], dF[:, :-1], dF[:, 1:]
    # cells to search: (pair, t_a, t_b, F_a, F_b, F'_a, F'_b, whole cell inside the range)
    ci, cj = np.nonzero(~outside)
    cells = [(ci, t[ci, cj], t[ci, cj + 1], F0[ci, cj], F1[ci, cj], G0[ci, cj], G1[ci, cj],
              inside[ci, cj])]  # fmt: skip
    ti, tj = np.nonzero(trim & ~out[pr][:, None])
    if len(ti):
        cells.append(_trimmed(surface, ray, pr, ti, t[ti, tj], t[ti, tj + 1],
                              z[ti, tj], z[ti, tj + 1], dz0[ti, tj], span))  # fmt: skip
    ci, ta, tb, fa0, fb0, ga0, gb0, whole = (np.concatenate(x) for x in zip(*cells))
    live = ~out[pr[ci]]
    ci, ta, tb, fa0, fb0, ga0, gb0, whole = (
        x[live] for x in (ci, ta, tb, fa0, fb0, ga0, gb0, whole)
    )
    chg = (fa0 > 0) != (fb0 > 0)
    out[pr[ci[chg & whole]]] = True
    # a cut end lies within the self-hit distance of the ray's own root, where F is
    # small without a root of interest: only grid nodes count as touching roots
    node = np.concatenate(
        [np.ones(len(cells[0][0]), bool)] + [np.zeros(len(x[0]), bool) for x in cells[1:]]
    )[live]
    sa, sb = node & (np.abs(fa0) <= ftol), node & (np.abs(fb0) <= ftol)
    if not g["closed"]:
        # at a rim only a sign change counts: the flip where a ray passes the rim
        # is then exactly where F at the end changes sign (no touching band)
        sa &= ta != t_all[0]
        sb &= tb != t_all[-1]
    turn = (
        ~chg
        & ~sa
        & ~sb
        & (((fa0 > 0) & (ga0 < 0) & (gb0 > 0)) | ((fa0 < 0) & (ga0 > 0) & (gb0 < 0)))
    )
    root_p, root_t = [ci[sa], ci[sb]], [ta[sa], tb[sb]]
    bsel = chg & ~whole
    br_p, br_a, br_b, br_fa, br_fb = [ci[bsel]], [ta[bsel]], [tb[bsel]], [fa0[bsel]], [fb0[bsel]]

    def f_at(x: np.ndarray, p: np.ndarray) -> np.ndarray:
        rr, zz = surface.rz(x)
        h = zz - hs[pr[p]]
        return (c * c)[pr[p]] * (rr * rr - d2[pr[p]]) - k2[pr[p]] * h * h

    ei = np.flatnonzero(turn)
    if len(ei):
        ep = ci[ei]

        derivatives = ray_derivatives(surface, c * c, k2, hs)

        def d_dd(x: np.ndarray, sel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            return derivatives(x, pr[ep[sel]])

        # F is flat at its extremum: t to 1e-9 gives F there to rounding level
        te = newton(d_dd, ta[ei], tb[ei], ga0[ei], gb0[ei], 1e-9 * span, 0.0)
        fe = f_at(te, ep)
        flip = (fe > 0) != (fa0[ei] > 0)
        touch = np.abs(fe) <= ftol
        root_p.append(ep[touch])
        root_t.append(te[touch])
        out[pr[ep[flip & whole[ei]]]] = True
        fl = flip & ~whole[ei]
        fi, tf, ff = ep[fl], te[fl], fe[fl]
        br_p += [fi, fi]
        br_a += [ta[ei][fl], tf]
        br_b += [tf, tb[ei][fl]]
        br_fa += [fa0[ei][fl], ff]
        br_fb += [ff, fb0[ei][fl]]
    bp = np.concatenate(br_p)
    if len(bp):
        a_, b_ = np.concatenate(br_a), np.concatenate(br_b)
        fa, fb = np.concatenate(br_fa), np.concatenate(br_fb)

        def f_df(x: np.ndarray, sel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            p = pr[bp[sel]]
            rr, zz = surface.rz(x)
            dr, dzz = surface.drz(x)
            h = zz - hs[p]
            cc = (c * c)[p]
            return cc * (rr * rr - d2[p]) - k2[p] * h * h, 2 * (cc * rr * dr - k2[p] * h * dzz)

        root_p.append(bp)
        root_t.append(newton(f_df, a_, b_, fa, fb, 4e-16 * span, NEWTON_FTOL * size * size))
    rp, tt = np.concatenate(root_p), np.concatenate(root_t)
    if not len(rp):
        return
    rr = pr[rp]
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
        out[rr[good]] = True
