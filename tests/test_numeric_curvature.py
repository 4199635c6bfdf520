"""Numeric lines of curvature: known circles on the torus and the Dupin
cyclide; elsewhere the paper's equation (3.3), checked with fundamental forms
computed here by finite differences (independent of the integrator)."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph.families.numeric import numeric_lines_of_curvature


def _samples(batches, n=120):
    for b in batches:
        for k in range(len(b)):
            t = np.linspace(b.t0[k], b.t1[k], n)
            x, uv = b.evaluate(np.full(n, k), t)
            yield b, k, t, x, uv


def _circle_error(x):
    """Largest distance of points from the best circle through them."""
    c = x.mean(axis=0)
    _, _, vt = np.linalg.svd(x - c)
    normal = vt[2]
    planar = np.abs((x - c) @ normal).max()
    q = np.stack([(x - c) @ vt[0], (x - c) @ vt[1]], axis=1)
    # algebraic circle fit  |q|^2 = 2 a.q + k
    A = np.column_stack([2 * q, np.ones(len(q))])
    sol, *_ = np.linalg.lstsq(A, (q**2).sum(axis=1), rcond=None)
    center = sol[:2]
    radius = np.sqrt(sol[2] + center @ center)
    return max(planar, np.abs(np.linalg.norm(q - center, axis=1) - radius).max())


def test_torus_lines_are_meridians_and_parallels():
    T = lg.Torus(3.0, 1.0)
    PT = lg.ParametricSurface(T.point, (0, 2 * np.pi), (0, 2 * np.pi), periodic=True)
    for S in (T, PT):
        batches = numeric_lines_of_curvature(S, 5, 4)
        assert sum(len(b) for b in batches) >= 9
        for _b, _k, _t, x, _uv in _samples(batches):
            rho = np.hypot(x[:, 0], x[:, 1])
            parallel = max(np.ptp(x[:, 2]), np.ptp(rho))
            phi = np.arctan2(x[:, 1], x[:, 0])
            meridian = (
                np.abs(np.sin(phi - phi[0])).max() * rho.max()
                + np.abs(np.hypot(rho - 3.0, x[:, 2]) - 1.0).max()
            )
            assert min(parallel, meridian) < 1e-6
        assert all(b.closed.all() for b in batches)


def test_cyclide_lines_are_circles():
    C = lg.DupinCyclide(2.0, 1.9, 1.0)
    batches = numeric_lines_of_curvature(C, 3, 3)
    assert sum(len(b) for b in batches) >= 6
    for _b, _k, _t, x, _uv in _samples(batches):
        assert _circle_error(x) < 1e-6


def _fd_forms(S, u1, u2, h=1e-4):
    """Fundamental forms from central differences of point() (written here)."""
    f = S.point
    x1 = (f(u1 + h, u2) - f(u1 - h, u2)) / (2 * h)
    x2 = (f(u1, u2 + h) - f(u1, u2 - h)) / (2 * h)
    H = 1e-3
    x0 = f(u1, u2)
    x11 = (f(u1 + H, u2) - 2 * x0 + f(u1 - H, u2)) / H**2
    x22 = (f(u1, u2 + H) - 2 * x0 + f(u1, u2 - H)) / H**2
    x12 = (f(u1 + H, u2 + H) - f(u1 + H, u2 - H) - f(u1 - H, u2 + H) + f(u1 - H, u2 - H)) / (
        4 * H * H
    )
    n = np.cross(x1, x2)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    dot = lambda a, b: np.einsum("ij,ij->i", a, b)  # noqa: E731
    return x1, x2, (dot(x1, x1), dot(x1, x2), dot(x2, x2)), (dot(n, x11), dot(n, x12), dot(n, x22))


def _angles_33(S, batches):
    """Angle between each line's tangent and the nearer direction solving (3.3)."""
    out = []
    for b, k, t, _x, uv in _samples(batches, 200):
        # parameter tangent of the drawn curve, by central differences in t
        h = 1e-6 * (b.t1[k] - b.t0[k])
        idx = np.full(len(t), k)
        (_, up), (_, um) = b.evaluate(idx, t + h), b.evaluate(idx, t - h)
        du = (up - um) / (2 * h)
        inner = slice(2, -2)
        u, d = uv[inner], du[inner]
        x1, x2, (g11, g12, g22), (L11, L12, L22) = _fd_forms(S, u[:, 0], u[:, 1])
        # (3.3): det [[L11 a + L12 b, g11 a + g12 b], [L12 a + L22 b, g12 a + g22 b]] = 0,
        # a quadratic A a^2 + B a b + C b^2 = 0 in the direction (a, b)
        A = L11 * g12 - L12 * g11
        B = L11 * g22 - L22 * g11
        C = L12 * g22 - L22 * g12
        ang = []
        for s in (1, -1):
            disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0))
            # homogeneous roots: (a, b) = (-B + s disc, 2A) or (2C, -B - s disc)
            r1 = np.stack([-B + s * disc, 2 * A], 1)
            r2 = np.stack([2 * C, -B - s * disc], 1)
            r = np.where(
                (np.linalg.norm(r1, axis=1) >= np.linalg.norm(r2, axis=1))[:, None], r1, r2
            )
            e = r[:, :1] * x1 + r[:, 1:] * x2
            tv = d[:, :1] * x1 + d[:, 1:] * x2
            c = np.abs(np.einsum("ij,ij->i", e, tv)) / (
                np.linalg.norm(e, axis=1) * np.linalg.norm(tv, axis=1)
            )
            ang.append(np.degrees(np.arccos(np.clip(c, 0, 1))))
        out.append(np.minimum(*ang))
    return np.concatenate(out)


