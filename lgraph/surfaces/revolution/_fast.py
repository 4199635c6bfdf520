"""Ray test of a surface of revolution whose profile has monotone height: the
root problem restricted to one interval of the profile grid per ray.

Where ``z(t)`` is strictly monotone, a steep line (``|c| >= FLAT_C``,
``c = v . a``) has ``lam = (z - o_a) / c``, monotone in ``t`` too: its
parameter range ``eps < lam < lam_max`` is one interval of heights, and so one
run of consecutive grid cells, each of whose heights lie between those of its
nodes.  A root of the ray function ``F = c^2 (rho^2 - d^2) - k^2 (z - h*)^2``
(:mod:`lgraph.surfaces.revolution._hits`) also needs ``F >= -ftol``, i.e.
``k^2 (z - h*)^2 <= c^2 (R^2 - d^2) + ftol`` with ``R`` a bound on ``rho``:
a window of heights about ``h*``.  ``R`` starts as the profile's bound and is
tightened to the largest bound of the cells the window still covers (a sparse
table gives that range maximum at once for all rays), once.  Only the nodes
of the remaining cells are scanned, as in the general test: a sign change or
a node at rounding level decides a hit, and a cell where ``F`` turns back
toward zero has its extremum located.  No cell needs cutting at ``lam = eps``
or ``lam = lam_max``: rays whose window reaches a cell holding either limit
are left to the general test (for rays toward the eye from the surface, none).

A ray from a point of the surface (decided by the local analysis of
:mod:`lgraph.surfaces.revolution._local`) starts in its own cell, on its own
root ``t0``.  There ``F'(t0) = -2 c rho |P'| N . v``, so just past ``t0``
toward the viewer ``F`` has the sign ``-sign(N . v) sign(z')``; with at most
one extremum of ``F`` in a cell (the grid's premise), the cell holds a second
root past ``t0`` exactly when ``F`` at its far node has the other sign (or
is at rounding level there).  So the own cell needs no refinement at all.
A contour point is the double root it stands for: ``F`` starts with the sign
of ``F''(t0)``, which changes at the cusps of the apparent contour
(:func:`cusp_function`).  :func:`far_margin` turns the same scan into a
transition function whose sign is the test's answer (docs/mathematics.rst,
"Surfaces of revolution": monotone heights, the own cell, contour points and
cusps, the far margin).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ._protocol import Revolved

__all__ = ["cusp_function", "far_margin", "monotone_tables", "newton", "own_sign", "scan"]


def monotone_tables(surface: Revolved, cellpad: np.ndarray) -> dict | None:
    """Node arrays in order of increasing height, and a sparse table of the
    cells' radius bounds (``max rho`` at the nodes plus ``cellpad``, the
    bulge between them); None when ``z`` is not strictly monotone on the grid
    (cached on the surface)."""
    g = surface._grid
    if "monotone" in g:
        return g["monotone"]
    z, dz = g["z"], g["dz"]
    steps = np.diff(z)
    mono = 1 if np.all(steps > 0) else -1 if np.all(steps < 0) else 0
    if mono and not np.all(mono * dz[1:-1] > 0):
        mono = 0
    if not mono or g["closed"]:
        g["monotone"] = None
        return None
    order = slice(None) if mono > 0 else slice(None, None, -1)
    rho, drho = g["rho"][order], g["drho"][order]
    pad = cellpad[order]
    # bound[k, i]: the largest radius bound of cells i .. i + 2^k - 1
    levels = [np.maximum(rho[:-1], rho[1:]) + pad]
    while (1 << len(levels)) <= len(levels[0]):
        prev, half = levels[-1], 1 << (len(levels) - 1)
        levels.append(np.maximum(prev[:-half], prev[half:]))
    bound = np.full((len(levels), len(levels[0])), -np.inf)
    for k, level in enumerate(levels):
        bound[k, : len(level)] = level
    out = {
        "mono": mono,
        "t": g["t"][order],
        "z": z[order],
        "rho2": rho * rho,
        # half of dF/dz up to the positive factor |z'|: the derivative along the nodes
        "rdr": mono * rho * drho,
        "dz": mono * dz[order],
        "bound": bound,
        "rmax": float(levels[0].max()),
    }
    g["monotone"] = out
    return out


def _range_max(bound: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Largest ``bound[0, lo : hi + 1]`` (``lo <= hi``) for each pair."""
    k = np.floor(np.log2(hi - lo + 1)).astype(np.int64)
    return np.maximum(bound[k, lo], bound[k, hi - (1 << k) + 1])


