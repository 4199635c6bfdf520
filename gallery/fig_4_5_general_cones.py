"""Figure 4.5: lines of curvature on two general cones."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 4.5. Lines of curvature on two general cones with vertex at the origin: the rulings "
    "and, by (4.4), the sections |x| = d by spheres about the vertex. Left: x = y(u1) + u2 "
    "y(u1)/|y(u1)| over the spherical curve y = 3 (sin p cos t, sin p sin t, cos p), "
    "p = 0.55 + 0.2 sin 3t, -3 <= u2 <= 0; as |y| = 3 is constant the lines of curvature are "
    "the parameter lines u1, u2 = const. Right: the general case, x = u2 y(u1) over "
    "y(t) = (2 cos t, 1.4 sin t, 3 + 0.6 sin 3t), 0 <= u2 <= 1: the spheres cut the "
    "patch obliquely."
)
TAU = 2 * np.pi


def build() -> list[tuple[lg.Scene, lg.Projector]]:
    def spherical(t: np.ndarray) -> np.ndarray:
        p = 0.55 + 0.2 * np.sin(3 * t)
        return 3 * np.stack([np.sin(p) * np.cos(t), np.sin(p) * np.sin(t), np.cos(p)], -1)

    def wavy(t: np.ndarray) -> np.ndarray:
        return np.stack([2 * np.cos(t), 1.4 * np.sin(t), 3 + 0.6 * np.sin(3 * t)], -1)

    left, right = lg.Scene(), lg.Scene()
    special = lg.GeneralCone(lg.Curve(spherical, 0, TAU, closed=True), apex=(0, 0, 0))
    left.add(special, lg.LinesOfCurvature(32, 6))
    general = lg.GeneralCone(lg.Curve(wavy, 0, TAU, closed=True), apex=(0, 0, 0), scaled=True)
    right.add(general, lg.LinesOfCurvature(32, 8))
    view = lg.ParallelProjector.from_angles(-60, 25)
    return [(left, view), (right, view)]


if __name__ == "__main__":
    run_script_main(__file__, build)
