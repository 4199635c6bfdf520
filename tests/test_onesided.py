"""The one-sided and self-intersecting built-ins: gluings, implicit equations,
known self-intersections.

Independent checks: the gluing identity ``x(lo, t) = x(hi, a + b - t)`` (and
``x(lo, t) = x(hi, t)`` for plain periodic parameters) evaluated at many
``t``; the implicit equations of the Roman surface (``X^2 Y^2 + Y^2 Z^2 +
Z^2 X^2 = a XYZ``, from ``x^2 + y^2 + z^2 = 1``) and the cross-cap (derived
in docs/gluings.rst); the self-intersections known in closed form (the
Roman surface's three axis segments, the cross-cap's segment, the figure-8
Klein bottle's circle of radius ``r``), located by dense sampling for
Boy's surface (two far-apart parameter points at one spatial point).
"""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg

ALL = [
    lg.MoebiusStrip(),
    lg.MoebiusStrip(radius=2, width=0.5),
    lg.KleinBottle(),
    lg.KleinBottle(form="figure8", radius=3),
    lg.BoySurface(),
    lg.RomanSurface(size=2),
    lg.CrossCap(size=0.5),
]
IDS = ["moebius", "moebius2", "bottle", "figure8", "boy", "roman", "crosscap"]


@pytest.mark.parametrize("surface", ALL, ids=IDS)
def test_gluing_identity(surface):
    d = surface.domain
    assert any(d.twisted)
    for i in (0, 1):
        if not d.glued[i]:
            continue
        lo, hi = d.range(i)
        t = np.linspace(*d.range(1 - i), 97)
        other = d.mirror(1 - i, t) if d.twisted[i] else t
        a = surface.point(lo, t) if i == 0 else surface.point(t, lo)
        b = surface.point(hi, other) if i == 0 else surface.point(other, hi)
        np.testing.assert_allclose(a, b, atol=1e-12 * surface.size)


@pytest.mark.parametrize("size", [1.0, 2.0])
def test_roman_surface_implicit_equation(size):
    s = lg.RomanSurface(size=size)
    rng = np.random.default_rng(1)
    u, v = rng.uniform(0, np.pi, (2, 2000))
    X, Y, Z = np.moveaxis(s.point(u, v), -1, 0)
    residual = X * X * Y * Y + Y * Y * Z * Z + Z * Z * X * X - size * X * Y * Z
    assert np.abs(residual).max() < 1e-15 * size**4
    # not a trivial identity: a point off the surface fails it
    assert abs(0.3**4 * 3 - size * 0.3**3) > 1e-3


@pytest.mark.parametrize("size", [1.0, 0.5])
def test_cross_cap_implicit_equation(size):
    s = lg.CrossCap(size=size)
    rng = np.random.default_rng(2)
    u, v = rng.uniform(0, np.pi, (2, 2000))
    X, Y, Z = np.moveaxis(s.point(u, v), -1, 0)
    lhs = (2 * X * X + Y * Y + Z * Z + size * Z) ** 2
    rhs = (Y * Y + Z * Z) * (size + Z) ** 2
    assert np.abs(lhs - rhs).max() < 1e-14 * size**4
    # and the sphere map is even (a map of the projective plane)
    p = s.point(u, v)
    np.testing.assert_allclose(p, s.point(np.pi - u, v + np.pi), atol=1e-15)


def _self_intersection_points(surface, n=200):
    (b,) = lg.SelfIntersection().batches(surface, None)
    out = []
    for k in range(len(b)):
        t = np.linspace(b.t0[k], b.t1[k], n)
        x, uv = b.evaluate(np.full(len(t), k), t)
        out.append(x)
    return out


def test_roman_surface_meets_itself_in_three_axis_segments():
    a = 1.0
    curves = _self_intersection_points(lg.RomanSurface(size=a))
    x = np.concatenate(curves)
    # every point on an axis ...
    off = np.sort(np.abs(x), axis=1)[:, :2]
    assert off.max() < 1e-8
    # ... and each axis covered from -a/2 to a/2 (the pinch points)
    axis = np.argmax(np.abs(x), axis=1)
    for k in range(3):
        c = x[axis == k, k]
        assert c.min() < -0.45 * a and c.max() > 0.45 * a, k
        assert np.abs(c).max() <= 0.5 * a + 1e-9
        # no gap larger than a few percent along the segment
        assert np.diff(np.sort(c)).max() < 0.06 * a


def test_cross_cap_meets_itself_in_a_segment():
    a = 1.0
    x = np.concatenate(_self_intersection_points(lg.CrossCap(size=a)))
    assert np.abs(x[:, :2]).max() < 1e-8
    assert x[:, 2].min() < 0.05 * a and x[:, 2].max() > 0.95 * a
    assert (x[:, 2] >= -1e-9).all() and (x[:, 2] <= a + 1e-9).all()
    assert np.diff(np.sort(x[:, 2])).max() < 0.06 * a


def test_figure8_klein_bottle_meets_itself_in_a_circle():
    r = 2.0
    x = np.concatenate(_self_intersection_points(lg.KleinBottle(form="figure8", radius=r)))
    np.testing.assert_allclose(np.hypot(x[:, 0], x[:, 1]), r, atol=1e-8)
    np.testing.assert_allclose(x[:, 2], 0.0, atol=1e-8)
    angle = np.arctan2(x[:, 1], x[:, 0])
    covered = np.unique(np.floor((angle + np.pi) / (2 * np.pi) * 36).astype(int))
    assert len(covered) >= 33  # nearly the whole circle