def _runs(
    tab: dict, ray: tuple, mine: np.ndarray, ftol: float, window: np.ndarray | None = None
) -> dict:
    """The nodes each ray scans (module docstring), flattened: ``rays`` (the
    rays with any), ``ray_of`` and ``node`` (one entry per scanned node), and
    per ray ``lo_in``, ``hi_in`` (the nodes strictly inside its parameter
    range), ``io`` (own cell), ``q`` (its far node toward the viewer),
    ``own_cut`` (the own cell holds ``lam = eps``, ``q`` inside the range),
    ``ze`` (height at ``lam = eps``) and ``undecided`` (left to the general
    test).  ``window``: which rays are cut to the window of heights (all by
    default)."""
    c, k2, d2, hs, oa, eps, lam_max = ray
    n = len(c)
    z, bound = tab["z"], tab["bound"]
    m = len(z) - 1
    up = c > 0
    # nodes strictly inside the parameter range (an open interval of heights)
    ze, zm = oa + c * eps, oa + c * lam_max  # c != 0: an infinite lam_max gives +-inf
    lo_in = np.searchsorted(z, np.minimum(ze, zm), side="right")
    hi_in = np.searchsorted(z, np.maximum(ze, zm), side="left") - 1
    # a ray from the surface: its own cell, the cell's far node q toward the viewer,
    # and whether the own cell holds lam = eps (with q inside the range)
    io = np.clip(np.searchsorted(z, oa, side="right") - 1, 0, m - 1)
    q = np.where(up, io + 1, io)
    own_cut = mine & np.where(up, lo_in == q, hi_in == q)
    undecided = mine & ((own_cut & (lo_in > hi_in)) | np.where(up, lo_in < q, hi_in > q))
    # cells to consider: those meeting the range, past the own cell
    cmin, cmax = np.maximum(lo_in - 1, 0), np.minimum(hi_in, m - 1)
    cmin = np.where(mine & up, np.maximum(cmin, io + 1), cmin)
    cmax = np.where(mine & ~up, np.minimum(cmax, io - 1), cmax)
    # ... and the window of heights where F >= -ftol is possible, tightened once
    r2 = np.full(n, tab["rmax"] ** 2)
    c2 = c * c
    first, last = cmin, cmax
    for _ in range(2 if window is None or window.any() else 0):
        room = c2 * (r2 - d2) + ftol
        with np.errstate(divide="ignore", invalid="ignore"):
            w = np.where(k2 > 0, np.sqrt(np.maximum(room, 0.0) / k2), np.inf)
        w = np.where(room < 0, -np.inf, w)
        first = np.maximum(np.searchsorted(z[1:], hs - w, side="left"), cmin)
        last = np.minimum(np.searchsorted(z[:-1], hs + w, side="right") - 1, cmax)
        some = first <= last
        if not some.any():
            break
        r = _range_max(bound, np.where(some, first, 0), np.where(some, last, 0))
        r2 = np.where(some, np.maximum(r, 0.0) ** 2, -np.inf)
    if window is not None:
        first, last = np.where(window, first, cmin), np.where(window, last, cmax)
    some = first <= last
    n_lo = np.where(some, first, m + 1)
    n_hi = np.where(some, last + 1, -1)
    n_lo = np.where(own_cut, np.minimum(n_lo, q), n_lo)
    n_hi = np.where(own_cut, np.maximum(n_hi, q), n_hi)
    rays = np.flatnonzero((n_lo <= n_hi) & ~undecided)
    counts = n_hi[rays] - n_lo[rays] + 1
    start = np.cumsum(counts) - counts
    ray_of = np.repeat(rays, counts)
    node = np.arange(len(ray_of)) - np.repeat(start - n_lo[rays], counts)
    return {
        "rays": rays, "ray_of": ray_of, "node": node, "lo_in": lo_in, "hi_in": hi_in,
        "io": io, "q": q, "own_cut": own_cut, "ze": ze, "undecided": undecided,
        "start": start, "n_lo": n_lo[rays], "n_hi": n_hi[rays],
    }  # fmt: skip


