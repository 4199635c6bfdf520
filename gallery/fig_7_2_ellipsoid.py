"""Paper Figure 7.2: lines of curvature on a triaxial ellipsoid."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 7.2. Lines of curvature on the ellipsoid x²/3² + y²/2² + z²/1.3² = 1: "
    "its intersections with the confocal hyperboloids of one and two sheets "
    "(Example 7.1, Dupin's theorem), 14 + 18 curves spread evenly along the principal "
    "ellipses. They close around the longest and the shortest axis and crowd "
    "toward the four umbilics in the xz-plane."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(14, 18))
    return scene, lg.CentralProjector.from_angles(35, 25, 16)


if __name__ == "__main__":
    run_script_main(__file__, build)
