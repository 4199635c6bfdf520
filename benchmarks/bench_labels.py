"""What labels cost: rendering and saving a figure with and without labels.

Run:  python benchmarks/bench_labels.py [--repeat 7]

Scene: an ellipsoid with 14 + 18 lines of curvature (central projection), and
the same scene with N labels ("$\\kappa_{k}$", TeX mathematics) and N points
spread over a sphere around it, half of them hidden.  Runs alternate in one
process; we report medians and the ratios labelled / plain.  The first
layout of each distinct text fills a cache (matplotlib's mathtext parse);
later figures with the same texts reuse it.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

import lgraph as lg


def scene(n_labels: int) -> lg.Scene:
    s = lg.Scene()
    s.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(14, 18))
    rng = np.random.default_rng(1)
    for k in range(n_labels):
        p = rng.normal(size=3)
        p *= 3.4 / np.linalg.norm(p)
        s.add(lg.Label(f"$\\kappa_{{{k}}}$", at=p, anchor="sw"))
        s.add(lg.Point(p))
    return s


def timed(func) -> float:
    t0 = time.perf_counter()
    func()
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    proj = lg.CentralProjector.from_angles(35, 25, 16)
    scenes = {n: scene(n) for n in (0, 20, 100)}
    with tempfile.TemporaryDirectory() as tmp:
        for n in scenes:  # warm up (imports, text cache)
            scenes[n].render(proj).save(Path(tmp) / "w.pdf")
        render = {n: [] for n in scenes}
        save = {(n, fmt): [] for n in scenes for fmt in ("pdf", "svg", "png")}
        for _ in range(args.repeat):
            for n, s in scenes.items():
                box = {}
                render[n].append(timed(lambda s=s, box=box: box.setdefault("d", s.render(proj))))
                for fmt in ("pdf", "svg", "png"):
                    path = Path(tmp) / f"a.{fmt}"
                    save[n, fmt].append(timed(lambda d=box["d"], p=path: d.save(p)))
    med = {k: statistics.median(v) for k, v in render.items()}
    print("render (s):", {n: round(t, 4) for n, t in med.items()},
          "ratios:", {n: round(med[n] / med[0], 3) for n in med})  # fmt: skip
    for fmt in ("pdf", "svg", "png"):
        m = {n: statistics.median(save[n, fmt]) for n in scenes}
        print(f"save {fmt} (s):", {n: round(t, 4) for n, t in m.items()},
              "ratios:", {n: round(m[n] / m[0], 3) for n in m})  # fmt: skip


if __name__ == "__main__":
    main()
