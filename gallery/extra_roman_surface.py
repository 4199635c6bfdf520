"""Steiner's Roman surface: the projective plane in space, with its self-intersection."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Steiner's Roman surface, lg.RomanSurface(): F(p) = (yz, zx, xy) of the unit sphere's "
    "point p = (sin u cos v, sin u sin v, cos u), an even map (F(p) = F(-p)), so the "
    "rectangle 0 ≤ u ≤ π, π/24 ≤ v ≤ 25π/24 is glued with a twist along its v edges "
    "(periodic=(False, 'twisted')) and the surface is a projective plane; it satisfies "
    "X²Y² + Y²Z² + Z²X² = XYZ. 8 + 12 parameter lines (no seam drawn) and the "
    "self-intersection (lg.SelfIntersection(), red): the three segments |X|, |Y|, |Z| ≤ 1/2 "
    "of the axes, through a triple point at the centre. Hidden parts dashed."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    hidden = lg.Style(width=0.3, dash=(2.0, 2.0), color=(0.5, 0.5, 0.5))
    red = {"self_intersection": lg.Style(color=(0.8, 0.0, 0.0), width=0.8)}
    scene = lg.Scene()
    scene.add(lg.RomanSurface(), lg.ParameterLines(8, 12), lg.SelfIntersection(), style=red)
    view = lg.ParallelProjector(direction=(1.0, 0.8, 0.6))
    return scene, view, {"hidden_lines": True, "hidden_style": hidden}


if __name__ == "__main__":
    run_script_main(__file__, build)
