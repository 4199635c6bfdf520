"""Independent geometric checks of what the curvature figures (paper Figures
3.1, 3.2, 3.3 and 4.3) show: every quantity is recomputed here from the
surfaces' point functions by finite differences or from implicit equations."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

import lgraph as lg

GALLERY = Path(__file__).resolve().parents[1] / "gallery"


def _load(stem: str):
    spec = importlib.util.spec_from_file_location(f"_gallery_{stem}", GALLERY / f"{stem}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _partials(f, u1, u2, h=1e-5):
    """First partial derivatives of a point function by central differences."""
    x1 = (f(u1 + h, u2) - f(u1 - h, u2)) / (2 * h)
    x2 = (f(u1, u2 + h) - f(u1, u2 - h)) / (2 * h)
    return x1, x2


def _unit(v):
    return v / np.linalg.norm(v)


def _items(scene, kind):
    return [n.item for n in scene.nodes if isinstance(n.item, kind)]


# -- Figure 3.1 -----------------------------------------------------------------
def test_fig_3_1_normal_tangents_and_plane():
    m = _load("fig_3_1_tangent_plane")
    scene, _ = m.build()
    S, (u1, u2) = m.SURFACE, m.UV
    P = S.point(u1, u2)
    x1, x2 = _partials(S.point, u1, u2)
    N = _unit(np.cross(x1, x2))
    arrows = _items(scene, lg.Arrow)
    normal = [a for a in arrows if np.linalg.norm(a.tail - P) < 1e-12]
    tangent = [a for a in arrows if np.linalg.norm(a.tail - P) >= 1e-12]
    assert len(normal) == 1 and len(tangent) == 2
    n_dir = _unit(normal[0].tip - normal[0].tail)
    assert np.allclose(n_dir, N, atol=1e-8)  # the paper's N = x1 x x2 / |x1 x x2|
    dirs = [_unit(a.tip - a.tail) for a in tangent]
    for d, x in zip(dirs, (x1, x2)):
        assert abs(d @ n_dir) < 1e-8  # orthogonal to the normal arrow
        assert np.linalg.norm(np.cross(d, _unit(x))) < 1e-8  # along x1, resp. x2
        assert d @ x > 0
    for a in tangent:  # the tangent arrows sit on the plane, just above it
        lift = (a.tail - P) @ N
        assert 0 < lift < 2 * a.shaft_radius
        assert np.linalg.norm(a.tail - P - lift * N) < 1e-12
    (plane,) = _items(scene, lg.Parallelogram)
    # P = origin + s e1 + t e2 with 0 <= s, t <= 1, and the plane is normal to N
    coef, *_ = np.linalg.lstsq(np.column_stack([plane.e1, plane.e2]), P - plane.origin, rcond=None)
    assert np.linalg.norm(plane.origin + plane.e1 * coef[0] + plane.e2 * coef[1] - P) < 1e-12
    assert np.all((coef > 0) & (coef < 1))
    assert abs(_unit(np.cross(plane.e1, plane.e2)) @ N) > 1 - 1e-12


# -- Figure 3.2 -----------------------------------------------------------------
def test_fig_3_2_curvature_vector_decomposition():
    m = _load("fig_3_2_curvature_vector")

    def x(t):
        uv = m.curve_uv(np.atleast_1d(t))
        return m.PATCH.point(uv[:, 0], uv[:, 1])

    def speed(t):
        return float(np.linalg.norm((x(t + 1e-6) - x(t - 1e-6)) / 2e-6))

    t0 = m.T0

    def t_of(s):  # inverse of the arc length measured from t0
        return brentq(lambda t: quad(speed, t0, t, epsabs=1e-13)[0] - s, t0 - 1, t0 + 1, xtol=1e-15)

    h = 2e-3
    X = [x(t_of(s))[0] for s in (-h, 0.0, h)]
    curvature = (X[0] - 2 * X[1] + X[2]) / h**2  # d^2x/ds^2 by differences in arc length
    uv0 = m.curve_uv(np.array([t0]))[0]
    x1, x2 = _partials(m.PATCH.point, uv0[0], uv0[1])
    N = _unit(np.cross(x1, x2))
    T = _unit(X[2] - X[0])
    d = m.decomposition(t0)
    assert np.allclose(d["P"], X[1], atol=1e-12)
    assert np.allclose(d["N"], N, atol=1e-8)
    assert np.allclose(d["G"], np.cross(N, T), atol=1e-5)
    assert np.allclose(d["kn"] * d["N"] + d["kg"] * d["G"], curvature, atol=1e-5)
    assert abs(d["kn"] - curvature @ N) < 1e-5
    assert abs(d["kg"]) > 0.1 and abs(d["kn"]) > 0.1  # both parts are really there
    # the arrows drawn at P are these vectors
    scene, _ = m.build()[0]
    tips = [a.tip for a in _items(scene, lg.Arrow)]
    for v in (curvature, (curvature @ N) * N, (curvature @ d["G"]) * d["G"]):
        assert min(np.linalg.norm(tip - (X[1] + m.VSCALE * v)) for tip in tips) < 1e-5


def test_fig_3_2_principal_directions():
    m = _load("fig_3_2_curvature_vector")
    P, e1, e2, n = m.principal_frame()
    axes = np.array([3.0, 2.0, 1.5])
    assert abs(np.sum((P / axes) ** 2) - 1) < 1e-12
    assert np.allclose(n, _unit(P / axes**2), atol=1e-12)
    # principal directions: eigenvectors of the Hessian of the implicit
    # equation restricted to the tangent plane (normal curvature extrema)
    b1 = _unit(np.cross(n, [0.0, 0.0, 1.0]))
    b2 = np.cross(n, b1)
    B = np.column_stack([b1, b2])
    _, vecs = np.linalg.eigh(B.T @ np.diag(2 / axes**2) @ B)
    expected = [B @ vecs[:, k] for k in (0, 1)]
    got = [e1, e2]
    for e in got:
        assert abs(e @ n) < 1e-8 and abs(np.linalg.norm(e) - 1) < 1e-12
    assert abs(e1 @ e2) < 1e-8
    for e in got:
        assert max(abs(e @ f) for f in expected) > 1 - 1e-8
    scene, _ = m.build()[1]
    dirs = [_unit(a.tip - a.tail) for a in _items(scene, lg.Arrow)]
    for v in (e1, e2, n):
        assert max(abs(d @ v) for d in dirs) > 1 - 1e-10


# -- Figure 3.3 -----------------------------------------------------------------
def test_fig_3_3_rulings_are_cone_normals_and_surface_is_developable():
    m = _load("fig_3_3_normal_ruled_surface")
    A, B = m.A, m.B
    R = m.NORMAL_SURFACE
    t = np.linspace(0, 2 * np.pi, 37)[:-1]
    y = R.point(t, 0 * t)
    # the directrix lies on the cone and on the sphere |x| = RHO
    assert np.abs(y[:, 0] ** 2 / A**2 + y[:, 1] ** 2 / B**2 - y[:, 2] ** 2).max() < 1e-12
    assert np.abs(np.linalg.norm(y, axis=1) - m.RHO).max() < 1e-12
    grad = np.stack([2 * y[:, 0] / A**2, 2 * y[:, 1] / B**2, -2 * y[:, 2]], 1)
    for u2 in (0.2, m.LENGTH):
        ruling = R.point(t, np.full_like(t, u2)) - y
        assert np.allclose(np.linalg.norm(ruling, axis=1), u2, atol=1e-12)
        # along the cone's normal, outward
        cos = np.einsum("ij,ij->i", ruling, grad) / (u2 * np.linalg.norm(grad, axis=1))
        assert np.abs(cos - 1).max() < 1e-10

    def det(surface, u):
        h = 1e-5
        y1, z = _partials(surface.point, u, 0 * u, h)
        z_plus = (surface.point(u + h, 0 * u + h) - surface.point(u + h, 0 * u - h)) / (2 * h)
        z_minus = (surface.point(u - h, 0 * u + h) - surface.point(u - h, 0 * u - h)) / (2 * h)
        z1 = (z_plus - z_minus) / (2 * h)
        d = np.einsum("ij,ij->i", y1, np.cross(z, z1))
        return d / (
            np.linalg.norm(y1, axis=1) * np.linalg.norm(z, axis=1) * np.linalg.norm(z1, axis=1)
        )

    assert np.abs(det(R, t)).max() < 1e-6
    # the check has teeth: normals along a plane section z = const are not developable
    section = lg.Curve(
        lambda s: np.stack([A * 0.8 * np.cos(s), B * 0.8 * np.sin(s), 0.8 + 0 * s], -1),
        0, 2 * np.pi, closed=True,
    )  # fmt: skip

    def cone_normal(s):
        p = section(s)
        g = np.stack([p[:, 0] / A**2, p[:, 1] / B**2, -p[:, 2]], -1)
        return g / np.linalg.norm(g, axis=1, keepdims=True)

    other = lg.RuledSurface(section, cone_normal, u2_range=(0, 0.5))
    assert np.abs(det(other, t)).max() > 1e-2


# -- Figure 4.3 -----------------------------------------------------------------
def test_fig_4_3_normal_curvature_matches_finite_differences():
    m = _load("fig_4_3_normal_curvature_torus")
    T = m.TORUS
    t = np.linspace(0, 2 * np.pi, 41)
    h = 1e-3

    def x(s):
        uv = m.curve_uv(s)
        return T.point(uv[:, 0], uv[:, 1])

    xt = (x(t + h) - x(t - h)) / (2 * h)
    xtt = (x(t + h) - 2 * x(t) + x(t - h)) / h**2
    uv = m.curve_uv(t)
    N = np.cross(*_partials(T.point, uv[:, 0], uv[:, 1]))
    N /= np.linalg.norm(N, axis=1, keepdims=True)
    # x_ss . N = x_tt . N / |x_t|^2 (the tangential part of x_tt does not count)
    kn_fd = np.einsum("ij,ij->i", xtt, N) / np.einsum("ij,ij->i", xt, xt)
    kn, N_fig = m.normal_curvature(t)
    assert np.allclose(N_fig, N, atol=1e-8)
    assert np.abs(kn - kn_fd).max() < 1e-5
    assert kn.min() < -0.1 and kn.max() > 0.1  # both signs occur along this curve
    assert np.allclose(m.y_curve(t), x(t) + kn_fd[:, None] * N, atol=1e-5)
    scene, _ = m.build()
    curves = _items(scene, lg.Curve)
    assert any(np.allclose(c(t), m.y_curve(t)) for c in curves if c.closed)


@pytest.mark.parametrize(
    "stem",
    [
        "fig_3_1_tangent_plane",
        "fig_3_2_curvature_vector",
        "fig_3_3_normal_ruled_surface",
        "fig_4_3_normal_curvature_torus",
    ],
)
def test_figures_have_captions_and_panels(stem):
    m = _load(stem)
    assert isinstance(m.CAPTION, str) and len(m.CAPTION) > 80
    result = m.build()
    panels = result if isinstance(result, list) else [result]
    for panel in panels:
        assert isinstance(panel[0], lg.Scene) and isinstance(panel[1], lg.Projector)
