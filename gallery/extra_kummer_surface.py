"""A Kummer quartic with its 16 nodes."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "A Kummer surface (x² + y² + z² − μ²)² = λ pqrs with μ = 1.3, λ = (3μ² − 1)/(3 − μ²) "
    "and the tetrahedron of planes p, q = 1 − z ∓ √2 x, r, s = 1 + z ± √2 y: a quartic with "
    "16 real nodes (dots; hidden ones grey). Plane sections z = const, the contour and the "
    "clip curve on the sphere of radius 2.6; hidden parts dashed. Parallel projection."
)


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    surface = lg.KummerSurface(1.3, radius=2.6)
    scene.add(surface, lg.LevelLines(13), lg.Singularities(size=4))
    projector = lg.ParallelProjector(direction=(1.0, 0.45, 0.35))
    return scene, projector, {"hidden_lines": True}


if __name__ == "__main__":
    run_script_main(__file__, build)
