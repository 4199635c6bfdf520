"""Visibility on surfaces of revolution against independent checks.

* every sample of every drawn stroke (egg: convex, decided by ``-N . v``;
  pseudosphere and vase: the ray test with its local analysis at the point's
  own contour) is classified again by a dense ray march against the implicit
  inside test ``r - R(h)`` of the profile, written from the profile formulas
  (the pseudosphere's ``R`` from a dense table of the tractrix);
* flips where a parallel crosses the contour lie where the closed-form
  contour angle says, to 1e-10;
* the convex shortcut agrees with the general ray test, also with the eye
  inside the egg; the convexity claims of the named profiles hold on a dense
  grid; a point's parameter is recovered to rounding level.
"""

from __future__ import annotations

import numpy as np
import pytest
from bruteforce import even_stations, sign_changes

import lgraph as lg
from lgraph._own import ON
from lgraph.surfaces.revolution import _hits as _revolution_hits
from lgraph.surfaces.revolution._contour import view_terms
from lgraph.surfaces.revolution._convex import t_of_points

EGG = lg.SurfaceOfRevolution("egg", (0, np.pi))
PSEUDO = lg.Pseudosphere(1.0, 3.0)
VASE = lg.SurfaceOfRevolution("vase", (0, 3.0))
SURFACES = {"egg": EGG, "pseudosphere": PSEUDO, "vase": VASE}
PROJECTORS = {
    "parallel": lg.ParallelProjector(direction=(1, -1.3, 0.7)),
    "central": lg.CentralProjector.from_angles(35, 25, 16),
    "central low": lg.CentralProjector(eye=(6, -5, -1.5)),
}

_TT = np.linspace(0.0, 3.0, 400001)
_PZ = _TT - np.tanh(_TT)  # the tractrix: z increasing, rho = sech t


def _radius(name: str, h: np.ndarray) -> np.ndarray:
    """``R(h)``: the profile's distance from the axis at height ``h`` (NaN off it)."""
    with np.errstate(invalid="ignore"):
        if name == "egg":  # z = -1.4 cos t, rho = sin t (1 + 0.18 cos t)
            c = -h / 1.4
            r = np.sqrt(1 - c * c) * (1 + 0.18 * c)
            return np.where(np.abs(h) <= 1.4, r, np.nan)
        if name == "vase":  # z = t, rho = 1 + 0.42 sin(2.2 t - 0.9)
            return np.where((h >= 0) & (h <= 3), 1 + 0.42 * np.sin(2.2 * h - 0.9), np.nan)
        if name == "pseudosphere":
            r = np.interp(h, _PZ, 1 / np.cosh(_TT))
            return np.where((h >= 0) & (h <= _PZ[-1]), r, np.nan)
    raise KeyError(name)


def _march(name, o, v, lam_max, start=2e-3, n=6000):
    """Hidden flags by sign changes of ``r - R(h)`` along each ray (unit ``v``),
    and a margin: the smallest ``|g|`` at a turning point (a near-tangency)."""
    lam = start + (np.minimum(lam_max, 14.0) - start)[:, None] * np.linspace(0, 1, n)
    p = o[:, None, :] + lam[..., None] * v[:, None, :]
    g = np.hypot(p[..., 0], p[..., 1]) - _radius(name, p[..., 2])
    return sign_changes(g)