def _position(run: dict, node: np.ndarray) -> np.ndarray:
    """Index into the flattened nodes of node ``node[i]`` of ray ``rays[i]``
    (-1 where that ray does not scan it)."""
    ok = (node >= run["n_lo"]) & (node <= run["n_hi"])
    return np.where(ok, run["start"] + node - run["n_lo"], -1)


def _values(tab: dict, ray: tuple, run: dict, ftol: float) -> dict:
    """``F`` at the scanned nodes (``f``), its derivative along the nodes up
    to a positive factor (``df``), which nodes lie inside the range
    (``inside``; the others end a cell holding a limit) and off the rims
    (``inner``), which pairs of consecutive entries are cells of one ray
    (``same``), hold a limit of the range (``cut``) or a sign change of
    ``F`` (``change``), and where ``F`` turns back toward zero (``turning``,
    indices of cells) or is at rounding level (``small``, indices of
    nodes)."""
    c, k2, d2, hs = ray[:4]
    ray_of, node = run["ray_of"], run["node"]
    rays, start, n_lo, n_hi = run["rays"], run["start"], run["n_lo"], run["n_hi"]
    m, size = len(tab["z"]) - 1, len(node)
    C2, K2 = (c * c)[ray_of], k2[ray_of]
    h = tab["z"][node] - hs[ray_of]
    f = C2 * (tab["rho2"][node] - d2[ray_of]) - K2 * h * h
    df = C2 * tab["rdr"][node] - K2 * h * tab["dz"][node]
    small = np.flatnonzero(np.abs(f) <= ftol)
    # the few special entries, from the runs' ends
    lo_in, hi_in = run["lo_in"][rays], run["hi_in"][rays]
    inside = np.ones(size, bool)
    inner = np.ones(size, bool)
    ends = start + n_hi - n_lo
    inside[start[n_lo < lo_in]] = False
    inside[ends[n_hi > hi_in]] = False
    inner[start[n_lo == 0]] = False
    inner[ends[n_hi == m]] = False
    same = np.ones(max(size - 1, 0), bool)
    same[ends[:-1]] = False
    cut = np.zeros(len(same), bool)
    for cell in (lo_in - 1, hi_in):
        at = _position(run, cell)
        cut[at[(at >= 0) & (cell < n_hi)]] = True
    pos = f > 0
    change = same & (pos[1:] != pos[:-1])
    up, down = df > 0, df < 0
    turning = np.flatnonzero(same & ((up[:-1] & down[1:]) | (down[:-1] & up[1:])))
    fa = f[turning]
    turning = turning[((fa > 0) & down[turning]) | ((fa < 0) & up[turning])]
    return {
        "f": f, "df": df, "pos": pos, "small": small, "inside": inside, "inner": inner,
        "same": same, "cut": cut, "change": change, "turning": turning,
    }  # fmt: skip


