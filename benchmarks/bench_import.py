"""Startup: how long ``import lgraph`` takes, next to ``import numpy, attrs``.

Run:  python benchmarks/bench_import.py [--repeat 15]

Each import runs in a fresh interpreter (``python -c``), the two commands
alternating, one untimed warm-up each; the table gives the medians of the
wall time measured inside the child (``time.perf_counter`` around the
import), the ratio, and which heavy libraries ``import lgraph`` loaded (none
should: scipy, reportlab and pillow are imported when first needed).
The target: ``import lgraph`` within 0.3 s.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CHILD = """
import sys, time
sys.path.insert(0, {root!r})
t = time.perf_counter()
import {what}
dt = time.perf_counter() - t
heavy = sorted({{m.split(".")[0] for m in sys.modules}} & {{"scipy", "reportlab", "PIL"}})
print(dt, ",".join(heavy) or "-")
"""


def once(what: str) -> tuple[float, str]:
    out = subprocess.run(
        [sys.executable, "-c", CHILD.format(root=str(ROOT), what=what)],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.split()
    return float(out[0]), out[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15)
    args = ap.parse_args()
    cases = {"lgraph": "lgraph", "numpy + attrs": "numpy, attrs"}
    times: dict[str, list[float]] = {k: [] for k in cases}
    heavy = ""
    for what in cases.values():
        once(what)  # warm-up (file system caches)
    for _ in range(args.repeat):
        for name, what in cases.items():
            dt, h = once(what)
            times[name].append(dt)
            if name == "lgraph":
                heavy = h
    med = {k: statistics.median(v) for k, v in times.items()}
    print("| import | median (s) | min (s) |")
    print("|---|---|---|")
    for k, v in times.items():
        print(f"| {k} | {med[k]:.3f} | {min(v):.3f} |")
    ratio = med["lgraph"] / med["numpy + attrs"]
    print(f"\nratio lgraph / (numpy + attrs): {ratio:.2f}; heavy modules loaded: {heavy}")
    print(f"target import lgraph <= 0.3 s: {'met' if med['lgraph'] <= 0.3 else 'NOT met'}")


if __name__ == "__main__":
    main()
