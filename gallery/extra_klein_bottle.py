"""The figure-8 Klein bottle, glued with a twist, and its circle of self-intersection."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "The figure-8 Klein bottle, lg.KleinBottle(form='figure8'): a figure-8 cross-section "
    "((2 + cos(u/2) sin v - sin(u/2) sin 2v) cos u, (...) sin u, sin(u/2) sin v + "
    "cos(u/2) sin 2v) turned half over while it goes once round, so u in [0, 2π] is glued "
    "with a twist (x(0, v) = x(2π, -v)) and v is periodic. The lines v = c run on across "
    "the seam as v = -c; none ends there. In red its self-intersection "
    "(lg.SelfIntersection()): the circle of radius 2 in the plane z = 0. Hidden parts dashed. "
    "The classical bottle is lg.KleinBottle()."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    hidden = lg.Style(width=0.3, dash=(2.0, 2.0), color=(0.5, 0.5, 0.5))
    red = {"self_intersection": lg.Style(color=(0.8, 0.0, 0.0), width=0.8)}
    scene = lg.Scene()
    scene.add(lg.KleinBottle(form="figure8"), lg.ParameterLines(12, 8), lg.SelfIntersection(),
              style=red)  # fmt: skip
    view = lg.ParallelProjector(direction=(0.5, -0.8, 0.9))
    return scene, view, {"hidden_lines": True, "hidden_style": hidden}


if __name__ == "__main__":
    run_script_main(__file__, build)