def scan(
    surface: Revolved,
    tab: dict,
    ray: tuple,
    mine: np.ndarray,
    s0: np.ndarray,
    ftol: float,
    out: np.ndarray,
) -> np.ndarray:
    """Decide the steep lines ``ray = (c, k2, d2, h*, o_a, eps, lam_max)``;
    ``mine``: rays from a point of the surface, and ``s0`` the sign of ``F``
    just past it toward the viewer (0: unknown; see :func:`own_sign`).
    Sets ``out`` for hits; returns which rays were decided (the others are
    for the general test)."""
    run = _runs(tab, ray, mine, ftol)
    undecided = run["undecided"]
    if not len(run["ray_of"]):
        return ~undecided
    ray_of, node = run["ray_of"], run["node"]
    val = _values(tab, ray, run, ftol)
    f, pos, small, cut, change = val["f"], val["pos"], val["small"], val["cut"], val["change"]
    # a node at rounding level inside the range, off the rims (there only a sign
    # change counts): a touching root
    touch = np.zeros(len(f), bool)
    touch[small[val["inside"][small] & val["inner"][small]]] = True
    out[ray_of[touch]] = True
    # a cell holding a limit must hold no root at all, else the general test decides
    tiny = np.zeros(len(f), bool)
    tiny[small] = True
    turning = np.zeros(len(cut), bool)
    turning[val["turning"]] = True
    ci = np.flatnonzero(cut)
    odd = change[ci] | turning[ci] | tiny[ci] | tiny[ci + 1]
    undecided[ray_of[ci[odd]]] = True
    out[ray_of[np.flatnonzero(change & ~cut)]] = True
    # the own cell: a second root past the point iff F at its far node has the
    # sign opposite to F just past the point
    rays = run["rays"]
    at_q = _position(run, run["q"][rays])
    at_q = at_q[run["own_cut"][rays] & (at_q >= 0)]
    r_q = ray_of[at_q]
    known = s0[r_q] != 0
    out[r_q[known & (pos[at_q] != (s0[r_q] > 0))]] = True
    # cells where F turns back toward zero: locate the extremum
    cells = val["turning"]
    cells = cells[~cut[cells] & ~touch[cells] & ~touch[cells + 1] & ~out[ray_of[cells]]]
    if len(cells):
        fe = _cell_extrema(surface, tab, ray, run, val["df"], cells)
        hit = ((fe > 0) != (f[cells] > 0)) | (np.abs(fe) <= ftol)
        out[ray_of[cells[hit]]] = True
    # the own cell of the others, cut at lam = eps, as in the general test
    k = at_q[~known & ~out[r_q]]
    if len(k):
        r = ray_of[k]
        _own_cut_cell(surface, tab, ray, r, run["io"][r], run["ze"][r], node[k], f[k],
                      touch[k], ftol, out)  # fmt: skip
    out[undecided] = False
    return ~undecided


def far_margin(
    surface: Revolved,
    tab: dict,
    ray: tuple,
    s0: np.ndarray,
    ftol: float,
) -> np.ndarray:
    """For rays from points of the surface with a known sign ``s0 = +-1`` of
    ``F`` just past the point: the largest ``-s0 F`` over the scanned nodes
    inside the range (for ``s0 > 0`` all nodes past the point; ``+ ftol``
    off the rims: the band :func:`scan` counts as touching) and over the
    extrema of the cells where ``-s0 F`` rises and falls again (where the
    nodes alone leave it at or below zero): positive exactly where
    :func:`scan` finds a hit, continuous where the hit appears (NaN: a ray
    left to the general test)."""
    n = len(s0)
    out = np.full(n, np.nan)
    known = s0 != 0
    # a ray into the solid (s0 > 0) is hidden where F turns negative: the cells
    # the window leaves out (F < -ftol there) count too
    run = _runs(tab, ray, known, ftol, window=s0 < 0)
    ray_of = run["ray_of"]
    if not len(ray_of):
        out[known & ~run["undecided"]] = 0.0
        return out
    val = _values(tab, ray, run, ftol)
    f, df, small, cut, inside = val["f"], val["df"], val["small"], val["cut"], val["inside"]
    bad = run["undecided"].copy()
    tiny = np.zeros(len(f), bool)
    tiny[small] = True
    turning = np.zeros(len(cut), bool)
    turning[val["turning"]] = True
    ci = np.flatnonzero(cut)
    bad[ray_of[ci[val["change"][ci] | turning[ci] | tiny[ci] | tiny[ci + 1]]]] = True
    sign = -s0[ray_of]
    v = np.where(inside, sign * f + np.where(val["inner"], ftol, 0.0), -np.inf)
    best = np.full(n, -np.inf)
    best[run["rays"]] = np.maximum.reduceat(v, run["start"])  # the runs are contiguous
    # interior maxima of -s0 F: cells where it rises then falls (needed only where
    # the nodes leave the margin at or below zero: above, it is positive anyway)
    sa = sign[:-1]
    rise = val["same"] & ~cut & (sa * df[:-1] > 0) & (sa * df[1:] < 0)
    cells = np.flatnonzero(rise & inside[:-1] & inside[1:])
    cells = cells[best[ray_of[cells]] <= 0]
    if len(cells):
        fe = _cell_extrema(surface, tab, ray, run, df, cells)
        np.maximum.at(best, ray_of[cells], sa[cells] * fe + ftol)
    ok = known & ~bad
    # no node to scan: nothing past the point can hide it (a point within eps of
    # a rim, where the margin of the rim tends to zero)
    out[ok] = np.where(np.isfinite(best[ok]), best[ok], 0.0)
    return out


