"""Level lines and parabolic lines, checked against plane equations, implicit
equations and Gaussian curvature from numeric fundamental forms."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg


def _points(batches, n=201):
    out = []
    for b in batches:
        idx = np.repeat(np.arange(len(b)), n)
        t = np.concatenate([np.linspace(a, c, n) for a, c in zip(b.t0, b.t1)])
        xyz, uv = b.evaluate(idx, t)
        out.append((idx, xyz, uv, b))
    return out


def _numeric_copy(surface):
    """The same surface with nothing but its point function (finite differences)."""
    d = surface.domain
    return lg.ParametricSurface(surface.point, d.u1, d.u2, periodic=d.periodic, poles=d.poles)


def _monkey_residual(x, c=0.6):
    return x[:, 2] - c * (x[:, 0] ** 3 - 3 * x[:, 0] * x[:, 1] ** 2)


CASES = {
    "torus": (lg.Torus(2, 0.8), lambda x: lg.Torus(2, 0.8).implicit(x) / 16),
    "monkey": (lg.MonkeySaddle(extent=1, c=0.6), _monkey_residual),
    "ellipsoid": (
        lg.Ellipsoid(3, 2, 1.3),
        lambda x: (x[:, 0] / 3) ** 2 + (x[:, 1] / 2) ** 2 + (x[:, 2] / 1.3) ** 2 - 1,
    ),
    "egg": (
        lg.SurfaceOfRevolution(lg.named_profile("egg"), (0, np.pi)),
        None,
    ),
}


@pytest.mark.parametrize("direction", [(0, 0, 1), (1, 0.5, 1)])
@pytest.mark.parametrize("name", list(CASES))
def test_plane_level_lines_lie_in_their_planes_and_on_the_surface(name, direction):
    s, implicit = CASES[name]
    fam = lg.LevelLines(5, direction=direction)
    values, _ = fam.levels(s)
    assert len(values) == 5 and np.all(np.diff(values) > 0)
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    batches = fam.batches(s, None)
    assert batches
    seen = set()
    for idx, xyz, uv, b in _points(batches):
        h = xyz @ d
        # each curve lies in one of the planes, to 1e-10
        for k in range(len(b)):
            hk = h[idx == k]
            j = int(np.argmin(np.abs(values - hk[0])))
            seen.add(j)
            assert np.abs(hk - values[j]).max() < 1e-10
        if uv is not None:
            assert np.allclose(s.points(uv), xyz, atol=1e-12)
        if implicit is not None:
            assert np.abs(implicit(xyz)).max() < 1e-10
        assert b.family == "level"
    assert len(seen) == 5


def test_level_lines_close_where_they_close():
    (b,) = lg.LevelLines(values=[0.3]).batches(lg.Torus(2, 0.8), None)
    assert len(b) == 2 and b.closed.all()  # two circles
    # a monkey saddle's level lines end on the patch boundary
    bs = lg.LevelLines(values=[0.2]).batches(lg.MonkeySaddle(), None)
    assert not any(b.closed.any() for b in bs)


def test_axial_levels_of_a_surface_of_revolution_are_parallels():
    s = CASES["egg"][0]
    (b,) = lg.LevelLines(values=[-1.0, 0.0, 0.7]).batches(s, None)
    assert len(b) == 3
    for idx, xyz, uv, _ in _points([b]):
        for k in range(3):
            assert np.ptp(uv[idx == k, 0]) == 0.0
        assert np.allclose(
            np.sort(np.unique(np.round(xyz[:, 2], 12))), [-1.0, 0.0, 0.7], atol=1e-12
        )


def test_functions_of_the_point_and_of_the_parameters():
    s = lg.Torus(2, 0.8)
    f = lg.LevelLines(function=lambda x: x[..., 0] ** 2 + x[..., 1], values=[1.0, 2.5])
    for _idx, xyz, _uv, _ in _points(f.batches(s, None)):
        r = xyz[:, 0] ** 2 + xyz[:, 1]
        assert np.all((np.abs(r - 1.0) < 1e-10) | (np.abs(r - 2.5) < 1e-10))
    g = lg.LevelLines(function=lambda u1, u2: np.sin(u1) + np.cos(u2), argument="uv", values=[0.5])
    for _idx, _xyz, uv, _ in _points(g.batches(s, None)):
        assert np.abs(np.sin(uv[:, 0]) + np.cos(uv[:, 1]) - 0.5).max() < 1e-10


def test_levels_of_the_gaussian_curvature():
    s = lg.MonkeySaddle(extent=1, c=0.6)
    ref = _numeric_copy(s)
    fam = lg.LevelLines(function="gaussian_curvature", values=[-1.0])
    (b,) = fam.batches(s, None)
    for _idx, _xyz, uv, _ in _points([b]):
        k1, k2 = ref.principal_curvatures(uv[:, 0], uv[:, 1])
        assert np.abs(k1 * k2 + 1).max() < 1e-6
    # K = -36 c^2 (x^2 + y^2) / (1 + |grad|^2)^2: the level -1 is a closed loop round the origin
    assert b.closed.all()


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: lg.LevelLines(values=[]), "non-empty"),
        (lambda: lg.LevelLines(values=[1, float("nan")]), "finite numbers"),
        (lambda: lg.LevelLines(function="torsion"), "function must be callable or one of"),
        (lambda: lg.LevelLines(function=np.sin, argument="xyz"), "argument must be"),
        (lambda: lg.LevelLines(-1), "n must be an integer"),
    ],
)
def test_bad_input(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_a_function_returning_nan_is_an_error_before_drawing():
    scene = lg.Scene()
    scene.add(lg.Torus(2, 0.8), lg.LevelLines(function=lambda x: np.log(x[..., 2]), values=[0]))
    with pytest.raises(ValueError, match="LevelLines: function must be finite on the surface"):
        scene.render(lg.ParallelProjector(direction=(1, 1, 1)))


# -- parabolic lines --------------------------------------------------------------
def test_torus_parabolic_lines_are_its_top_and_bottom_circles():
    R, r = 2.0, 0.8
    (b,) = lg.ParabolicLines().batches(lg.Torus(R, r), None)
    ((idx, xyz, uv, _),) = _points([b])
    assert len(b) == 2 and b.family == "parabolic"
    rho = np.hypot(xyz[:, 0], xyz[:, 1])
    assert np.abs(rho - R).max() < 1e-9
    assert np.abs(np.abs(xyz[:, 2]) - r).max() < 1e-9
    assert {round(float(np.sign(xyz[idx == k, 2][0]))) for k in range(2)} == {-1, 1}


@pytest.mark.parametrize(
    "surface",
    [lg.Torus(2, 0.8), lg.DupinCyclide(2, 1.9, 1.0),
     lg.SurfaceOfRevolution(lg.named_profile("vase"), (0, 3.0))],
    ids=["torus", "cyclide", "vase"],
)  # fmt: skip
def test_closed_form_parabolic_lines_have_zero_gaussian_curvature(surface):
    ref = _numeric_copy(surface)
    batches = lg.ParabolicLines().batches(surface, None)
    assert batches
    d = surface.domain
    for _idx, _xyz, uv, _ in _points(batches, 41):
        k1, k2 = ref.principal_curvatures(uv[:, 0], uv[:, 1])
        assert np.abs(k1 * k2).max() < 1e-6
        # and K changes sign across the line
        du = np.array([1e-3 * d.span(0), 1e-3 * d.span(1)])
        for i in (0, 1):
            step = np.zeros(2)
            step[i] = du[i]
            ka = np.prod(ref.principal_curvatures(*(uv + step).T), axis=0)
            kb = np.prod(ref.principal_curvatures(*(uv - step).T), axis=0)
            if np.abs(ka - kb).min() > 1e-6:
                assert np.all(ka * kb < 0)
    if isinstance(surface, lg.SurfaceOfRevolution):
        # the vase: its profile's inflections; parallels of constant height
        (b,) = batches
        assert len(b) >= 2


def test_numeric_parabolic_lines_of_a_parametric_torus():
    R, r = 2.0, 0.8
    s = _numeric_copy(lg.Torus(R, r))
    batches = lg.ParabolicLines(grid=97).batches(s, None)
    pts = np.concatenate([xyz for _, xyz, _, _ in _points(batches, 101)])
    assert len(pts)
    assert np.abs(np.hypot(pts[:, 0], pts[:, 1]) - R).max() < 1e-5
    assert np.abs(np.abs(pts[:, 2]) - r).max() < 1e-5


def test_scene_renders_level_and_parabolic_families():
    scene = lg.Scene()
    scene.add(lg.Torus(2, 0.8), lg.LevelLines(5), lg.ParabolicLines())
    d = scene.render(lg.ParallelProjector(direction=(1, -1, 1)), hidden_lines=True)
    fams = {s.family for s in d.strokes}
    assert {"level", "parabolic", "contour"} <= fams


@pytest.mark.parametrize(
    "surface, direction, view",
    [
        (lg.Ellipsoid(3, 2, 1.5), (0, 1, 0), (1, 0.3, 0.4)),
        (lg.Ellipsoid(3, 2, 1.5), (1, 1, 0), (-0.2, 1, 0.5)),
        (lg.Sphere(1.3), (0, 0, 1), (0.3, -1, 0.2)),
    ],
)
def test_closed_form_plane_sections_are_hidden_by_their_own_quadric(surface, direction, view):
    # plane sections of a closed quadric lie on it: the far half of every
    # section is hidden by the surface itself.  Independent check at every
    # stroke point: on a convex quadric a point is hidden exactly where the
    # outward normal (the gradient of x^2/a^2 + ...) faces away from the eye.
    sc = lg.Scene()
    sc.add(surface, lg.LevelLines(7, direction=direction))
    p = lg.ParallelProjector(direction=view)
    dr = sc.render(p, hidden_lines=True)
    level = [s for s in dr.strokes if s.family == "level"]
    assert any(s.visible for s in level) and any(not s.visible for s in level)
    w = p.frame[2]
    for s in level:
        x = s.xyz
        g = x / np.array(_axes(surface)) ** 2  # half the gradient
        facing = g @ w / (np.linalg.norm(g, axis=1) * np.linalg.norm(w))
        interior = facing[1:-1]  # the ends lie on the contour (facing = 0)
        if s.visible:
            assert np.all(interior > -1e-7)
        else:
            assert np.all(interior < 1e-7)


def _axes(surface):
    return (surface.r,) * 3 if isinstance(surface, lg.Sphere) else (surface.a, surface.b, surface.c)


def test_level_line_families_differing_in_direction_or_function_are_both_drawn():
    """Families that differ only in ``direction`` (or ``function``) are
    different families: they compared equal once, and the family cache gave
    the second the first one's curves (z sections twice, no x sections)."""
    a, b = lg.LevelLines(5), lg.LevelLines(5, direction=(1, 0, 0))
    same = lg.LevelLines(5, direction=(0.0, 0.0, 1.0))
    assert a != b and a == same and hash(a) == hash(same)
    assert lg.LevelLines(3, function=np.sin) != lg.LevelLines(3, function=np.cos)
    scene = lg.Scene()
    scene.add(lg.Torus(2, 0.7), a, b, contour=False)
    d = scene.render(lg.ParallelProjector.from_angles(30, 25))
    level = [s for s in d.strokes if s.family == "level"]
    flat_x = [s for s in level if np.ptp(s.xyz[:, 0]) < 1e-9]
    flat_z = [s for s in level if np.ptp(s.xyz[:, 2]) < 1e-9]
    assert flat_x and flat_z and len(flat_x) + len(flat_z) == len(level)
