"""Paper Figure 6.1: the triply orthogonal system of spherical coordinates."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 6.1. The triply orthogonal system of Example 6.1, "
    "y(u1, u2, u3) = (u1 cos u2 cos u3, u1 cos u2 sin u3, u1 sin u2): the sphere u1 = 1, "
    "the cone of half-angle 55° about the z-axis (both nappes; u2 = ±35°) and the "
    "half-plane u3 = -40°, each with its parameter lines. The bold curves where they "
    "meet (two circles of latitude, a meridian and two rulings) are lines of curvature "
    "on each surface, by Dupin's theorem."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    system = lg.TripleOrthogonalSystem.spherical(radius=1.0, polar_angle=55, azimuth=-40)
    scene = system.scene(lg.ParameterLines(8, 16))
    return scene, lg.CentralProjector.from_angles(-20, 25, 8)


if __name__ == "__main__":
    run_script_main(__file__, build)
