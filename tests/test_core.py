"""Core geometry: ellipsoid/sphere, contours, transforms, projectors, validation."""

from __future__ import annotations

import math

import numpy as np
import pytest

import lgraph as lg

PROJECTORS = [
    lg.ParallelProjector(direction=(1.0, -0.8, 0.6)),
    lg.ParallelProjector(direction=(0, 0, 1)),
    lg.CentralProjector(eye=(9.0, -7.0, 6.0), target=(0.3, 0.2, 0.1)),
    lg.CentralProjector.from_angles(200, -30, 12),
]


def implicit_ellipsoid(x, axes):
    return np.sum((x / axes) ** 2, axis=-1) - 1.0


@pytest.mark.parametrize("surf", [lg.Ellipsoid(3, 2, 1.5), lg.Ellipsoid(1, 1, 4), lg.Sphere(2.5)])
@pytest.mark.parametrize("proj", PROJECTORS)
def test_strokes_lie_on_the_ellipsoid_and_contour_is_exact(surf, proj):
    scene = lg.Scene()
    scene.add(surf, lg.ParameterLines(6, 9))
    d = scene.render(proj, hidden_lines=True)
    axes = np.array(surf.bounds()[1])
    assert {s.family for s in d.strokes} == {"u1", "u2", "contour"}
    for s in d.strokes:
        # on the surface to 1e-12 relative (independent implicit equation)
        assert np.max(np.abs(implicit_ellipsoid(s.xyz, axes))) < 1e-12
        # xyz is point(uv)
        assert np.allclose(surf.point(s.uv[:, 0], s.uv[:, 1]), s.xyz, atol=1e-12 * axes.max())
        # xy is the projection of xyz
        assert np.allclose(proj.project(s.xyz), s.xy, atol=1e-12 * axes.max())
    contour = np.concatenate([s.xyz for s in d.strokes if s.family == "contour"])
    normal = contour / axes**2  # gradient of the implicit equation
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    w = proj.view_vectors(contour)
    w = w / np.linalg.norm(w, axis=-1, keepdims=True)
    assert np.max(np.abs(np.einsum("ij,ij->i", normal, w))) < 1e-9
    # the contour of a convex body is entirely visible when alone
    assert all(s.visible for s in d.strokes if s.family == "contour")


def test_contour_closed_and_single_stroke():
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1), lg.ParameterLines(0, 0))
    d = scene.render(lg.ParallelProjector(direction=(1, 2, 3)))
    assert len(d.strokes) == 1
    s = d.strokes[0]
    assert s.family == "contour"
    assert np.allclose(s.xy[0], s.xy[-1])


def test_transformed_contour_matches_transformed_surface():
    """Transforms commute with contours: N.view = 0 in world coordinates."""
    t = lg.translate(1, 2, -1) @ lg.rotate((1, 2, 3), 33) @ lg.scale(1.0, 0.5, 2.0)
    surf = lg.Ellipsoid(2, 1.5, 1)
    for proj in PROJECTORS:
        scene = lg.Scene()
        scene.add(surf, lg.ParameterLines(0, 0), transform=t)
        d = scene.render(proj)
        x = np.concatenate([s.xyz for s in d.strokes])
        local = t.inverse().apply(x)
        assert np.max(np.abs(implicit_ellipsoid(local, np.array([2, 1.5, 1])))) < 1e-12
        n_world = t.apply_normal(local / np.array([4, 2.25, 1]))
        w = proj.view_vectors(x)
        w = w / np.linalg.norm(w, axis=-1, keepdims=True)
        assert np.max(np.abs(np.einsum("ij,ij->i", n_world, w))) < 1e-9


def test_numeric_derivatives_match_analytic():
    e = lg.Ellipsoid(3, 2, 1.5)
    u1 = np.linspace(-1.2, 1.2, 7)
    u2 = np.linspace(0.1, 6, 7)
    x1, x2 = e.derivatives(u1, u2)
    n1, n2 = lg.Surface.derivatives(e, u1, u2)
    assert np.allclose(x1, n1, atol=1e-9) and np.allclose(x2, n2, atol=1e-9)
    a = e.second_derivatives(u1, u2)
    n = lg.Surface.second_derivatives(e, u1, u2)
    for p, q in zip(a, n):
        assert np.allclose(p, q, atol=1e-7)


