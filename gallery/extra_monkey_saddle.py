"""Extra figure: numeric lines of curvature on the monkey saddle (umbilic at the origin)."""

from __future__ import annotations

from pathlib import Path

import lgraph as lg

CAPTION = (
    "Lines of curvature on the monkey saddle z = x^3 - 3xy^2, |x|, |y| <= 1, integrated "
    "numerically from the principal direction field; they stop at the flat umbilic at the origin."
)


def build() -> tuple[lg.Scene, lg.Projector]:
    scene = lg.Scene()
    scene.add(lg.MonkeySaddle(extent=1.0, c=0.6), lg.LinesOfCurvature(14, 14))
    return scene, lg.ParallelProjector.from_angles(-35, 30)


if __name__ == "__main__":
    scene, proj = build()
    drawing = scene.render(proj)
    for suffix in (".pdf", ".png"):
        drawing.save(Path(__file__).stem + suffix)
