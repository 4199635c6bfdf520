"""Our vectorized Illinois root finder vs scipy's ``elementwise.find_root`` (issue 12).

Run:  python benchmarks/bench_root_finding.py [--repeat 7] [--n 20000]

The problem is the one the ruled surfaces solve for every ray: a root of a
smooth function in each of many brackets, here ``f_k(x) = cos(x) - c_k x`` on
``[0, 2]`` (one root each, c_k in (0.5, 3)), solved to 1e-15 of the bracket.
``lgraph.surfaces.ruled._illinois`` calls ``f(x, sel)`` for the still-active
brackets; scipy's ``find_root`` (Chandrupatla's method, scipy >= 1.15) calls
``f(x, c)`` likewise.  Reported: medians of the wall time, the number of
calls of ``f``, and the largest error against a reference polished by Newton.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

import numpy as np


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--n", type=int, default=20000)
    args = parser.parse_args(argv)
    from lgraph.surfaces.ruled import _illinois

    try:
        from scipy.optimize.elementwise import find_root
    except ImportError:  # scipy < 1.15
        print("scipy.optimize.elementwise.find_root needs scipy >= 1.15; nothing to compare")
        return 0
    rng = np.random.default_rng(3)
    c = rng.uniform(0.5, 3.0, args.n)
    a, b = np.zeros(args.n), np.full(args.n, 2.0)
    # reference: bisection to the last bit, then Newton
    lo, hi = a.copy(), b.copy()
    for _ in range(200):
        m = 0.5 * (lo + hi)
        pos = np.cos(m) - c * m > 0
        lo, hi = np.where(pos, m, lo), np.where(pos, hi, m)
    ref = 0.5 * (lo + hi)
    for _ in range(3):
        ref -= (np.cos(ref) - c * ref) / (-np.sin(ref) - c)

    calls = {"lgraph": 0, "scipy": 0}

    def ours() -> np.ndarray:
        def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
            calls["lgraph"] += 1
            return np.cos(x) - c[sel] * x

        return _illinois(f, a, b, np.cos(a) - c * a, np.cos(b) - c * b, xtol=2e-15)

    def theirs() -> np.ndarray:
        def f(x: np.ndarray, cc: np.ndarray) -> np.ndarray:
            calls["scipy"] += 1
            return np.cos(x) - cc * x

        res = find_root(f, (a, b), args=(c,), tolerances={"xatol": 2e-15, "xrtol": 0.0})
        return res.x

    times: dict[str, list[float]] = {"lgraph": [], "scipy": []}
    errors: dict[str, float] = {}
    for _ in range(args.repeat):
        for name, fn in (("lgraph", ours), ("scipy", theirs)):
            calls[name] = 0
            t = time.perf_counter()
            x = fn()
            times[name].append(time.perf_counter() - t)
            errors[name] = float(np.abs(x - ref).max())
    print(f"{args.n} brackets, medians of {args.repeat} alternating runs")
    print("| solver | time (ms) | calls of f | largest error |")
    print("|---|---|---|---|")
    for name in ("lgraph", "scipy"):
        print(f"| {name} | {1e3 * statistics.median(times[name]):.1f} | {calls[name]} | "
              f"{errors[name]:.1e} |")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