@pytest.mark.parametrize("pname", list(PROJECTORS))
@pytest.mark.parametrize("name", list(SURFACES))
def test_drawn_visibility_agrees_with_a_dense_ray_march(name, pname):
    surface, projector = SURFACES[name], PROJECTORS[pname]
    scene = lg.Scene()
    scene.add(surface, lg.LinesOfCurvature(10, 16))
    d = scene.render(projector, hidden_lines=True)
    # points evenly along the strokes (the renderer samples densely near
    # contours), away from the flips that end each stroke
    x0, y0, x1, y1 = d.bounds()
    spacing = 2e-3 * np.hypot(x1 - x0, y1 - y0)
    picks = [even_stations(s.xy, spacing) for s in d.strokes]
    x = np.concatenate([s.xyz[i] for s, i in zip(d.strokes, picks)])
    hid = np.concatenate([np.full(len(i), not s.visible) for s, i in zip(d.strokes, picks)])
    v, smax = projector.rays(x)
    speed = np.linalg.norm(v, axis=1)
    ref, margin = _march(name, x, v / speed[:, None], smax * speed)
    # rays leaving their point almost tangentially are fragile for the march
    uv = np.concatenate([s.uv[i] for s, i in zip(d.strokes, picks)])
    n = surface.normal(uv[:, 0], uv[:, 1])
    grazing = np.abs(np.einsum("ij,ij->i", n, v / speed[:, None])) < 0.02
    clear = (margin > 5e-3) & ~grazing
    # most points are checked (the pseudosphere's rim grazes many rays)
    assert clear.sum() > 0.7 * len(x) and clear.sum() > 1000, (clear.mean(), len(x))
    bad = np.flatnonzero(clear & (ref != hid))
    assert not len(bad), (name, pname, x[bad[:5]], hid[bad[:5]])
    assert hid.sum() > 100 and (~hid).sum() > 100


@pytest.mark.parametrize("pname", ["parallel", "central"])
@pytest.mark.parametrize("name", ["egg", "pseudosphere"])
def test_flips_on_parallels_lie_on_the_closed_form_contour(name, pname):
    surface, projector = SURFACES[name], PROJECTORS[pname]
    scene = lg.Scene()
    scene.add(surface, lg.LinesOfCurvature(10, 0))
    d = scene.render(projector, hidden_lines=True)
    central, wa, r0, psi0 = view_terms(surface, projector)
    checked = 0
    for s in d.strokes:
        if s.family != "curvature":
            continue
        t = s.uv[0, 0]
        assert np.allclose(s.uv[:, 0], t, atol=0, rtol=0)  # a parallel
        (rho,), (z,) = surface.rz(np.array([t]))
        (dr,), (dz,) = surface.drz(np.array([t]))
        c = dz * rho + dr * (wa - z) if central else dr * wa
        with np.errstate(invalid="ignore"):  # NaN: this parallel meets no contour
            phi_c = psi0 + np.array([1, -1]) * np.arccos(c / (dz * r0))
        for phi in (s.uv[0, 1], s.uv[-1, 1]):
            gap = np.abs(np.angle(np.exp(1j * (phi - phi_c))))
            if gap.min() < 1e-6:  # this flip is a contour crossing
                assert gap.min() < 1e-10, (t, phi, phi_c)
                checked += 1
    assert checked >= 4


def test_convex_shortcut_agrees_with_the_general_ray_test():
    rng = np.random.default_rng(11)
    t = rng.uniform(0, np.pi, 3000)
    phi = rng.uniform(0, 2 * np.pi, 3000)
    x = EGG.point(t, phi)
    own = np.full(len(x), ON, np.int8)
    for eye in [(7, -6, 4), (0.1, 0.2, 0.3)]:  # outside, inside the egg
        p = lg.CentralProjector(eye=eye)
        v, smax = p.rays(x)
        fast = EGG.hits(x, v, smax, own)
        general = _revolution_hits.hits(EGG, x, v, smax, own)
        nv = np.einsum("ij,ij->i", EGG.normal(t, phi), v / np.linalg.norm(v, axis=1)[:, None])
        clear = np.abs(nv) > 1e-6
        assert np.array_equal(fast[clear], general[clear])
        assert fast.any() == (eye[0] == 7)  # from inside, nothing hides the egg's points


