"""ImplicitSurface: curves on F = 0 checked against the equations, and hidden
lines against an independent dense ray march of F."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph.surfaces.implicit import ImplicitSurface


def ellipsoid_F(x, y, z):
    return x**2 / 4 + y**2 + z**2 / 2.25 - 1


def torus_F(x, y, z, R=2.0, r=0.7):
    q = x**2 + y**2 + z**2 + R**2 - r**2
    return q**2 - 4 * R**2 * (x**2 + y**2)


def march(F, points, direction, lo, hi, steps=4000):
    """Sign changes of F along each ray points + s direction, lo < s < hi,
    by a dense uniform scan (independent of lgraph's ray tests)."""
    hi = np.maximum(hi, lo)  # a ray leaving the region at once meets nothing
    s = np.linspace(0, 1, steps)[None, :] * (hi - lo)[:, None] + lo[:, None]
    x = points[:, None, :] + s[..., None] * direction
    f = F(x[..., 0], x[..., 1], x[..., 2])
    return (np.sign(f[:, :-1]) * np.sign(f[:, 1:]) < 0).sum(axis=1)


def ball_exit(points, d, r):
    """s where points + s d (unit d) leaves the ball |x| <= r."""
    b = points @ d
    c = np.einsum("ij,ij->i", points, points) - r * r
    return -b + np.sqrt(np.maximum(b * b - c, 0))


def test_parametric_methods_refused():
    s = ImplicitSurface(ellipsoid_F, radius=3)
    with pytest.raises(TypeError, match="no parametrization"):
        s.point(0.1, 0.2)
    with pytest.raises(TypeError, match="no parametrization"):
        s.domain  # noqa: B018
    with pytest.raises(TypeError, match="no parameter lines"):
        lg.ParameterLines(3, 3).batches(s, None)
    with pytest.raises(ValueError, match="exactly one of bounds or radius"):
        ImplicitSurface(ellipsoid_F, radius=1, bounds=((0, 1), (0, 1), (0, 1)))
    with pytest.raises(ValueError, match="ImplicitSurface: bounds must be"):
        ImplicitSurface(ellipsoid_F, bounds=((0, 1), (1, 0), (0, 1)))
    with pytest.raises(TypeError, match="ImplicitSurface: F must be callable"):
        ImplicitSurface("x^2", radius=1)
    with pytest.raises(ValueError, match="ImplicitSurface: grid must be"):
        ImplicitSurface(ellipsoid_F, radius=1, grid=4)


def test_numeric_derivatives_against_closed_forms():
    s = ImplicitSurface(ellipsoid_F, radius=3)
    p = np.random.default_rng(1).normal(size=(20, 3))
    exact = np.stack([p[:, 0] / 2, 2 * p[:, 1], 2 * p[:, 2] / 2.25], axis=1)
    assert np.allclose(s.grad(p), exact, atol=1e-9)
    assert np.allclose(s.hess(p), np.diag([0.5, 2, 2 / 2.25]), atol=1e-6)


@pytest.mark.parametrize(
    "projector",
    [
        lg.ParallelProjector(direction=(1.0, 0.6, 0.5)),
        lg.CentralProjector(eye=(7.0, 4.0, 3.0)),
    ],
)
def test_contour_on_the_surface_and_tangent_to_the_rays(projector):
    s = ImplicitSurface(ellipsoid_F, radius=3)
    (batch,) = s.contour(projector)
    assert len(batch) == 1 and batch.closed.all()  # one closed outline
    t = np.linspace(batch.t0[0], batch.t1[0], 400)
    x, uv = batch.evaluate(np.zeros(len(t), int), t)
    assert uv is None
    assert np.abs(ellipsoid_F(*x.T)).max() < 1e-12
    g = np.stack([x[:, 0] / 2, 2 * x[:, 1], 2 * x[:, 2] / 2.25], axis=1)
    v = projector.view_vectors(x)
    cos = np.einsum("ij,ij->i", g, v) / np.linalg.norm(g, axis=1) / np.linalg.norm(v, axis=1)
    assert np.abs(cos).max() < 1e-10
    if isinstance(projector, lg.ParallelProjector):
        # the contour of an ellipsoid in a parallel view is the plane x . (A w) = 0
        w = projector.frame[2]
        normal = np.array([1 / 4, 1, 1 / 2.25]) * w
        assert np.abs(x @ normal).max() < 1e-10
        # it goes round once: its length (chords of the traced points) is the
        # perimeter of that plane section (dense polygon)
        assert batch.t1[0] == pytest.approx(_section_length(normal), rel=1e-3)


def _section_length(normal):
    """Perimeter of the ellipse where the plane x . normal = 0 cuts the ellipsoid."""
    n = normal / np.linalg.norm(normal)
    a = np.cross(n, [0.3, 0.1, 1.0])
    a /= np.linalg.norm(a)
    b = np.cross(n, a)
    phi = np.linspace(0, 2 * np.pi, 200001)
    d = np.outer(np.cos(phi), a) + np.outer(np.sin(phi), b)
    r = 1 / np.sqrt(d[:, 0] ** 2 / 4 + d[:, 1] ** 2 + d[:, 2] ** 2 / 2.25)
    p = d * r[:, None]
    return np.linalg.norm(np.diff(p, axis=0), axis=1).sum()


def test_level_lines_and_ball_boundary():
    s = ImplicitSurface(torus_F, radius=2.4)
    d = np.array([0.0, 0.3, 1.0]) / np.hypot(0.3, 1.0)
    levels = lg.LevelLines(values=[-0.5, 0.0, 0.4], direction=d).batches(s, None)
    (batch,) = levels
    t = np.concatenate([np.linspace(a, b, 50) for a, b in zip(batch.t0, batch.t1)])
    k = np.repeat(np.arange(len(batch)), 50)
    x, _ = batch.evaluate(k, t)
    scale = 4 * 2.0**2 * 2.4**2  # |F| of order R^2 |x|^2 on the ball
    assert np.abs(torus_F(*x.T)).max() < 1e-12 * scale
    h = x @ d
    assert {round(v, 9) for v in h.tolist()} <= {-0.5, 0.0, 0.4}
    assert np.linalg.norm(x, axis=1).max() <= 2.4 + 1e-9
    (bd,) = s.boundary()
    xb, _ = bd.evaluate(np.zeros(100, int), np.linspace(bd.t0[0], bd.t1[0], 100))
    assert np.abs(np.linalg.norm(xb, axis=1) - 2.4).max() < 1e-12
    assert np.abs(torus_F(*xb.T)).max() < 1e-12 * scale
    # the sphere of radius 2.4 cuts the torus (R=2, r=0.7) in two circles
    assert len(bd) == 2 and bd.closed.all()


def test_box_boundary_on_the_faces():
    s = ImplicitSurface(ellipsoid_F, bounds=((-1.5, 1.5), (-2, 2), (-2, 2)))
    (bd,) = s.boundary()
    assert len(bd) == 2  # the ellipses x = +-1.5
    xb, _ = bd.evaluate(np.repeat([0, 1], 50), np.tile(np.linspace(0, bd.t1.min(), 50), 2))
    assert np.allclose(np.abs(xb[:, 0]), 1.5, atol=1e-12)
    assert np.abs(ellipsoid_F(*xb.T)).max() < 1e-12


def test_hits_against_roots_of_the_sphere():
    rng = np.random.default_rng(3)
    o = rng.uniform(-2, 2, (3000, 3))
    v = rng.normal(size=(3000, 3))
    s = ImplicitSurface(lambda x, y, z: x**2 + y**2 + z**2 - 1, radius=5, lipschitz=10.0)
    # exact: roots of |o + s v|^2 = 1 in (0, inf)
    a, b, c = (v * v).sum(1), 2 * (o * v).sum(1), (o * o).sum(1) - 1
    disc = b * b - 4 * a * c
    r = np.sqrt(np.maximum(disc, 0))
    roots = np.stack([(-b - r) / (2 * a), (-b + r) / (2 * a)], axis=1)
    exact = ((roots > 0) & (disc > 0)[:, None]).sum(1)
    clear = np.abs(disc) > 1e-6 * a  # leave out grazing rays, undecidable in floating point
    got = s.hit_count(o, v, np.full(3000, np.inf))
    assert np.array_equal(got[clear], exact[clear])


def _check_visibility(surface, F, projector, radius, min_points=200):
    scene = lg.Scene()
    scene.add(surface, lg.LevelLines(5))
    drawing = scene.render(projector, hidden_lines=True)
    d = projector.frame[2]
    checked = {True: 0, False: 0}
    for stroke in drawing.strokes:
        n = len(stroke.xyz)
        if n < 8:
            continue
        p = stroke.xyz[n // 4 : n - n // 4]  # away from the transitions at the ends
        lo = np.full(len(p), 1e-6)
        hi = ball_exit(p, d, radius)
        crossings = march(F, p + 0 * d, d, lo, hi)
        if stroke.visible:
            assert (crossings == 0).all(), stroke.family
        else:
            assert (crossings > 0).all(), stroke.family
        checked[stroke.visible] += len(p)
    assert checked[True] > min_points and checked[False] > min_points


def test_hidden_lines_against_dense_ray_march_torus():
    s = ImplicitSurface(torus_F, radius=2.6)
    p = lg.ParallelProjector(direction=(0.4, -1.0, 0.7))
    _check_visibility(s, torus_F, p, 2.6)


def test_rendered_strokes_lie_on_the_surface():
    s = ImplicitSurface(torus_F, radius=2.6)
    scene = lg.Scene()
    scene.add(s)  # default: plane sections, contour, boundary
    drawing = scene.render(lg.ParallelProjector(direction=(0.4, -1.0, 0.7)), hidden_lines=True)
    fams = {st.family for st in drawing.strokes}
    assert fams == {"level", "contour", "boundary"}
    x = np.concatenate([st.xyz for st in drawing.strokes])
    assert np.abs(torus_F(*x.T)).max() < 1e-10 * 4 * 4 * 2.6**2
    assert all(st.uv is None and st.surface is s for st in drawing.strokes)


def test_intersection_with_a_sphere_lies_on_both():
    s = lg.CayleyCubic(radius=2.0)
    scene = lg.Scene()
    scene.add(s, lg.LevelLines(3))
    scene.add(lg.Sphere(1.2), lg.ParameterLines(4, 6), transform=lg.translate(0.1, 0, 0))
    drawing = scene.render(lg.ParallelProjector(direction=(1, 0.7, 0.45)), hidden_lines=True)
    x = np.concatenate([st.xyz for st in drawing.strokes if st.family == "intersection"])
    assert np.abs(s.implicit(x)).max() < 1e-12
    assert np.abs(np.linalg.norm(x - [0.1, 0, 0], axis=1) - 1.2).max() < 1e-12
    # the sphere meets the four necks of the cubic's cones: four closed loops
    (batch,) = s.meeting_curves(lg.Sphere(1.2), lg.translate(0.1, 0, 0))
    assert len(batch) == 4 and batch.closed.all()


def test_intersection_with_an_open_patch_warns():
    s = ImplicitSurface(ellipsoid_F, radius=3)
    with pytest.warns(UserWarning, match="not drawn"):
        assert s.meeting_curves(lg.Helicoid(), lg.translate(0, 0, 0)) == []


def test_intersection_curve_family_with_a_torus():
    c, t = lg.CayleyCubic(), lg.Torus(1.5, 0.5)
    for on, other in ((t, c), (c, t)):  # drawn on either node: the same space curves
        (b,) = lg.IntersectionCurve(other).batches(on, None)
        assert b.surface is on and b.family == "intersection" and len(b) == 2
        k = np.repeat(np.arange(len(b)), 60)
        x, _ = b.evaluate(k, np.concatenate([np.linspace(0, e, 60) for e in b.t1]))
        assert np.abs(c.implicit(x)).max() < 1e-12
        assert np.abs(t.implicit(x)).max() < 1e-11


def test_default_family_in_a_fresh_process():
    import subprocess
    import sys

    code = (
        "import lgraph as lg; s = lg.Scene(); s.add(lg.CayleyCubic()); "
        "print(type(s.nodes[0].families[0]).__name__)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip() == "LevelLines", out.stderr[-2000:]
