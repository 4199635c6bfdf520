"""Lines of curvature on the elliptic paraboloid (the case the paper omits)."""

from __future__ import annotations

import lgraph as lg
from lgraph.gallery import run_script_main

CAPTION = (
    "Lines of curvature on the elliptic paraboloid z = x²/1² + y²/1.6², z <= 2, which "
    "the paper leaves out. The confocal paraboloids x²/(p-λ) + y²/(q-λ) = 2z - λ "
    "(p = a²/2, q = b²/2) form a triply orthogonal system, so by Dupin's theorem the "
    "lines of curvature are the intersections with the other two families. The bold "
    "rings, drawn on the surface, mark the two umbilics (±sqrt(p(q-p)), 0, (q-p)/2), "
    "where the lines of curvature of both families crowd together."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    surface = lg.EllipticParaboloid(1.0, 1.6, height=2.0)
    families = [lg.LinesOfCurvature(10, 16), lg.Umbilics(radius=0.06)]
    scene.add(surface, *families, style={"umbilic": lg.Style(width=1.2), "default": lg.Style()})
    return scene, lg.CentralProjector.from_angles(-70, 55, 12)


if __name__ == "__main__":
    run_script_main(__file__, build)
