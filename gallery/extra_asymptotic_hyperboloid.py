"""Asymptotic lines on a hyperboloid of one sheet: its two families of rulings."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Asymptotic lines (directions with normal curvature zero, II(du, du) = 0) on the "
    "hyperboloid of one sheet x² + y² - z²/1.2² = 1, |z| <= 2. On a doubly ruled "
    "surface they are exactly its two families of straight rulings, drawn from the "
    "closed form x = (cos θ - s sin θ, sin θ + s cos θ, ±1.2 s): 8 + 8 of them, "
    "crossing the waist circle, with the rims |z| = 2."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.HyperboloidOneSheet(1.0, 1.0, 1.2, height=2.0), lg.AsymptoticLines(8, 8))
    return scene, lg.CentralProjector.from_angles(-40, 20, 14)


if __name__ == "__main__":
    run_script_main(__file__, build)
