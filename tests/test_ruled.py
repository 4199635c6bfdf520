"""Ruled surfaces (paper §4): general cylinders, cones, tangent surfaces.

Every check is independent of the code under test: fundamental forms by
finite differences of ``point()``, the paper's equation (3.3) solved here,
contours against a sign scan of ``det(x1, x2, view)`` on a fine grid, and
visibility against a ray cast through a fine triangulation.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

import lgraph as lg
from lgraph.surfaces.ruled import GeneralCone, GeneralCylinder, RuledSurface, TangentSurface

TAU = 2 * np.pi


# -- surfaces used below --------------------------------------------------------
def flower(t):  # non-convex closed plane curve (r = 2 + 0.6 cos 3t)
    r = 2 + 0.6 * np.cos(3 * t)
    return np.stack([r * np.cos(t), r * np.sin(t), 0 * t], axis=-1)


def wavy(t):  # closed space curve
    return np.stack([2 * np.cos(t), 1.4 * np.sin(t), 3 + 0.5 * np.sin(3 * t)], axis=-1)


def helix(t):
    return np.stack([np.cos(t), np.sin(t), 0.3 * t], axis=-1)


def cylinder():  # numeric derivatives on purpose
    return GeneralCylinder(lg.Curve(flower, 0, TAU, closed=True), (0.2, 0.1, 1), u2_range=(0, 3))


def cone(scaled=False):
    c = lg.Curve(wavy, 0, TAU, closed=True)
    if scaled:
        return GeneralCone(c, apex=(0.3, -0.2, 0), scaled=True, u2_range=(0, 1.2))
    return GeneralCone(c, apex=(0.3, -0.2, 0))


def tangent_surface():
    return TangentSurface(lg.Curve(helix, 0, 4 * np.pi), u2_range=(-2, 2))


def fig_4_2_surface():
    y = lg.Curve(lambda t: np.stack([4 * np.cos(t), 4 * np.sin(t), 0 * t], -1), 0, TAU, closed=True)

    def z(t):
        return np.stack([np.cos(t) * np.sin(4 * t), np.sin(t) * np.sin(4 * t), np.cos(4 * t)], -1)

    return RuledSurface(y, z, u2_range=(0, 3))


# -- independent finite-difference geometry ----------------------------------------
H = 1e-3


def fd_forms(surf, uv):
    """x1, x2 and g11, g12, g22, L11, L12, L22 by central differences of point()."""
    u, v = uv[:, 0], uv[:, 1]
    f = surf.point
    x1 = (-f(u + 2 * H, v) + 8 * f(u + H, v) - 8 * f(u - H, v) + f(u - 2 * H, v)) / (12 * H)
    x2 = (-f(u, v + 2 * H) + 8 * f(u, v + H) - 8 * f(u, v - H) + f(u, v - 2 * H)) / (12 * H)
    x0 = f(u, v)
    x11 = -f(u + 2 * H, v) + 16 * f(u + H, v) - 30 * x0 + 16 * f(u - H, v) - f(u - 2 * H, v)
    x22 = -f(u, v + 2 * H) + 16 * f(u, v + H) - 30 * x0 + 16 * f(u, v - H) - f(u, v - 2 * H)
    x11, x22 = x11 / (12 * H * H), x22 / (12 * H * H)
    x12 = (f(u + H, v + H) - f(u + H, v - H) - f(u - H, v + H) + f(u - H, v - H)) / (4 * H * H)
    n = np.cross(x1, x2)
    n /= np.linalg.norm(n, axis=1, keepdims=True)

    def dot(a, b):
        return np.einsum("ij,ij->i", a, b)

    g = (dot(x1, x1), dot(x1, x2), dot(x2, x2))
    L = (dot(n, x11), dot(n, x12), dot(n, x22))
    return x1, x2, g, L


def principal_angle(surf, uv, duv):
    """Angle (deg) between x1 du1 + x2 du2 and the nearer root of equation (3.3),
    and the larger principal curvature magnitude (to skip flat points)."""
    x1, x2, (g11, g12, g22), (L11, L12, L22) = fd_forms(surf, uv)
    # (3.3): (L11 du1 + L12 du2)(g12 du1 + g22 du2) - (g11 du1 + g12 du2)(L12 du1 + L22 du2) = 0
    A = L11 * g12 - g11 * L12
    B = L11 * g22 - g11 * L22
    C = L12 * g22 - g12 * L22
    disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0))
    q = -0.5 * (B + np.where(B >= 0, 1, -1) * disc)
    t = duv[:, :1] * x1 + duv[:, 1:] * x2
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    ang = []
    for d in (np.stack([q, A], 1), np.stack([C, q], 1)):
        e = d[:, :1] * x1 + d[:, 1:] * x2
        ne = np.linalg.norm(e, axis=1)
        c = np.abs(np.einsum("ij,ij->i", e, t)) / np.where(ne > 0, ne, 1)
        ang.append(np.where(ne > 0, np.degrees(np.arccos(np.clip(c, 0, 1))), 90.0))
    gdet = g11 * g22 - g12 * g12
    H_ = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * gdet)
    K = (L11 * L22 - L12 * L12) / gdet
    kmax = np.abs(H_) + np.sqrt(np.maximum(H_ * H_ - K, 0))
    return np.minimum(*ang), kmax


def lagrange_slope(x, y):
    """dy/dx at the middle of every five consecutive (uneven) samples: derivative
    of the interpolating quartic (fourth-order accurate)."""
    n = len(x) - 4
    X = np.stack([x[k : k + n] for k in range(5)], 1)
    Y = np.stack([y[k : k + n] for k in range(5)], 1)
    xi = X[:, 2]
    slope = np.zeros(n)
    for j in range(5):
        if j == 2:
            w = sum(1 / (xi - X[:, k]) for k in range(5) if k != 2)
        else:
            w = 1 / (X[:, j] - xi)
            for k in range(5):
                if k not in (2, j):
                    w = w * (xi - X[:, k]) / (X[:, j] - X[:, k])
        slope += w * Y[:, j]
    return slope


def curvature_points(surf, drawing):
    """Interior points of the curvature strokes with their tangents (rulings:
    ``(0, 1)``; the other family is a graph ``u2(u1)``)."""
    uv, duv = [], []
    period = surf.domain.span(0) if surf.domain.periodic[0] else None
    for s in drawing.strokes:
        if s.family != "curvature" or len(s.uv) < 5:
            continue
        # xyz lies exactly on the surface at uv
        np.testing.assert_allclose(
            s.xyz, surf.point(s.uv[:, 0], s.uv[:, 1]), rtol=0, atol=1e-12 * surf.size
        )
        u, v = s.uv[:, 0].copy(), s.uv[:, 1]
        if np.ptp(u) == 0:
            uv.append(s.uv)
            duv.append(np.tile([0.0, 1.0], (len(u), 1)))
            continue
        if period:  # closed strokes may run across the seam
            du = (np.diff(u) + period / 2) % period - period / 2
            u = np.concatenate([[u[0]], u[0] + np.cumsum(du)])
        keep = np.concatenate([[True], np.abs(np.diff(u)) > 1e-9])  # both sides of flips
        u, v, pts = u[keep], v[keep], s.uv[keep]
        if len(u) < 5:
            continue
        slope = lagrange_slope(u, v)
        uv.append(pts[2:-2])
        duv.append(np.column_stack([np.ones_like(slope), slope]))
    return np.concatenate(uv), np.concatenate(duv)


@pytest.mark.parametrize(
    "make, singular",
    [
        (cylinder, None),
        (cone, "vertex"),
        (lambda: cone(scaled=True), "vertex"),
        (tangent_surface, "edge"),
    ],
    ids=["cylinder", "cone", "scaled-cone", "tangent-helix"],
)
def test_lines_of_curvature_satisfy_3_3(make, singular):
    surf = make()
    scene = lg.Scene()
    scene.add(surf, lg.LinesOfCurvature(12, 10))
    d = scene.render(lg.ParallelProjector(direction=(1, -0.7, 0.5)), hidden_lines=True)
    fams = {s.family for s in d.strokes}
    assert "curvature" in fams
    lo, hi = surf.domain.u2
    uv, duv = curvature_points(surf, d)
    assert np.all((uv[:, 1] >= lo - 1e-12) & (uv[:, 1] <= hi + 1e-12))
    keep = np.linalg.norm(duv, axis=1) > 0
    if singular == "vertex":  # stay away from the vertex
        dist = np.linalg.norm(surf.point(uv[:, 0], uv[:, 1]) - surf.apex, axis=1)
        keep &= dist > 0.05 * surf.size
    if singular == "edge":  # stay away from the edge of regression u2 = 0
        keep &= np.abs(uv[:, 1]) > 0.05 * (hi - lo)
    ang, kmax = principal_angle(surf, uv[keep], duv[keep])
    flat = kmax * surf.size < 1e-2  # planar points: principal directions undefined
    ang = ang[~flat]
    assert len(ang) > 500
    assert np.percentile(ang, 99) <= 0.5
    assert ang.max() <= 2.0


def test_second_family_is_not_the_parameter_lines():
    """For a general cone the curves |x - apex| = d cross the u2 = const lines;
    over a spherical directrix they are the u2 lines (paper Fig. 4.5)."""
    c = cone()
    batch = c.lines_of_curvature(0, 6)[0]
    t = np.linspace(batch.t0[0], batch.t1[0], 50)
    xyz, uv = batch.evaluate(np.zeros(50, int), t)
    r = np.linalg.norm(xyz - c.apex, axis=1)
    assert np.ptp(r) < 1e-12 * c.size and np.ptp(uv[:, 1]) > 0.05
    sph = lg.Curve(
        lambda t: 3 * np.stack([np.cos(t) * 0.6, np.sin(t) * 0.6, 0 * t + 0.8], -1),
        0,
        TAU,
        closed=True,
    )
    s = GeneralCone(sph, apex=(0, 0, 0))
    assert s.domain.u2 == pytest.approx((-3, 0))
    b = s.lines_of_curvature(0, 4)[0]
    assert np.all(b.closed)
    _, uv = b.evaluate(np.repeat(np.arange(4), 20), np.tile(np.linspace(0, TAU, 20), 4))
    assert np.ptp(uv[:, 1].reshape(4, 20), axis=1).max() < 1e-12


def test_analytic_derivatives_match_finite_differences():
    for surf in (cylinder(), cone(), cone(scaled=True), tangent_surface(), fig_4_2_surface()):
        rng = np.random.default_rng(1)
        lo, hi = surf.domain.u2
        t0, t1 = surf.domain.u1
        uv = np.column_stack([rng.uniform(t0 + 0.1, t1 - 0.1, 40), rng.uniform(lo, hi, 40)])
        uv = uv[np.abs(uv[:, 1]) > 0.1]
        x1, x2, _, _ = fd_forms(surf, uv)
        a1, a2 = surf.derivatives(uv[:, 0], uv[:, 1])
        np.testing.assert_allclose(a1, x1, atol=1e-7 * surf.size)
        np.testing.assert_allclose(a2, x2, atol=1e-7 * surf.size)
        x11, x12, x22 = surf.second_derivatives(uv[:, 0], uv[:, 1])
        f = surf.point
        u, v = uv[:, 0], uv[:, 1]
        h = 1e-3
        fd12 = (f(u + h, v + h) - f(u + h, v - h) - f(u - h, v + h) + f(u - h, v - h)) / (4 * h * h)
        fd11 = (f(u + h, v) - 2 * f(u, v) + f(u - h, v)) / (h * h)
        np.testing.assert_allclose(x12, fd12, atol=1e-4 * surf.size)
        np.testing.assert_allclose(x11, fd11, atol=1e-4 * surf.size)
        assert np.all(x22 == 0)


# -- contours ---------------------------------------------------------------------------
PROJECTORS = [
    lg.ParallelProjector(direction=(1, -0.7, 0.25)),
    lg.CentralProjector(eye=(11, -8, 6), target=(0, 0, 1)),
]


def view_det(surf, uv, projector):
    x1, x2, _, _ = fd_forms(surf, uv)
    p = surf.point(uv[:, 0], uv[:, 1])
    if isinstance(projector, lg.CentralProjector):
        w = projector.eye - p
    else:
        w = np.broadcast_to(projector.frame[2], p.shape)
    n = np.cross(x1, x2)
    return np.einsum("ij,ij->i", n, w) / (
        np.linalg.norm(x1, axis=1) * np.linalg.norm(x2, axis=1) * np.linalg.norm(w, axis=1)
    ), np.linalg.norm(n, axis=1) / (np.linalg.norm(x1, axis=1) * np.linalg.norm(x2, axis=1))


def contour_uv(surf, projector, n=400):
    out = []
    for b in surf.contour(projector):
        k = len(b)
        idx = np.repeat(np.arange(k), n)
        t = (b.t0[:, None] + (b.t1 - b.t0)[:, None] * np.linspace(0, 1, n)).ravel()
        xyz, uv = b.evaluate(idx, t)
        np.testing.assert_allclose(xyz, surf.point(uv[:, 0], uv[:, 1]), atol=1e-12 * surf.size)
        out.append(uv)
    return np.concatenate(out)


@pytest.mark.parametrize("projector", PROJECTORS, ids=["parallel", "central"])
@pytest.mark.parametrize(
    "make", [cylinder, cone, tangent_surface, fig_4_2_surface], ids=["cyl", "cone", "tan", "ruled"]
)
def test_contour_points_and_completeness(make, projector):
    surf = make()
    lo, hi = surf.domain.u2
    t0, t1 = surf.domain.u1
    uv = contour_uv(surf, projector)
    assert np.all(np.isfinite(uv))
    inner = (uv[:, 1] > lo + 1e-9) & (uv[:, 1] < hi - 1e-9) & (uv[:, 0] > t0) & (uv[:, 0] < t1)
    det, regular = view_det(surf, uv[inner], projector)
    regular = regular > 1e-3
    if make is tangent_surface:  # the edge of regression is drawn too (singular)
        regular &= np.abs(uv[inner][:, 1]) > 1e-6
    assert regular.sum() > 50
    assert np.abs(det[regular]).max() <= 1e-9
    # completeness: every sign change of det(x1, x2, view) on a fine grid is near the contour
    g1, g2 = np.meshgrid(np.linspace(t0, t1, 601), np.linspace(lo, hi, 61), indexing="ij")
    guv = np.column_stack([g1.ravel(), g2.ravel()])
    gd, greg = view_det(surf, guv, projector)
    gd = np.where(greg > 1e-3, gd, np.nan).reshape(g1.shape)
    flip = (gd[1:, :] * gd[:-1, :] < 0) & (np.abs(gd[1:, :] - gd[:-1, :]) < 0.5)
    cells = np.column_stack([g1[1:, :][flip], g2[1:, :][flip]])
    scale = np.array([(t1 - t0) / 600, (hi - lo) / 60])
    dist, _ = cKDTree(uv / scale).query(cells / scale)
    assert len(cells) > 10
    assert dist.max() < 3


def test_cylinder_and_cone_contours_are_rulings():
    for surf in (cylinder(), cone()):
        rulings = 0
        for b in surf.contour(PROJECTORS[0]):
            idx = np.arange(len(b))
            _, a = b.evaluate(idx, b.t0)
            _, e = b.evaluate(idx, b.t1)
            ruling = np.all(a[:, 0] == e[:, 0])
            assert ruling or np.all(a[:, 1] == e[:, 1])  # else a u2 edge of the patch
            rulings += len(b) if ruling else 0
        assert rulings >= 2


def test_no_nan_at_singular_sets():
    """A cone reaching its vertex and a tangent surface with both sheets render
    without NaN (the renderer refuses non-finite points)."""
    sph = lg.Curve(
        lambda t: np.stack([2 * np.cos(t), 2 * np.sin(t), 0 * t + 2], -1), 0, TAU, closed=True
    )
    scene = lg.Scene()
    scene.add(GeneralCone(sph, apex=(0, 0, 0)), lg.LinesOfCurvature(8, 4))
    scene.add(tangent_surface(), lg.LinesOfCurvature(8, 4), transform=lg.translate(6, 0, 0))
    for p in PROJECTORS:
        d = scene.render(p, tolerance=1e-3)
        assert all(np.all(np.isfinite(s.xy)) for s in d.strokes)
    edge = [b for b in tangent_surface().contour(PROJECTORS[0]) if len(b) == 1]
    _, uv = edge[-1].evaluate(np.zeros(5, int), np.linspace(0, 4 * np.pi, 5))
    assert np.any(np.all(uv[:, 1:] == 0, axis=0))  # the edge of regression u2 = 0 is drawn


# -- visibility against a ray cast through a fine triangulation ---------------------------
def triangles(surf, transform, n1, n2):
    d = surf.domain
    u1, u2 = np.meshgrid(np.linspace(*d.u1, n1 + 1), np.linspace(*d.u2, n2 + 1), indexing="ij")
    p = transform.apply(surf.point(u1, u2).reshape(-1, 3)).reshape(n1 + 1, n2 + 1, 3)
    a, b, c, e = p[:-1, :-1], p[1:, :-1], p[1:, 1:], p[:-1, 1:]
    return np.concatenate(
        [np.stack([a, b, c], 2).reshape(-1, 3, 3), np.stack([a, c, e], 2).reshape(-1, 3, 3)]
    )


def brute_hidden(tris, pts, dirs, smax, smin):
    """Moeller-Trumbore: does the ray pts + s dirs (smin < s < smax) cross a triangle?"""
    v0, e1, e2 = tris[:, 0], tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
    out = np.zeros(len(pts), bool)
    for k in range(0, len(pts), 64):
        P, D = pts[k : k + 64, None, :], dirs[k : k + 64, None, :]
        pv = np.cross(D, e2)
        det = np.einsum("ijk,jk->ij", pv, e1)
        ok = np.abs(det) > 1e-14
        inv = 1 / np.where(ok, det, 1)
        tv = P - v0
        a = np.einsum("ijk,ijk->ij", tv, pv) * inv
        qv = np.cross(tv, e1)
        b = np.einsum("ijk,ijk->ij", D, qv) * inv
        s = np.einsum("jk,ijk->ij", e2, qv) * inv
        hit = ok & (a >= 0) & (b >= 0) & (a + b <= 1) & (s > smin) & (s < smax[k : k + 64, None])
        out[k : k + 64] = hit.any(axis=1)
    return out


def check_visibility(scene, projector, meshes, npts=400, seed=0):
    d = scene.render(projector, hidden_lines=True, tolerance=5e-4)
    xy = np.concatenate([s.xy for s in d.strokes])
    diag = np.linalg.norm(xy.max(0) - xy.min(0))
    # stay away from transitions: ends of visible strokes (a hidden stroke also
    # ends where the number of sheets in front changes, still hidden) and every
    # contour (incl. patch edges)
    avoid = [s.xy[[0, -1]] for s in d.strokes if s.visible]
    avoid += [s.xy for s in d.strokes if s.family == "contour"]
    tree = cKDTree(np.concatenate(avoid))
    pts, vis = [], []
    for s in d.strokes:
        if s.family == "contour":
            continue
        far = tree.query(s.xy)[0] > 0.02 * diag
        pts.append(s.xyz[far])
        vis.append(np.full(far.sum(), s.visible))
    pts, vis = np.concatenate(pts), np.concatenate(vis)
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(pts), size=min(npts, len(pts)), replace=False)
    pts, vis = pts[pick], vis[pick]
    assert vis.sum() > 50 and (~vis).sum() > 50
    dirs, smax = projector.rays(pts)
    tris = np.concatenate(meshes)
    hidden = brute_hidden(tris, pts, dirs, smax, 2e-3 * diag)
    bad = hidden == vis
    assert bad.sum() == 0, f"{bad.sum()} of {len(pts)} points disagree with the ray cast"


def test_visibility_cylinder_sphere_parallel():
    scene = lg.Scene()
    cyl = cylinder()
    sph, tr = lg.Sphere(1.3), lg.translate(0.5, -2.6, 1.5)
    scene.add(cyl, lg.LinesOfCurvature(24, 8))
    scene.add(sph, lg.ParameterLines(8, 12), transform=tr)
    meshes = [triangles(cyl, lg.translate(0, 0, 0), 160, 12), triangles(sph, tr, 24, 36)]
    check_visibility(scene, lg.ParallelProjector(direction=(1, -0.8, 0.6)), meshes)


def test_visibility_cone_ellipsoid_central():
    scene = lg.Scene()
    c = cone()
    ell, tr = lg.Ellipsoid(1.6, 1, 0.8), lg.translate(1.5, -1.0, 2.2)
    scene.add(c, lg.LinesOfCurvature(24, 8))
    scene.add(ell, lg.ParameterLines(8, 12), transform=tr)
    meshes = [triangles(c, lg.translate(0, 0, 0), 160, 16), triangles(ell, tr, 24, 36)]
    check_visibility(scene, lg.CentralProjector(eye=(11, -8, 6), target=(0, 0, 1.5)), meshes)


def test_visibility_general_ruled_surface_with_sphere():
    """Fig. 4.2's surface hides itself heavily; a sphere sits inside it."""
    scene = lg.Scene()
    s = fig_4_2_surface()
    sph = lg.Sphere(2)
    scene.add(s, lg.ParameterLines(32, 6))
    scene.add(sph, lg.ParameterLines(6, 12), transform=lg.translate(0, 0, 1))
    meshes = [
        triangles(s, lg.translate(0, 0, 0), 300, 16),
        triangles(sph, lg.translate(0, 0, 1), 24, 36),
    ]
    check_visibility(scene, lg.ParallelProjector(direction=(1, 0.4, 0.45)), meshes)


