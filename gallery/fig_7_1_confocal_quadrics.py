"""Paper Figure 7.1: confocal ellipsoid and hyperboloids, a triply orthogonal system."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

A, B, C = 1.0, 2.0, 3.0
LAMS = (-1.0, 2.5, 7.0)

CAPTION = (
    "Figure 7.1. Three members of the confocal family x²/(a²-λ) + y²/(b²-λ) + "
    "z²/(c²-λ) = 1 with a, b, c = 1, 2, 3 (Lemma 7.1): the ellipsoid λ = -1, the "
    "hyperboloid of one sheet λ = 2.5 (axis x) and the hyperboloid of two sheets "
    "λ = 7 (axis z), the hyperboloids cut at distance 2.5 from the centre along their "
    "axes. Each carries 7 + 7 of its lines of curvature; the bold curves are the "
    "intersections of the members, lines of curvature on both by Dupin's theorem."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    system = lg.TripleOrthogonalSystem.confocal(A, B, C, LAMS, height=2.5)
    scene = lg.Scene()
    for member in system.members:
        scene.add(member, lg.LinesOfCurvature(7, 7))
    for curve in system.curves:
        scene.add(curve, style=lg.Style(width=1.0))
    return scene, lg.CentralProjector.from_angles(-60, 30, 24)


if __name__ == "__main__":
    run_script_main(__file__, build)
