"""Several surfaces hiding one another, placed with composed transforms."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "A composition of five quadrics that hide one another: a central ellipsoid "
    "x²/2.2² + y²/1.4² + z²/1² = 1, three smaller ellipsoids (semi-axes 1.6, 0.5, 0.5) "
    "rotated about z by -20°, 115° and 215° after being tilted 30° about y and moved 3.1 "
    "along x, and a sphere of radius 0.9 centred at (-1, 2.2, 1), behind. Every point "
    "of every line is tested against all five surfaces; transforms compose with @ "
    "(the right one acts first)."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(2.2, 1.4, 1.0), lg.ParameterLines(9, 20))
    petal = lg.Ellipsoid(1.6, 0.5, 0.5)
    for angle in (-20, 115, 215):
        t = lg.rotate("z", angle) @ lg.translate(3.1, 0, 0) @ lg.rotate("y", 30)
        scene.add(petal, lg.ParameterLines(7, 14), transform=t)
    scene.add(lg.Sphere(0.9), lg.ParameterLines(7, 12), transform=lg.translate(-1, 2.2, 1))
    return scene, lg.CentralProjector.from_angles(-35, 17, 16)


if __name__ == "__main__":
    run_script_main(__file__, build)
