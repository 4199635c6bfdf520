"""Boy's surface: an immersion of the projective plane, with its self-intersection."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Boy's surface, lg.BoySurface(): Bryant and Kusner's parametrization, a minimal "
    "immersion of the projective plane after an inversion, over the chart u in [0, π] "
    "(poles at both ends) and v in [0, π] glued with a twist (x(u, 0) = x(π - u, π)). "
    "8 + 12 parameter lines run on across the seam, none ends there; the outline is the "
    "numeric contour. In red its self-intersection (lg.SelfIntersection()): three loops "
    "through one triple point on the axis of the surface's threefold symmetry (seen "
    "here from the side: the axis runs up from the pole at the bottom, where the 12 "
    "lines meet). Hidden parts dashed, the self-intersection's in red."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    hidden = {
        "default": lg.Style(width=0.3, dash=(2.0, 2.0), color=(0.5, 0.5, 0.5)),
        "self_intersection": lg.Style(width=0.5, dash=(2.0, 1.5), color=(0.8, 0.0, 0.0)),
    }
    red = {"self_intersection": lg.Style(color=(0.8, 0.0, 0.0), width=0.8)}
    scene = lg.Scene()
    scene.add(lg.BoySurface(), lg.ParameterLines(8, 12), lg.SelfIntersection(), style=red)
    view = lg.ParallelProjector(direction=(1.0, 0.3, 0.2))
    return scene, view, {"hidden_lines": True, "hidden_style": hidden}


if __name__ == "__main__":
    run_script_main(__file__, build)
