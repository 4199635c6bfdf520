"""The cross-cap: the projective plane with a segment of self-intersection and two pinch points."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "The cross-cap, lg.CrossCap(): (yz, 2xy, x² - y²) of the unit sphere's point, an even map, "
    "so the chart u in [0, π], v in [0, π] is glued with a twist and the surface is a "
    "projective plane; it satisfies (2X² + Y² + Z² + Z)² = (Y² + Z²)(1 + Z)². "
    "8 + 12 parameter lines (no seam drawn) and, in red, the self-intersection "
    "(lg.SelfIntersection()): the segment X = Y = 0, 0 ≤ Z ≤ 1, which ends in two pinch "
    "points where the outline (the numeric contour) comes to a point. Hidden parts dashed, "
    "the self-intersection's in red."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    hidden = {
        "default": lg.Style(width=0.3, dash=(2.0, 2.0), color=(0.5, 0.5, 0.5)),
        "self_intersection": lg.Style(width=0.5, dash=(2.0, 1.5), color=(0.8, 0.0, 0.0)),
    }
    red = {"self_intersection": lg.Style(color=(0.8, 0.0, 0.0), width=0.8)}
    scene = lg.Scene()
    scene.add(lg.CrossCap(), lg.ParameterLines(8, 12), lg.SelfIntersection(), style=red)
    view = lg.ParallelProjector(direction=(0.3, 1.0, 0.3))
    return scene, view, {"hidden_lines": True, "hidden_style": hidden}


if __name__ == "__main__":
    run_script_main(__file__, build)
