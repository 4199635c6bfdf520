"""Figure 4.8: lines of curvature on a cone in hyperbolic parametrization."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 4.8. Lines of curvature on the cone x^2/a^2 - y^2/b^2 = z^2, a = 1, b = 1.2, in "
    "the hyperbolic parametrization of Example 4.2(b): x = u2 y(u1) with the hyperbola "
    "branches y(t) = (+-a cosh t, b sinh t, 1), -1.3 <= t <= 1.3, and -1 <= u2 <= 1, so "
    "u2 < 0 gives the second nappe. Lines of curvature: the rulings and the spherical "
    "sections u2 = k / sqrt(a^2 cosh^2 t + b^2 sinh^2 t + 1)."
)
A, B, T = 1.0, 1.2, 1.3


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    for sign in (1, -1):
        branch = lg.Curve(
            lambda t, s=sign: np.stack([s * A * np.cosh(t), B * np.sinh(t), 0 * t + 1], -1),
            -T, T,
        )  # fmt: skip
        cone = lg.GeneralCone(branch, apex=(0, 0, 0), scaled=True, u2_range=(-1, 1))
        scene.add(cone, lg.LinesOfCurvature(16, 14))
    return scene, lg.ParallelProjector.from_angles(-75, 25)


if __name__ == "__main__":
    run_script_main(__file__, build)
