"""Extra figure: lines of curvature on a torus and on a Dupin cyclide (all circles)."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Lines of curvature on a ring torus (R = 3, r = 1: meridians and parallels) and on a "
    "ring Dupin cyclide (a = 2, b = 1.9, d = 1), whose lines of curvature are all circles."
)


def build() -> list[tuple[lg.Scene, lg.Projector]]:
    view = lg.ParallelProjector.from_angles(-60, 35)
    torus, cyclide = lg.Scene(), lg.Scene()
    torus.add(lg.Torus(3, 1), lg.LinesOfCurvature(36, 16))
    cyclide.add(lg.DupinCyclide(2.0, 1.9, 1.0), lg.LinesOfCurvature(36, 16))
    return [(torus, view), (cyclide, view)]


if __name__ == "__main__":
    run_script_main(__file__, build)
