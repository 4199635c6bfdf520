"""Extra figure: level lines on the monkey saddle and on a torus."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Level lines. Left: the monkey saddle z = 0.6 (x³ − 3xy²), |x|, |y| ≤ 1, cut by 15 "
    "horizontal planes spread evenly over its heights; the level z = 0 is three lines "
    "through the flat point at the origin. Right: the torus with R = 2, r = 0.8 cut by "
    "9 planes perpendicular to (1, 0, 1), hidden parts dashed. Each level line is traced "
    "on a parameter grid and projected onto its plane by Newton's method (to 1e-12)."
)


def build() -> list[tuple]:
    saddle = lg.Scene()
    saddle.add(lg.MonkeySaddle(extent=1.0, c=0.6), lg.LevelLines(15))
    torus = lg.Scene()
    torus.add(lg.Torus(2.0, 0.8), lg.LevelLines(9, direction=(1, 0, 1)))
    return [
        (saddle, lg.ParallelProjector.from_angles(-35, 30)),
        (torus, lg.CentralProjector.from_angles(35, 30, 12), {"hidden_lines": True}),
    ]


if __name__ == "__main__":
    run_script_main(__file__, build)
