"""Extra figure: the triaxial ellipsoid of Figure 7.2 turning about its shortest axis."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Turntable (animated GIF, 36 frames): the lines of curvature of the ellipsoid "
    "x²/3² + y²/2² + z²/1.3² = 1 (Figure 7.2) seen from all around, central projection "
    "from distance 16 at elevation 25°. The curves are computed once; every frame redoes "
    "only the contour and the visibility (lg.orbit, lg.animate)."
)

#: the turntable: lg.orbit(elevation=25, frames=36, distance=16), 360 px wide
ANIMATION = {"frames": 36, "elevation": 25, "distance": 16, "fps": 12, "width": 360}


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(14, 18))
    return scene, lg.CentralProjector.from_angles(35, 25, 16)


if __name__ == "__main__":
    run_script_main(__file__, build)
