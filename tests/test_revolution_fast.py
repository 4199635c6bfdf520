"""The ray test of surfaces of revolution with monotone heights
(``lgraph/surfaces/revolution/_fast.py``): one run of grid cells per ray,
pruned by a window of heights, and the transition functions built on it.

Independent checks: the general scan of ring-bounded blocks (``general=True``)
and a dense evaluation of the ray function ``F`` on 60 001 parameters per
ray (roots by sign changes, their ray parameters from the heights); rays whose
dense ``F`` comes within rounding of a tangency, or whose roots lie near the
ends of their range, are ambiguous for every test and left out.
"""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph._own import CONTOUR, OFF, ON
from lgraph.surfaces.revolution import _hits as _revolution_hits
from lgraph.surfaces.revolution._fast import monotone_tables

PSEUDO = lg.Pseudosphere(1.0, 3.0)
VASE = lg.SurfaceOfRevolution("vase", (0, 3.0))
# heights decreasing along the profile, derivatives by finite differences
DOWN = lg.SurfaceOfRevolution(lambda t: (1.2 + 0.35 * np.sin(2.5 * t), -t), (-1.5, 1.5))
TILTED = lg.SurfaceOfRevolution("vase", (0, 3.0), axis=(1, -2, 2))
SURFACES = {"pseudosphere": PSEUDO, "vase": VASE, "down": DOWN, "tilted": TILTED}
PROJECTORS = [
    lg.CentralProjector.from_angles(35, 25, 16),
    lg.CentralProjector(eye=(6, -5, -1.5)),
    lg.ParallelProjector(direction=(1, -1.3, 0.7)),
    lg.CentralProjector(eye=(2.5, 0.5, 1.0)),  # close, at the height of the surface
]
TT = {name: np.linspace(*s.t_range, 60001) for name, s in SURFACES.items()}


def _dense(name, o, v, lam_max, eps, own):
    """Reference from a dense scan of ``F``: hit flags and which rays are clear
    (no root within ``1e-5`` of the size from ``eps`` or ``lam_max``, nor for
    a point within ``1e-3`` of it but its own root; no extremum of ``F``
    away from the point within ``1e-9 size^2`` of zero; steep lines only)."""
    s = SURFACES[name]
    speed, _, _, c, k2, d2, hs, ss = _revolution_hits.ray_terms(s, o, v)
    lam_max = lam_max * speed
    rho, z = s.rz(TT[name])
    size = s.size
    hit = np.zeros(len(o), bool)
    clear = np.abs(c) > 0.05
    for i in range(len(o)):
        f = c[i] ** 2 * (rho * rho - d2[i]) - k2[i] * (z - hs[i]) ** 2
        lam_of = ss[i] + (z - hs[i]) / c[i]
        j = np.flatnonzero(np.sign(f[1:]) != np.sign(f[:-1]))
        lam = lam_of[j]
        close = 1e-5 * size
        if own[i] == ON:  # the point's own root (to the dense grid's resolution)
            lam = np.delete(lam, np.argmin(np.abs(lam))) if len(lam) else lam
            close = 1e-3 * size
        near = (np.abs(lam - eps[i]) < close) | (np.abs(lam - lam_max[i]) < 1e-5 * size)
        df = np.diff(f)
        turn = np.flatnonzero(np.sign(df[1:]) != np.sign(df[:-1])) + 1
        turn = turn[np.abs(lam_of[turn]) > 1e-3 * size]
        graze = np.abs(f[turn]).min(initial=np.inf) < 1e-9 * size**2
        clear[i] &= not near.any() and not graze
        hit[i] = ((lam > eps[i]) & (lam < lam_max[i])).any()
    return hit, clear


