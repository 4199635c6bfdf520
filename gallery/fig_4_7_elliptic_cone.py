"""Figure 4.7: lines of curvature on an elliptic cone."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 4.7. Lines of curvature on the elliptic cone x^2/a^2 + y^2/b^2 = z^2, a = 1.5, "
    "b = 1, |z| <= 1 (Example 4.2(a)): the rulings and the sections by spheres about the vertex, "
    "u1 = k / sqrt(a^2 cos^2 u2 + b^2 sin^2 u2 + 1)."
)
A, B, H = 1.5, 1.0, 1.0


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.EllipticCone(A, B, height=H), lg.LinesOfCurvature(8, 32))
    return scene, lg.ParallelProjector.from_angles(-60, 20)


if __name__ == "__main__":
    run_script_main(__file__, build)
