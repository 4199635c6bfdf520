"""Raster frames of a turntable: the drawing to pixels and the GIF frame, old vs new.

Run:  python benchmarks/bench_raster_frames.py [--repeat 9] [--threads]

The 24 drawings of ``lg.orbit(elevation=30, frames=24)`` (what
``lg.animate(..., "a.gif")`` hands to the raster backend: the frames' common
window, 480 px wide) of Figure 7.2 (``gallery/fig_7_2_ellipsoid.py``) and of
the monkey saddle (``gallery/extra_monkey_saddle.py``) are rendered once; then,
in this process, alternating, ``--repeat`` times:

* new: ``render_image(d, size=..., gray=True)`` and the GIF writer
  (``GifWriter.add``: only the box that changed since the last frame);
* old: the straightforward way (``tests/raster_reference.py``: the whole
  supersampled canvas, each run handed to pillow as Python floats, the whole
  canvas reduced; the whole frame inverted through a copy and GIF-encoded);
* the cold frame's raster part, ``write_png(d, size=480)`` of the figure's own
  view (an RGB image), old (reference image, saved the same way) and new.

Reported: medians per frame in ms, the ratio new / old of the medians (wall
clock and CPU time) and of the minima (the least disturbed runs on a loaded
machine), and that the GIF frames decode to the reference pixels.  With
``--threads``: which of pillow's calls let another Python thread run (see
:func:`gil`).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "gallery"))
sys.path.insert(0, str(ROOT / "tests"))

import raster_reference as ref  # noqa: E402
from PIL import Image  # noqa: E402

import lgraph as lg  # noqa: E402
import lgraph.output.backends.png as png  # noqa: E402
from lgraph.animation.writers import GifWriter  # noqa: E402

STEMS = ("fig_7_2_ellipsoid", "extra_monkey_saddle")


def frame_drawings(stem: str, tmp: Path) -> tuple[list, object]:
    """The 24 turntable drawings as ``lg.animate`` renders them, and the
    figure's own drawing (the cold frame)."""
    module = __import__(stem)
    scene, projector = module.build()
    seen = []
    real = png.render_image

    def spy(d, **kw):
        seen.append((d, kw))
        return real(d, **kw)

    png.render_image = spy
    try:
        lg.animate(scene, lg.orbit(elevation=30, frames=24), tmp / "t.gif", progress=False,
                   workers=1)  # fmt: skip
    finally:
        png.render_image = real
    return seen, scene.render(projector)


def timed(f) -> tuple[float, float]:
    t0, c0 = time.perf_counter(), time.process_time()
    f()
    return time.perf_counter() - t0, time.process_time() - c0


def compare(stem: str, tmp: Path, repeat: int) -> dict:
    """Old and new alternating, 24 frames each (raster and GIF frame timed
    apart), the other way round every other run; then the cold PNG, both ways."""
    frames, cold = frame_drawings(stem, tmp)
    n = len(frames)

    def old_png() -> None:  # as write_png saves it
        from PIL.PngImagePlugin import PngInfo

        info = PngInfo()
        info.add_text("Software", "lgraph")
        img, dpi = ref.render_image(cold, size=480)
        img.save(tmp / "o.png", format="PNG", dpi=(dpi, dpi), pnginfo=info)

    keys = ("old raster", "new raster", "old GIF", "new GIF", "old PNG", "new PNG")
    wall: dict[str, list[float]] = {k: [] for k in keys}
    cpu: dict[str, list[float]] = {k: [] for k in keys}
    for r in range(repeat):
        run_wall = dict.fromkeys(keys, 0.0)
        run_cpu = dict.fromkeys(keys, 0.0)
        writer = GifWriter(tmp / "n.gif", n, 12)
        old_file = open(tmp / "o.gif", "wb")  # noqa: SIM115 - closed below
        for version in ("old", "new") if r % 2 == 0 else ("new", "old"):
            for d, kw in frames:
                t0, c0 = time.perf_counter(), time.process_time()
                im = (ref if version == "old" else png).render_image(d, **kw)[0]
                t1, c1 = time.perf_counter(), time.process_time()
                if version == "old":
                    old_file.write(ref.gif_frame(im))
                else:
                    writer.add(im)
                t2, c2 = time.perf_counter(), time.process_time()
                run_wall[f"{version} raster"] += t1 - t0
                run_wall[f"{version} GIF"] += t2 - t1
                run_cpu[f"{version} raster"] += c1 - c0
                run_cpu[f"{version} GIF"] += c2 - c1
        writer.close()
        old_file.close()
        for version, f in (
            ("old", old_png),
            ("new", lambda: png.write_png(cold, tmp / "n.png", size=480)),
        ):
            run_wall[f"{version} PNG"], run_cpu[f"{version} PNG"] = timed(f)
        for k in keys:
            wall[k].append(run_wall[k])
            cpu[k].append(run_cpu[k])

    def total(times: dict, version: str) -> list[float]:
        return [a + b for a, b in zip(times[f"{version} raster"], times[f"{version} GIF"])]

    med = {k: statistics.median(v) for k, v in wall.items()}
    old, new = total(wall, "old"), total(wall, "new")
    gif = Image.open(tmp / "n.gif")
    same = gif.n_frames == n
    for k, (d, kw) in enumerate(frames):
        gif.seek(k)
        want = np.asarray(ref.render_image(d, **kw)[0])
        same = same and np.array_equal(np.asarray(gif.convert("L")), want)
    return {
        "figure": stem,
        "size": frames[0][1]["size"],
        "old ms/frame": 1e3 * statistics.median(old) / n,
        "new ms/frame": 1e3 * statistics.median(new) / n,
        "ratio": statistics.median(new) / statistics.median(old),
        "CPU ratio": statistics.median(total(cpu, "new")) / statistics.median(total(cpu, "old")),
        "ratio of minima": min(new) / min(old),
        "raster old ms": 1e3 * med["old raster"] / n,
        "raster new ms": 1e3 * med["new raster"] / n,
        "GIF old ms": 1e3 * med["old GIF"] / n,
        "GIF new ms": 1e3 * med["new GIF"] / n,
        "cold PNG old ms": 1e3 * med["old PNG"],
        "cold PNG new ms": 1e3 * med["new PNG"],
        "cold PNG ratio": med["new PNG"] / med["old PNG"],
        "cold PNG ratio of minima": min(wall["new PNG"]) / min(wall["old PNG"]),
        "GIF kB old/new": f"{(tmp / 'o.gif').stat().st_size // 1024}/"
        f"{(tmp / 'n.gif').stat().st_size // 1024}",
        "same pixels": same,
    }


