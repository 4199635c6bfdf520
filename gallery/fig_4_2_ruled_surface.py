"""Figure 4.2: a ruled surface with a twisting director."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 4.2. The ruled surface x(u1, u2) = y(u1) + u2 z(u1) with "
    "z(u1) = (cos u1 sin 4u1, sin u1 sin 4u1, cos 4u1) on [0, 2 pi] x [0, 3]. The paper's "
    "extracted text garbles the directrix as 'y(u1) = 4 cos u1'; we take the evident reading, "
    "the circle y(u1) = (4 cos u1, 4 sin u1, 0) of radius 4 in the xy-plane. "
    "Parameter lines: 48 rulings u1 = const and 5 lines u2 = const."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    circle = lg.Curve(
        lambda t: np.stack([4 * np.cos(t), 4 * np.sin(t), 0 * t], -1),
        0, 2 * np.pi, closed=True,
        derivative_func=lambda t: np.stack([-4 * np.sin(t), 4 * np.cos(t), 0 * t], -1),
    )  # fmt: skip

    def director(t: np.ndarray) -> np.ndarray:
        return np.stack([np.cos(t) * np.sin(4 * t), np.sin(t) * np.sin(4 * t), np.cos(4 * t)], -1)

    surface = lg.RuledSurface(circle, director, u2_range=(0, 3))
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(48, 5))
    return scene, lg.ParallelProjector.from_angles(-60, 30)


if __name__ == "__main__":
    run_script_main(__file__, build)
