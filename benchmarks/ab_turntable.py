"""A/B comparison of the turntable target between two source trees.

Run:  python benchmarks/ab_turntable.py TREE [PAIRS] [FIGURE]

Imports lgraph from ``TREE`` (a checkout or ``git worktree`` of any commit),
then alternates, ``PAIRS`` times (default 12), one cold frame (the figure's
own view rendered with the geometry cache empty and saved as a 480 px PNG)
and one 24-frame turntable GIF (``lg.orbit(elevation=30, frames=24)``, in
this process), as ``bench_animation.py`` does.  Prints the best and median
times and the ratios.  Run it for two trees in turn, several rounds, on
this shared machine: the best times are the least disturbed.
"""

from __future__ import annotations

import importlib
import statistics
import sys
import tempfile
import time
from pathlib import Path


def main() -> None:
    tree = str(Path(sys.argv[1]).resolve())
    pairs = int(sys.argv[2]) if len(sys.argv) > 2 else 12
    stem = sys.argv[3] if len(sys.argv) > 3 else "fig_7_2_ellipsoid"
    sys.path[:0] = [tree, tree + "/gallery"]
    import lgraph as lg
    from lgraph.families import cache

    if not lg.__file__.startswith(tree):
        sys.exit(f"lgraph comes from {lg.__file__}, not from {tree}")
    scene, projector = importlib.import_module(stem).build()
    views = lg.orbit(elevation=30, frames=24)
    tmp = Path(tempfile.mkdtemp())
    lg.animate(scene, views, tmp / "warm.gif", progress=False, workers=1)

    def cold() -> None:
        scene.render(projector).save(tmp / "one.png", size=480)

    def turntable() -> None:
        lg.animate(scene, views, tmp / "turn.gif", progress=False, workers=1)

    def run(f) -> float:
        cache.clear()
        t0 = time.perf_counter()
        f()
        return time.perf_counter() - t0

    c, t = [], []
    for _ in range(pairs):
        c.append(run(cold))
        t.append(run(turntable))
    med = statistics.median
    print(
        f"{stem}: turntable best {min(t) * 1e3:.1f} median {med(t) * 1e3:.1f} ms | cold frame "
        f"best {min(c) * 1e3:.1f} median {med(c) * 1e3:.1f} ms | ratio of medians "
        f"{med(t) / med(c):.2f}, of bests {min(t) / min(c):.2f}"
    )


if __name__ == "__main__":
    main()
