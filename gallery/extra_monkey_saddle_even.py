"""Extra figure: evenly spaced lines of curvature on the monkey saddle (spacing="even")."""

from __future__ import annotations

import lgraph as lg

CAPTION = (
    'The monkey saddle of the previous figure with LinesOfCurvature(14, 14, spacing="even"): '
    "lines are seeded to lie evenly spaced and cut where they come closer than half the "
    "spacing to another line of their family (evenly spaced streamlines), so they never "
    "bunch up near the flat umbilic but no longer run from edge to edge."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.MonkeySaddle(extent=1.0, c=0.6), lg.LinesOfCurvature(14, 14, spacing="even"))
    return scene, lg.ParallelProjector.from_angles(-35, 30)


if __name__ == "__main__":
    from lgraph.gallery import run_script_main

    run_script_main(__file__, build)
