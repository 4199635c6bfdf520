"""Figure 4.6: lines of curvature on a tangent surface."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 4.6. Lines of curvature on the tangent surface x = y(u1) + u2 y'(u1)/|y'(u1)| of "
    "the helix y(t) = (cos t, sin t, 0.3 t), 0 <= t <= 4 pi, 0 <= u2 <= 3: the rulings "
    "(tangents) and, by (4.5), the involutes u2 = d - s(u1), s the arc length. The helix "
    "itself is the edge of regression."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    helix = lg.Curve(
        lambda t: np.stack([np.cos(t), np.sin(t), 0.3 * t], -1),
        0, 4 * np.pi,
        derivative_func=lambda t: np.stack([-np.sin(t), np.cos(t), 0 * t + 0.3], -1),
        second_derivative_func=lambda t: np.stack([-np.cos(t), -np.sin(t), 0 * t], -1),
    )  # fmt: skip
    scene = lg.Scene()
    scene.add(lg.TangentSurface(helix, u2_range=(0, 3)), lg.LinesOfCurvature(48, 16))
    return scene, lg.ParallelProjector.from_angles(-50, 30)


if __name__ == "__main__":
    run_script_main(__file__, build)
