"""Tests of the Dupin cyclide plugin against independent checks: the sphere
family it envelops, finite-difference normals, brute-force ray marching."""

from __future__ import annotations

import importlib.metadata as md

import numpy as np
import pytest
from lgraph_cyclide import DiagonalLines, DupinCyclide

import lgraph as lg
from lgraph._own import CONTOUR, OFF, ON

CYCLIDES = [DupinCyclide(5, 2, 3), DupinCyclide(4, 1, 1.5), DupinCyclide(3, 0, 1)]
VIEWS = [
    lg.ParallelProjector.from_angles(30, 35),
    lg.ParallelProjector(direction=(0, 1, 0.05)),
    lg.ParallelProjector(direction=(0, 0, 1)),
    lg.CentralProjector.from_angles(30, 35, 25),
    lg.CentralProjector.from_angles(-60, 15, 14),
]
TWO_PI = 2 * np.pi


def fd_derivatives(s, u, v, h=1e-5):
    xu = (s.point(u + h, v) - s.point(u - h, v)) / (2 * h)
    xv = (s.point(u, v + h) - s.point(u, v - h)) / (2 * h)
    return xu, xv


def fd_normal(s, u, v):
    xu, xv = fd_derivatives(s, u, v)
    n = np.cross(xu, xv)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def inside_depth(s, x, nu=720):
    """min over the sphere family of |x - m(u)| - r(u): < 0 inside the solid.

    Written from the definition (envelope of spheres centred on the ellipse
    (a cos u, b sin u, 0) with radii mu - c cos u), not from the code under test.
    Computed in chunks to bound memory.
    """
    u = np.linspace(0, TWO_PI, nu, endpoint=False)
    b = np.sqrt(s.a**2 - s.c**2)
    m = np.stack([s.a * np.cos(u), b * np.sin(u), 0 * u], axis=-1)
    r = s.mu - s.c * np.cos(u)
    flat = np.asarray(x, float).reshape(-1, 3)
    out = np.empty(len(flat))
    for k in range(0, len(flat), 20000):
        p = flat[k : k + 20000]
        d2 = (p * p).sum(1)[:, None] - 2 * p @ m.T + (m * m).sum(1)[None, :]
        out[k : k + 20000] = (np.sqrt(np.maximum(d2, 0)) - r).min(axis=1)
    return out.reshape(np.shape(x)[:-1])


@pytest.mark.parametrize("cy", CYCLIDES, ids=repr)
def test_points_lie_on_the_sphere_family_and_implicit_equation(cy):
    u, v = np.meshgrid(np.linspace(0, TWO_PI, 37), np.linspace(0, TWO_PI, 41), indexing="ij")
    p = cy.point(u, v)
    b = np.sqrt(cy.a**2 - cy.c**2)
    m = np.stack([cy.a * np.cos(u), b * np.sin(u), 0 * u], axis=-1)
    assert np.allclose(np.linalg.norm(p - m, axis=-1), cy.mu - cy.c * np.cos(u), atol=1e-12)
    # implicit quartic, written out here independently
    x, y = p[..., 0], p[..., 1]
    q = (p * p).sum(-1) + b * b - cy.mu**2
    f = q * q - 4 * (cy.a * x - cy.c * cy.mu) ** 2 - 4 * b * b * y * y
    assert np.abs(f).max() < 1e-9 * cy.a**4
    assert np.allclose(cy.implicit(p), f, atol=1e-9 * cy.a**4)
    lo, hi = cy.bounds()
    assert np.all(p >= lo - 1e-12) and np.all(p <= hi + 1e-12)
    assert np.allclose(p.min(axis=(0, 1)), lo, atol=0.05 * cy.a)  # and the box is tight


@pytest.mark.parametrize("cy", CYCLIDES, ids=repr)
def test_analytic_derivatives_match_finite_differences(cy):
    rng = np.random.default_rng(1)
    u, v = rng.uniform(0, TWO_PI, (2, 50))
    xu, xv = cy.derivatives(u, v)
    fu, fv = fd_derivatives(cy, u, v)
    assert np.allclose(xu, fu, atol=1e-7) and np.allclose(xv, fv, atol=1e-7)


@pytest.mark.parametrize("cy", CYCLIDES, ids=repr)
def test_parameter_lines_are_lines_of_curvature(cy):
    # g12 = 0 and L12 = 0 (paper eq. 3.3 holds for both parameter directions)
    rng = np.random.default_rng(2)
    u, v = rng.uniform(0, TWO_PI, (2, 60))
    h = 1e-4
    xu, xv = fd_derivatives(cy, u, v)
    xuv = (
        cy.point(u + h, v + h) - cy.point(u + h, v - h) - cy.point(u - h, v + h)
        + cy.point(u - h, v - h)
    ) / (4 * h * h)  # fmt: skip
    n = fd_normal(cy, u, v)
    scale = np.linalg.norm(xu, axis=1) * np.linalg.norm(xv, axis=1)
    assert np.abs((xu * xv).sum(1) / scale).max() < 1e-8
    assert np.abs((n * xuv).sum(1) / scale).max() < 1e-5
    batches = lg.LinesOfCurvature(5, 7).batches(cy, None)
    assert sum(len(b) for b in batches) == 12
    assert {b.family for b in batches} == {"curvature"}


