"""Many views rendered together (``lgraph.render.render_views``): each
drawing equals the drawing ``Scene.render`` gives for its view alone."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph.render import render_views

PARALLEL = lg.orbit(elevation=30, frames=5)
CENTRAL = lg.orbit(elevation=20, frames=4, distance=14)
MIXED = [PARALLEL[1], CENTRAL[2], lg.ParallelProjector(direction=(0.2, -1, 0.4))]


def _ellipsoid() -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(6, 7))
    return scene


def _composition() -> lg.Scene:
    """Two grouped quadrics, a torus asked one by one, a free curve, a label
    and a point mark."""
    scene = lg.Scene()
    scene.add(lg.Sphere(1.2), lg.ParameterLines(5, 8), transform=lg.translate(-1.5, 0, 0))
    scene.add(lg.Ellipsoid(1, 0.8, 0.6), lg.ParameterLines(4, 6), transform=lg.translate(2, 1, 0))
    scene.add(lg.Torus(1.6, 0.5), lg.ParameterLines(6, 10), transform=lg.translate(0, -1, 0.3))
    scene.add(lg.Curve(lambda t: np.stack([t, 0 * t + 2.5, np.sin(3 * t)], -1), -3, 3))
    scene.add(lg.Label("$P$", at=(-1.5, 0, 1.2)))
    scene.add(lg.Point((2, 1, 0.6)))
    return scene


def _saddle() -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.MonkeySaddle(), lg.ParameterLines(6, 6))
    return scene


def _revolution() -> lg.Scene:
    scene = lg.Scene()
    vase = lg.SurfaceOfRevolution(lg.named_profile("vase"), (0, 3))
    scene.add(vase, lg.LinesOfCurvature(6, 8), transform=lg.translate(0, 0, -1.5))
    return scene


def _assert_same(alone: lg.Drawing, together: lg.Drawing) -> None:
    assert len(alone.strokes) == len(together.strokes)
    extent = max(1.0, *(float(np.abs(s.xy).max()) for s in alone.strokes))
    for a, b in zip(alone.strokes, together.strokes):
        same = (a.visible, a.family, a.style, a.surface)
        assert same == (b.visible, b.family, b.style, b.surface)
        assert a.xy.shape == b.xy.shape
        # the same samples; a root located by SIMD transcendental functions may
        # differ in its last bits with the point's place in an array
        assert np.allclose(a.xy, b.xy, rtol=0, atol=1e-11 * extent)
        assert np.allclose(a.xyz, b.xyz, rtol=0, atol=1e-11 * extent)
        assert (a.uv is None) == (b.uv is None)
        if a.uv is not None:  # parameters: angles and lengths of order one
            assert np.allclose(a.uv, b.uv, rtol=0, atol=1e-9, equal_nan=True)
    assert [(p.text, p.visible, p.anchor) for p in alone.labels] == [
        (p.text, p.visible, p.anchor) for p in together.labels
    ]
    for p, q in zip(alone.labels, together.labels):
        assert np.allclose(p.xy, q.xy, rtol=0, atol=1e-12 * extent)


@pytest.mark.parametrize("make", [_ellipsoid, _composition, _saddle, _revolution])
@pytest.mark.parametrize(
    ("views", "hidden_lines"), [(PARALLEL, False), (CENTRAL, True), (MIXED, False)]
)
def test_each_view_is_drawn_as_alone(make, views, hidden_lines):
    scene = make()
    together = render_views(scene, views, hidden_lines=hidden_lines)
    assert len(together) == len(views)
    for view, d in zip(views, together):
        _assert_same(scene.render(view, hidden_lines=hidden_lines), d)


def test_a_curve_batch_is_evaluated_once_for_all_views():
    """The fixed cost of a stage is paid once: the curve's function is called
    about as often for five views as for one (once per pipeline step)."""
    calls = []

    def f(t):
        calls.append(len(t))
        return np.stack([np.cos(t), np.sin(t), 0.3 * np.sin(5 * t)], -1)

    scene = lg.Scene()
    scene.add(lg.Sphere(0.8), lg.ParameterLines(3, 4))
    scene.add(lg.Curve(f, 0, 2 * np.pi))
    scene.render(PARALLEL[0])
    one = len(calls)
    calls.clear()
    render_views(scene, PARALLEL)
    assert len(calls) <= one + 2
    assert sum(calls) > 3 * 33  # yet every view's samples were evaluated


def test_views_that_cannot_share_a_pass_are_rendered_one_by_one():
    # the eye inside the sphere's bounding box (outside the sphere) in one view only
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(4, 6))
    views = [lg.CentralProjector(eye=(0.95, 0.95, 0.2)), PARALLEL[0], CENTRAL[1]]
    together = render_views(scene, views)
    for view, d in zip(views, together):
        _assert_same(scene.render(view), d)


def test_edge_cases_and_errors():
    assert render_views(_ellipsoid(), []) == []
    empty = render_views(lg.Scene(), PARALLEL[:2])
    assert [len(d.strokes) for d in empty] == [0, 0]
    with pytest.raises(TypeError, match=r"projectors\[1\] must be a ParallelProjector"):
        render_views(_ellipsoid(), [PARALLEL[0], "front"])
    with pytest.raises(ValueError, match="behind the eye"):
        render_views(_ellipsoid(), [PARALLEL[0], lg.CentralProjector(eye=(0, 0, 0.5))])
    with pytest.raises(ValueError, match="tolerance must be a number"):
        render_views(_ellipsoid(), PARALLEL, tolerance=0)


def test_a_batch_over_the_point_budget_is_rendered_view_by_view(tmp_path, monkeypatch):
    """The budget counts the samples of all views together: ``render_views``
    refuses a batch that one view alone would fit; ``animate`` then renders
    that batch view by view, with the same frames."""
    from lgraph import _tolerance
    from lgraph.animation import frames as animation
    from lgraph.render.sampling import PointBudgetError

    scene = _ellipsoid()
    views = PARALLEL[:4]
    want = lg.animate(scene, views, tmp_path / "a.gif", width=96, progress=False, workers=1)
    one = max(sum(len(s.xy) for s in d.strokes) for d in render_views(scene, views))
    monkeypatch.setattr(_tolerance, "MAX_POINTS", 2 * one)  # one view fits, four do not
    with pytest.raises(PointBudgetError, match="sample points"):
        render_views(scene, views)
    got = lg.animate(scene, views, tmp_path / "b.gif", width=96, progress=False, workers=1)
    assert got.read_bytes() == want.read_bytes()
    assert animation.BATCH_FRAMES >= len(views)  # the four views were one batch


def test_contours_of_all_views_are_evaluated_in_one_call(monkeypatch):
    """An ellipsoid's exact contour differs in every view, but all of them are
    ellipses evaluated by the surface's one kernel: the renderer stacks their
    parameters and calls it as often for five views as for one."""
    from lgraph.surfaces.quadrics import quadric as quadrics

    calls = []
    real = quadrics._EllipseKernel.__call__

    def counting(self, params, t):
        calls.append(len(params))
        return real(self, params, t)

    monkeypatch.setattr(quadrics._EllipseKernel, "__call__", counting)
    scene = _ellipsoid()
    scene.render(PARALLEL[0])
    one = len(calls)
    calls.clear()
    together = render_views(scene, PARALLEL)
    assert one > 0 and len(calls) <= one
    assert sum(calls) >= len(PARALLEL) * 33  # every view's contour was sampled
    for view, d in zip(PARALLEL, together):
        _assert_same(scene.render(view), d)


def test_a_kernel_needs_one_row_a_curve():
    from lgraph.curves import CurveBatch

    def f(params, t):
        return np.zeros((len(t), 3)), None

    with pytest.raises(ValueError, match="kernel parameters must have 2 rows"):
        CurveBatch("c", [0, 0], [1, 1], lambda i, t: f(None, t), kernel=(f, np.zeros((3, 1))))


def test_chord_bounds_the_chords_of_every_view_by_one_length():
    # the unit circle z = 0 seen along the z axis from the eye (0, 0, 2): its
    # projection is a circle of radius distance / 2 (1 and 4 here), so each
    # chord's distance from the curve is r (1 - cos(angle / 2))
    scene = lg.Scene()
    scene.add(lg.Curve(lambda t: np.stack([np.cos(t), np.sin(t), 0 * t], -1), 0, 2 * np.pi))
    views = [lg.CentralProjector(eye=(0, 0, 2), target=(0, 0, z), up=(0, 1, 0)) for z in (0, -6)]
    chord = 2e-5
    sags, counts = [], []
    for d, radius in zip(render_views(scene, views, chord=chord), (1.0, 4.0)):
        (xy,) = [s.xy for s in d.strokes]
        assert np.allclose(np.hypot(*xy.T), radius, rtol=1e-12)
        angle = np.diff(np.unwrap(np.arctan2(xy[:, 1], xy[:, 0])))
        assert angle.sum() == pytest.approx(2 * np.pi, rel=1e-12)
        sags.append(float((radius * (1 - np.cos(angle / 2))).max()))
        counts.append(len(xy))
    # one length in both views: refined until within it, not far below it,
    # with about sqrt(4) times the points on the larger circle
    assert all(chord / 10 < s <= chord for s in sags)
    assert 1.5 * counts[0] < counts[1] < 2.5 * counts[0]
    # a relative tolerance scales with each view's figure: the same points
    same = [len(d.strokes[0].xy) for d in render_views(scene, views, tolerance=5e-6)]
    assert same[0] == same[1]
    with pytest.raises(ValueError, match="chord must be a positive finite number"):
        render_views(scene, views, chord=0)
