"""Lines of curvature on the elliptic paraboloid (the case the paper omits)."""

from __future__ import annotations

import numpy as np

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


class UmbilicRings(lg.Family):
    """Small closed curves on the surface around its umbilics (radius ~ r in space)."""

    def __init__(self, r: float) -> None:
        self.r = r

    def batches(self, surface: lg.Surface, projector: lg.Projector) -> list[lg.CurveBatch]:
        uv0 = surface.uv_of(surface.umbilics())
        g11, _, g22 = surface.first_fundamental_form(uv0[:, 0], uv0[:, 1])
        radii = self.r / np.sqrt(np.column_stack([g11, g22]))
        n = len(uv0)

        def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            ring = np.column_stack([np.cos(t), np.sin(t)])
            return uv0[idx] + radii[idx] * ring

        return [lg.CurveBatch.from_uv(surface, "umbilic", np.zeros(n), np.full(n, 2 * np.pi),
                                      uv, closed=True)]  # fmt: skip


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    surface = lg.EllipticParaboloid(1.0, 1.6, height=2.0)
    families = [lg.LinesOfCurvature(10, 16), lg.ParameterLines(2, 0), UmbilicRings(0.06)]
    scene.add(surface, *families, style={"umbilic": lg.Style(width=1.2), "default": lg.Style()})
    return scene, lg.CentralProjector.from_angles(-70, 55, 12)


if __name__ == "__main__":
    run_script_main(__file__, build)
