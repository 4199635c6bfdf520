"""Figure 3.1: the tangent vectors x1, x2, the tangent plane and the surface normal N."""

from __future__ import annotations

import numpy as np

import lgraph as lg

CAPTION = (
    "Figure 3.1. At the point P = x(u1, u2) of the torus "
    "x(u1, u2) = ((3 + 1.5 cos u2) cos u1, (3 + 1.5 cos u2) sin u1, 1.5 sin u2), with "
    "(u1, u2) = (-0.3, 1.15): the tangent vectors x1 = dx/du1 and x2 = dx/du2 (both scaled by "
    "0.5), a piece of the tangent plane they span and the surface normal "
    "N = x1 x x2 / |x1 x x2|, all drawn as solid objects that hide and are hidden. "
    "Thick: the parameter lines through P, to which x1 and x2 are tangent. The labels "
    "are hidden exactly like the lines (each anchor's ray is cast against the scene)."
)

SURFACE = lg.Torus(3, 1.5)
UV = (-0.3, 1.15)
SCALE = 0.5  # drawn length of x1, x2 relative to their true length
_HEAD = {"head_length": 0.22, "head_radius": 0.065}


def frame() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``P, x1, x2, N`` at :data:`UV` (x1, x2 unscaled, N of unit length)."""
    P = SURFACE.point(*UV)
    x1, x2 = SURFACE.derivatives(*UV)
    N = np.cross(x1, x2)
    return P, x1, x2, N / np.linalg.norm(N)


def build() -> tuple[lg.Scene, lg.Projector]:
    P, x1, x2, N = frame()
    scene = lg.Scene()
    scene.add(SURFACE, lg.ParameterLines(16, 10))
    thick = lg.Style(width=1.3)
    u1, u2 = UV
    scene.add(lg.CurveOnSurface(SURFACE, lambda t: np.stack([t, np.full_like(t, u2)], -1),
                                u1 - 1.0, u1 + 1.0), style=thick)  # fmt: skip
    scene.add(lg.CurveOnSurface(SURFACE, lambda t: np.stack([np.full_like(t, u1), t], -1),
                                u2 - 1.2, u2 + 1.2), style=thick)  # fmt: skip
    # the tangent plane patch, and the tangent vectors on it, lifted by the
    # shaft radius so that the plane does not cut them in half
    scene.add(lg.Parallelogram.centered(P, 0.55 * x1, 0.9 * x2), lg.Contour(), contour=False)
    x1_name = lg.Label("$\\mathbf{x}_1$", at=P + SCALE * x1, anchor="n", offset=(0, -3))
    for v, name in ((x1, x1_name), (x2, "$\\mathbf{x}_2$")):
        probe = lg.Arrow(P, P + SCALE * v, **_HEAD)
        lift = 1.5 * probe.shaft_radius * N
        arrow = lg.Arrow(P + lift, P + SCALE * v + lift, **_HEAD, label=name)
        scene.add(arrow, lg.Contour(), contour=False)
    scene.add(lg.Arrow(P, P + 1.6 * N, **_HEAD, label="$N$"), lg.Contour(), contour=False)
    # P lies inside the tail of the normal's shaft, which would hide it: always drawn
    scene.add(lg.Point(P, size=3.0, always=True))
    scene.add(lg.Label("$P$", at=P, anchor="n", offset=(0, -3), always=True))
    return scene, lg.ParallelProjector.from_angles(-75, 28)


if __name__ == "__main__":
    from lgraph.gallery import run_script_main

    run_script_main(__file__, build)