def own_sign(
    surface: Revolved,
    tab: dict,
    ray: tuple,
    contour: np.ndarray,
    t: np.ndarray,
    nv: np.ndarray,
) -> np.ndarray:
    """The sign of ``F`` just past a ray's own point toward the viewer (0:
    unknown).  For a point of the surface, ``F'(t0) = -2 c rho |P'| N . v``
    gives ``-sign(N . v) sign(z')`` (``nv``: ``N . v``).  A ``contour`` point
    is treated as the double root it is (``N . v = 0``; so is a point where
    ``N . v`` is 0 or undefined, as on a cuspidal rim): there ``F`` has the
    sign of ``F''(t0)``, and its own cell holds no second root of ``F`` past
    the point unless ``F`` changes sign again before its far node.  Where
    ``F''(t0)`` changes sign along the contour (a cusp of the apparent
    contour, the view direction asymptotic there) the contour starts or
    stops being hidden by the surface next to it (:func:`cusp_function`)."""
    s = -tab["mono"] * np.sign(np.nan_to_num(nv))
    k = np.flatnonzero((contour | (s == 0)) & np.isfinite(t))
    if len(k):
        s[k] = np.sign(np.nan_to_num(cusp_function(surface, ray, k, t[k])))
    return s


def cusp_function(surface: Revolved, ray: tuple, p: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``F''(t) / size^2`` of rays ``p`` at their points' parameters ``t``."""
    c, k2, _, hs = ray[:4]
    rr, zz = surface.rz(t)
    dr, dzz = surface.drz(t)
    ddr, ddz = surface.ddrz(t)
    cc, hh = (c * c)[p], zz - hs[p]
    fpp = 2 * (cc * (dr * dr + rr * ddr) - k2[p] * (dzz * dzz + hh * ddz))
    return fpp / surface.size**2


def _ray_function(surface: Revolved, ray: tuple, p: np.ndarray, x: np.ndarray) -> tuple:
    """``F`` and ``F'`` of rays ``p`` at parameters ``x``."""
    c, k2, d2, hs = ray[:4]
    rr, zz = surface.rz(x)
    dr, dzz = surface.drz(x)
    cc, hh = (c * c)[p], zz - hs[p]
    return cc * (rr * rr - d2[p]) - k2[p] * hh * hh, 2 * (cc * rr * dr - k2[p] * hh * dzz)


def _own_cut_cell(surface, tab, ray, p, io, ze, q, fq, touch_q, ftol, out) -> None:  # noqa: ANN001
    """Own cells (``io``) of rays ``p`` from the surface whose sign past the
    point is not known (contour points): the part past ``lam = eps`` (height
    ``ze``) up to the far node ``q`` is scanned like a cell of the general
    test (a sign change, or an extremum turning back across zero; the cut
    end is no node and counts no touching)."""
    t, z = tab["t"], tab["z"]
    span = abs(t[-1] - t[0])
    ta, tb = t[io], t[io + 1]
    fa, fb = z[io] - ze, z[io + 1] - ze
    swap = ta > tb
    a, b = np.where(swap, tb, ta), np.where(swap, ta, tb)
    fa, fb = np.where(swap, fb, fa), np.where(swap, fa, fb)

    def f_df(x: np.ndarray, sel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return surface.rz(x)[1] - ze[sel], surface.drz(x)[1]

    te = newton(f_df, a, b, fa, fb, 4e-16 * span, 0.0)
    fe, ge = _ray_function(surface, ray, p, te)
    _, gq = _ray_function(surface, ray, p, t[q])
    out[p[(fe > 0) != (fq > 0)]] = True
    # in t order: the cut end first or the node first
    first = t[q] > te
    f0, g0, g1 = np.where(first, fe, fq), np.where(first, ge, gq), np.where(first, gq, ge)
    turning = ((f0 > 0) & (g0 < 0) & (g1 > 0)) | ((f0 < 0) & (g0 > 0) & (g1 < 0))
    k = np.flatnonzero(turning & ~touch_q & ~out[p])
    if len(k):
        lo, hi = np.minimum(te[k], t[q[k]]), np.maximum(te[k], t[q[k]])
        fx = _extrema(surface, ray, p[k], lo, hi)
        out[p[k][((fx > 0) != (fq[k] > 0)) | (np.abs(fx) <= ftol)]] = True


def _cell_extrema(surface, tab, ray, run, df, cells) -> np.ndarray:  # noqa: ANN001
    """``F`` at the extremum inside the scanned cells ``cells`` (pairs of
    consecutive entries), from the nodes' derivatives (``df`` along the
    nodes is ``mono F' / 2``)."""
    node = run["node"][cells]
    t = tab["t"]
    if tab["mono"] > 0:
        a, b, ga, gb = t[node], t[node + 1], df[cells], df[cells + 1]
    else:
        a, b, ga, gb = t[node + 1], t[node], -df[cells + 1], -df[cells]
    return _extrema(surface, ray, run["ray_of"][cells], a, b, ga, gb)


def _extrema(surface, ray, p, a, b, ga=None, gb=None) -> np.ndarray:  # noqa: ANN001
    """``F`` of rays ``p`` at the extremum in ``[a, b]`` (where ``F'``
    changes sign; ``ga``, ``gb``: ``F'`` at the ends up to a common positive
    factor, when known)."""
    c, k2, _, hs = ray[:4]
    span = float(np.ptp(surface._grid["t"]))

    def d_dd(x: np.ndarray, sel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        r = p[sel]
        rr, zz = surface.rz(x)
        dr, dzz = surface.drz(x)
        ddr, ddz = surface.ddrz(x)
        cc, kk, hh = (c * c)[r], k2[r], zz - hs[r]
        return (
            2 * (cc * rr * dr - kk * hh * dzz),
            2 * (cc * (dr * dr + rr * ddr) - kk * (dzz * dzz + hh * ddz)),
        )

    if ga is None:
        ga = _ray_function(surface, ray, p, a)[1]
        gb = _ray_function(surface, ray, p, b)[1]
    # F is flat at its extremum: t to 1e-9 gives F there to rounding level; start
    # where the chord of F' crosses zero
    x0 = a + ga / (ga - gb) * (b - a)  # inside: ga, gb of opposite signs
    te = newton(d_dd, a, b, ga, gb, 1e-9 * span, 0.0, x0)
    return _ray_function(surface, ray, p, te)[0]


def newton(f_df, a, b, fa, fb, xtol, ftol, x0=None):  # noqa: ANN001, ANN202
    """Roots in brackets ``[a, b]`` (``fa``, ``fb`` of opposite signs): Newton steps
    from the middle (or from ``x0``), bisection when a step leaves the
    bracket; all at once.  Stops at ``|f| <= ftol`` (rounding level) or a
    step below ``xtol``."""
    a, b, fa = a.copy(), b.copy(), fa.copy()
    x = 0.5 * (a + b) if x0 is None else np.clip(x0, a, b)
    idx = np.arange(len(a))
    for _ in range(80):
        xi = x[idx]
        f, df = f_df(xi, idx)
        left = (f > 0) == (fa[idx] > 0)  # root in [x, b]
        ai = np.where(left, xi, a[idx])
        bi = np.where(left, b[idx], xi)
        a[idx], b[idx] = ai, bi
        fa[idx] = np.where(left, f, fa[idx])
        with np.errstate(invalid="ignore", divide="ignore"):
            nx = xi - f / df
        newton = (nx >= ai) & (nx <= bi)
        nx = np.where(newton, nx, 0.5 * (ai + bi))
        x[idx] = nx
        converged = newton & (np.abs(nx - xi) <= xtol)
        keep = (np.abs(f) > ftol) & ~converged & (bi - ai > xtol)
        idx = idx[keep]
        if not len(idx):
            break
    return x