def test_visibility_tangent_surface_sphere_central():
    scene = lg.Scene()
    t = tangent_surface()
    sph, tr = lg.Sphere(1.0), lg.translate(0, 0, 2)
    scene.add(t, lg.LinesOfCurvature(30, 8))
    scene.add(sph, lg.ParameterLines(6, 12), transform=tr)
    meshes = [triangles(t, lg.translate(0, 0, 0), 300, 24), triangles(sph, tr, 24, 36)]
    check_visibility(scene, lg.CentralProjector(eye=(9, -6, 3), target=(0, 0, 2)), meshes)


def test_hits_own_points_and_grazing_rays():
    """Rays leaving points of a cylinder: outward along the normal nothing is hit
    (convex part), inward the opposite wall is hit; contour points are not
    hidden by their own tangency."""
    circ = lg.Curve(lambda t: np.stack([np.cos(t), np.sin(t), 0 * t], -1), 0, TAU, closed=True)
    cyl = GeneralCylinder(circ, (0, 0, 1), u2_range=(0, 1))
    t = np.linspace(0, TAU, 50, endpoint=False)
    p = cyl.point(t, 0.5)
    n = p * [1, 1, 0]
    own = np.full(len(t), lg.surfaces.ON)
    assert not cyl.hits(p, n, np.inf, own).any()
    assert cyl.hits(p, -n, np.inf, own).all()
    assert not cyl.hits(p, -n, np.full(len(t), 1.9), own).any()  # the wall is 2 away
    # contour rulings for the view (1, 0, 0) lie at t = pi/2, 3pi/2
    proj = lg.ParallelProjector(direction=(1, 0, 0))
    u1 = []
    for b in cyl.contour(proj):
        a, e = (b.evaluate(np.arange(len(b)), t)[1] for t in (b.t0, b.t1))
        if np.all(a[:, 0] == e[:, 0]):
            u1.append(a[:, 0])
    u1 = np.sort(np.concatenate(u1))
    np.testing.assert_allclose(np.mod(u1, TAU), [np.pi / 2, 3 * np.pi / 2], atol=1e-13)
    q = cyl.point(u1, 0.5)
    assert not cyl.hits(
        q, np.tile([1.0, 0, 0], (2, 1)), np.inf, np.full(2, lg.surfaces.CONTOUR)
    ).any()


