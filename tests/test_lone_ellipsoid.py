"""One ellipsoid drawn by exact ellipses: visibility in closed form
(lgraph/render/lone.py) against the general pipeline, brute-force rays and
the exact visible arc of a parallel nearly tangent to the contour."""

from __future__ import annotations

import numpy as np
import pytest
from bruteforce import classify, even_stations

import lgraph as lg
import lgraph.render as render
import lgraph.render.lone as lone


def _spy(monkeypatch) -> list[int]:  # noqa: ANN001
    taken: list[int] = []
    real = render.lone_visibility

    def spy(s, node, abs_tol, hidden_lines):  # noqa: ANN001, ANN202
        taken.append(1)
        return real(s, node, abs_tol, hidden_lines)

    monkeypatch.setattr(render, "lone_visibility", spy)
    return taken


P = lg.CentralProjector.from_angles(30, 25, 6.0)


def _line(t: np.ndarray) -> np.ndarray:
    return np.stack([t, 0 * t, 0 * t + 2.0], -1)


@pytest.mark.parametrize(
    "build, expected",
    [
        (lambda sc: sc.add(lg.Sphere(1.0), lg.ParameterLines(6, 8)), True),
        (lambda sc: sc.add(lg.Ellipsoid(3, 2, 1), lg.ParameterLines(4, 4)), True),
        # a second surface, a free curve, lines that are no ellipses: the general path
        (
            lambda sc: (
                sc.add(lg.Sphere(1.0), lg.ParameterLines(4, 4)),
                sc.add(lg.Sphere(0.5), lg.ParameterLines(2, 2), transform=lg.translate(3, 0, 0)),
            ),
            False,
        ),
        (
            lambda sc: (
                sc.add(lg.Sphere(1.0), lg.ParameterLines(4, 4)),
                sc.add(lg.Curve(_line, -3.0, 3.0)),
            ),
            False,
        ),
        (lambda sc: sc.add(lg.Ellipsoid(3, 2, 1), lg.LinesOfCurvature(4, 4)), False),
        (lambda sc: sc.add(lg.HyperboloidOneSheet(1, 1, 1), lg.ParameterLines(4, 4)), False),
    ],
)
def test_the_closed_form_path_is_taken_for_one_ellipsoid_of_ellipses_only(
    build, expected, monkeypatch
) -> None:  # noqa: ANN001
    taken = _spy(monkeypatch)
    sc = lg.Scene()
    build(sc)
    sc.render(lg.CentralProjector.from_angles(30, 25, 12.0), hidden_lines=True)
    assert bool(taken) is expected


def _random_scene(seed: int) -> tuple[lg.Scene, object, bool, float]:
    rng = np.random.default_rng(seed)
    axes = rng.uniform(0.5, 3.0, 3)
    angle = rng.uniform(0, 360)
    transform = lg.translate(*rng.uniform(-2, 2, 3)) @ lg.rotate(rng.normal(size=3), angle)
    sc = lg.Scene()
    sc.add(
        lg.Ellipsoid(*axes),
        lg.ParameterLines(int(rng.integers(1, 12)), int(rng.integers(1, 16))),
        transform=transform,
    )
    az, el = rng.uniform(0, 360), rng.uniform(-80, 80)
    if seed % 2:
        proj = lg.ParallelProjector.from_angles(az, el)
    else:
        proj = lg.CentralProjector.from_angles(az, el, float(rng.uniform(4, 12) * axes.max()))
    # the projector looks at the origin; the ellipsoid sits near it
    return sc, proj, bool(rng.integers(0, 2)), float(2 * axes.max())


def _by_position(d: lg.Drawing) -> np.ndarray:
    rows = [(*s.xyz[0], *s.xyz[-1], s.visible, s.occlusion) for s in d.strokes]
    return np.array(sorted(rows))


