"""Surfaces written as formulas (lgraph.formula) vs the same expressions in numpy.

Run:  python benchmarks/bench_formula.py [--repeat 15]

Surfaces (x, y, z of u, v, as a scene file writes them):
  moebius:  (1 + v/2*cos(u/2))*cos(u), (1 + v/2*cos(u/2))*sin(u), v/2*sin(u/2)
  dini:     cos(u)*sin(v), sin(u)*sin(v), cos(v) + log(tan(v/2)) + b*u  (b = 0.2)
  enneper:  u - u^3/3 + u*v^2, v - v^3/3 + v*u^2, u^2 - v^2

Each on a 1000 x 1000 grid (full arrays, as np.meshgrid gives them) and on
10^4 points (100 x 100).  ``compile_formulas`` (one shared program for x, y, z)
against a hand transcription into numpy of the same three expressions (each
written out, as one would by hand).  Runs alternate (which goes first
alternates too) in one process after an untimed warm-up; we report medians of
the wall time and the median of the per-run ratios formula / numpy.  The
target: ratio <= 1.5.  For information, the cost of the values with their
first and second derivatives (``derivatives=2``, 18 arrays) relative to the
values alone.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable

import numpy as np

B = 0.2
SURFACES: dict[str, tuple[tuple[str, str, str], Callable, tuple[float, float, float, float]]] = {
    "moebius": (
        ("(1 + v/2*cos(u/2))*cos(u)", "(1 + v/2*cos(u/2))*sin(u)", "v/2*sin(u/2)"),
        lambda u, v: [
            (1 + v / 2 * np.cos(u / 2)) * np.cos(u),
            (1 + v / 2 * np.cos(u / 2)) * np.sin(u),
            v / 2 * np.sin(u / 2),
        ],
        (0.0, 2 * np.pi, -1.0, 1.0),
    ),
    "dini": (
        ("cos(u)*sin(v)", "sin(u)*sin(v)", "cos(v) + log(tan(v/2)) + b*u"),
        lambda u, v: [
            np.cos(u) * np.sin(v),
            np.sin(u) * np.sin(v),
            np.cos(v) + np.log(np.tan(v / 2)) + B * u,
        ],
        (0.0, 4 * np.pi, 0.01, 2.0),
    ),
    "enneper": (
        ("u - u^3/3 + u*v^2", "v - v^3/3 + v*u^2", "u^2 - v^2"),
        lambda u, v: [u - u**3 / 3 + u * v**2, v - v**3 / 3 + v * u**2, u**2 - v**2],
        (-2.0, 2.0, -2.0, 2.0),
    ),
}


def main(argv: list[str] | None = None) -> int:
    from lgraph.formula import compile_formulas, formula

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15)
    args = ap.parse_args(argv)
    cases = {}
    for name, (texts, by_hand, (u0, u1, v0, v1)) in SURFACES.items():
        parsed = [formula(t, ("u", "v"), {"b": B}) for t in texts]
        compiled, second = compile_formulas(parsed), compile_formulas(parsed, derivatives=2)
        for n in (1000, 100):
            u, v = np.meshgrid(np.linspace(u0, u1, n), np.linspace(v0, v1, n), indexing="ij")
            for a, b in zip(compiled(u, v), by_hand(u, v)):  # the same numbers
                np.testing.assert_allclose(a, b, rtol=1e-14, atol=1e-15)
            cases[f"{name} {n}x{n}"] = (compiled, by_hand, second, u, v)
    times: dict[str, dict[str, list[float]]] = {k: {"f": [], "np": [], "d2": []} for k in cases}
    ratios: dict[str, list[float]] = {k: [] for k in cases}
    for compiled, by_hand, second, u, v in cases.values():  # warm-up
        compiled(u, v), by_hand(u, v), second(u, v)
    for r in range(args.repeat):
        for key, (compiled, by_hand, second, u, v) in cases.items():
            reps = 1 if u.size > 10**5 else 20  # small grids: 20 calls per timing
            order = [("f", compiled), ("np", by_hand)]
            for tag, fn in order if r % 2 == 0 else order[::-1]:
                t0 = time.perf_counter()
                for _ in range(reps):
                    fn(u, v)
                times[key][tag].append((time.perf_counter() - t0) / reps)
            t0 = time.perf_counter()
            for _ in range(reps):
                second(u, v)
            times[key]["d2"].append((time.perf_counter() - t0) / reps)
            ratios[key].append(times[key]["f"][-1] / times[key]["np"][-1])
    print(f"medians of {args.repeat} alternating runs")
    print("| surface, grid | formulas (ms) | numpy by hand (ms) | ratio | numpy calls "
          "| values + 2 derivatives (ms) | / values |")  # fmt: skip
    print("|---|---|---|---|---|---|---|")
    worst = 0.0
    for key, (compiled, _, second, _, _) in cases.items():
        f, h, d2 = (statistics.median(times[key][t]) for t in ("f", "np", "d2"))
        ratio = statistics.median(ratios[key])
        worst = max(worst, ratio)
        print(
            f"| {key} | {1e3 * f:.3f} | {1e3 * h:.3f} | {ratio:.2f} | "
            f"{compiled.program_length} / {second.program_length} | {1e3 * d2:.3f} "
            f"| {d2 / f:.1f} |"
        )
    verdict = "met" if worst <= 1.5 else "NOT met"
    print(f"result: worst median ratio formulas / numpy {worst:.2f} (target <= 1.5): {verdict}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
