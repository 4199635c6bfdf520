"""The monkey saddle's transition functions (lgraph/surfaces/classical/_saddle_margins.py)
against its exact ray test, and the drawings they produce against the ones
found by bisection on the ray test alone."""

from __future__ import annotations

import attrs
import numpy as np
import pytest
from scipy.optimize import brentq

import lgraph as lg
from lgraph._own import CONTOUR, ON
from lgraph.surfaces.classical._polyroots import real_roots
from lgraph.surfaces.classical._saddle_margins import _Rays, grazing_function, margins

SURFACE = lg.MonkeySaddle(extent=1.0, c=0.6)
NAMES = ["contour", "rim x+", "rim x-", "rim y+", "rim y-", "grazing"]


def _views(rng: np.random.Generator) -> list:
    views = [lg.ParallelProjector(direction=rng.normal(size=3)) for _ in range(6)]
    for _ in range(3):
        d = rng.normal(size=3)
        views.append(lg.CentralProjector(eye=4 * d / np.linalg.norm(d)))
    return views


def _state(projector, pts: np.ndarray, own: int) -> np.ndarray:
    v, smax = projector.rays(pts)
    return SURFACE.hits(pts, v, smax, np.full(len(pts), own, np.int8))


def _margins(projector, pts: np.ndarray, own: int, which: int | None = None) -> np.ndarray:
    v, smax = projector.rays(pts)
    return margins(SURFACE, pts, v, smax, np.full(len(pts), own, np.int8), which)


def _check_curve(curve, projector, own: int, n: int = 1500) -> tuple[int, list[int]]:
    """Every change of the ray test's answer between ``n`` samples of
    ``curve`` (a function ``t -> points``, ``t in [0, 1]``) is a root of a
    transition function, and at that root the ray test changes its answer
    within 1e-10 of the parameter.  Returns the number of flips and the
    functions that located them."""
    t = np.linspace(0.0, 1.0, n)
    pts = curve(t)
    hid = _state(projector, pts, own)
    m = _margins(projector, pts, own)
    used = []
    flips = np.flatnonzero(hid[1:] != hid[:-1])
    for i in flips:
        ok = False
        for k in np.flatnonzero(m[:, i] * m[:, i + 1] < 0):

            def g(x: float, k: int = k) -> float:
                return float(_margins(projector, curve(np.array([x])), own, k)[0, 0])

            try:
                root = brentq(g, t[i], t[i + 1], xtol=1e-15, rtol=1e-15)
            except ValueError:  # NaN inside the bracket: the function stops applying
                continue
            near = curve(np.array([root - 1e-10, root + 1e-10]))
            if (_state(projector, near, own) == hid[[i, i + 1]]).all():
                ok, _ = True, used.append(int(k))
                break
        assert ok, (projector, own, t[i], m[:, i], m[:, i + 1])
    return len(flips), used


def test_every_flip_on_random_curves_is_a_root_of_a_transition_function() -> None:
    rng = np.random.default_rng(14)
    n_flips, used = 0, []
    for projector in _views(rng):
        for _ in range(12):
            a, b = rng.uniform(-1, 1, size=(2, 2))

            def curve(t: np.ndarray, a: np.ndarray = a, b: np.ndarray = b) -> np.ndarray:
                uv = a + np.asarray(t)[:, None] * (b - a)
                return SURFACE.point(uv[:, 0], uv[:, 1])

            k, u = _check_curve(curve, projector, ON)
            n_flips += k
            used += u
    assert n_flips >= 50
    # every kind of transition occurs and is located by its own function
    assert set(used) == set(range(6)), sorted({NAMES[k] for k in used})


def test_every_flip_on_contour_curves_is_a_root_of_a_transition_function() -> None:
    rng = np.random.default_rng(7)
    n_flips = 0
    for projector in _views(rng):
        for batch in SURFACE.contour(projector):
            for j in range(len(batch.t0)):
                t0, t1 = float(batch.t0[j]), float(batch.t1[j])

                def curve(t: np.ndarray, j: int = j, t0: float = t0, t1: float = t1,
                          batch=batch) -> np.ndarray:  # fmt: skip
                    tt = t0 + np.asarray(t) * (t1 - t0)
                    return batch.evaluate(np.full(len(tt), j), tt)[0]

                n_flips += _check_curve(curve, projector, CONTOUR, 600)[0]
    assert n_flips >= 5