def _contour_points(cy, proj, n=400):
    pts, uvs = [], []
    for b in cy.contour(proj):
        for k in range(len(b)):
            t = np.linspace(b.t0[k], b.t1[k], n)
            x, uv = b.evaluate(np.full(n, k), t)
            pts.append(x)
            uvs.append(uv)
    return np.concatenate(pts), np.concatenate(uvs)


def _view(proj, x):
    return proj.view_vectors(x)


@pytest.mark.parametrize("proj", VIEWS, ids=lambda p: p.describe())
@pytest.mark.parametrize("cy", CYCLIDES, ids=repr)
def test_contour_is_exact_and_complete(cy, proj):
    x, uv = _contour_points(cy, proj, n=6000)
    # on the surface, at its own parameters, with N . w = 0
    assert np.allclose(cy.point(uv[:, 0], uv[:, 1]), x, atol=1e-10)
    w = _view(proj, x)
    w = w / np.linalg.norm(w, axis=-1, keepdims=True)
    assert np.abs((fd_normal(cy, uv[:, 0], uv[:, 1]) * w).sum(1)).max() < 1e-7
    # complete: every sign change of N . w along circles u = const (brute
    # force) lies on the returned contour
    us = np.linspace(0, TWO_PI, 23, endpoint=False) + 0.0123
    vs = np.linspace(0, TWO_PI, 4001)
    U, V = np.meshgrid(us, vs, indexing="ij")
    P = cy.point(U, V)
    W = _view(proj, P)
    g = (fd_normal(cy, U, V) * W).sum(-1)
    i, j = np.nonzero(np.sign(g[:, 1:]) != np.sign(g[:, :-1]))
    assert len(i) > 0
    t = g[i, j] / (g[i, j] - g[i, j + 1])
    found = P[i, j] + t[:, None] * (P[i, j + 1] - P[i, j])
    dist = np.linalg.norm(found[:, None, :] - x[None, :, :], axis=-1).min(axis=1)
    assert dist.max() < 2e-3 * cy.a  # dense polyline: vertex spacing is the error
    # and the contour's circles u = const meet it nowhere else
    assert len(found) <= len(us) * 4


def test_torus_contour_from_above_is_two_circles():
    torus = DupinCyclide(3, 0, 1)
    x, _ = _contour_points(torus, lg.ParallelProjector(direction=(0, 0, 1)))
    rho = np.hypot(x[:, 0], x[:, 1])
    assert np.allclose(np.sort(np.unique(np.round(rho, 9))), [2.0, 4.0])
    assert np.allclose(x[:, 2], 0, atol=1e-12)


def brute_force_hits(cy, o, v, smax, start, n=500):
    """March each ray over (start, smax) up to where it leaves the bounding
    sphere; a hit is a sample inside the solid (depth < 0)."""
    far = (np.linalg.norm(o, axis=1) + cy.a + cy.c + cy.mu) / np.linalg.norm(v, axis=1)
    end = np.minimum(smax, far)
    s = start[:, None] + (end - start)[:, None] * np.linspace(0, 1, n)
    depth = inside_depth(cy, o[:, None, :] + s[..., None] * v[:, None, :])
    return depth.min(axis=1), depth


@pytest.mark.parametrize("cy", CYCLIDES[:2], ids=repr)
def test_hits_of_outside_rays_agree_with_ray_marching(cy):
    rng = np.random.default_rng(3)
    n = 300
    lo, hi = cy.bounds()
    o = rng.uniform(lo * 1.6, hi * 1.6, (n, 3))
    o = o[inside_depth(cy, o) > 0.05]
    target = rng.uniform(lo, hi, (len(o), 3))
    v = (target - o) * rng.uniform(0.5, 2, (len(o), 1))  # not unit vectors
    smax = np.where(rng.uniform(size=len(o)) < 0.5, np.inf, rng.uniform(0.3, 2, len(o)))
    got = cy.hits(o, v, smax, np.full(len(o), OFF, np.int8))
    mind, _ = brute_force_hits(cy, o, v, smax, np.zeros(len(o)))
    clear = np.abs(mind) > 0.02  # skip rays grazing the surface (ambiguous for marching)
    assert clear.sum() > 150
    assert np.array_equal(got[clear], (mind < 0)[clear])
    assert got[clear].any() and (~got[clear]).any()


