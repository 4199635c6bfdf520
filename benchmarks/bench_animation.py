"""Turntables and many frames: cached geometry, local workers, bounded memory.

Run:  python benchmarks/bench_animation.py [--only turntable,workers,memory]

* turntable: a 24-frame turntable (``lg.orbit(elevation=30, frames=24)``, an
  animated GIF 480 px wide) of the gallery's monkey saddle figure
  (``gallery/extra_monkey_saddle.py``, numeric lines of curvature) and of
  Figure 7.2 (``gallery/fig_7_2_ellipsoid.py``), rendered in this process
  (``workers=1``), against one cold frame (what a user does for one picture
  of the same size: the figure's own view rendered and saved as a 480 px
  PNG, geometry cache empty, imports warmed up), in the same process.
  Target: at most 5 cold frames.  Every turntable run (each variant
  ``--repeat`` times, default 9) follows a cold frame; ratios are medians of
  the runs over the median of all cold frames, in wall-clock time and, for
  the runs in this process, in CPU time (``time.process_time``: less
  disturbed by other processes on a loaded machine).  The turntable renders
  its views in batches of ``lgraph.animation.frames.BATCH_FRAMES`` and samples its
  raster frames to a quarter pixel (``tolerance="pixel"``, animate's default
  for raster frames).  Also the turntable with the cache turned off (4 of
  the frames, times 6, once) and with the default executor
  (``executor=None, workers=None``: a local process pool only when the run
  is long enough, see ``lgraph.animation.frames.POOL_MIN_SECONDS``) and with a pool
  forced (``workers=2``), and serially with ``render_options={"tolerance":
  1e-4}`` (the cold frame's own sampling: chords within 1e-4 of the
  figure's diagonal).
* workers: 72 frames of Figure 7.2 as a GIF, 2 local worker processes vs
  this process; the speed-up.
* memory: peak resident memory of a child process writing a 360-frame GIF
  of Figure 7.2 against one writing 36 frames (frames are streamed to the
  writer, so the peak must not grow with the frame count).
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "gallery"))

import lgraph as lg  # noqa: E402
from lgraph.families import cache as family_cache  # noqa: E402


def _build(stem: str):
    module = __import__(stem)
    return module.build()


def _timed(f) -> float:
    t0 = time.perf_counter()
    f()
    return time.perf_counter() - t0


def _warm_up(tmp: Path) -> None:
    """Import everything a render and a GIF need (not part of any timing)."""
    scene = lg.Scene()
    scene.add(lg.Torus(2, 0.5), lg.LinesOfCurvature(3, 3))
    lg.animate(scene, lg.orbit(frames=2), tmp / "warm.gif", progress=False, workers=1)


def turntable(stem: str, tmp: Path, repeat: int = 3) -> dict:
    scene, projector = _build(stem)
    views = lg.orbit(elevation=30, frames=24)

    def one_frame() -> None:  # what a user does for one picture of the same size
        d = scene.render(projector)
        d.save(tmp / "one.png", size=480)

    def cold_run(f) -> float:
        family_cache.clear()
        return _timed(f)

    fine = {"tolerance": 1e-4}
    variants = {
        "serial": lambda: lg.animate(scene, views, tmp / "a.gif", progress=False, workers=1),
        "fine": lambda: lg.animate(
            scene, views, tmp / "e.gif", progress=False, workers=1, render_options=fine
        ),
        "default": lambda: lg.animate(scene, views, tmp / "c.gif", progress=False),
        "pool": lambda: lg.animate(scene, views, tmp / "d.gif", progress=False, workers=2),
    }
    runs: dict[str, list[float]] = {k: [] for k in ("cold", *variants)}
    cpu: dict[str, list[float]] = {k: [] for k in ("cold", *variants)}
    for _ in range(repeat):
        for name, f in variants.items():  # a cold frame before every run
            for key, g in (("cold", one_frame), (name, f)):
                c0 = time.process_time()
                runs[key].append(cold_run(g))
                cpu[key].append(time.process_time() - c0)
    family_cache.set_max_entries(0)  # 4 of the 24 frames, times 6: as before the cache
    four = views[::6]
    uncached = 6 * _timed(lambda: lg.animate(scene, four, tmp / "b.gif", progress=False, workers=1))
    family_cache.set_max_entries(family_cache.MAX_ENTRIES)
    family_cache.clear()
    cold = statistics.median(runs["cold"])
    serial = statistics.median(runs["serial"])

    def ratio(name: str, times: dict[str, list[float]] = runs) -> float:
        return statistics.median(times[name]) / statistics.median(times["cold"])

    return {
        "figure": stem,
        "cold frame s": cold,
        "cold frames s": "/".join(f"{c:.3f}" for c in sorted(runs["cold"])),
        "24 frames s": serial,
        "per later frame s": (serial - cold) / 23,
        "ratio": ratio("serial"),
        "CPU time ratio": ratio("serial", cpu),
        "tolerance 1e-4 ratio": ratio("fine"),
        "tolerance 1e-4 CPU time ratio": ratio("fine", cpu),
        "uncached ratio": uncached / cold,
        "default executor ratio": ratio("default"),
        "2-process pool ratio": ratio("pool"),
    }


def workers(tmp: Path) -> dict:
    scene, _ = _build("fig_7_2_ellipsoid")
    views = lg.orbit(elevation=25, frames=72, distance=16)
    lg.animate(scene, views[:4], tmp / "w.gif", progress=False, workers=1)  # warm-up
    one = _timed(lambda: lg.animate(scene, views, tmp / "s.gif", progress=False, workers=1))
    two = _timed(lambda: lg.animate(scene, views, tmp / "p.gif", progress=False, workers=2))
    return {"serial s": one, "2 workers s": two, "speed-up": one / two}


_CHILD = """
import resource, sys, time
sys.path.insert(0, {gallery!r})
import lgraph as lg
import fig_7_2_ellipsoid as f
scene, _ = f.build()
views = lg.orbit(elevation=25, frames={n}, distance=16)
t0 = time.perf_counter()
lg.animate(scene, views, {out!r}, progress=False, workers=1)
print(time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
"""


def memory(tmp: Path) -> dict:
    out = {}
    for n in (36, 360):
        code = _CHILD.format(gallery=str(ROOT / "gallery"), n=n, out=str(tmp / f"m{n}.gif"))
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True)  # fmt: skip
        took, rss = r.stdout.split()
        out[f"{n} frames: peak RSS MB"] = int(rss) / 1024
        out[f"{n} frames: s"] = float(took)
        out[f"{n} frames: GIF MB"] = (tmp / f"m{n}.gif").stat().st_size / 2**20
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--only", default="turntable,workers,memory")
    p.add_argument("--repeat", type=int, default=9, help="turntable runs (medians)")
    args = p.parse_args()
    only = set(args.only.split(","))
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        _warm_up(tmp)
        if "turntable" in only:
            for stem in ("extra_monkey_saddle", "fig_7_2_ellipsoid"):
                row = turntable(stem, tmp, args.repeat)
                print({k: round(v, 3) if isinstance(v, float) else v for k, v in row.items()},
                      flush=True)  # fmt: skip
        if "workers" in only:
            print({k: round(v, 3) for k, v in workers(tmp).items()}, flush=True)
        if "memory" in only:
            print({k: round(v, 2) for k, v in memory(tmp).items()}, flush=True)


if __name__ == "__main__":
    main()