def test_grazing_function_is_non_negative_exactly_where_the_roots_count_as_real() -> None:
    rng = np.random.default_rng(3)
    uv = rng.uniform(-1, 1, size=(20000, 2))
    o = SURFACE.point(uv[:, 0], uv[:, 1])
    v = rng.normal(size=(20000, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    own = np.full(len(o), ON, np.int8)
    r = _Rays(SURFACE, o, v, np.full(len(o), np.inf), own)
    g = grazing_function(r, own)
    fin = np.isfinite(g)
    assert fin.sum() > 1000
    d = r.d[fin, 1:]
    real = np.isfinite(real_roots(d, r.scale[fin])).all(axis=1)
    assert ((g[fin] >= 0) == real).all()


@attrs.frozen
class _Bisected(lg.MonkeySaddle):
    """The same surface without transition functions: every flip bisected."""

    def visibility_margins(self, *args, **kwargs):
        return None


def _strokes(surface, projector, hidden_lines: bool) -> list:
    scene = lg.Scene()
    scene.add(surface, lg.LinesOfCurvature(6, 6))
    return scene.render(projector, hidden_lines=hidden_lines).strokes


@pytest.mark.parametrize("hidden_lines", [False, True])
def test_drawing_equals_the_bisected_one(hidden_lines: bool, monkeypatch) -> None:
    # the margin search against K-section on the exact ray test; without margins
    # a flip at the own contour would be taken at the zero of N . ray instead
    # (N . ray there is about 1e-13, at the margins' flips 1e-9)
    from lgraph.render import flips

    monkeypatch.setattr(flips, "_own_guided", lambda *args: None)
    rng = np.random.default_rng(21)
    views = [lg.ParallelProjector.from_angles(-35, 30), *_views(rng)[::2]]
    fast, slow = SURFACE, _Bisected(extent=1.0, c=0.6)
    size = fast.size
    for projector in views:
        a, b = _strokes(fast, projector, hidden_lines), _strokes(slow, projector, hidden_lines)
        assert len(a) == len(b)
        for sa, sb in zip(a, b):
            assert (sa.family, sa.visible) == (sb.family, sb.visible)
            assert sa.xyz.shape == sb.xyz.shape
            np.testing.assert_allclose(sa.xyz, sb.xyz, rtol=0, atol=1e-11 * size)


# -- the numeric contour's Newton projection with the analytic gradient -------


@pytest.mark.parametrize(
    "surface", [SURFACE, lg.Helicoid(), lg.Enneper(), lg.Torus(2, 0.5)], ids=type
)
def test_contour_projection_with_analytic_gradient_equals_the_central_difference_one(
    surface,
) -> None:
    from lgraph.surfaces.parametric import _contour as nc

    rng = np.random.default_rng(8)
    d = surface.domain
    span = np.array([d.span(0), d.span(1)])
    for projector in (
        lg.ParallelProjector(direction=rng.normal(size=3)),
        lg.CentralProjector(eye=5 * rng.normal(size=3)),
    ):
        assert nc._analytic_second_derivatives(surface)
        batch = surface.contour(projector)[0]
        idx = np.repeat(np.arange(len(batch.t0)), 100)
        t = np.concatenate([np.linspace(a, b, 100) for a, b in zip(batch.t0, batch.t1)])
        uv = batch.evaluate(idx, t)[1] + rng.normal(size=(len(t), 2)) * 1e-4 * span
        # away from the patch's edges, where Newton's steps are cut back into
        # the patch (tests/test_domain_evaluation.py checks the edges)
        inner = np.ones(len(uv), bool)
        for i in (0, 1):
            if not d.glued[i]:
                lo, hi = d.range(i)
                inner &= np.minimum(uv[:, i] - lo, hi - uv[:, i]) > 1e-3 * span[i]
        uv = uv[inner]
        f, g1, g2 = nc.view_cosine_gradient(surface, projector, uv[:, 0], uv[:, 1])
        np.testing.assert_allclose(f, nc.view_cosine(surface, projector, uv[:, 0], uv[:, 1]),
                                   rtol=0, atol=1e-15)  # fmt: skip
        h = 1e-5 * span
        for g, e in ((g1, np.array([h[0], 0.0])), (g2, np.array([0.0, h[1]]))):
            # fourth-order central differences: error near 1e-10 of the gradient
            fd = sum(
                w * nc.view_cosine(surface, projector, *(uv + k * e).T)
                for k, w in ((-2, 1 / 12), (-1, -2 / 3), (1, 2 / 3), (2, -1 / 12))
            ) / np.linalg.norm(e)
            np.testing.assert_allclose(g, fd, rtol=0, atol=1e-8 * np.abs(g).max())
        exact = nc.project_to_contour(surface, projector, uv)

        def fun(u1, u2, projector=projector):
            return nc.view_cosine(surface, projector, u1, u2)

        numeric = nc.project_to_zero(surface, fun, uv, 4, 1e-14)
        np.testing.assert_allclose(exact, numeric, rtol=0, atol=1e-13 * span.max())
        res = nc.view_cosine(surface, projector, *exact.T)
        assert np.abs(res).max() < 1e-13 and len(uv) > 50


def test_surfaces_with_numeric_second_derivatives_keep_central_differences() -> None:
    from lgraph.surfaces.parametric import _contour as nc

    def saddle(u1, u2):
        return np.stack(np.broadcast_arrays(u1, u2, u1 * u2), axis=-1)

    assert not nc._analytic_second_derivatives(lg.ParametricSurface(saddle, (0, 1), (0, 1)))
    assert nc._analytic_second_derivatives(SURFACE)
