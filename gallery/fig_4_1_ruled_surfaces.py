"""Figure 4.1: a general cone, a tangent surface and a general cylinder."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Figure 4.1. Left: the general cone x = a + u2 (y(u1) - a) over the closed space curve "
    "y(t) = (2 cos t, 1.4 sin t, 3 + 0.5 sin 3t) with vertex a = 0, 0 <= u2 <= 1. "
    "Middle: the tangent surface x = y(u1) + u2 y'(u1)/|y'(u1)| of the helix "
    "y(t) = (cos t, sin t, 0.3 t), 0 <= t <= 4 pi, 0 <= u2 <= 2.5. "
    "Right: the general cylinder x = y(u1) + u2 (0, 0, 1) over the non-convex curve "
    "r = 2 + 0.6 cos 3t in the xy-plane, 0 <= u2 <= 2. Parameter lines and contours."
)
TAU = 2 * np.pi


def build() -> list[tuple[lg.Scene, lg.Projector]]:
    wavy = lg.Curve(
        lambda t: np.stack([2 * np.cos(t), 1.4 * np.sin(t), 3 + 0.5 * np.sin(3 * t)], -1),
        0, TAU, closed=True,
    )  # fmt: skip
    helix = lg.Curve(lambda t: np.stack([np.cos(t), np.sin(t), 0.3 * t], -1), 0, 4 * np.pi)
    r = lambda t: 2 + 0.6 * np.cos(3 * t)  # noqa: E731
    flower = lg.Curve(
        lambda t: np.stack([r(t) * np.cos(t), r(t) * np.sin(t), 0 * t], -1), 0, TAU, closed=True
    )
    cone, tangent, cylinder = lg.Scene(), lg.Scene(), lg.Scene()
    cone.add(lg.GeneralCone(wavy, apex=(0, 0, 0), scaled=True), lg.ParameterLines(24, 6))
    tangent.add(lg.TangentSurface(helix, u2_range=(0, 2.5)), lg.ParameterLines(40, 4))
    cylinder.add(lg.GeneralCylinder(flower, (0, 0, 1), u2_range=(0, 2)), lg.ParameterLines(36, 5))
    view = lg.ParallelProjector.from_angles(-50, 25)
    return [(cone, view), (tangent, view), (cylinder, view)]


if __name__ == "__main__":
    run_script_main(__file__, build)
