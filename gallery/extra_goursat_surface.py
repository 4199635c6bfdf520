"""Goursat's quartic with the symmetries of the cube."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "A Goursat surface x⁴ + y⁴ + z⁴ − (x² + y² + z²) + 0.4 = 0: a quartic with the "
    "symmetries of the cube, of genus 5 (six arms around a hollow centre). Plane "
    "sections x = const and z = const and the contour; hidden parts dashed. Parallel "
    "projection."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    surface = lg.GoursatSurface(0.0, -1.0, 0.4)
    scene.add(surface, lg.LevelLines(9), lg.LevelLines(9, direction=(1, 0, 0)))
    projector = lg.ParallelProjector.from_angles(30, 25)
    return scene, projector, {"hidden_lines": True}


if __name__ == "__main__":
    run_script_main(__file__, build)
