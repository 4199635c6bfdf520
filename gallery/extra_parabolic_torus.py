"""Extra figure: the parabolic lines of a torus."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Parabolic lines of the torus with R = 2, r = 0.8 (bold): where the Gaussian "
    "curvature K = cos u2 / (r (R + r cos u2)) vanishes, its top and bottom circles. They "
    "separate the elliptic outer half (K > 0) from the hyperbolic inner half (K < 0). "
    "Thin: 24 meridians and 12 parallels; hidden parts dashed."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    scene.add(
        lg.Torus(2.0, 0.8),
        lg.ParameterLines(24, 12),
        lg.ParabolicLines(),
        style={"parabolic": lg.Style(width=2.2)},
    )
    return scene, lg.CentralProjector.from_angles(35, 30, 12), {"hidden_lines": True}


if __name__ == "__main__":
    run_script_main(__file__, build)