@pytest.mark.parametrize("proj", VIEWS[:2] + VIEWS[3:4], ids=lambda p: p.describe())
def test_hits_of_rays_from_the_surface_agree_with_ray_marching(proj):
    cy = CYCLIDES[0]
    rng = np.random.default_rng(4)
    u, v = rng.uniform(0, TWO_PI, (2, 300))
    p = cy.point(u, v)
    d, smax = proj.rays(p)
    n = fd_normal(cy, u, v)
    steep = np.abs((n * d).sum(1)) > 0.25  # leave the surface clearly in or out
    got = cy.hits(p, d, smax, np.full(len(p), ON, np.int8))
    # march from s = 0.3: clear of the origin, still inside for inward rays
    # (the tube is at least 2 (mu - c) = 2 wide, so a steep chord is > 0.5)
    mind, _ = brute_force_hits(cy, p, d, smax, np.full(len(p), 0.3))
    clear = steep & (np.abs(mind) > 0.02)
    assert clear.sum() > 90
    assert np.array_equal(got[clear], (mind < 0)[clear])
    assert got[clear].any() and (~got[clear]).any()


def test_contour_points_are_hidden_only_by_other_parts():
    cy = CYCLIDES[0]
    proj = lg.ParallelProjector(direction=(0, 1, 0.05))
    x, _ = _contour_points(cy, proj, n=200)
    d, smax = proj.rays(x)
    got = cy.hits(x, d, smax, np.full(len(x), CONTOUR, np.int8))
    mind, _ = brute_force_hits(cy, x, d, smax, np.full(len(x), 0.05))
    clear = np.abs(mind) > 0.02
    assert clear.sum() > 100
    assert np.array_equal(got[clear], (mind < 0)[clear])
    assert got.any() and (~got).any()  # the inner contour hides behind the near tube


def test_rendered_visibility_agrees_with_ray_marching():
    cy = CYCLIDES[0]
    proj = lg.CentralProjector.from_angles(30, 35, 25)
    scene = lg.Scene()
    scene.add(cy, lg.LinesOfCurvature(10, 12))
    d = scene.render(proj, hidden_lines=True)
    pts, uvs, vis = [], [], []
    for s in d.strokes:
        if s.family == "curvature" and len(s.xyz) > 8:
            for k in (len(s.xyz) // 4, len(s.xyz) // 2, 3 * len(s.xyz) // 4):
                pts.append(s.xyz[k])
                uvs.append(s.uv[k])
                vis.append(s.visible)
    pts, uvs, vis = np.array(pts), np.array(uvs), np.array(vis)
    dirs, smax = proj.rays(pts)
    steep = np.abs((fd_normal(cy, uvs[:, 0], uvs[:, 1]) * dirs).sum(1)) > 0.25
    mind, _ = brute_force_hits(cy, pts, dirs, smax, np.full(len(pts), 0.3))
    clear = steep & (np.abs(mind) > 0.02)
    assert clear.sum() > 30 and vis[clear].any() and (~vis[clear]).any()
    assert np.array_equal(np.array(vis)[clear], (mind >= 0)[clear])


def test_validation():
    with pytest.raises(ValueError, match="0 <= c < mu < a"):
        DupinCyclide(5, 3, 3)
    with pytest.raises(ValueError, match="finite numbers"):
        DupinCyclide(5, "2", 3)


@pytest.mark.parametrize("surface", [CYCLIDES[0], lg.Ellipsoid(3, 2, 1)], ids=repr)
def test_diagonal_lines_lie_on_the_surface_and_wind(surface):
    fam = DiagonalLines(6, turns=2)
    (batch,) = fam.batches(surface, None)
    assert len(batch) == 6 and batch.family == "diagonal"
    t = np.linspace(0, 1, 50)
    x, uv = batch.evaluate(np.full(50, 3), t)
    assert np.allclose(surface.point(uv[:, 0], uv[:, 1]), x)
    (lo1, hi1), (lo2, hi2) = surface.domain.u1, surface.domain.u2
    assert np.allclose(uv[:, 0], lo1 + t * (hi1 - lo1))
    unwrapped = np.unwrap(uv[:, 1], period=hi2 - lo2)
    assert np.isclose(unwrapped[-1] - unwrapped[0], 2 * (hi2 - lo2))


def test_diagonal_lines_validation():
    with pytest.raises(ValueError, match="n must be an integer"):
        DiagonalLines(-1)
    with pytest.raises(ValueError, match="turns must be a non-zero integer"):
        DiagonalLines(3, turns=0)


def test_registered_through_entry_points():
    try:
        dist = md.distribution("lgraph-cyclide")
    except md.PackageNotFoundError:  # pragma: no cover
        pytest.fail("lgraph-cyclide is not installed: run pip install -e plugins/lgraph-cyclide")
    groups = {(ep.group, ep.name) for ep in dist.entry_points}
    assert ("lgraph.surfaces", "cyclide") in groups
    assert ("lgraph.families", "diagonal_lines") in groups
    from lgraph.plugins import get_family, get_surface

    assert get_surface("cyclide") is DupinCyclide
    assert get_family("diagonal_lines") is DiagonalLines
