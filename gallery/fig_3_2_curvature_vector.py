"""Figure 3.2: the curvature vector of a curve on a surface split into its
normal and geodesic parts (left); the principal directions at a point (right)."""

from __future__ import annotations

import numpy as np

import lgraph as lg

CAPTION = (
    "Figure 3.2. Left: the curve x(s) = x(u(s)), u(t) = (0.15 + 0.75 cos t, 0.6 sin t), "
    "on the patch z = 0.3 x^2 + 0.12 y^2 (|x|, |y| <= 1.2) and, at t = -1.1, its unit "
    "tangent x' and its "
    "vector of curvature x'' (s the arc length), split as x'' = kn N + kg (N x x'): the normal "
    "curvature kn times the surface normal N = x1 x x2 / |x1 x x2| and the geodesic curvature "
    "kg times N x x' (vectors scaled by 0.8; thin lines complete the rectangle). The patch "
    "is drawn transparent so that the vectors in its tangent plane, which lie just off the "
    "curved patch, stay in view. Right: the principal directions e1, e2 (scaled by 1.2, "
    "tangent to the lines of curvature) and the outer unit normal at a point of the "
    "ellipsoid x^2/9 + y^2/4 + z^2/2.25 = 1, drawn with 8 + 8 of its lines of curvature."
)

ALPHA, BETA = 0.3, 0.12  # z = ALPHA x^2 + BETA y^2
T0 = -1.1  # where the curvature vector is drawn
VSCALE = 0.8  # drawn length of the curvature vectors per unit of curvature
_HEAD = {"head_length": 0.13, "head_radius": 0.04}


def _graph(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    u, v = np.broadcast_arrays(u, v)
    return np.stack([u, v, ALPHA * u * u + BETA * v * v], -1)


PATCH = lg.ParametricSurface(_graph, (-1.2, 1.2), (-1.2, 1.2))


def curve_uv(t: np.ndarray) -> np.ndarray:
    """The curve in the parameter plane (the patch is a graph: ``(u, v) = (x, y)``)."""
    t = np.asarray(t, float)
    return np.stack([0.15 + 0.75 * np.cos(t), 0.6 * np.sin(t)], -1)


def decomposition(t: float) -> dict[str, np.ndarray]:
    """At ``t``: point ``P``, unit tangent ``T``, curvature vector ``k`` (the
    second derivative by arc length), unit normal ``N``, ``kn``, ``kg`` and
    ``G = N x T``, from exact derivatives of the curve."""
    u, v = 0.15 + 0.75 * np.cos(t), 0.6 * np.sin(t)
    du, dv = -0.75 * np.sin(t), 0.6 * np.cos(t)
    ddu, ddv = -0.75 * np.cos(t), -0.6 * np.sin(t)
    fu, fv = 2 * ALPHA * u, 2 * BETA * v
    d1 = np.array([du, dv, fu * du + fv * dv])
    d2 = np.array([ddu, ddv, 2 * ALPHA * du * du + 2 * BETA * dv * dv + fu * ddu + fv * ddv])
    speed = np.linalg.norm(d1)
    T = d1 / speed
    k = (d2 - (d2 @ T) * T) / speed**2  # d2x/ds2
    N = np.cross([1.0, 0.0, fu], [0.0, 1.0, fv])
    N /= np.linalg.norm(N)
    G = np.cross(N, T)
    return {"P": _graph(u, v), "T": T, "k": k, "N": N, "G": G, "kn": k @ N, "kg": k @ G}


def _segment(p: np.ndarray, q: np.ndarray) -> lg.Curve:
    return lg.Curve(lambda s: p + s[:, None] * (q - p), 0.0, 1.0)


def _mark(scene: lg.Scene, P: np.ndarray, anchor: str = "n") -> None:
    """The point P: a dot and its name (P lies inside the arrows' tails, which
    would hide it: drawn always)."""
    scene.add(lg.Point(P, size=3.0, always=True))
    offset = {"n": (0, -3), "e": (-4, 0)}[anchor]
    scene.add(lg.Label("$P$", at=P, anchor=anchor, offset=offset, always=True))


def _left() -> tuple[lg.Scene, lg.Projector]:
    d = decomposition(T0)
    P = d["P"]
    scene = lg.Scene()
    scene.add(PATCH, lg.ParameterLines(11, 11), hides=False)
    scene.add(lg.CurveOnSurface(PATCH, curve_uv, -np.pi, np.pi, closed=True),
              style=lg.Style(width=1.3))  # fmt: skip
    ends = {
        "k": P + VSCALE * d["k"],
        "n": P + VSCALE * d["kn"] * d["N"],
        "g": P + VSCALE * d["kg"] * d["G"],
    }
    names = {
        "k": "$\\mathbf{x}''$",
        "n": "$\\kappa_n N$",
        "g": "$\\kappa_g\\,(N \\times \\mathbf{x}')$",
    }
    for key, tip in ends.items():
        scene.add(lg.Arrow(P, tip, **_HEAD, label=names[key]), lg.Contour(), contour=False)
    tangent = lg.Arrow(P, P + 0.7 * d["T"], **_HEAD, label="$\\mathbf{x}'$")
    scene.add(tangent, lg.Contour(), contour=False)
    _mark(scene, P, "e")
    thin = lg.Style(width=0.3)
    scene.add(_segment(ends["n"], ends["k"]), style=thin)
    scene.add(_segment(ends["g"], ends["k"]), style=thin)
    return scene, lg.ParallelProjector.from_angles(-25, 30)


ELLIPSOID = lg.Ellipsoid(3, 2, 1.5)
UV_RIGHT = (0.75, 0.6)


def principal_frame() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``P, e1, e2, outer unit normal`` at :data:`UV_RIGHT` on the ellipsoid."""
    u1, u2 = (np.array([x]) for x in UV_RIGHT)
    P = ELLIPSOID.point(u1, u2)[0]
    e1, e2 = lg.principal_directions(ELLIPSOID, u1, u2)
    n = P / np.array([9.0, 4.0, 2.25])  # gradient of the implicit equation
    return P, e1[0], e2[0], n / np.linalg.norm(n)


def _right() -> tuple[lg.Scene, lg.Projector]:
    P, e1, e2, n = principal_frame()
    scene = lg.Scene()
    scene.add(ELLIPSOID, lg.LinesOfCurvature(8, 8))
    # (the signs of e1, e2 are free: let them point back over the body)
    e1, e2 = (-e if e @ P > 0 else e for e in (e1, e2))
    for v, name in ((1.2 * e1, "$\\mathbf{e}_1$"), (1.2 * e2, "$\\mathbf{e}_2$"), (1.4 * n, "$N$")):
        scene.add(lg.Arrow(P, P + v, **_HEAD, label=name), lg.Contour(), contour=False)
    _mark(scene, P)
    # seen from the normal's azimuth, 45 degrees below it: N points straight up
    az, el = np.degrees(np.arctan2(n[1], n[0])), np.degrees(np.arcsin(n[2]))
    return scene, lg.ParallelProjector.from_angles(az, el - 45)


def build() -> list[tuple[lg.Scene, lg.Projector]]:
    return [_left(), _right()]


if __name__ == "__main__":
    from lgraph.gallery import run_script_main

    run_script_main(__file__, build)
