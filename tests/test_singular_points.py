"""The numeric contour reaches isolated singular points (pinch points) and
collapsed edges (poles) instead of stopping a grid cell short of them
(lgraph/surfaces/parametric/_singular_points.py): checked against the
singular points in closed form, with a mutation check."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
import lgraph.surfaces.parametric._contour as contour_module

#: Steiner's Roman surface (yz, zx, xy) of the unit sphere: pinch points at
#: the ends of the three double segments, +-1/2 on each axis; the sphere's
#: poles map to the origin
ROMAN_PINCHES = np.vstack([np.eye(3) * 0.5, -np.eye(3) * 0.5])

VIEWS = [
    lg.ParallelProjector(direction=(1.0, 0.8, 0.6)),
    lg.ParallelProjector.from_angles(20, 35),
    lg.CentralProjector.from_angles(-40, 25, 6.0),
]


def _ends(surface: object, view: object) -> np.ndarray:
    """The end points in space of every open piece of the numeric contour."""
    out = []
    for batch in surface.contour(view):
        for k in range(len(batch)):
            if batch.closed[k]:
                continue
            x, _ = batch.evaluate(np.array([k, k]), np.array([batch.t0[k], batch.t1[k]]))
            out.extend(x)
    return np.array(out).reshape(-1, 3)


def _distance(points: np.ndarray, targets: np.ndarray) -> np.ndarray:
    return np.linalg.norm(points[:, None, :] - targets[None], axis=-1).min(axis=1)


@pytest.mark.parametrize("view", VIEWS, ids=["parallel", "parallel2", "central"])
def test_the_roman_surfaces_contour_runs_into_its_pinch_points(view) -> None:  # noqa: ANN001
    ends = _ends(lg.RomanSurface(), view)
    assert len(ends) >= 4
    # every piece ends on a pinch point or on the poles' image (the origin)
    targets = np.vstack([ROMAN_PINCHES, np.zeros((1, 3))])
    assert _distance(ends, targets).max() < 1e-9
    # and the outline passes through: each such point ends an even number of pieces
    near = np.linalg.norm(ends[:, None, :] - targets[None], axis=-1).argmin(axis=1)
    assert all(n % 2 == 0 for n in np.bincount(near, minlength=len(targets)))


def test_without_carrying_the_ends_the_roman_contour_stops_short(monkeypatch) -> None:  # noqa: ANN001
    """Mutation check: the grid alone leaves gaps of the order of a cell."""
    monkeypatch.setattr(contour_module, "to_singular_points", lambda s, c, g, f: c)
    ends = _ends(lg.RomanSurface(), VIEWS[0])
    assert _distance(ends, np.vstack([ROMAN_PINCHES, np.zeros((1, 3))])).max() > 1e-3


def _umbrella() -> lg.ParametricSurface:
    """Whitney's umbrella (u v, u, v^2), written by a user: point only."""
    return lg.ParametricSurface(
        lambda u, v: np.stack(np.broadcast_arrays(u * v, u, v * v), -1), (-1.0, 1.0), (-1.0, 1.0)
    )


def test_the_umbrellas_contour_reaches_the_pinch_point() -> None:
    view = lg.ParallelProjector.from_angles(-62, 22)
    ends = _ends(_umbrella(), view)
    inside = np.abs(ends).max(axis=1) < 0.9  # not on the patch's rim
    assert inside.sum() >= 2
    assert np.abs(ends[inside]).max() < 1e-9  # the origin


def test_the_cross_caps_contour_reaches_its_pole_and_pinch_point() -> None:
    ends = _ends(lg.CrossCap(), VIEWS[0])
    s = lg.CrossCap()
    u = np.array([0.0, np.pi / 2])
    pole = s.point(np.array([1e-9]), np.array([1.0]))[0]  # the edge u1 = 0 is one point
    pinch = np.array([s.point(u[1:], np.array([np.pi]))[0]])
    assert _distance(ends, np.vstack([pole, pinch])).max() < 1e-6


def test_a_regular_contour_is_left_as_it_was(monkeypatch) -> None:  # noqa: ANN001
    """A torus (no singular point): the same contour with and without the step."""
    torus = lg.ParametricSurface(
        lambda u, v: np.stack(
            [(2 + 0.7 * np.cos(v)) * np.cos(u), (2 + 0.7 * np.cos(v)) * np.sin(u), 0.7 * np.sin(v)],
            -1,
        ),
        (0.0, 2 * np.pi),
        (0.0, 2 * np.pi),
        periodic=(True, True),
    )
    view = lg.CentralProjector.from_angles(30, 25, 10.0)
    t = np.linspace(0, 1, 7)

    def sampled() -> list[np.ndarray]:
        out = []
        for b in torus.contour(view):
            for k in range(len(b)):
                tt = b.t0[k] + (b.t1[k] - b.t0[k]) * t
                out.append(b.evaluate(np.full(len(t), k), tt)[0])
        return out

    with_step = sampled()
    monkeypatch.setattr(contour_module, "to_singular_points", lambda s, c, g, f: c)
    without = sampled()
    assert len(with_step) == len(without)
    assert all(np.array_equal(a, b) for a, b in zip(with_step, without))