def test_principal_curvatures_of_ellipsoid_vertices():
    # at (a, 0, 0) the principal curvatures are a/b^2 and a/c^2 (up to sign)
    a, b, c = 3.0, 2.0, 1.5
    k1, k2 = lg.Ellipsoid(a, b, c).principal_curvatures(np.array([0.0]), np.array([0.0]))
    assert np.allclose(sorted(np.abs([k1[0], k2[0]])), sorted([a / b**2, a / c**2]))


def test_transform_composition_and_inverse():
    t = lg.translate(1, 0, 0) @ lg.rotate("z", 90)
    assert np.allclose(t.apply([1, 0, 0]), [1, 1, 0])
    r = lg.rotate((0, 0, 2), 90)
    assert np.allclose(r.apply([1, 0, 0]), [0, 1, 0])
    x = np.random.default_rng(1).normal(size=(5, 3))
    assert np.allclose(t.inverse().apply(t.apply(x)), x)
    assert (t @ t.inverse()).is_identity or np.allclose((t @ t.inverse()).matrix, np.eye(3))


def test_projector_frames_and_angles():
    p = lg.ParallelProjector.from_angles(0, 0)
    assert np.allclose(p.frame[2], [1, 0, 0])
    # z appears upward
    xy = p.project(np.array([[0, 0, 1.0], [0, 1.0, 0]]))
    assert xy[0, 1] > 0 and abs(xy[0, 0]) < 1e-15 and xy[1, 0] > 0
    c = lg.CentralProjector.from_angles(90, 0, 10, target=(1, 1, 1))
    assert np.allclose(c.eye, [1, 11, 1])
    d, smax = c.rays(np.array([[1.0, 1, 1]]))
    assert np.allclose(d, [[0, 1, 0]]) and np.isclose(smax[0], 10)
    # looking straight down still has a valid frame
    top = lg.ParallelProjector(direction=(0, 0, 1))
    assert np.all(np.isfinite(top.frame))


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: lg.Ellipsoid(0, 1, 1), "Ellipsoid: a must be a positive finite number, got 0"),
        (lambda: lg.Ellipsoid(1, -2, 1), "b must be a positive finite number, got -2"),
        (lambda: lg.Ellipsoid(1, 1, math.inf), "c must be a positive finite number, got inf"),
        (lambda: lg.Ellipsoid(1, 1, "2"), "c must be a positive finite number"),
        (lambda: lg.Sphere(math.nan), "Sphere: r must be a positive finite number, got nan"),
        (lambda: lg.Sphere(True), "Sphere: r must be a positive finite number"),
        (lambda: lg.ParameterLines(10**9, 2), "n1 must be an integer from 0 to 100000"),
        (lambda: lg.ParameterLines(2.5, 2), "n1 must be an integer"),
        (lambda: lg.ParallelProjector(direction=(0, 0, 0)), "direction must be a non-zero"),
        (lambda: lg.ParallelProjector(direction=(0, math.nan, 1)), "direction must be 3 finite"),
        (lambda: lg.CentralProjector(eye=(1, 1, 1), target=(1, 1, 1)), "eye must differ"),
        (lambda: lg.CentralProjector(eye=(1, 1)), "eye must be 3 finite numbers"),
        (lambda: lg.CentralProjector.from_angles(0, 0, -1), "distance must be a positive"),
        (lambda: lg.ParallelProjector.from_angles(0, 95), "elevation must lie in"),
        (lambda: lg.rotate("w", 10), "axis must be 'x', 'y', 'z'"),
        (lambda: lg.rotate((0, 0, 0), 10), "axis must be a non-zero"),
        (lambda: lg.rotate("x", math.nan), "degrees must be a finite number"),
        (lambda: lg.translate(0, math.inf, 0), "must be 3 finite numbers"),
        (lambda: lg.scale(0), "factors must be non-zero"),
        (lambda: lg.Style(width=-1), "Style: width must be a positive finite number"),
        (lambda: lg.Style(color="mauve"), "Style: color must be"),
        (lambda: lg.Style(dash=(1,)), "Style: dash must be an even-length"),
        (lambda: lg.Page(100, None), "give both width and height"),
        (lambda: lg.Curve(lambda t: t, 0, 1), "func must map an array"),
        (lambda: lg.Curve(lambda t: np.zeros((len(t), 3)), 1, 0), "t0 must be less than t1"),
    ],
)
def test_validation_messages(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_scene_add_rejects_bad_input():
    scene = lg.Scene()
    with pytest.raises(TypeError, match="item must be a Surface or a Curve"):
        scene.add("sphere")
    with pytest.raises(TypeError, match="families must be line families"):
        scene.add(lg.Sphere(1), 12)
    with pytest.raises(TypeError, match="transform must be a Transform"):
        scene.add(lg.Sphere(1), transform=(1, 2, 3))
    with pytest.raises(TypeError, match="style must be a Style"):
        scene.add(lg.Sphere(1), style="red")
    with pytest.raises(TypeError, match="projector must be"):
        scene.render("top")
    scene.add(lg.Sphere(1))
    with pytest.raises(ValueError, match="tolerance must be a number"):
        scene.render(lg.ParallelProjector(direction=(0, 0, 1)), tolerance=0)


def test_empty_scene_renders_empty_drawing(tmp_path):
    d = lg.Scene().render(lg.ParallelProjector(direction=(1, 0, 0)))
    assert len(d.strokes) == 0


def test_style_per_family_and_contour_width():
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 3), style={"u1": lg.Style(color="red")})
    scene.add(
        lg.Sphere(1),
        lg.ParameterLines(3, 3),
        style=lg.Style(width=1.0),
        transform=lg.translate(3, 0, 0),
    )
    d = scene.render(lg.ParallelProjector(direction=(0, -1, 0.3)))
    first = [s for s in d.strokes if s.surface is scene.nodes[0].surface]
    assert all(s.style.color == (1.0, 0.0, 0.0) for s in first if s.family == "u1")  # CSS red
    assert all(s.style.color == (0.0, 0.0, 0.0) for s in first if s.family == "u2")
    second = [s for s in d.strokes if s.surface is scene.nodes[1].surface]
    assert {s.style.width for s in second if s.family == "contour"} == {1.6}


