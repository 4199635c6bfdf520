"""The Clebsch diagonal cubic with its 27 real lines."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Clebsch's diagonal cubic surface, the cubic surface whose 27 lines are all real, in the "
    "ball of radius 1: plane sections z = const, the contour and the clip curve on the "
    "sphere, and the 27 lines as exact straight segments (thick). Hidden parts dashed; "
    "every visibility decision is a certain root count of the cubic along the ray "
    "(Bernstein coefficients, Descartes' rule). Parallel projection."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    surface = lg.ClebschCubic(radius=1.0)
    scene = lg.Scene()
    scene.add(surface, lg.LevelLines(9), style={"level": lg.Style(width=0.35)})
    for line in surface.lines():
        scene.add(line, style=lg.Style(width=1.0))
    projector = lg.ParallelProjector(direction=(1.0, 0.8, 0.6))
    return scene, projector, {"hidden_lines": True}


if __name__ == "__main__":
    run_script_main(__file__, build)