def gil(repeat: int) -> dict:
    """Which pillow calls release the GIL: a thread counts in a loop while this
    one makes one long call (of the kind a frame makes); the counter's progress
    during the call over its rate while this thread sleeps.  The interpreter's
    switch interval is set to 1 s meanwhile, so the counter runs only where the
    call releases the GIL (it then keeps it until the interval is over, and the
    call waits: the share can exceed 1): about 0 means the call holds the GIL
    throughout.  Control: SHA-256 of 256 MB (released)."""
    import hashlib
    import io

    from PIL import ImageDraw

    count, stop = [0], [False]

    def counter() -> None:
        while not stop[0]:
            count[0] += 1

    rng = np.random.default_rng(0)
    canvas = Image.new("L", (6000, 6000), 255)
    sheet = Image.new("L", (3000, 3000), 255)
    line = np.trunc(rng.uniform(0, 3000, (3000, 2))).astype(np.float32)
    pal = Image.new("L", (4000, 4000), 0)
    ImageDraw.Draw(pal).line(line[:300], fill=200, width=2)
    pal.putpalette(bytes(range(256)) * 3)
    data = bytes(256 << 20)
    lut = list(range(255, -1, -1))

    def to_file() -> None:
        with tempfile.TemporaryFile() as f:
            pal.save(f, "GIF", optimize=False)

    calls = {
        "control: SHA-256": lambda: hashlib.sha256(data).digest(),
        "draw.line, width 2 (3000 segments)": lambda: ImageDraw.Draw(sheet).line(
            line, fill=0, width=2
        ),
        "reduce(3)": lambda: canvas.reduce(3),
        "point(LUT)": lambda: canvas.point(lut),
        "Image.new": lambda: Image.new("L", (6000, 6000), 255),
        "GIF into a BytesIO": lambda: pal.save(io.BytesIO(), "GIF", optimize=False),
        "GIF into a file": to_file,
    }
    thread = threading.Thread(target=counter, daemon=True)
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1.0)
    thread.start()
    out = {}
    try:
        for name, f in calls.items():
            shares = []
            for _ in range(repeat):
                c0, t0 = count[0], time.perf_counter()
                time.sleep(0.1)
                free = (count[0] - c0) / (time.perf_counter() - t0)
                c0, t0 = count[0], time.perf_counter()
                f()
                shares.append((count[0] - c0) / (free * (time.perf_counter() - t0)))
            out[name] = statistics.median(shares)
    finally:
        stop[0] = True
        thread.join()
        sys.setswitchinterval(interval)
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=9)
    p.add_argument("--threads", action="store_true", help="also measure the GIL overlap")
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        for stem in STEMS:
            row = compare(stem, tmp, args.repeat)
            print({k: round(v, 3) if isinstance(v, float) else v for k, v in row.items()},
                  flush=True)  # fmt: skip
        if args.threads:
            print({k: round(v, 2) for k, v in gil(args.repeat).items()}, flush=True)


if __name__ == "__main__":
    main()
