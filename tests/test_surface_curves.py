"""Asymptotic lines, geodesics, intersection curves, arrows and planar patches."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph._own import ON
from lgraph.curvature import fundamental_forms


def test_asymptotic_lines_have_zero_normal_curvature():
    S = lg.MonkeySaddle()
    (b, *_rest) = lg.AsymptoticLines(3, 3).batches(S, None)
    assert b.family == "asymptotic"
    for k in range(len(b)):
        t = np.linspace(b.t0[k], b.t1[k], 120)
        _, uv = b.evaluate(np.full(len(t), k), t)
        d = np.gradient(uv, t, axis=0)[2:-2]
        g11, g12, g22, L11, L12, L22 = fundamental_forms(S, uv[2:-2, 0], uv[2:-2, 1])
        II = L11 * d[:, 0] ** 2 + 2 * L12 * d[:, 0] * d[:, 1] + L22 * d[:, 1] ** 2
        first = g11 * d[:, 0] ** 2 + 2 * g12 * d[:, 0] * d[:, 1] + g22 * d[:, 1] ** 2
        k1, k2 = lg.principal_curvatures(S, uv[2:-2, 0], uv[2:-2, 1])
        assert np.all(k1 * k2 <= 1e-9)  # only where K <= 0
        assert np.percentile(np.abs(II / first) / (np.abs(k1) + np.abs(k2) + 1e-12), 99) < 1e-3


def test_geodesic_on_sphere_is_a_great_circle():
    S = lg.ParametricSurface(
        lg.Sphere(2.0).point, (-1.5, 1.5), (0, 2 * np.pi), periodic=(False, True)
    )
    g = lg.geodesic(S, (0.2, 0.3), (0.4, 1.0), 6.0)
    x = g(np.linspace(0, g.t1, 200))
    assert np.abs(np.linalg.norm(x, axis=1) - 2).max() < 1e-9
    n = np.cross(x[0], x[50])
    assert np.abs(x @ n / np.linalg.norm(n)).max() < 1e-7  # in a plane through the centre


def test_geodesic_family_on_torus_outer_equator():
    T = lg.Torus(3, 1)
    (b,) = lg.Geodesic((0.0, 0.0), (1.0, 0.0), length=10.0, both_ways=True).batches(T, None)
    x, _ = b.evaluate(np.zeros(50, int), np.linspace(b.t0[0], b.t1[0], 50))
    assert np.abs(x[:, 2]).max() < 1e-9
    assert np.allclose(np.hypot(x[:, 0], x[:, 1]), 4.0)


def test_intersection_curve_of_sphere_and_cylinder():
    """Viviani-like: sphere r=2 and the cylinder (x-1)^2 + y^2 = 1 meet in one closed curve."""
    sph = lg.ParametricSurface(
        lg.Sphere(2.0).point,
        (-np.pi / 2, np.pi / 2),
        (0, 2 * np.pi),
        periodic=(False, True),
        poles=(True, False),
    )
    cyl = lg.ParametricSurface(
        lambda u, v: np.stack(np.broadcast_arrays(1 + np.cos(u), np.sin(u), v), -1),
        (0, 2 * np.pi),
        (-2.5, 2.5),
        periodic=(True, False),
    )
    (b,) = lg.IntersectionCurve(cyl).batches(sph, None)
    assert b.family == "intersection"
    t = np.concatenate([np.linspace(a, c, 400) for a, c in zip(b.t0, b.t1)])
    idx = np.repeat(np.arange(len(b)), 400)
    x, _ = b.evaluate(idx, t)
    assert np.abs(np.linalg.norm(x, axis=1) - 2).max() < 1e-9
    assert np.abs(np.hypot(x[:, 0] - 1, x[:, 1]) - 1).max() < 1e-9
    # the whole curve: it reaches both the top and the bottom of the sphere
    assert x[:, 2].max() > 1.99 and x[:, 2].min() < -1.99


def test_parallelogram_hits_and_contour():
    P = lg.Parallelogram((0, 0, 0), (2, 0, 0), (0, 1, 0))
    o = np.array([[0.5, 0.5, -1], [3.0, 0.5, -1], [0.5, 0.5, 1]])
    v = np.array([[0, 0, 1.0]] * 3)
    assert P.hits(o, v, np.full(3, np.inf)).tolist() == [True, False, False]
    assert not P.hits(o[:1] * [1, 1, 0], v[:1], np.array([np.inf]), np.array([ON])).any()
    (c,) = P.contour(lg.ParallelProjector(direction=(0, 0, 1)))
    x, _ = c.evaluate(np.zeros(5, int), np.arange(5.0))
    assert np.allclose(x, [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0], [0, 0, 0]])


def test_arrow_hits_and_outline():
    a = lg.Arrow((0, 0, 0), (0, 0, 2), head_length=0.5, head_radius=0.2, shaft_radius=0.05)
    o = np.array([[-1, 0, 1.0], [-1, 0, 1.7], [-1, 0.19, 1.6], [-1, 0.3, 1.0]])
    v = np.array([[1.0, 0, 0]] * 4)
    # shaft, head, outside the head's cone, beside the shaft
    assert a.hits(o, v, np.full(4, np.inf)).tolist() == [True, True, False, False]
    with pytest.raises(ValueError, match="shaft_radius must be smaller"):
        lg.Arrow((0, 0, 0), (0, 0, 1), head_radius=0.1, shaft_radius=0.2)
    scene = lg.Scene()
    scene.add(lg.Sphere(0.5), lg.ParameterLines(4, 4), transform=lg.translate(0, 0, 1.0))
    scene.add(a, lg.Contour(), contour=False, transform=lg.translate(0, 1.5, 0))
    d = scene.render(lg.ParallelProjector(direction=(1, 0.3, 0.2)), hidden_lines=True)
    arrow_strokes = [s for s in d.strokes if s.surface is a]
    assert arrow_strokes and any(s.visible for s in arrow_strokes)
    # the rim's back half is hidden by the head itself
    assert any(not s.visible for s in arrow_strokes)
