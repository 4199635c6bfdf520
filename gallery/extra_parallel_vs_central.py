"""One scene in parallel and in central projection."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "The same scene in parallel (left) and central projection (right): a row of three "
    "spheres of radius 1 along the x-axis, 3 apart, behind an ellipsoid "
    "x²/4² + y²/1² + z²/1.2² = 1 set in front of them. Both views look from azimuth -60°, "
    "elevation 25°; the central projection puts the eye 7.5 units from the target, so "
    "the nearer sphere looks larger and the contours are the circles cut by the eye's "
    "polar planes instead of great circles."
)


def _scene() -> lg.Scene:
    scene = lg.Scene()
    for x in (-3.0, 0.0, 3.0):
        scene.add(lg.Sphere(1), lg.ParameterLines(7, 12), transform=lg.translate(x, 1.5, 0))
    scene.add(
        lg.Ellipsoid(4, 1, 1.2), lg.ParameterLines(7, 20), transform=lg.translate(0, -1.6, -0.4)
    )
    return scene


def build() -> list[tuple[lg.Scene, lg.Projector]]:
    scene = _scene()
    return [
        (scene, lg.ParallelProjector.from_angles(-60, 25)),
        (scene, lg.CentralProjector.from_angles(-60, 25, 7.5)),
    ]


if __name__ == "__main__":
    run_script_main(__file__, build)
