"""Unit tests of the renderer's sampling stage (lgraph.render.sampling)."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.geometry.transforms import IDENTITY
from lgraph.render.sampling import Samples, _predicted_deviation, merge, seg_distance


def test_predicted_deviation_of_a_circle_is_its_sagitta() -> None:
    """Uniform samples of circles of radius 1 and 3: every chord's predicted
    deviation equals the sagitta r (1 - cos(dt / 2)) to a few per cent."""
    n = 33
    t = np.linspace(0, 2 * np.pi, n)
    xy = np.concatenate(
        [np.column_stack([np.cos(t), np.sin(t)]), 3 * np.column_stack([np.cos(t), np.sin(t)])]
    )
    cid = np.repeat([0, 1], n)
    dev = _predicted_deviation(xy, cid, np.concatenate([t, t]))
    sagitta = 1 - np.cos(np.pi / (n - 1))
    same = cid[1:] == cid[:-1]
    assert np.allclose(dev[same][: n - 1], sagitta, rtol=0.03)
    assert np.allclose(dev[same][n - 1 :], 3 * sagitta, rtol=0.03)
    assert dev[~same].tolist() == [0.0]  # the step between two curves is no chord
    # a straight line, and too few points, predict nothing
    line = np.column_stack([np.linspace(0, 1, 5), np.linspace(0, 2, 5)])
    assert np.allclose(_predicted_deviation(line, np.zeros(5, int), np.arange(5.0)), 0.0)
    assert _predicted_deviation(line[:2], np.zeros(2, int), np.arange(2.0)).tolist() == [0.0]
    # uneven spacing predicts nothing (its second differences are no curvature)
    uneven = np.array([0.0, 0.1, 0.5, 0.6, 1.0])
    bent = np.column_stack([uneven, uneven**2])
    assert _predicted_deviation(bent, np.zeros(5, int), uneven).tolist() == [0.0] * 4


def test_seg_distance_against_brute_force() -> None:
    rng = np.random.default_rng(1)
    p, a, b = (rng.normal(size=(200, 2)) for _ in range(3))
    b[:10] = a[:10]  # degenerate segments: distance to the point
    s = np.linspace(0, 1, 2001)
    pts = a[:, None, :] + s[None, :, None] * (b - a)[:, None, :]
    brute = np.linalg.norm(pts - p[:, None, :], axis=2).min(axis=1)
    assert np.allclose(
        seg_distance(p, a, b), brute, atol=1e-3 * np.linalg.norm(b - a, axis=1).max()
    )
    assert np.allclose(
        seg_distance(p[:10], a[:10], b[:10]), np.linalg.norm(p[:10] - a[:10], axis=1)
    )


def test_merge_matches_np_insert() -> None:
    """merge inserts new samples after the given rows in every array (equal
    rows keep their order) and marks them fresh; hidden flags come along."""
    sphere = lg.Sphere(1)
    proj = lg.ParallelProjector(direction=(1, 2, 3))
    batch = lg.ParameterLines(2, 3).batches(sphere, proj)[0]
    s = Samples([(0, batch, IDENTITY)], proj)
    s.fresh[:] = False
    old_t, old_xyz = s.t.copy(), s.xyz.copy()
    after = np.array([0, 0, 5, 40])
    k = len(after)
    t = np.arange(k) + 100.0
    xyz = np.arange(3 * k, dtype=float).reshape(k, 3)
    new = merge(s, after, s.cid[after], t, xyz, np.zeros((k, 2)), np.zeros((k, 2)))
    assert np.array_equal(s.t, np.insert(old_t, after + 1, t))
    assert np.array_equal(s.xyz, np.insert(old_xyz, after + 1, xyz, axis=0))
    assert np.array_equal(np.flatnonzero(new), after + 1 + np.arange(k))
    assert np.array_equal(s.fresh, new) and not s.hidden.any()
    assert (s.cause == -1).all()
    merge(
        s,
        np.array([1]),
        s.cid[[1]],
        [0.5],
        np.zeros((1, 3)),
        np.zeros((1, 2)),
        np.zeros((1, 2)),
        [True],
    )
    assert s.hidden[2] and not s.fresh[2] and s.hidden.sum() == 1


def test_scene_samples_evaluate_every_batch_in_any_order() -> None:
    """One sample set holds the curves of all batches (here parameter lines of
    a moved sphere and a free curve); evaluating mixed, unsorted curve ids
    gives what each batch gives on its own, moved by its node's transform."""
    sphere = lg.Sphere(2)
    proj = lg.CentralProjector(eye=(9, -7, 6))
    lines = lg.ParameterLines(2, 3).batches(sphere, proj)[0]
    free = lg.Curve(lambda t: np.stack([t, t**2, 0 * t], axis=-1), -1, 1).batch()
    move = lg.translate(1, 2, 3)
    s = Samples([(0, lines, move), (1, free, IDENTITY)], proj)
    assert len(s.parts) == 2 and s.parts[1].first == len(lines)
    rng = np.random.default_rng(2)
    cid = rng.integers(0, len(lines) + 1, 40)
    t = rng.uniform(0, 1, 40)
    xyz, uv, xy = s.evaluate(cid, t, proj)
    on_lines = cid < len(lines)
    ref, ref_uv = lines.evaluate(cid[on_lines], t[on_lines])
    assert np.allclose(xyz[on_lines], move.apply(ref))
    assert np.allclose(uv[on_lines], ref_uv)
    x = t[~on_lines]
    assert np.allclose(xyz[~on_lines], np.column_stack([x, x**2, 0 * x]))
    assert np.isnan(uv[~on_lines]).all() and s.no_uv == {1}
    assert np.allclose(xy, proj.project(xyz))
    assert s.evaluate(cid, t, None)[2] is None
    # per-curve ownership: the sphere's node for its lines, none for the free curve
    owner, _ = s.owners(np.array([0, len(s.t) - 1]))
    assert owner.tolist() == [0, -1]
