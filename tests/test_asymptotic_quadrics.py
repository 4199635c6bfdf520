"""Closed-form asymptotic lines (rulings) of the doubly ruled quadrics."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg

SURFACES = [
    lg.HyperboloidOneSheet(1.0, 1.5, 1.2, height=2.0),
    lg.HyperboloidOneSheet(2.0, 2.0, 0.5),
    lg.HyperbolicParaboloid(1.0, 1.5, extent=1.2),
    lg.HyperbolicParaboloid(2.0, 0.7),
]


def _implicit(surface, x):
    """The quadric's equation written out here (independent of the classes)."""
    if isinstance(surface, lg.HyperboloidOneSheet):
        return (
            (x[:, 0] / surface.a) ** 2 + (x[:, 1] / surface.b) ** 2 - (x[:, 2] / surface.c) ** 2 - 1
        )
    return (x[:, 0] / surface.a) ** 2 - (x[:, 1] / surface.b) ** 2 - x[:, 2]


@pytest.mark.parametrize("surface", SURFACES, ids=repr)
def test_rulings_are_straight_lines_on_the_surface(surface):
    scene = lg.Scene()
    scene.add(surface, lg.AsymptoticLines(7, 5))
    d = scene.render(lg.ParallelProjector(direction=(1, -0.6, 0.5)), hidden_lines=True)
    strokes = [s for s in d.strokes if s.family == "asymptotic"]
    assert strokes
    for s in strokes:
        x = s.xyz
        assert np.max(np.abs(_implicit(surface, x))) < 1e-12 * (1 + np.abs(x).max() ** 2)
        # straight: every point on the chord from first to last point
        u = (x[-1] - x[0]) / np.linalg.norm(x[-1] - x[0])
        off = (x - x[0]) - ((x - x[0]) @ u)[:, None] * u
        assert np.max(np.linalg.norm(off, axis=1)) < 1e-12 * np.abs(x).max()
        # asymptotic: a line lying in the surface has zero normal curvature
        assert np.allclose(surface.point(s.uv[:, 0], s.uv[:, 1]), x, atol=1e-12 * np.abs(x).max())
    # whole lines run from patch edge to patch edge (visible + hidden pieces joined)
    ends = np.concatenate([s.xyz[[0, -1]] for s in strokes])
    if isinstance(surface, lg.HyperboloidOneSheet):
        on_rim = np.isclose(np.abs(ends[:, 2]), surface.height)
    else:
        e = surface.extent
        on_rim = np.isclose(np.abs(ends[:, 0] / surface.a), e) | np.isclose(
            np.abs(ends[:, 1] / surface.b), e
        )
    assert on_rim.sum() >= 2 * 12  # 7 + 5 lines, two rim ends each (more with splits)


def test_hyperboloid_rulings_cross_the_waist_at_even_angles():
    h = lg.HyperboloidOneSheet(1.0, 1.0, 1.0, height=1.0)
    (b1, b2) = h.asymptotic_lines(6, 6)
    x, _ = b1.evaluate(np.arange(6), np.zeros(6))
    ang = np.sort(np.mod(np.arctan2(x[:, 1], x[:, 0]), 2 * np.pi))
    assert np.allclose(np.diff(ang), np.pi / 3)
    # the two families are distinct: directions differ in the sign of dz
    xa, _ = b1.evaluate(np.array([0, 0]), np.array([0.0, 0.5]))
    xb, _ = b2.evaluate(np.array([0, 0]), np.array([0.0, 0.5]))
    assert (xa[1, 2] - xa[0, 2]) * (xb[1, 2] - xb[0, 2]) < 0


def test_asymptotic_lines_are_a_registered_family_for_scene_files(tmp_path):
    from lgraph.scenefile import load_scene_file

    path = tmp_path / "asym.toml"
    path.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 30\nelevation = 20\n\n'
        '[[object]]\nsurface = "hyperbolic_paraboloid"\nparams = { a = 1, b = 1.5 }\n'
        'families = [{ name = "asymptotic_lines", n1 = 4, n2 = 3 }]\n'
    )
    scene, projector, _ = load_scene_file(path)
    d = scene.render(projector, hidden_lines=True)
    assert len({tuple(s.xyz[0].round(9)) for s in d.strokes if s.family == "asymptotic"}) >= 7
