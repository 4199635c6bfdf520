"""Paper Figure 5.1: lines of curvature on a hyperbolic paraboloid."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 5.1. Lines of curvature on the hyperbolic paraboloid z = x²/a² - y²/b², "
    "a = 1.2, b = 1, over the patch |x| <= 1.4 a, |y| <= 1.4 b (x = (a u1, b u2, "
    "u1² - u2²), Example 5.1). In the rotated parameters u1 ± u2 the equation (3.3) "
    "separates, and the lines of curvature are the curves arsinh(4 ū2 / sqrt(a²+b²)) "
    "± arsinh(4 ū1 / sqrt(a²+b²)) = const; lgraph draws them in closed form, cut "
    "exactly at the patch boundary (drawn as the parameter lines u1, u2 = ±1.4)."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    surface = lg.HyperbolicParaboloid(1.2, 1.0, extent=1.4)
    scene.add(surface, lg.LinesOfCurvature(14, 14))
    return scene, lg.CentralProjector.from_angles(-60, 30, 12)


if __name__ == "__main__":
    run_script_main(__file__, build)
