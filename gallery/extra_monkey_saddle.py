"""Extra figure: numeric lines of curvature on the monkey saddle (umbilic at the origin)."""

from __future__ import annotations

import lgraph as lg

CAPTION = (
    "Lines of curvature on the monkey saddle z = 0.6 (x^3 - 3xy^2), |x|, |y| <= 1, integrated "
    "numerically from the principal direction field: 14 complete lines of each family, each "
    "running from edge to edge of the patch or into the flat umbilic at the origin, chosen to "
    "cover the patch as evenly as the lines allow."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.MonkeySaddle(extent=1.0, c=0.6), lg.LinesOfCurvature(14, 14))
    return scene, lg.ParallelProjector.from_angles(-35, 30)


if __name__ == "__main__":
    from lgraph.gallery import run_script_main

    run_script_main(__file__, build)