def test_boy_surface_self_intersection_is_double():
    s = lg.BoySurface()
    (b,) = lg.SelfIntersection().batches(s, None)
    assert len(b) >= 1
    # dense sampling: each point of the curve has two far-apart preimages
    n = 601
    u, v = np.meshgrid(np.linspace(0, np.pi, n), np.linspace(0, np.pi, n), indexing="ij")
    grid = s.point(u, v).reshape(-1, 3)
    uvs = np.stack([u.ravel(), v.ravel()], 1)
    k = 0
    t = np.linspace(b.t0[k], b.t1[k], 9)[1:-1]
    x, _ = b.evaluate(np.full(len(t), k), t)
    h = np.pi / (n - 1)
    for p in x:
        dist = np.linalg.norm(grid - p, axis=1)
        near = uvs[dist < 0.02 * s.size]
        # two clusters of preimages, more than a few cells apart (across the gluing too)
        q = near[np.argmin(np.linalg.norm(grid[dist < 0.02 * s.size] - p, axis=1))]
        gaps = np.abs((s.domain.nearest_image(q, near) - q) / h).max(axis=1)
        assert gaps.max() > 20


def test_klein_bottle_self_intersection_is_one_closed_curve():
    """The bottle's neck passes through its side in one closed curve (its
    preimage on the side is a small loop of about 3 x 1 cells of the search
    grid: a search that tested only the shifted cell of each leaf pair lost a
    quarter of it)."""
    s = lg.KleinBottle()
    (b,) = lg.SelfIntersection().batches(s, None)
    assert len(b) == 1 and bool(b.closed[0])
    t = np.linspace(b.t0[0], b.t1[0], 2001)
    x, _ = b.evaluate(np.zeros(len(t), int), t)
    step = np.linalg.norm(np.diff(x, axis=0), axis=1)
    assert np.linalg.norm(x[-1] - x[0]) <= 2 * step.max()
    assert step.max() < 3 * np.median(step)  # no jump over a missing piece


def test_boy_surface_self_intersection_is_three_equal_loops_through_the_triple_point():
    """Boy's surface (threefold symmetric about the z axis) meets itself in
    three loops through one triple point on the axis: the curve drawn is
    whole (its ends at the triple point, no piece missing), it returns to the
    triple point after each third of its length, and a turn by 120 degrees
    maps it onto itself.  (A search that lost leaf pairs, or split the
    preimage at the wrong places, drew two pieces ending in mid-air.)"""
    s = lg.BoySurface()
    curves = _self_intersection_points(s, n=6001)
    ends = np.array([p for x in curves for p in (x[0], x[-1])])
    triple = ends[0]
    assert np.abs(triple[:2]).max() < 1e-6 * s.size  # on the axis
    np.testing.assert_allclose(ends, np.broadcast_to(triple, ends.shape), atol=1e-4 * s.size)
    x = np.concatenate(curves)
    step = np.linalg.norm(np.diff(x, axis=0), axis=1)
    length = np.r_[0.0, np.cumsum(step)]
    # passages through the triple point: one every third of the length
    near = np.linalg.norm(x - triple, axis=1) < 1e-3 * s.size
    passes = np.unique(np.round(length[near] / length[-1] * 3).astype(int))
    assert passes.tolist() == [0, 1, 2, 3]
    c, sn = np.cos(2 * np.pi / 3), np.sin(2 * np.pi / 3)
    turn = np.array([[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]])
    from scipy.spatial import cKDTree

    gap, _ = cKDTree(x).query(x @ turn.T)
    assert gap.max() < 2 * step.max()


def test_every_builtin_draws_its_self_intersection():
    for s in (lg.KleinBottle(), lg.BoySurface(), lg.RomanSurface(), lg.CrossCap()):
        curves = _self_intersection_points(s, n=1000)
        assert curves
        for x in curves:
            assert np.isfinite(x).all()
            assert np.linalg.norm(np.diff(x, axis=0), axis=1).max() < 0.05 * s.size


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: lg.MoebiusStrip(width=-1), "MoebiusStrip: width must be a positive finite"),
        (lambda: lg.KleinBottle(form="8"), "KleinBottle: form must be one of 'bottle'"),
        (lambda: lg.KleinBottle(radius=float("nan")), "KleinBottle: radius must be a positive"),
        (lambda: lg.BoySurface(size=0), "BoySurface: size must be a positive finite"),
        (lambda: lg.RomanSurface(size="x"), "RomanSurface: size must be a positive finite"),
        (lambda: lg.CrossCap(size=-2), "CrossCap: size must be a positive finite"),
    ],
)
def test_parameters_are_validated(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_renders_with_hidden_lines():
    sc = lg.Scene()
    sc.add(lg.MoebiusStrip(), lg.ParameterLines(4, 4))
    d = sc.render(lg.ParallelProjector(direction=(1.0, 0.7, 0.6)), hidden_lines=True)
    fams = {s.family for s in d.strokes}
    assert {"u1", "u2", "contour", "boundary"} <= fams
    assert any(not s.visible for s in d.strokes) and any(s.visible for s in d.strokes)
