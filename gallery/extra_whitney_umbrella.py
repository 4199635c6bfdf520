"""Extra figure: the Whitney umbrella and its line of self-intersection."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "The Whitney umbrella x = (u1 u2, u1, u2²), |u1|, |u2| ≤ 1, that is x² = y² z: it "
    "passes through itself along the segment x = y = 0, 0 < z ≤ 1 (bold), whose points "
    "have the two parameter pairs (0, ±u2); the segment ends at the pinch point, the "
    "origin. The self-intersection is found numerically and hides like any other "
    "surface: the sheet in front hides the one behind. Parameter lines 14 + 14."
)


def umbrella() -> lg.ParametricSurface:
    return lg.ParametricSurface(
        lambda u, v: np.stack(np.broadcast_arrays(u * v, u, v * v), -1),
        (-1.0, 1.0),
        (-1.0, 1.0),
        derivatives_func=lambda u, v: (
            np.stack(np.broadcast_arrays(v, 1 + 0 * u, 0 * v), -1),
            np.stack(np.broadcast_arrays(u, 0 * u, 2 * v), -1),
        ),
    )


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(
        umbrella(),
        lg.ParameterLines(14, 14),
        lg.SelfIntersection(),
        style={"self_intersection": lg.Style(width=2.2)},
    )
    return scene, lg.ParallelProjector.from_angles(-62, 22)


if __name__ == "__main__":
    run_script_main(__file__, build)
