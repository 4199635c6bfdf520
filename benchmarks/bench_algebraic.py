"""Algebraic surfaces against the parametric torus (issue #29, speed).

Run:  python benchmarks/bench_algebraic.py [ROUNDS]

Renders, with hidden lines, the torus R = 2, r = 0.7 with 9 plane sections
(normal (1, 0, 0.3)) and its contour three ways -- the parametric
``lg.Torus``, the same quartic as ``lg.AlgebraicSurface`` (clip ball of
radius 3, which clips nothing) and as ``lg.ImplicitSurface`` with numeric
derivatives -- alternating ``ROUNDS`` times (default 3) in one process, new
surface objects each time (no cached curves), and prints the medians and
the ratios to the parametric torus; then the gallery figures of the
Clebsch cubic (with its 27 lines), the Cayley cubic and a Kummer surface.
"""

from __future__ import annotations

import runpy
import statistics
import sys
import time
from pathlib import Path

import lgraph as lg

R, r = 2.0, 0.7
TORUS = f"(x^2 + y^2 + z^2 + {R * R - r * r})^2 - {4 * R * R}*(x^2 + y^2)"


def torus_F(x, y, z):
    q = x * x + y * y + z * z + R * R - r * r
    return q * q - 4 * R * R * (x * x + y * y)


MAKERS = {
    "lg.Torus (parametric)": lambda: lg.Torus(R, r),
    "AlgebraicSurface": lambda: lg.AlgebraicSurface(TORUS, radius=3),
    "ImplicitSurface (numeric derivatives)": lambda: lg.ImplicitSurface(torus_F, radius=3),
}


def render(make) -> float:
    scene = lg.Scene()
    scene.add(make(), lg.LevelLines(9, direction=(1, 0, 0.3)))
    t = time.perf_counter()
    scene.render(lg.ParallelProjector(direction=(0.4, -1.0, 0.7)), hidden_lines=True)
    return time.perf_counter() - t


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    times: dict[str, list[float]] = {k: [] for k in MAKERS}
    for _ in range(rounds):
        for name, make in MAKERS.items():
            times[name].append(render(make))
    base = statistics.median(times["lg.Torus (parametric)"])
    print("| surface | median (s) | ratio to lg.Torus |\n|---|---|---|")
    for name, ts in times.items():
        m = statistics.median(ts)
        print(f"| {name} | {m:.3f} | {m / base:.2f} |")
    gallery = Path(__file__).resolve().parent.parent / "gallery"
    from lgraph.gallery import render_figure

    print("\n| gallery figure | render (s) |\n|---|---|")
    for stem in ("extra_clebsch_cubic", "extra_cayley_cubic", "extra_kummer_surface"):
        build = runpy.run_path(str(gallery / f"{stem}.py"))["build"]
        t = time.perf_counter()
        render_figure(build())
        print(f"| {stem} | {time.perf_counter() - t:.2f} |")


if __name__ == "__main__":
    main()