BUMPY = lg.ParametricSurface(
    lambda u, v: np.stack(
        np.broadcast_arrays(u, v, 0.35 * np.sin(1.3 * u) * np.cos(v) + 0.1 * u * v), -1
    ),
    (-2, 2),
    (-2, 2),
)


@pytest.mark.parametrize(
    "S",
    [lg.MonkeySaddle(), lg.Helicoid(), lg.Catenoid(), lg.Enneper(), BUMPY],
    ids=["monkey", "helicoid", "catenoid", "enneper", "bumpy"],
)
def test_equation_3_3_holds(S):
    batches = numeric_lines_of_curvature(S, 3, 3)
    assert sum(len(b) for b in batches) >= 6
    ang = _angles_33(S, batches)
    assert np.percentile(ang, 99) <= 0.5, np.percentile(ang, [50, 99, 100])


def test_helicoid_lines_bisect_the_asymptotic_lines():
    """On a minimal surface the lines of curvature make 45 degrees with the
    asymptotic lines; on the helicoid these are the rulings u2 = const."""
    S = lg.Helicoid()
    for _b, _k, t, _x, uv in _samples(numeric_lines_of_curvature(S, 3, 3), 100):
        d = np.gradient(uv, t, axis=0)[2:-2]
        x1, x2 = S.derivatives(uv[2:-2, 0], uv[2:-2, 1])
        tv = d[:, :1] * x1 + d[:, 1:] * x2
        c = np.abs(np.einsum("ij,ij->i", tv, x1)) / (
            np.linalg.norm(tv, axis=1) * np.linalg.norm(x1, axis=1)
        )
        assert np.abs(np.degrees(np.arccos(c)) - 45).max() < 0.2


def test_lines_stop_at_the_umbilic_and_the_boundary():
    S = lg.MonkeySaddle()
    for b, k, _t, _x, uv in _samples(numeric_lines_of_curvature(S, 4, 4), 50):
        assert np.all(np.abs(uv) <= 1 + 1e-12)
        assert not b.closed[k]
    # the renderer draws them (default family on a surface without closed forms)
    scene = lg.Scene()
    scene.add(S, lg.LinesOfCurvature(2, 2))
    d = scene.render(lg.ParallelProjector(direction=(1, -2, 1.5)), tolerance=1e-2)
    assert any(s.family == "curvature" for s in d.strokes)
