"""Arguments are validated when a public function is called: numpy scalars
are numbers, and every error names the bad parameter."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import lgraph as lg

P = lg.ParallelProjector(direction=(1, 2, 3))


def _sphere_scene() -> lg.Scene:
    sc = lg.Scene()
    sc.add(lg.Sphere(1))
    return sc


def test_numpy_scalars_are_numbers_for_projectors() -> None:
    a = lg.ParallelProjector.from_angles(np.int64(0), np.float32(20))
    b = lg.ParallelProjector.from_angles(0, 20)
    assert np.allclose(a.frame, b.frame)
    c = lg.CentralProjector.from_angles(np.int64(30), 20, np.float64(5))
    assert np.allclose(c.eye, lg.CentralProjector.from_angles(30, 20, 5).eye)
    with pytest.raises(ValueError, match="azimuth must be a finite number"):
        lg.ParallelProjector.from_angles(True, 20)


@pytest.mark.parametrize("direction", [(1e-320, 0, 0), (1e300, 1e300, 0), (0, 0, 1e-310)])
def test_extreme_but_valid_directions_view_like_their_unit_vectors(direction) -> None:
    d = np.array(direction, dtype=float)
    unit = d / np.abs(d).max()
    a = _sphere_scene().render(lg.ParallelProjector(direction=direction))
    b = _sphere_scene().render(lg.ParallelProjector(direction=unit))
    assert len(a.strokes) == len(b.strokes)
    assert np.allclose(a.strokes[0].xy, b.strokes[0].xy)


def test_render_arguments_are_checked_before_rendering() -> None:
    sc = _sphere_scene()
    with pytest.raises(TypeError, match="hidden_style must be a Style"):
        sc.render(P, hidden_style="grey")
    with pytest.raises(TypeError, match="hidden_lines must be True or False"):
        sc.render(P, hidden_lines="yes")
    with pytest.raises(TypeError, match="hidden_lines must be True or False"):
        sc.render(P, hidden_lines=1)
    with pytest.raises(ValueError, match="page must be a Page"):
        sc.render(P, page="a4")
    d = sc.render(P, hidden_lines=np.bool_(True), page=(200, 100))
    assert d.page.width == 200


def test_style_dict_with_an_unknown_family_warns() -> None:
    sc = lg.Scene()
    sc.add(lg.Sphere(1), style={"kontour": lg.Style(), "u1": lg.Style(), "boundary": lg.Style()})
    with pytest.warns(UserWarning, match=r"styles for \['kontour'\]"):
        sc.render(P)
    ok = lg.Scene()
    ok.add(lg.Sphere(1), style={"contour": lg.Style(), "default": lg.Style()})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ok.render(P)


def test_quartic_surfaces_refuse_overflowing_sizes() -> None:
    with pytest.raises(ValueError, match="DupinCyclide: a must be at most 1e\\+75"):
        lg.DupinCyclide(1e300, 1, 1)
    with pytest.raises(ValueError, match="Torus: R must be at most"):
        lg.Torus(1e300, 1)
    assert lg.Torus(np.float64(3), np.int32(1)).R == 3


def test_a_bad_derivatives_func_is_reported_at_construction() -> None:
    def f(u, v):
        return np.stack(np.broadcast_arrays(u, v, u * v), -1)

    with pytest.raises(ValueError, match="derivatives_func"):
        lg.ParametricSurface(f, (0, 1), (0, 1), derivatives_func=lambda u, v: (u,))
    with pytest.raises(ValueError, match=r"derivatives_func must map .* got shapes"):
        lg.ParametricSurface(f, (0, 1), (0, 1), derivatives_func=lambda u, v: (u, v))

    def good(u, v):
        u, v = np.broadcast_arrays(u, v)
        one, zero = np.ones_like(u), np.zeros_like(u)
        return np.stack([one, zero, v], -1), np.stack([zero, one, u], -1)

    s = lg.ParametricSurface(f, (0, 1), (0, 1), derivatives_func=good)
    x1, x2 = s.derivatives(np.array([0.5]), np.array([0.25]))
    assert np.allclose(x1, [[1, 0, 0.25]]) and np.allclose(x2, [[0, 1, 0.5]])


def test_more_calls_name_their_bad_parameter(tmp_path) -> None:
    s = lg.Sphere(1)
    with pytest.raises(TypeError, match="principal_curvatures: surface must be a Surface"):
        lg.principal_curvatures("x", 0, 0)
    with pytest.raises(ValueError, match="principal_directions: u1 must be a finite number"):
        lg.principal_directions(s, np.nan, 0)
    with pytest.raises(ValueError, match="Geodesic: uv0 must be a pair of finite numbers"):
        lg.Geodesic("ab", (1, 0))
    with pytest.raises(TypeError, match="Scene.add: contour must be True or False"):
        lg.Scene().add(s, contour="no")
    sc = lg.Scene()
    sc.add(s)
    d = sc.render(P)
    for bad in (123, None):
        with pytest.raises(TypeError, match="Drawing.save: path must be a file name"):
            d.save(bad)
    k1, k2 = lg.principal_curvatures(s, np.float64(0.3), np.array([0.1, 0.2]))
    assert np.allclose(k1, k2)  # a sphere is umbilic everywhere
    assert np.allclose(np.abs(k1), 1.0)


@pytest.mark.parametrize(
    "family",
    [lg.ParameterLines(3, 3), lg.LinesOfCurvature(3, 3), lg.AsymptoticLines(2, 2),
     lg.LevelLines(3), lg.ParabolicLines(), lg.Umbilics()],
    ids=lambda f: type(f).__name__,
)  # fmt: skip
def test_families_name_a_non_surface(family) -> None:
    with pytest.raises(TypeError, match=rf"{type(family).__name__}.batches: surface must be"):
        family.batches("a sphere", None)
    with pytest.raises(TypeError, match="projector must be a Projector or None"):
        family.batches(lg.Sphere(1), (1, 2, 3))