@pytest.mark.parametrize("seed", range(12))
def test_the_closed_form_path_draws_what_the_general_pipeline_draws(seed, monkeypatch) -> None:
    sc, proj, hidden_lines, size = _random_scene(seed)
    taken = _spy(monkeypatch)
    fast = sc.render(proj, hidden_lines=hidden_lines)
    assert taken
    monkeypatch.setattr(render, "lone_ellipsoid", lambda *args: None)
    general = sc.render(proj, hidden_lines=hidden_lines)
    assert len(fast.strokes) == len(general.strokes)
    a, b = _by_position(fast), _by_position(general)
    # the same pieces, ends within 1e-9 of the figure, the same visibility and depth
    assert np.abs(a[:, :6] - b[:, :6]).max() <= 1e-9 * size
    assert (a[:, 6:] == b[:, 6:]).all()
    assert {s.occlusion for s in fast.strokes} <= {0, 1}


@pytest.mark.parametrize("seed", range(6))
def test_the_closed_form_path_agrees_with_brute_force_rays(seed) -> None:
    sc, proj, _, size = _random_scene(100 + seed)
    d = sc.render(proj, hidden_lines=True)
    node = sc.nodes[0]
    A, b, c = node.surface.coefficients
    objects = [(A, b, c, node.transform, None, size)]
    checked = 0
    for s in d.strokes:
        if s.family == "contour":
            continue
        idx = even_stations(s.xy, 0.01 * size)
        if not len(idx):
            continue
        hidden, margin = classify(objects, proj, s.xyz[idx], np.zeros(len(idx), int))
        firm = margin > 1e-6
        assert (hidden[firm] == (not s.visible)).all()
        checked += int(firm.sum())
    assert checked > 200


def _near_tangent(eps: float) -> tuple[lg.Scene, lg.ParallelProjector, float, float]:
    """The unit sphere's parallel at 45 degrees seen from 45 - eps degrees below
    the equator: visible only on the arc |t - a| < delta (cos delta = tan(pi/4
    - eps) * tan(pi/4)), with ``a`` half the first samples' spacing (the arc
    lies between two of them)."""
    a = np.pi / 32
    e = -np.pi / 4 + eps
    w = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    delta = float(np.arccos(np.tan(np.pi / 4) * np.tan(np.pi / 4 - eps)))
    sc = lg.Scene()
    sc.add(lg.Sphere(1.0), lg.ParameterLines(3, 4))
    return sc, lg.ParallelProjector(direction=w), a, delta


def _arc_strokes(d: lg.Drawing) -> list:
    return [
        s
        for s in d.strokes
        if s.visible and s.family == "u1" and np.allclose(s.xyz[:, 2], np.sqrt(0.5))
    ]


@pytest.mark.parametrize("hidden_lines", [False, True])
def test_a_short_visible_arc_between_two_hidden_samples_is_drawn_exactly(hidden_lines) -> None:
    sc, proj, a, delta = _near_tangent(1e-5)
    assert 2 * delta < 0.2 * (2 * np.pi / 32)  # far shorter than a chord
    arcs = _arc_strokes(sc.render(proj, hidden_lines=hidden_lines))
    assert len(arcs) == 1
    r = np.sqrt(0.5)
    t = np.sort([a - delta, a + delta])
    exact = np.stack([r * np.cos(t), r * np.sin(t), [r, r]], -1)
    ends = np.array([arcs[0].xyz[0], arcs[0].xyz[-1]])
    ends = ends[np.argsort(np.arctan2(ends[:, 1], ends[:, 0]))]
    assert np.abs(ends - exact).max() < 1e-9


def test_without_the_closed_form_crossings_the_arc_is_lost(monkeypatch) -> None:
    """Mutation check: testing only the samples misses the arc."""
    sc, proj, _, _ = _near_tangent(1e-5)
    monkeypatch.setattr(lone, "_crossings", lambda s, *args: (np.empty(0, int), np.empty(0)))
    assert not _arc_strokes(sc.render(proj, hidden_lines=False))


def test_many_views_at_once_match_one_by_one() -> None:
    sc = lg.Scene()
    sc.add(lg.Ellipsoid(2, 1.5, 1), lg.ParameterLines(5, 7))
    views = [lg.CentralProjector.from_angles(az, 20, 9.0) for az in (0, 50, 130)]
    together = render.render_views(sc, views, hidden_lines=True)
    for d, p in zip(together, views):
        alone = sc.render(p, hidden_lines=True)
        assert len(d.strokes) == len(alone.strokes)
        assert np.abs(_by_position(d) - _by_position(alone)).max() < 1e-12
