"""Hidden lines on surfaces other than quadrics: time per figure.

Run:  python benchmarks/bench_hidden_surfaces.py [--repeat 3]

Figures (parallel view, azimuth 30, elevation 35, hidden lines drawn, 12 + 12
parameter lines):

  enneper   the built-in Enneper surface (extent 2, self-intersecting)
  dini      Dini's surface written by a user as a ParametricSurface
  torus     the built-in torus (R = 2, r = 0.6)

Each figure is rendered once untimed (imports, caches), then ``--repeat``
times; the median is printed.  To compare two trees, run the script under
each in turn, alternating (``PYTHONPATH=<tree> python ...``): the machines
are shared and noisy, only ratios of alternating runs mean anything.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

import numpy as np


def figures():
    import lgraph as lg

    def dini_point(u, v):
        a, b = 1.0, 0.2
        return np.stack(
            np.broadcast_arrays(
                a * np.cos(u) * np.sin(v),
                a * np.sin(u) * np.sin(v),
                a * (np.cos(v) + np.log(np.tan(v / 2))) + b * u,
            ),
            -1,
        )

    return {
        "enneper": lg.Enneper(extent=2),
        "dini": lg.ParametricSurface(dini_point, (0, 4 * np.pi), (0.1, 1.4)),
        "torus": lg.Torus(2, 0.6),
    }


def main(argv: list[str] | None = None) -> int:
    import lgraph as lg

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    view = lg.ParallelProjector.from_angles(30, 35)
    for name, surface in figures().items():
        scene = lg.Scene()
        scene.add(surface, lg.ParameterLines(12, 12))
        with np.errstate(all="ignore"):
            scene.render(view, hidden_lines=True)
            times = []
            for _ in range(args.repeat):
                t0 = time.perf_counter()
                scene.render(view, hidden_lines=True)
                times.append(time.perf_counter() - t0)
        print(f"{name:8s} {statistics.median(times):.3f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