def _rays(surface, rng, n):
    """Rays from the surface toward several viewers (own ON), and free rays
    (OFF) from a box around it, some ending inside the box."""
    t = rng.uniform(*surface.t_range, n)
    phi = rng.uniform(0, 2 * np.pi, n)
    x = surface.point(t, phi)
    o, v, sm, own = [], [], [], []
    for p in PROJECTORS:
        d, smax = p.rays(x)
        o.append(x), v.append(d), sm.append(smax), own.append(np.full(n, ON, np.int8))
    lo, hi = surface.bounds()
    box = lo - 0.5 * (hi - lo), hi + 0.5 * (hi - lo)
    start = rng.uniform(*box, (n, 3))
    target = surface.point(rng.uniform(*surface.t_range, n), rng.uniform(0, 7, n))
    d = target - start + rng.normal(0, 0.05, (n, 3))
    smax = np.where(rng.uniform(size=n) < 0.3, rng.uniform(0.3, 1.5, n), np.inf)
    o.append(start), v.append(d), sm.append(smax), own.append(np.full(n, OFF, np.int8))
    return np.concatenate(o), np.concatenate(v), np.concatenate(sm), np.concatenate(own)


@pytest.mark.parametrize("name", list(SURFACES))
def test_the_profiles_take_the_fast_path(name):
    tab = monotone_tables(SURFACES[name], _revolution_hits._blocks(SURFACES[name])["cellpad"])
    assert tab is not None and tab["mono"] == (-1 if name == "down" else 1)
    # the sparse table gives the largest radius bound of any run of cells
    rng = np.random.default_rng(1)
    lo = rng.integers(0, 256, 500)
    hi = np.minimum(lo + rng.integers(0, 256, 500), 255)
    from lgraph.surfaces.revolution._fast import _range_max

    ref = np.array([tab["bound"][0, a : b + 1].max() for a, b in zip(lo, hi)])
    assert np.array_equal(_range_max(tab["bound"], lo, hi), ref)


@pytest.mark.parametrize("name", list(SURFACES))
def test_fast_ray_test_agrees_with_the_general_one_and_a_dense_scan(name):
    s = SURFACES[name]
    rng = np.random.default_rng(7)
    o, v, sm, own = _rays(s, rng, 200)
    fast = s.hits(o, v, sm, own)
    general = _revolution_hits.hits(s, o, v, sm, own, general=True)
    eps = np.where(own == ON, 1e-6, 1e-9) * s.size  # the local analysis' cut for points
    ref, clear = _dense(name, o, v, sm, eps, own)
    # the dense scan cannot see the own root's neighbour: points near their contour
    nv = np.full(len(o), 1.0)
    on = own == ON
    speed = np.linalg.norm(v, axis=1)
    a = s.frame[2]
    h = o @ a
    r = np.linalg.norm(o - h[:, None] * a, axis=1)
    from lgraph.surfaces.revolution._convex import t_of_points

    t = t_of_points(s, h[on], r[on])
    phi = np.arctan2(o[on] @ s.frame[1], o[on] @ s.frame[0])
    nv[on] = np.einsum("ij,ij->i", s.normal(t, phi), v[on] / speed[on, None])
    clear &= np.abs(nv) > 1e-3
    assert clear.sum() > 0.7 * len(o)
    assert ref[clear].sum() > 100 and (~ref[clear]).sum() > 100
    assert np.array_equal(fast[clear], ref[clear])
    assert np.array_equal(general[clear], ref[clear])
    # and the two tests agree on every clear ray, own or not, and on most others
    assert (fast != general).sum() <= 0.01 * len(o)


@pytest.mark.parametrize("name", ["pseudosphere", "vase", "down"])
def test_grazing_rays_inside_one_cell_are_found(name):
    # lines tangent to the surface at a point, moved off it along the normal:
    # two roots of F close together, nearly always within one cell
    s = SURFACES[name]
    rng = np.random.default_rng(3)
    t = rng.uniform(s.t_range[0] + 0.1, s.t_range[1] - 0.1, 300)
    phi = rng.uniform(0, 2 * np.pi, 300)
    x, n = s.point(t, phi), s.normal(t, phi)
    x1, x2 = s.derivatives(t, phi)
    w = rng.normal(size=(300, 2))
    tangent = w[:, :1] * x1 / np.linalg.norm(x1, axis=1, keepdims=True) + w[:, 1:] * x2 / (
        np.linalg.norm(x2, axis=1, keepdims=True)
    )
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    shift = rng.choice([-1.0, 1.0], 300)[:, None] * 10.0 ** rng.uniform(-7, -4, (300, 1))
    o = x + shift * n - 3 * tangent
    sm = np.full(300, np.inf)
    own = np.zeros(300, np.int8)
    fast = s.hits(o, tangent, sm, own)
    general = _revolution_hits.hits(s, o, tangent, sm, own, general=True)
    assert np.array_equal(fast, general)
    assert fast.sum() > 30 and (~fast).sum() > 30