def test_convexity_claims_hold_on_a_dense_grid():
    for s in (EGG, lg.SurfaceOfRevolution(lg.named_profile("circle", center=(0, 0)),
                                          (-np.pi / 2, np.pi / 2))):  # fmt: skip
        assert s.convex
        lo, hi = s.profile.convex
        t = np.linspace(lo, hi, 100001)[1:-1]
        dr, dz = s.drz(t)
        ddr, ddz = s.ddrz(t)
        sigma = np.sign(dz[len(t) // 2])
        assert np.all(sigma * dz > 0)
        assert np.all(sigma * (dr * ddz - dz * ddr) >= 0)
    assert not PSEUDO.convex and not VASE.convex
    assert lg.named_profile("egg", e=0.8).convex is None
    # a full turn and both poles are needed
    assert not lg.SurfaceOfRevolution("egg", (0, np.pi), angle_range=(0, 3)).convex
    assert not lg.SurfaceOfRevolution("egg", (0.1, np.pi)).convex


@pytest.mark.parametrize("surface", [EGG, PSEUDO, VASE])
def test_parameter_of_a_point_is_recovered(surface):
    rng = np.random.default_rng(2)
    t = np.concatenate([rng.uniform(*surface.t_range, 2000), surface.t_range])
    phi = rng.uniform(0, 2 * np.pi, len(t))
    x = surface.point(t, phi)
    a = surface.frame[2]
    h = x @ a
    r = np.linalg.norm(x - h[:, None] * a, axis=1)
    assert np.abs(t_of_points(surface, h, r) - t).max() < 1e-12


@pytest.mark.parametrize("name", ["vase", "pseudosphere"])
def test_grazing_function_changes_sign_where_the_ray_test_does(name):
    # a family of parallel lines swept across the surface's outline: the ray test
    # changes its answer where a line touches the surface, and the transition
    # function (positive where two roots exist) changes sign at the same place
    surface = SURFACES[name]
    z0 = 1.2 if name == "vase" else 0.6
    v = np.array([[-1.0, 0.0, 0.05]])

    def rays(y: np.ndarray) -> np.ndarray:
        return np.column_stack([np.full(len(y), 5.0), y, np.full(len(y), z0)])

    y = np.linspace(0, 2, 2001)
    inf = np.full(len(y), np.inf)
    hit = surface.hits(rays(y), np.repeat(v, len(y), 0), inf)
    k = np.flatnonzero(hit[1:] != hit[:-1])
    assert len(k) >= 1
    lo, hi = y[k[-1]], y[k[-1] + 1]  # the outermost touching
    h_lo = hit[k[-1]]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if surface.hits(rays(np.array([mid])), v, np.array([np.inf]))[0] == h_lo:
            lo = mid
        else:
            hi = mid
    off = np.zeros(2, np.int8)
    g = _revolution_hits.grazing(
        surface, rays(np.array([lo, hi])), np.repeat(v, 2, 0), np.full(2, np.inf), off
    )
    assert hi - lo < 1e-13
    assert (g[0] > 0) == h_lo and (g[1] > 0) != h_lo


def test_the_ray_test_shortcut_has_the_sign_of_the_exact_margin():
    # the ray test takes t from the height grid unless the margin there is within
    # the cell's bound of zero; points near the contour must take the exact path
    from lgraph.surfaces.revolution._convex import margin

    p = PROJECTORS["central"]
    central, wa, r0, psi0 = view_terms(EGG, p)
    t = np.linspace(0.01, np.pi - 0.01, 400)
    rho, z = EGG.rz(t)
    dr, dz = EGG.drz(t)
    c = dz * rho + dr * (wa - z)
    with np.errstate(invalid="ignore"):
        phi_c = psi0 + np.arccos(c / (dz * r0))
    t, phi_c = t[np.isfinite(phi_c)], phi_c[np.isfinite(phi_c)]
    rng = np.random.default_rng(4)
    tt = np.concatenate([np.repeat(t, 4), rng.uniform(0, np.pi, 2000)])
    phi = np.concatenate(
        [(phi_c[:, None] + [-1e-9, -1e-12, 1e-12, 1e-9]).ravel(), rng.uniform(0, 7, 2000)]
    )
    x = EGG.point(tt, phi)
    v, smax = p.rays(x)
    own = np.full(len(x), ON, np.int8)
    fast = margin(EGG, x, v, smax, own, exact=False)
    exact = margin(EGG, x, v, smax, own, np.column_stack([tt, phi]))
    assert np.array_equal(fast > 0, exact > 0)
    assert (exact[: 4 * len(t)] > 0).sum() == 2 * len(t)  # both sides of the contour
