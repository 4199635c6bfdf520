"""Numeric lines of curvature: the gallery's monkey saddle vs matplotlib.

Run:  python benchmarks/bench_numeric_families.py [--repeat 7]

lgraph: ``MonkeySaddle(extent=1, c=0.6)`` with ``LinesOfCurvature(14, 14)``
(integrated numerically from the principal direction field, complete lines,
exact hidden-line removal), parallel view from azimuth -35, elevation 30,
saved to PDF.  matplotlib: ``plot_surface`` of the same patch with 14 x 14
mesh lines (a 57 x 57 grid, ``rcount=ccount=14``), saved to PDF.  A fresh
scene every run (nothing cached).  Runs alternate between the two in one
process; we report medians and the ratio lgraph / matplotlib (issue target:
at most 10, aim 3).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def cold_caches() -> None:
    """Forget every cached family and surface result (not timed)."""
    import lgraph.families.cache
    import lgraph.surfaces._memo

    lgraph.families.cache.clear()
    lgraph.surfaces._memo.clear()


def lgraph_figure(path: Path) -> None:
    import lgraph as lg

    scene = lg.Scene()
    scene.add(lg.MonkeySaddle(extent=1.0, c=0.6), lg.LinesOfCurvature(14, 14))
    scene.render(lg.ParallelProjector.from_angles(-35, 30)).save(path)


def matplotlib_figure(path: Path) -> None:
    import matplotlib.pyplot as plt

    u = np.linspace(-1, 1, 57)
    x, y = np.meshgrid(u, u)
    z = 0.6 * (x**3 - 3 * x * y * y)
    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(x, y, z, rcount=14, ccount=14, color="white", edgecolor="black", lw=0.5)
    ax.view_init(elev=30, azim=-35)
    ax.set_axis_off()
    fig.savefig(path)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args(argv)
    import matplotlib

    matplotlib.use("Agg")
    with tempfile.TemporaryDirectory() as tmp:
        a, b = Path(tmp) / "lgraph.pdf", Path(tmp) / "mpl.pdf"
        lgraph_figure(a)  # imports and first-call costs
        matplotlib_figure(b)
        times: dict[str, list[float]] = {"lgraph": [], "matplotlib": []}
        runs = (("lgraph", lgraph_figure, a), ("matplotlib", matplotlib_figure, b))
        for _ in range(args.repeat):
            for name, fn, path in runs:
                cold_caches()
                t = time.perf_counter()
                fn(path)
                times[name].append(time.perf_counter() - t)
    lg_t, mpl_t = statistics.median(times["lgraph"]), statistics.median(times["matplotlib"])
    print(f"monkey saddle, LinesOfCurvature(14, 14), PDF: lgraph {lg_t * 1e3:.0f} ms, "
          f"matplotlib plot_surface {mpl_t * 1e3:.0f} ms, ratio {lg_t / mpl_t:.2f}")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
