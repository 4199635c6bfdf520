"""Paper Figure 7.3: lines of curvature on hyperboloids of one and two sheets."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 7.3. Left: lines of curvature on the hyperboloid of one sheet "
    "x²/1.2² + y²/1.8² - z²/1.5² = 1, |z| <= 3. Right: on the hyperboloid of two sheets "
    "x²/1.2² + y²/1.8² - z²/1.5² = -1, 1.5 <= |z| <= 3.75. Both are intersections "
    "with the confocal quadrics (Example 7.1); the rims |z| = height bound the drawn "
    "patches. The two-sheeted hyperboloid's lines of curvature wind around its "
    "four umbilics."
)


def build() -> list[tuple[lg.Scene, lg.Projector]]:
    one = lg.Scene()
    one.add(lg.HyperboloidOneSheet(1.2, 1.8, 1.5, height=3), lg.LinesOfCurvature(10, 16))
    two = lg.Scene()
    two.add(lg.HyperboloidTwoSheets(1.2, 1.8, 1.5), lg.LinesOfCurvature(8, 12))
    return [
        (one, lg.CentralProjector.from_angles(-40, 20, 18)),
        (two, lg.CentralProjector.from_angles(-40, 20, 22)),
    ]


if __name__ == "__main__":
    run_script_main(__file__, build)
