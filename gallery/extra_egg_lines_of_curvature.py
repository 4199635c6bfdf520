"""Extra figure: lines of curvature of an egg written by the user as a plain parametric surface."""

from __future__ import annotations

import numpy as np

import lgraph as lg

CAPTION = (
    "An egg x = (r(u) cos v, r(u) sin v, -1.4 cos u), r(u) = sin u (1 + 0.25 cos u), given only "
    "by its point function and domain (poles at both ends of u), with LinesOfCurvature(8, 12). "
    "On a surface of revolution the lines of curvature are the parallels and the meridians "
    "(g12 = L12 = 0, the paper's Proposition 4.1): every meridian runs from pole to pole and "
    "every parallel closes, hidden parts dashed."
)


def egg(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    r = np.sin(u) * (1 + 0.25 * np.cos(u))
    return np.stack(np.broadcast_arrays(r * np.cos(v), r * np.sin(v), -1.4 * np.cos(u)), -1)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    surface = lg.ParametricSurface(egg, (0, np.pi), (0, 2 * np.pi), periodic=(False, True),
                                   poles=True)  # fmt: skip
    scene = lg.Scene()
    scene.add(surface, lg.LinesOfCurvature(8, 12))
    return scene, lg.CentralProjector(eye=(6, -7, 3.5), target=(0, 0, 0)), {"hidden_lines": True}


if __name__ == "__main__":
    from lgraph.gallery import run_script_main

    run_script_main(__file__, build)
