"""Extra figure: surfaces of revolution with their lines of curvature."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Surfaces of revolution x = (ρ(t) cos φ, ρ(t) sin φ, z(t)) and their lines of "
    "curvature, the meridians and the parallels, in closed form. Left: an egg, "
    "ρ = sin t (1 + 0.18 cos t), z = −1.4 cos t, 0 ≤ t ≤ π (poles found "
    "automatically). Middle: a vase, ρ = 1 + 0.42 sin(2.2 t − 0.9), z = t, 0 ≤ t ≤ 3. "
    "Right: Beltrami's pseudosphere, the tractrix ρ = sech t, z = t − tanh t turned "
    "about its asymptote (Gaussian curvature −1). 12 parallels and 24 meridians each; "
    "contours per parallel in closed form, hidden lines by one root problem per ray."
)


def build() -> list[tuple]:
    egg = lg.Scene()
    egg.add(lg.SurfaceOfRevolution(lg.named_profile("egg"), (0, 3.141592653589793)),
            lg.LinesOfCurvature(12, 24))  # fmt: skip
    vase = lg.Scene()
    vase.add(lg.SurfaceOfRevolution(lg.named_profile("vase"), (0, 3)), lg.LinesOfCurvature(12, 24))
    pseudo = lg.Scene()
    pseudo.add(lg.Pseudosphere(1.0, 3.0), lg.LinesOfCurvature(12, 24))
    view = lg.CentralProjector.from_angles(30, 22, 14, target=(0, 0, 0))
    return [
        (egg, view),
        (vase, lg.CentralProjector.from_angles(30, 22, 16, target=(0, 0, 1.5))),
        (pseudo, lg.CentralProjector.from_angles(30, 18, 16, target=(0, 0, 1.2))),
    ]


if __name__ == "__main__":
    run_script_main(__file__, build)
