"""Extra figure: a Möbius strip from a scene file with formulas (no Python)."""

from __future__ import annotations

from pathlib import Path

from lgraph.gallery import run_script_main
from lgraph.scenefile import load_scene_file

CAPTION = (
    "A Möbius strip written as formulas in a scene file, extra_moebius_formulas.toml: "
    "x = (R + v cos(u/2)) cos u, y = (R + v cos(u/2)) sin u, z = v sin(u/2), 0 ≤ u ≤ 2π, "
    "|v| ≤ w, with R = 1 and w = 0.5 declared as constants; 24 + 6 parameter lines, hidden "
    "parts dashed, and the core circle as a free curve in red. The formulas are parsed by "
    "lgraph's own expression language (never run as Python) and differentiated exactly. "
    "The same file renders with lgraph render, lgraph animate and vpype lgraph."
)

SCENE = Path(__file__).with_suffix(".toml")


def build() -> tuple:
    scene, projector, options = load_scene_file(SCENE)
    return scene, projector, options["render"]


if __name__ == "__main__":
    run_script_main(__file__, build)
