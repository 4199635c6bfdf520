"""The four umbilics of a triaxial ellipsoid, marked."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "The four umbilic points of the ellipsoid x²/3² + y²/2² + z²/1.3² = 1, marked by "
    "small circles in their tangent planes: (±a sqrt((a²-b²)/(a²-c²)), 0, "
    "±c sqrt((b²-c²)/(a²-c²))), in the plane of the longest and shortest axes. There "
    "the two principal curvatures agree (both equal ac/b³), and the lines of curvature"
    " of both families (10 + 14 shown) wind around them. Seen from above "
    "(elevation 50°), parallel projection."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(10, 14), lg.Umbilics(radius=0.08))
    return scene, lg.ParallelProjector.from_angles(35, 50)


if __name__ == "__main__":
    run_script_main(__file__, build)
