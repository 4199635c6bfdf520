"""Figure 4.4: lines of curvature on a general cylinder."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 4.4. Lines of curvature on the general cylinder x = y(u1) + u2 c over the "
    "non-convex closed curve y(t) = r(t) (cos t, sin t, 0), r = 2 + 0.5 cos 3t + 0.3 sin 2t, "
    "with the oblique unit direction c = (0.35, 0, 1)/|(0.35, 0, 1)|, 0 <= u2 <= 3: the "
    "rulings and, by (4.3), the curves u2 = d - c . y(u1), the sections by planes normal to c."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    def y(t: np.ndarray) -> np.ndarray:
        r = 2 + 0.5 * np.cos(3 * t) + 0.3 * np.sin(2 * t)
        return np.stack([r * np.cos(t), r * np.sin(t), 0 * t], -1)

    directrix = lg.Curve(y, 0, 2 * np.pi, closed=True)
    cylinder = lg.GeneralCylinder(directrix, (0.35, 0, 1), u2_range=(0, 3))
    scene = lg.Scene()
    scene.add(cylinder, lg.LinesOfCurvature(40, 7))
    return scene, lg.ParallelProjector.from_angles(-70, 25)


if __name__ == "__main__":
    run_script_main(__file__, build)
