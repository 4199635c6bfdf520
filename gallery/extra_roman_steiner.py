"""Steiner's Roman surface from its implicit equation."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Steiner's Roman surface x²y² + y²z² + z²x² − xyz = 0, the image of the unit sphere "
    "under (yz, zx, xy), drawn from its quartic equation (not from a parametrization): "
    "plane sections z = const, the contour and the clip curve on the sphere of radius 0.6; "
    "hidden parts dashed. The surface is singular along three segments of the axes, where "
    "the sections cross. Central projection."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    scene.add(lg.RomanSteiner(), lg.LevelLines(11))
    projector = lg.CentralProjector.from_angles(35, 28, 4.0)
    return scene, projector, {"hidden_lines": True}


if __name__ == "__main__":
    run_script_main(__file__, build)
