"""View-independent results kept per surface object (lgraph.surfaces._memo):
reused across views without changing a single stroke, dropped with the surface,
bounded in number."""

from __future__ import annotations

import gc

import numpy as np

import lgraph as lg
from lgraph.surfaces import _memo
from lgraph.surfaces._memo import per_surface


def _saddle() -> lg.ParametricSurface:
    def point(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return np.stack([u, v, u**3 - 3 * u * v**2], axis=-1)

    return lg.ParametricSurface(point, (-1, 1), (-1, 1))


VIEWS = [
    lg.ParallelProjector.from_angles(30, 25),
    lg.CentralProjector.from_angles(120, 35, 8),
    lg.ParallelProjector.from_angles(250, 60),
]


def _strokes(surface: lg.ParametricSurface, projector: lg.Projector) -> list:
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(4, 4))
    d = scene.render(projector, hidden_lines=True)
    return [(s.family, s.visible, s.xy) for s in d.strokes]


def test_a_second_view_of_the_same_surface_draws_exactly_what_a_fresh_surface_draws() -> None:
    shared = _saddle()
    for view in VIEWS:
        reused = _strokes(shared, view)  # bounds, boxes and contour grid kept from earlier views
        fresh = _strokes(_saddle(), view)  # a new object: everything computed anew
        assert len(reused) == len(fresh) > 0
        for (fa, va, xa), (fb, vb, xb) in zip(reused, fresh):
            assert fa == fb and va == vb and np.array_equal(xa, xb)


def test_results_are_computed_once_per_object_and_go_with_it() -> None:
    _memo.clear()
    s, calls = _saddle(), []
    for _ in range(3):
        assert per_surface(s, "k", lambda: calls.append(1) or 7) == 7
    assert len(calls) == 1
    assert per_surface(_saddle(), "k", lambda: 8) == 8  # an equal surface is another object
    sid = id(s)
    del s
    gc.collect()
    assert sid not in _memo._MEMO


def test_the_number_of_surfaces_remembered_is_bounded() -> None:
    _memo.clear()
    keep = [_saddle() for _ in range(_memo.MAX_SURFACES + 10)]
    for s in keep:
        per_surface(s, "k", lambda: 0)
    assert len(_memo._MEMO) == _memo.MAX_SURFACES
    assert id(keep[-1]) in _memo._MEMO and id(keep[0]) not in _memo._MEMO


def test_default_bounds_are_copies() -> None:
    s = _saddle()
    lo, hi = s.bounds()
    lo[:] = 99.0
    assert (s.bounds()[0] < 2).all() and np.all(s.bounds()[1] == hi)