def test_umbilics_family_marks_the_four_umbilics():
    e = lg.Ellipsoid(3, 2, 1.3)
    scene = lg.Scene()
    scene.add(e, lg.Umbilics(radius=0.05))
    d = scene.render(lg.ParallelProjector(direction=(0.2, -1, 0.4)), hidden_lines=True)
    marks = [s for s in d.strokes if s.family == "umbilic"]
    # every mark lies within its radius of an umbilic, and all 4 are marked
    u = e.umbilics()
    assert u.shape == (4, 3)
    near = set()
    for s in marks:
        # on the surface (implicit equation), about the radius from an umbilic
        assert np.max(np.abs(np.sum((s.xyz / [3, 2, 1.3]) ** 2, 1) - 1)) < 1e-12
        dist = np.linalg.norm(s.xyz[:, None, :] - u[None], axis=2)
        k = int(np.argmin(dist.min(axis=0)))
        assert np.allclose(dist[:, k], 0.05, rtol=0.01)
        near.add(k)
    assert near == {0, 1, 2, 3}
    # an umbilic is one where both principal curvatures agree (independent check)
    assert np.allclose(np.abs(u[:, 1]), 0) and np.allclose(np.sum((u / [3, 2, 1.3]) ** 2, 1), 1)
    assert lg.Sphere(1).umbilics().shape == (0, 3)
    with pytest.raises(ValueError, match="Umbilics: radius must be a positive"):
        lg.Umbilics(radius=-1)


def test_parameter_lines_come_from_the_surface():
    """Surfaces made of pieces draw their parameter lines per piece (no false
    line joining the two sheets)."""
    h = lg.HyperboloidTwoSheets(1, 1.5, 1)
    scene = lg.Scene()
    scene.add(h, lg.ParameterLines(4, 6))
    d = scene.render(lg.ParallelProjector(direction=(1, 0.3, 0.2)), hidden_lines=True)
    for s in d.strokes:
        z = s.xyz[:, 2]
        assert np.all(z > 0) or np.all(z < 0)  # never crosses between the sheets


def test_absurd_line_counts_fail_fast_with_a_clear_error():
    scene = lg.Scene()
    for _ in range(7):
        scene.add(lg.Sphere(1), lg.ParameterLines(100_000, 100_000))
    with pytest.raises(ValueError, match="draw fewer lines"):
        scene.render(lg.ParallelProjector(direction=(1, 0, 0)))


def test_drawing_select_by_family_and_visibility():
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 4))
    d = scene.render(lg.ParallelProjector(direction=(1, 0.2, 0.3)), hidden_lines=True)
    hidden_u2 = d.select(family="u2", visible=False)
    assert len(hidden_u2) and all(s.family == "u2" and not s.visible for s in hidden_u2.strokes)
    assert len(d.select(family="contour")) + len(d.select(family="u1")) + len(
        d.select(family="u2")
    ) == len(d)