@pytest.mark.parametrize("name", ["pseudosphere", "vase"])
def test_far_margin_has_the_sign_of_the_ray_test(name):
    s = SURFACES[name]
    rng = np.random.default_rng(9)
    n = 1500
    t = rng.uniform(*s.t_range, n)
    phi = rng.uniform(0, 2 * np.pi, n)
    x = s.point(t, phi)
    uv = np.column_stack([t, phi])
    for p in PROJECTORS[:3]:
        v, sm = p.rays(x)
        own = np.full(n, ON, np.int8)
        hit = s.hits(x, v, sm, own)
        m = s.visibility_margins(x, v, sm, own, uv)
        far = m[-1]  # the last row
        ok = np.isfinite(far) & (np.abs(far) > 1e-13)
        assert ok.sum() > 0.9 * n
        # where the point's own contour decides (N.v and the second root next to
        # the point), the far margin speaks for the rest of the ray only
        own_side = np.abs(m[0]) < 1e-6
        sel = ok & ~own_side
        assert np.array_equal(far[sel] > 0, hit[sel])


def test_contour_cusps_flip_where_the_view_is_asymptotic():
    # the pseudosphere's contour has two cusps in this view; the drawn contour
    # ends there, where the view direction is asymptotic: II(v, v) = 0 (from
    # the fundamental form, independent of the ray function)
    p = lg.CentralProjector.from_angles(35, 25, 16)
    scene = lg.Scene()
    scene.add(PSEUDO, lg.LinesOfCurvature(12, 24))
    d = scene.render(p, hidden_lines=True)
    ends = np.concatenate([s.uv[[0, -1]] for s in d.strokes if s.family == "contour"])
    t, phi = ends[:, 0], ends[:, 1]
    x = PSEUDO.point(t, phi)
    v, _ = p.rays(x)
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    x1, x2 = PSEUDO.derivatives(t, phi)
    x11, x12, x22 = PSEUDO.second_derivatives(t, phi)
    n = PSEUDO.normal(t, phi)
    # v = a x1 + b x2 (v lies in the tangent plane at contour points)
    a = np.einsum("ij,ij->i", v, x1) / np.einsum("ij,ij->i", x1, x1)
    b = np.einsum("ij,ij->i", v, x2) / np.einsum("ij,ij->i", x2, x2)
    ii = (
        a * a * np.einsum("ij,ij->i", x11, n)
        + 2 * a * b * np.einsum("ij,ij->i", x12, n)
        + b * b * np.einsum("ij,ij->i", x22, n)
    )
    cusp = np.abs(ii) < 1e-3
    assert cusp.sum() >= 2
    assert np.abs(ii[cusp]).max() < 1e-9
    # both cusps symmetric about the view's plane of symmetry, to the flips' precision
    cusp_t = np.sort(t[cusp])
    assert cusp_t[-1] - cusp_t[0] < 1e-9


def test_contour_points_are_double_roots_of_the_ray_function():
    # away from cusps a contour point hides itself only through a root past its
    # own (near-)double root: the fast test and the general one agree there
    p = lg.CentralProjector.from_angles(35, 25, 16)
    for s in (PSEUDO, VASE):
        pts = []
        for b in s.contour(p):
            idx = np.repeat(np.arange(len(b)), 101)
            tt = np.concatenate([np.linspace(a, c, 101) for a, c in zip(b.t0, b.t1)])
            xyz, uv = b.evaluate(idx, tt)
            pts.append((xyz, uv))
        x = np.concatenate([q[0] for q in pts])
        uv = np.concatenate([q[1] for q in pts])
        v, sm = p.rays(x)
        own = np.full(len(x), CONTOUR, np.int8)
        fast = s.hits(x, v, sm, own)
        general = _revolution_hits.hits(s, x, v, sm, own, general=True)
        m = s.visibility_margins(x, v, sm, own, uv)
        far_from_cusp = np.abs(m[-2]) > 1e-4  # the cusp function
        assert far_from_cusp.sum() > 0.8 * len(x)
        assert np.array_equal(fast[far_from_cusp], general[far_from_cusp])
