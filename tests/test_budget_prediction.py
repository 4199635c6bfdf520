"""Budgets predicted, and the right culprit named (issue #25, part 5).

A render that would exceed a budget is refused before the expensive stage,
from quantities known early, with a message naming the part that costs and
the knob that helps (docs/limits.rst).  No wall time is asserted (machines
are noisy): each test makes the expensive stage fail if it is reached, or
counts the calls of the surface's ``point``.  Measured times are in
benchmarks/RESULTS.md (2026-12-03, session 12)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import lgraph as lg
import lgraph.render as render_module
from lgraph import _tolerance as tol
from lgraph.render.sampling import PointBudgetError

VIEW = lg.ParallelProjector(direction=(1, 2, 3))


def _torus() -> lg.ParametricSurface:
    def f(u: Any, v: Any) -> np.ndarray:
        u, v = np.broadcast_arrays(u, v)
        r = 2 + np.cos(v)
        return np.stack([r * np.cos(u), r * np.sin(u), np.sin(v)], -1)

    return lg.ParametricSurface(f, (0, 2 * np.pi), (0, 2 * np.pi))


def _no_ray_tests(monkeypatch: pytest.MonkeyPatch) -> None:
    """Make the ray tests and the refinement fail if the render reaches them."""

    def reached(*args: Any, **kwargs: Any) -> None:
        raise AssertionError("the expensive stage was reached before the refusal")

    monkeypatch.setattr(render_module, "_classify", reached)
    monkeypatch.setattr(render_module, "refine", reached)


def _count_ray_tests(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The number of samples each ray-test call of the render asks (recorded
    in the returned list)."""
    calls: list[int] = []
    classify = render_module._classify

    def counted(s: Any, vis: Any, rows: Any = None) -> None:
        calls.append(int(s.fresh.sum()) if rows is None else len(rows))
        classify(s, vis, rows)

    monkeypatch.setattr(render_module, "_classify", counted)
    return calls


@pytest.mark.parametrize("surface", ["sphere", "torus"])
def test_a_tiny_tolerance_with_many_lines_is_refused_before_the_ray_tests(
    monkeypatch: pytest.MonkeyPatch, surface: str
) -> None:
    """500 + 500 parameter lines at the smallest tolerance would need some 25
    million samples: refused from the first samples' chords, before any ray
    test (before: 3.8 s for the sphere, 12 s for a numeric torus, then
    refused at the second refinement pass)."""
    _no_ray_tests(monkeypatch)
    scene = lg.Scene()
    scene.add(lg.Sphere(1) if surface == "sphere" else _torus(), lg.ParameterLines(500, 500))
    with pytest.raises(PointBudgetError) as info:
        scene.render(VIEW, tolerance=tol.MIN_CHORD_TOLERANCE)
    message = str(info.value)
    assert "would need about" in message and "predicted from the first 33 samples" in message
    assert "of node 0" in message and ("'u1'" in message or "'u2'" in message)
    assert "raise tolerance (about" in message and "fewer lines" in message
    assert f"the limit is {tol.MAX_POINTS}" in message


def test_a_wiggly_contour_is_named_with_its_knob(monkeypatch: pytest.MonkeyPatch) -> None:
    """When the contour is what costs, the message names it and contour=False."""
    _no_ray_tests(monkeypatch)

    def f(u: Any, v: Any) -> np.ndarray:
        u, v = np.broadcast_arrays(u, v)
        return np.stack([u, v, 0.6 * np.sin(3 * u) * np.sin(3 * v)], -1)

    scene = lg.Scene()
    scene.add(lg.ParametricSurface(f, (-1, 1), (-1, 1)), lg.ParameterLines(1, 1))
    # 297 first samples fit; the refined ~2700 (62 % of them the contour's) do not
    monkeypatch.setattr(tol, "MAX_POINTS", 300)
    with pytest.raises(PointBudgetError) as info:
        scene.render(lg.ParallelProjector(direction=(1, 0.5, 0.3)), tolerance=1e-6)
    message = str(info.value)
    assert "family 'contour' of node 0, ParametricSurface" in message
    assert "contour=False on that node" in message


