"""A surface of revolution vs the ellipsoid of Figure 7.2, rendered in one process.

Run:  python benchmarks/bench_revolution.py [--repeat 9]

Scenes (the projector of Figure 7.2: central, azimuth 35, elevation 25, distance 16):
  ellipsoid:  Figure 7.2, x^2/3^2 + y^2/2^2 + z^2/1.3^2 = 1, 14 + 18 lines of curvature
              (closed forms, exact quadric ray test)
  egg:        SurfaceOfRevolution of the built-in egg profile, 12 parallels +
              24 meridians (its lines of curvature)
  pseudo:     the pseudosphere, 12 + 24 lines of curvature
  vase:       the built-in vase (open at both ends, not convex), 12 + 24
  egg hidden: the egg again with hidden lines drawn (render option hidden_lines=True)

The target of issue 16: the surface of revolution renders within twice the time of
the ellipsoid (ratio <= 2).  Runs alternate between the scenes; we report medians
of render() alone (wall clock, and CPU time of this process, which other work on
a shared machine disturbs less) and of render() + PDF save, and the ratios to
the ellipsoid.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def scenes() -> dict:
    import lgraph as lg

    out = {}
    s = lg.Scene()
    s.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(14, 18))
    out["ellipsoid (fig 7.2)"] = (s, {})
    s = lg.Scene()
    s.add(lg.SurfaceOfRevolution("egg", (0, np.pi)), lg.LinesOfCurvature(12, 24))
    out["egg 12+24"] = (s, {})
    s = lg.Scene()
    s.add(lg.Pseudosphere(1.0, 3.0), lg.LinesOfCurvature(12, 24))
    out["pseudosphere 12+24"] = (s, {})
    s = lg.Scene()
    s.add(lg.SurfaceOfRevolution("vase", (0, 3)), lg.LinesOfCurvature(12, 24))
    out["vase 12+24"] = (s, {})
    out["egg 12+24, hidden lines"] = (out["egg 12+24"][0], {"hidden_lines": True})
    return out


def main(argv: list[str] | None = None) -> int:
    import lgraph as lg

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=9)
    args = ap.parse_args(argv)
    projector = lg.CentralProjector.from_angles(35, 25, 16)
    table = scenes()
    render: dict[str, list[float]] = {k: [] for k in table}
    cpu: dict[str, list[float]] = {k: [] for k in table}
    total: dict[str, list[float]] = {k: [] for k in table}
    points: dict[str, int] = {}
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "fig.pdf"
        for scene, kw in table.values():  # untimed warm-up
            scene.render(projector, **kw).save(path)
        for _ in range(args.repeat):
            for name, (scene, kw) in table.items():
                c0, t0 = time.process_time(), time.perf_counter()
                d = scene.render(projector, **kw)
                t1, c1 = time.perf_counter(), time.process_time()
                cpu[name].append(c1 - c0)
                d.save(path)
                t2 = time.perf_counter()
                render[name].append(t1 - t0)
                total[name].append(t2 - t0)
                points[name] = d.n_points
    base = "ellipsoid (fig 7.2)"
    base_r, base_c = statistics.median(render[base]), statistics.median(cpu[base])
    base_t = statistics.median(total[base])
    print(
        "| scene | render median (s) | ratio | render CPU (s) | ratio | render + PDF (s) "
        "| ratio | points |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for name in table:
        r, t = statistics.median(render[name]), statistics.median(total[name])
        c = statistics.median(cpu[name])
        print(
            f"| {name} | {r:.4f} | {r / base_r:.2f} | {c:.4f} | {c / base_c:.2f} "
            f"| {t:.4f} | {t / base_t:.2f} | {points[name]} |"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
