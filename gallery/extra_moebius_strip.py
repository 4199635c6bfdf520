"""A Moebius strip glued with a twist: its lines run on across the seam."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "lg.MoebiusStrip(width=0.8): x = ((1 + v cos(u/2)) cos u, (1 + v cos(u/2)) sin u, "
    "v sin(u/2)), 0 ≤ u ≤ 2π glued with a twist (periodic=('twisted', False): "
    "x(0, v) = x(2π, -v)). No seam is drawn; each line v = c runs on as v = -c and closes "
    "after two turns, and the strip's edge is one closed curve. 16 + 6 parameter lines, "
    "hidden parts dashed."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    scene.add(lg.MoebiusStrip(width=0.8), lg.ParameterLines(16, 6))
    hidden = lg.Style(width=0.3, dash=(2.0, 2.0), color=(0.45, 0.45, 0.45))
    return (
        scene,
        lg.CentralProjector.from_angles(30, 35, 9),
        {
            "hidden_lines": True,
            "hidden_style": hidden,
        },
    )


if __name__ == "__main__":
    run_script_main(__file__, build)
