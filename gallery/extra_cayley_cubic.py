"""Cayley's nodal cubic with its four nodes."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Cayley's nodal cubic x² + y² + z² − 2xyz = 1 in the ball of radius 2: plane sections "
    "z = const, the contour and the clip curve, and its four nodes (dots), at (1, 1, 1), "
    "(1, −1, −1), (−1, 1, −1) and (−1, −1, 1), found with certainty by subdivision with "
    "Bernstein bounds and Newton's method on grad F = 0. Hidden parts dashed. Parallel "
    "projection."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    scene.add(lg.CayleyCubic(radius=2.0), lg.LevelLines(11), lg.Singularities(size=4))
    projector = lg.ParallelProjector(direction=(1.0, 0.55, 0.5))
    return scene, projector, {"hidden_lines": True}


if __name__ == "__main__":
    run_script_main(__file__, build)
