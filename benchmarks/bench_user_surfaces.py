"""User-written surfaces with hidden lines vs matplotlib's plot_surface (issue #25, part 6).

Run:  python benchmarks/bench_user_surfaces.py [--repeat 5] [--scene enneper dini boy]

Each scene is a ``lg.ParametricSurface`` written as a new user would: a numpy
``point(u, v)`` function only, no derivatives.  lgraph draws 12 + 12
parameter lines and the contour with exact hidden-line removal, central view
(azimuth 30, elevation 25), saved to PDF; a fresh surface object every run
(caches emptied before every run).  matplotlib draws ``plot_surface`` of the same
surface on a 50 x 50 grid, saved to PDF.  Runs alternate between the two in
one process; we report medians and the ratio lgraph / matplotlib (issue
target: at most 3).

Scenes:
  enneper  u, v in [-2, 2]: (u - u^3/3 + u v^2, v - v^3/3 + v u^2, u^2 - v^2)
  dini     u in [0, 4 pi], v in [0.1, 1.4]: (a cos u sin v, a sin u sin v,
           a (cos v + log tan(v/2)) + b u), a = 1, b = 0.2
  boy      Apery's Boy surface, u, v in [0, pi]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from bench_numeric_families import cold_caches  # noqa: E402
from user_surfaces import boy, dini, enneper  # noqa: E402  (the tests' user-written surfaces)

#: name -> (point, u range, v range, eye distance)
SCENES = {
    "enneper": (enneper, (-2.0, 2.0), (-2.0, 2.0), 20.0),
    "dini": (dini, (0.0, 4 * np.pi), (0.1, 1.4), 15.0),
    "boy": (boy, (0.0, np.pi), (0.0, np.pi), 8.0),
}


def lgraph_figure(name: str, path: Path) -> int:
    import lgraph as lg

    func, r1, r2, dist = SCENES[name]
    scene = lg.Scene()
    scene.add(lg.ParametricSurface(func, r1, r2), lg.ParameterLines(12, 12))
    d = scene.render(lg.CentralProjector.from_angles(30, 25, dist), hidden_lines=True)
    d.save(path)
    return d.n_points


def matplotlib_figure(name: str, path: Path) -> None:
    import matplotlib.pyplot as plt

    func, r1, r2, _ = SCENES[name]
    u, v = np.meshgrid(np.linspace(*r1, 50), np.linspace(*r2, 50), indexing="ij")
    p = func(u, v)
    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(p[..., 0], p[..., 1], p[..., 2], color="white", edgecolor="black", lw=0.5)
    ax.view_init(elev=25, azim=30)
    ax.set_proj_type("persp")
    ax.set_axis_off()
    fig.savefig(path)
    plt.close(fig)


def measure(names: list[str], repeat: int) -> dict[str, tuple[float, float, int]]:
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        a, b = Path(tmp) / "lgraph.pdf", Path(tmp) / "mpl.pdf"
        for name in names:
            npts = lgraph_figure(name, a)  # imports and first-call costs, not timed
            matplotlib_figure(name, b)
            times: dict[str, list[float]] = {"lgraph": [], "matplotlib": []}
            for _ in range(repeat):
                for key, fn, path in (
                    ("lgraph", lgraph_figure, a),
                    ("matplotlib", matplotlib_figure, b),
                ):
                    cold_caches()
                    t = time.perf_counter()
                    fn(name, path)
                    times[key].append(time.perf_counter() - t)
            out[name] = (
                statistics.median(times["lgraph"]),
                statistics.median(times["matplotlib"]),
                npts,
            )
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--scene", nargs="*", default=list(SCENES), choices=list(SCENES))
    args = parser.parse_args(argv)
    import matplotlib

    matplotlib.use("Agg")
    res = measure(args.scene, args.repeat)
    print("| scene | lgraph median (s) | matplotlib median (s) | ratio | lgraph points |")
    print("|---|---|---|---|---|")
    for name, (lg_t, mpl_t, npts) in res.items():
        print(f"| {name} | {lg_t:.3f} | {mpl_t:.3f} | {lg_t / mpl_t:.2f} | {npts} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
