"""Figure 4.3: the normal curvature along a curve on a torus, drawn as the curve
y(t) = x(u(t)) + kn(t) N(u(t))."""

from __future__ import annotations

import numpy as np

import lgraph as lg

TORUS = lg.Torus(2.2, 1)
AMP, WAVES = 0.45, 3  # u(t) = (t, pi + AMP sin(WAVES t))

CAPTION = (
    "Figure 4.3. The closed curve x(u(t)), u(t) = (t, pi + 0.45 sin 3t), 0 <= t <= 2 pi, on the "
    "torus ((2.2 + cos u2) cos u1, (2.2 + cos u2) sin u1, sin u2), winding around the hole "
    "on the saddle-shaped inner half (thick), and the curve y(t) = x(u(t)) + kn(t) N(u(t)) "
    "(thick), where kn = II(u')/I(u') "
    "is the normal curvature in the curve's direction and N = x1 x x2 / |x1 x x2|; thin "
    "segments join x(t) to y(t) at 30 points. kn N does not depend on the sign of N: y "
    "lies on the concave side, in the hole where the curve runs along the inner equator, "
    "inside the tube where it climbs steeply; y meets the torus where the curve's "
    "direction is asymptotic (kn = 0)."
)


def curve_uv(t: np.ndarray) -> np.ndarray:
    t = np.asarray(t, float)
    return np.stack([t, np.pi + AMP * np.sin(WAVES * t)], -1)


def normal_curvature(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(kn, N)`` along the curve, from the fundamental forms of the torus:
    ``kn = (L11 u1'^2 + 2 L12 u1' u2' + L22 u2'^2) / (g11 u1'^2 + 2 g12 u1' u2' + g22 u2'^2)``."""
    t = np.asarray(t, float)
    uv = curve_uv(t)
    du = np.stack([np.ones_like(t), AMP * WAVES * np.cos(WAVES * t)], -1)
    x1, x2 = TORUS.derivatives(uv[:, 0], uv[:, 1])
    x11, x12, x22 = TORUS.second_derivatives(uv[:, 0], uv[:, 1])
    N = np.cross(x1, x2)
    N /= np.linalg.norm(N, axis=-1, keepdims=True)
    a, b = du[:, 0], du[:, 1]

    def dot(p: np.ndarray, q: np.ndarray) -> np.ndarray:
        return np.einsum("ij,ij->i", p, q)

    first = dot(x1, x1) * a * a + 2 * dot(x1, x2) * a * b + dot(x2, x2) * b * b
    second = dot(N, x11) * a * a + 2 * dot(N, x12) * a * b + dot(N, x22) * b * b
    return second / first, N


def y_curve(t: np.ndarray) -> np.ndarray:
    """``y(t) = x(u(t)) + kn(t) N(u(t))``."""
    kn, N = normal_curvature(t)
    return TORUS.points(curve_uv(t)) + kn[:, None] * N


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(TORUS, lg.ParameterLines(24, 12))
    thick = lg.Style(width=1.3)
    scene.add(lg.CurveOnSurface(TORUS, curve_uv, 0.0, 2 * np.pi, closed=True), style=thick)
    scene.add(lg.Curve(y_curve, 0.0, 2 * np.pi, closed=True), style=thick)
    for t in 2 * np.pi * np.arange(30) / 30:
        p, q = TORUS.points(curve_uv(np.array([t])))[0], y_curve(np.array([t]))[0]
        if np.linalg.norm(q - p) > 1e-9:
            scene.add(lg.Curve(lambda s, p=p, q=q: p + s[:, None] * (q - p), 0.0, 1.0),
                      style=lg.Style(width=0.35))  # fmt: skip
    return scene, lg.ParallelProjector.from_angles(-70, 66)


if __name__ == "__main__":
    from lgraph.gallery import run_script_main

    run_script_main(__file__, build)
