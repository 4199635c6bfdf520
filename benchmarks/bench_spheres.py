"""lgraph vs matplotlib's plot_wireframe: the same parameter lines to PDF.

Run:  python benchmarks/bench_spheres.py [--repeat 7]

Scenes (central projection, eye at azimuth 30, elevation 25):
  one:  unit sphere, 18 parallels + 36 meridians
  grid: 100 spheres of radius 0.4 on a 10 x 10 grid, same lines each

matplotlib draws the same lines (each parallel and meridian sampled at
1-degree steps, as `plot_wireframe` rows/columns) with NO hidden-line
removal; lgraph removes hidden lines exactly.  Runs alternate between the
two in one process; we report medians and the ratio lgraph / matplotlib.
"""

from __future__ import annotations

import argparse
import io
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def lgraph_figure(n: int, path: Path) -> int:
    import lgraph as lg

    scene = lg.Scene()
    r = 1.0 if n == 1 else 0.4
    side = int(round(np.sqrt(n)))
    for k in range(n):
        t = (
            None
            if n == 1
            else lg.translate(k % side - (side - 1) / 2, k // side - (side - 1) / 2, 0)
        )
        scene.add(lg.Sphere(r), lg.ParameterLines(18, 36), transform=t)
    dist = 6.0 if n == 1 else 16.0
    d = scene.render(lg.CentralProjector.from_angles(30, 25, dist))
    d.save(path)
    return d.n_points


def matplotlib_figure(n: int, path: Path) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lat = np.radians(np.linspace(-90, 90, 181))
    lon = np.radians(np.linspace(0, 360, 361))
    u1, u2 = np.meshgrid(lat, lon, indexing="ij")
    r = 1.0 if n == 1 else 0.4
    side = int(round(np.sqrt(n)))
    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=25, azim=30)
    ax.set_proj_type("persp")
    npts = 0
    for k in range(n):
        cx = 0 if n == 1 else k % side - (side - 1) / 2
        cy = 0 if n == 1 else k // side - (side - 1) / 2
        x = cx + r * np.cos(u1) * np.cos(u2)
        y = cy + r * np.cos(u1) * np.sin(u2)
        z = r * np.sin(u1)
        # 18 parallels (rows every 10 degrees, poles excluded) + 36 meridians
        ax.plot_wireframe(x, y, z, rstride=10, cstride=10, color="k", linewidth=0.5)
        npts += 18 * 361 + 36 * 181
    ax.set_axis_off()
    fig.savefig(path)
    plt.close(fig)
    return npts


def measure(repeat: int) -> dict:
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in (1, 100):
            times = {"lgraph": [], "matplotlib": []}
            points = {}
            # warm-up (imports, caches) once each, not timed
            points["lgraph"] = lgraph_figure(n, Path(tmp) / "w1.pdf")
            points["matplotlib"] = matplotlib_figure(n, Path(tmp) / "w2.pdf")
            for _ in range(repeat):
                for name, fn in (("lgraph", lgraph_figure), ("matplotlib", matplotlib_figure)):
                    t0 = time.perf_counter()
                    fn(n, Path(tmp) / f"{name}.pdf")
                    times[name].append(time.perf_counter() - t0)
            med = {k: statistics.median(v) for k, v in times.items()}
            out[n] = (med, points)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args(argv)
    res = measure(args.repeat)
    buf = io.StringIO()
    print("| scene | lgraph median (s) | matplotlib median (s) | ratio | lgraph points |", file=buf)
    print("|---|---|---|---|---|", file=buf)
    for n, (med, pts) in res.items():
        name = "1 unit sphere" if n == 1 else "100 spheres r=0.4"
        ratio = med["lgraph"] / med["matplotlib"]
        print(
            f"| {name} | {med['lgraph']:.4f} | {med['matplotlib']:.4f} | {ratio:.3f} | "
            f"{pts['lgraph']} |",
            file=buf,
        )
    sys.stdout.write(buf.getvalue())
    return 0


if __name__ == "__main__":
    sys.exit(main())