def test_the_prediction_keeps_the_exact_check_as_the_backstop(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Just over the budget (within the prediction's margin) the render is
    refused by the exact check before a refinement pass, as before."""
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(20, 20))
    n = sum(len(s.xy) for s in scene.render(VIEW).strokes)
    monkeypatch.setattr(tol, "MAX_POINTS", n // 2)
    with pytest.raises(PointBudgetError, match="the curves need") as info:
        scene.render(VIEW)
    assert "predicted" not in str(info.value)


def test_the_prediction_is_close_to_the_refined_count() -> None:
    """On ordinary figures the predicted count is within a factor 2 of the
    refined one (the margin ``POINTS_PREDICTION_MARGIN`` is 4; on the gallery
    the ratio is 0.91 to 1.54)."""
    with pytest.MonkeyPatch.context() as m:
        predicted, refined = _spy_prediction(m)
        for hidden in (False, True):
            scene = lg.Scene()
            scene.add(lg.Ellipsoid(1.5, 1, 0.7), lg.LinesOfCurvature(10, 10))
            scene.add(_torus(), lg.ParameterLines(8, 8), transform=lg.translate(0, 0, 3))
            assert scene.render(VIEW, hidden_lines=hidden).strokes
    assert len(predicted) == len(refined) == 2
    for p, r in zip(predicted, refined):
        assert 0.5 < p / r < 2.0, (p, r)
    assert tol.POINTS_PREDICTION_MARGIN >= 4


def _bumpy(k: int = 200) -> lg.ParametricSurface:
    """A sphere with ``k`` bumps round its axis: each ray meets dozens of patch boxes."""

    def f(u: Any, v: Any) -> np.ndarray:
        u, v = np.broadcast_arrays(u, v)
        r = 1 + 0.05 * np.sin(k * u)
        return np.stack([r * np.cos(u) * np.sin(v), r * np.sin(u) * np.sin(v), r * np.cos(v)], -1)

    return lg.ParametricSurface(f, (0, 2 * np.pi), (0.01, np.pi - 0.01))


def test_costly_ray_tests_are_refused_before_they_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """The ray tests against a surface whose rays meet dozens of patch boxes
    each are refused after the first samples' ray tests (which measure the
    boxes a ray), before the refinement: the samples predicted (the bumpy
    sphere's lines are aliased: predicted from denser samples) and the
    visibility flips between the first samples, each located by K-section.
    Here with the budget lowered, so that the test is quick: 2 + 2 lines."""
    from lgraph.render.prediction import RayBudgetError

    calls = _count_ray_tests(monkeypatch)

    def reached(*args: Any, **kwargs: Any) -> None:
        raise AssertionError("the refinement was reached before the refusal")

    monkeypatch.setattr(render_module, "refine", reached)
    monkeypatch.setattr(tol, "MAX_RAY_BOXES", 20_000)
    scene = lg.Scene()
    scene.add(_bumpy(), lg.ParameterLines(2, 2), contour=False)
    with pytest.raises(RayBudgetError) as info:
        scene.render(VIEW)
    assert len(calls) == 1  # the first samples only
    message = str(info.value)
    assert "the ray tests of" in message and "predicted samples and locating about" in message
    assert "visibility flips" in message and "draw fewer lines" in message
    assert "the patch boxes of node 0 (ParametricSurface(...))" in message
    assert "draw fewer lines or raise tolerance" in message and "u1_range/u2_range" in message
    assert "lgraph._tolerance.MAX_RAY_BOXES" in message
    assert "family 'u2' of node 0" in message and "oscillate faster" in message


def test_the_bumpy_sphere_is_refused_at_the_probe(monkeypatch: pytest.MonkeyPatch) -> None:
    """The issue's case: 24 + 24 lines of the bumpy sphere with hidden lines
    and no contour.  Before: predicted 6 000 samples (its lines aliased),
    refused only after all first samples' ray tests (8.6 s on a loaded
    machine); the 12 + 12 version rendered in 248 s.  After: predicted from
    denser samples (64 000; refined 69 000) and refused after the probe's
    RAY_PROBE ray tests, the message naming the sheets counted at every
    hidden sample and the knobs (0.5-1.6 s by hand)."""
    from lgraph.render.prediction import RayBudgetError

    calls = _count_ray_tests(monkeypatch)
    for n in (24, 12):
        calls.clear()
        scene = lg.Scene()
        scene.add(_bumpy(), lg.ParameterLines(n, n), contour=False)
        with pytest.raises(RayBudgetError) as info:
            scene.render(VIEW, hidden_lines=True)
        assert calls == [tol.RAY_PROBE]
        message = str(info.value)
        assert "predicted samples and counting the sheets in front of about" in message
        assert "contour=True on node 0" in message and "hidden_lines=False" in message
        assert "family 'u2' of node 0" in message and "oscillate faster" in message


def test_many_predicted_samples_are_probed_before_the_first_ray_tests(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """With many lines, a probe of RAY_PROBE first samples is tested first;
    the rest are not when the prediction is over the budget."""
    from lgraph.render.prediction import RayBudgetError

    calls = _count_ray_tests(monkeypatch)
    monkeypatch.setattr(tol, "MAX_RAY_BOXES", 50_000)
    scene = lg.Scene()
    scene.add(_bumpy(), lg.ParameterLines(40, 40), contour=False)
    with pytest.raises(RayBudgetError, match="predicted samples would meet"):
        scene.render(VIEW)
    assert calls == [tol.RAY_PROBE]


def test_ordinary_numeric_scenes_are_not_refused() -> None:
    """A few gallery scenes with numeric surfaces and hidden lines render."""
    import importlib.util
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] / "gallery"
    for stem in ("extra_moebius_strip", "extra_whitney_umbrella", "fig_7_2_ellipsoid"):
        spec = importlib.util.spec_from_file_location(f"_bp_{stem}", root / f"{stem}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        scene, projector, *kwargs = module.build()
        assert scene.render(projector, **(kwargs[0] if kwargs else {})).strokes


def _spy_prediction(m: pytest.MonkeyPatch) -> tuple[list[int], list[int]]:
    """The predicted and the refined sample counts of every render (lists)."""
    predicted, refined = [], []
    predict, refine = render_module.predict_points, render_module.refine

    def spy_predict(s: Any, abs_tol: Any) -> int:
        predicted.append(predict(s, abs_tol))
        return predicted[-1]

    def spy_refine(s: Any, *args: Any) -> None:
        refine(s, *args)
        refined.append(len(s.t))

    m.setattr(render_module, "predict_points", spy_predict)
    m.setattr(render_module, "refine", spy_refine)
    return predicted, refined


@pytest.mark.parametrize("waves", [0, 100, 400, 1000])
def test_aliased_curves_are_predicted_from_denser_samples(
    monkeypatch: pytest.MonkeyPatch, waves: int
) -> None:
    """A curve that oscillates faster than its 33 first samples resolve
    (aliased) is predicted from denser samples of it: not below half the
    refined count (before: 1/40 of it for 1000 waves), nor above the margin
    (the refinement, which checks midpoints of even chords, may itself stop
    early on an aliased curve: 854 samples for the 400 waves, which need
    about 2500; predicted 2499); a smooth one is predicted as before."""
    predicted, refined = _spy_prediction(monkeypatch)
    scene = lg.Scene()
    scene.add(lg.Curve(lambda t: np.stack([t, 0.01 * np.sin(waves * t), 0.1 * t * t], -1), 0, 6.28))
    scene.render(VIEW)
    assert 0.5 < predicted[0] / refined[0] < tol.POINTS_PREDICTION_MARGIN, (predicted, refined)


def test_a_smooth_scene_pays_one_probe_call_a_batch(monkeypatch: pytest.MonkeyPatch) -> None:
    """The aliasing probe of a scene whose curves are resolved evaluates a
    few curves of every family once (one call for all), and none of an
    ellipsoid's exact ellipses."""
    from lgraph.render import prediction, sampling

    calls: list[int] = []
    evaluate = sampling.Samples.evaluate

    def counted(self: Any, cid: Any, t: Any, project: Any) -> Any:
        calls.append(len(t))
        return evaluate(self, cid, t, project)

    monkeypatch.setattr(sampling.Samples, "evaluate", counted)
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(10, 10))
    s = sampling.Samples(
        [(0, b, lg.Transform()) for b in scene.view_batches(scene.nodes[0], [VIEW])[0]], VIEW
    )
    prediction.predict_points(s, 1e-4)
    assert calls == []  # the lines and the contour are exact ellipses: no probe
    calls.clear()
    scene = lg.Scene()
    scene.add(_torus(), lg.ParameterLines(10, 10), contour=False)
    s = sampling.Samples(
        [(0, b, lg.Transform()) for b in scene.view_batches(scene.nodes[0], [VIEW])[0]], VIEW
    )
    prediction.predict_points(s, 1e-4)
    # one call: 4 curves of each of the two families, at 129 samples (96 of them new)
    assert calls == [2 * tol.ALIAS_PROBE_CURVES * 32 * (tol.ALIAS_STEP - 1)]