def test_validation_messages():
    c = lg.Curve(wavy, 0, TAU)
    with pytest.raises(TypeError, match="RuledSurface: directrix must be an lg.Curve"):
        RuledSurface(wavy, wavy)
    with pytest.raises(ValueError, match="GeneralCylinder: direction must be a non-zero vector"):
        GeneralCylinder(c, (0, 0, 0))
    with pytest.raises(ValueError, match="GeneralCone: the ruling direction must be a non-zero"):
        GeneralCone(c, apex=wavy(np.array([0.0]))[0])
    with pytest.raises(ValueError, match="u2_range must be a pair"):
        GeneralCylinder(c, (0, 0, 1), u2_range=(1, 0))
    with pytest.raises(ValueError, match="need a developable surface"):
        fig_4_2_surface().lines_of_curvature(3, 3)


def test_numeric_curve_derivatives_are_accurate():
    c = lg.Curve(lambda t: np.stack([np.cos(4 * t), 3 * np.sin(t), t * t], -1), 0, TAU)
    t = np.linspace(0.5, 5.5, 9)
    d1 = np.stack([-4 * np.sin(4 * t), 3 * np.cos(t), 2 * t], -1)
    d2 = np.stack([-16 * np.cos(4 * t), -3 * np.sin(t), 2 + 0 * t], -1)
    np.testing.assert_allclose(c.derivative(t), d1, atol=1e-11)
    np.testing.assert_allclose(c.second_derivative(t), d2, atol=1e-9)
