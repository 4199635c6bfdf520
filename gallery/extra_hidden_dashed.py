"""Hidden lines drawn dashed, in the style of a technical drawing."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Hidden lines drawn dashed, as in a technical drawing: the ellipsoid "
    "x²/3² + y²/2² + z²/1.5² = 1 with 9 latitudes and 16 meridians, and the sphere "
    "x² + y² + z² = 1.1² behind it, centred at (1.5, 3.2, 0.6). Visible parts are solid; "
    "parts hidden by either surface are thin grey dashes (render option hidden_lines=True). "
    "Central projection."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.5), lg.ParameterLines(9, 16))
    scene.add(lg.Sphere(1.1), lg.ParameterLines(7, 12), transform=lg.translate(1.5, 3.2, 0.6))
    projector = lg.CentralProjector.from_angles(-55, 22, 18, target=(0.5, 1, 0))
    return scene, projector, {"hidden_lines": True}


if __name__ == "__main__":
    run_script_main(__file__, build)
