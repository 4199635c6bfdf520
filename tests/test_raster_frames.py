"""Cheaper raster frames, the same pixels: ``render_image`` (coordinates handed
to pillow as truncated float32 arrays, only the box the strokes reach cleared
and box-reduced, a grey frame's canvas kept for the next one) and the GIF
writer (only the box that changed since the last grey frame) against the
straightforward way in ``tests/raster_reference.py``, pixel for pixel."""

from __future__ import annotations

import struct
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
import raster_reference as ref
from PIL import Image, ImageDraw

import lgraph as lg
import lgraph.output.backends.png as png
from lgraph.animation.writers import GifWriter
from lgraph.output.drawing import Drawing, Page, Stroke, Style


def _same(drawing: Drawing, **options: object) -> None:
    """``render_image`` gives the reference's image, byte for byte."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # sub-pixel dashes, page-wide strokes
        got, dpi = png.render_image(drawing, **options)
        want, dpi_ref = ref.render_image(drawing, **options)
    assert (got.mode, got.size, dpi) == (want.mode, want.size, dpi_ref)
    a, b = np.asarray(got, dtype=int), np.asarray(want, dtype=int)
    assert np.array_equal(a, b), f"{(a != b).sum()} pixels differ, by up to {np.abs(a - b).max()}"


def _stroke(xy, **style: object) -> Stroke:
    xy = np.asarray(xy, dtype=float)
    return Stroke(xy=xy, xyz=np.zeros((len(xy), 3)), style=Style(**style))


def _random_drawing(seed: int, background: object = (1.0, 1.0, 1.0)) -> Drawing:
    """Polylines of every kind the backend draws, some reaching past the page
    (a 100 x 60 window on a 200 x 120 pt page): hairlines, 2-px lines, wide
    lines with round joins and caps, dashes, breaks (NaN), grey and black."""
    rng = np.random.default_rng(seed)
    strokes = []
    for k in range(12):
        n = int(rng.integers(2, 40))
        start = rng.uniform([-10, -10], [110, 70])
        xy = start + np.cumsum(rng.normal(0, 4, (n, 2)), axis=0)
        if k % 5 == 4 and n > 4:
            xy[n // 2] = np.nan  # a break
        width = float(rng.choice([0.05, 0.3, 0.5, 0.8, 1.5, 4.0]))
        dash = (2.0, 1.5) if k % 3 == 0 else None
        grey = float(rng.choice([0.0, 0.35, 0.6]))
        strokes.append(_stroke(xy, width=width, dash=dash, color=(grey, grey, grey)))
    return Drawing(strokes=strokes, page=Page(width=200.0, height=120.0, margin=0.0),
                   background=background, window=(0.0, 0.0, 100.0, 60.0))  # fmt: skip


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("supersample", [1, 2, 3, 4])
def test_random_strokes_give_the_reference_pixels(seed, supersample):
    d = _random_drawing(seed)
    for size in (97, 240, 401):  # odd sizes: boxes at every phase of the supersampling
        _same(d, size=size, supersample=supersample, gray=True)
    _same(d, size=240, supersample=supersample)  # RGB


@pytest.mark.parametrize(
    "background", [(0.5, 0.5, 0.5), (1.0, 0.9, 0.8), (0.0, 0.0, 0.0), None], ids=str
)
def test_backgrounds_outside_the_ink_are_the_reference_ones(background):
    # the page outside the reduced box is filled with the background as the
    # box filter gives it (RGB, grey, black, transparent RGBA)
    d = _random_drawing(7, background=background)
    for ss in (2, 3, 5):
        _same(d, size=150, supersample=ss, gray=True)


def test_hidden_lines_labels_and_page_wide_strokes():
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(5, 6))
    view = lg.ParallelProjector.from_angles(30, 25)
    d = scene.render(view, hidden_lines=True, page=(240, 180))  # grey dashed hidden lines
    for options in ({"size": 320, "gray": True}, {"size": 320}, {"dpi": 300}):
        _same(d, **options)
    scene.add(lg.Label("P", at=(0, 0, 1.3)))  # labels: the whole canvas, as before
    _same(scene.render(view, page=(240, 180)), size=320, gray=True)
    wide = lg.Drawing(strokes=(*d.strokes, _stroke([[0, 0], [1, 1]], width=5e4)), page=(240, 180))
    _same(wide, size=200)


def test_strokes_reach_at_most_half_their_width_and_2_px_beyond_their_points():
    # the bound behind the box that is cleared and reduced (png._ink_box): pillow's own
    # lines, wide polygons and discs, drawn on a whole canvas, brute force
    rng = np.random.default_rng(3)
    for lw in range(1, 16):
        for _ in range(20):
            px = rng.uniform(30, 70, 2) + np.cumsum(
                rng.normal(0, 6, (int(rng.integers(2, 6)), 2)), 0
            )
            img = Image.new("L", (100, 100), 255)
            ref.draw_polyline(ImageDraw.Draw(img), px, 0, lw)
            rows = np.flatnonzero((np.asarray(img) < 255).any(axis=1))
            cols = np.flatnonzero((np.asarray(img) < 255).any(axis=0))
            reach = lw / 2 + 2
            assert px[:, 1].min() - reach <= rows[0] and rows[-1] <= px[:, 1].max() + reach
            assert px[:, 0].min() - reach <= cols[0] and cols[-1] <= px[:, 0].max() + reach


@pytest.mark.parametrize("supersample", [2, 3, 4])
def test_small_boxes_at_every_phase_of_the_supersampling(supersample):
    # short strokes in a band of the page: the box starts inside the
    # page, at every offset against the supersampling grid
    rng = np.random.default_rng(supersample)
    for k in range(24):
        y = 8.0 + k * 1.7 + rng.uniform(0, 1)
        x = rng.uniform(10, 80)
        strokes = (
            _stroke([[x, y], [x + 9, y + 0.3], [x + 2, y + 2.5]], width=0.5 + k % 4),
            _stroke([[x, y + 1], [x + 5, y + 1]], width=0.2, dash=(1.0, 0.7)),
        )
        d = Drawing(strokes=strokes, page=Page(width=200.0, height=120.0, margin=0.0),
                    window=(0.0, 0.0, 100.0, 60.0))  # fmt: skip
        _same(d, size=int(rng.integers(150, 260)), supersample=supersample, gray=True)


def test_a_kept_canvas_shows_nothing_of_the_frame_before():
    # a grey frame's canvas is reused: ink of the last frame outside this one's box
    big = _random_drawing(11)
    small = Drawing(strokes=(_stroke([[40.0, 20.0], [60.0, 35.0]], width=0.5),),
                    page=big.page, window=big.window)  # fmt: skip
    for d in (big, small, big, _random_drawing(12), small):
        _same(d, size=240, gray=True)


def test_threads_draw_on_canvases_of_their_own():
    drawings = [_random_drawing(seed) for seed in range(8)]
    want = [np.asarray(ref.render_image(d, size=240, gray=True)[0]) for d in drawings]

    def render(d: Drawing) -> np.ndarray:
        return np.asarray(png.render_image(d, size=240, gray=True)[0])

    with ThreadPoolExecutor(4) as pool:
        for _ in range(3):
            got = list(pool.map(render, drawings))
            assert all(np.array_equal(g, w) for g, w in zip(got, want))


def test_far_off_points_and_empty_drawings():
    far = _stroke([[50.0, 30.0], [50.0, 3e7], [60.0, 30.0]], width=1.0)  # beyond 2**24 px
    near = _stroke([[10.0, 10.0], [90.0, 50.0]], width=2.0, dash=(3.0, 2.0))
    for strokes in ((far, near), (near,), ()):
        d = Drawing(strokes=strokes, page=Page(width=200.0, height=120.0, margin=0.0),
                    window=(0.0, 0.0, 100.0, 60.0))  # fmt: skip
        _same(d, size=240, gray=True)
        _same(d, size=240, supersample=1)
    outside = Drawing(strokes=(_stroke([[200.0, 200.0], [300.0, 250.0]]),),
                      page=Page(width=200.0, height=120.0, margin=0.0),
                      window=(0.0, 0.0, 100.0, 60.0))  # fmt: skip
    _same(outside, size=240, gray=True)  # nothing on the page


# -- GIF frames ----------------------------------------------------------------
def _turntable_frames(monkeypatch, tmp_path, hidden_lines: bool) -> list[tuple[Drawing, dict]]:
    """The drawings ``lg.animate`` rasterizes for a small turntable."""
    seen = []
    real = png.render_image

    def spy(d, **kw):
        seen.append((d, kw))
        return real(d, **kw)

    monkeypatch.setattr(png, "render_image", spy)
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(6, 8))
    lg.animate(scene, lg.orbit(elevation=30, frames=6), tmp_path / "t.gif", width=160,
               hidden_lines=hidden_lines, progress=False, workers=1)  # fmt: skip
    monkeypatch.undo()
    return seen


def _descriptors(path) -> list[tuple[int, int, int, int]]:
    """(left, top, width, height) of every image in a GIF without a global table."""
    data = path.read_bytes()
    assert data[:6] == b"GIF89a" and not data[10] & 0x80
    pos, out = 13, []

    def skip_blocks(pos: int) -> int:
        while data[pos]:
            pos += data[pos] + 1
        return pos + 1

    while data[pos] != 0x3B:
        if data[pos] == 0x21:
            pos = skip_blocks(pos + 2)
            continue
        assert data[pos] == 0x2C
        out.append(struct.unpack("<HHHH", data[pos + 1 : pos + 9]))
        flags = data[pos + 9]
        pos += 10 + (3 << ((flags & 7) + 1) if flags & 0x80 else 0)
        pos = skip_blocks(pos + 1)
    return out


@pytest.mark.parametrize("hidden_lines", [False, True])
def test_gif_frames_decode_to_the_reference_pixels(monkeypatch, tmp_path, hidden_lines):
    frames = _turntable_frames(monkeypatch, tmp_path, hidden_lines)
    want = [ref.render_image(d, **kw)[0] for d, kw in frames]
    got = [png.render_image(d, **kw)[0] for d, kw in frames]
    assert all(im.mode == "L" for im in got)
    # the last frame twice (nothing changes: one pixel is encoded), the first again
    images, want = [*got, got[-1], got[0]], [*want, want[-1], want[0]]
    w = GifWriter(tmp_path / "a.gif", n_frames=len(images), fps=10)
    for im in images:
        w.add(im)
    path = w.close()
    gif = Image.open(path)
    assert gif.n_frames == len(images)
    for k, im in enumerate(want):
        gif.seek(k)
        assert np.array_equal(np.asarray(gif.convert("L")), np.asarray(im)), k
    # the whole first frame, then only the boxes that changed
    boxes = _descriptors(path)
    full = (0, 0, *want[0].size)
    assert boxes[0] == full and boxes[-2] == (0, 0, 1, 1)
    assert all(b[2] * b[3] < full[2] * full[3] for b in boxes[1:])
    # smaller than whole frames, each encoded as before
    whole = sum(len(ref.gif_frame(im)) for im in want)
    assert path.stat().st_size < whole


def test_gif_boxes_across_colour_frames_and_sizes(tmp_path):
    # a colour frame in between: the grey frame after it is whole again
    grey = Image.new("L", (40, 30), 255)
    grey.paste(0, (5, 5, 9, 9))
    moved = Image.new("L", (40, 30), 255)
    moved.paste(0, (20, 10, 24, 14))
    colour = Image.new("RGB", (40, 30), (255, 0, 0))
    w = GifWriter(tmp_path / "a.gif", n_frames=4, fps=10)
    for im in (grey, moved, colour, grey):
        w.add(im)
    path = w.close()
    assert _descriptors(path) == [(0, 0, 40, 30), (5, 5, 19, 9), (0, 0, 40, 30), (0, 0, 40, 30)]
    gif = Image.open(path)
    for k, want in enumerate((grey, moved, colour.convert("L"), grey)):
        gif.seek(k)
        assert np.array_equal(np.asarray(gif.convert("L")), np.asarray(want)), k
    w = GifWriter(tmp_path / "b.gif", n_frames=2, fps=10)
    w.add(grey)
    with pytest.raises(ValueError, match=r"frame 1 is \(30, 40\) px, the first \(40, 30\)"):
        w.add(Image.new("L", (30, 40), 255))
    w.abort()


def test_two_pixel_lines_weigh_the_same_at_every_angle():
    # a 2-px line (supersampled) through the middle of the page at 0 .. 180
    # degrees: its ink (grey levels summed, in output pixels) per unit of
    # length is 2/3 px (2 px / supersample 3) give or take the pen's shape;
    # pillow's own 2-px polygons would give 0.39 at 10 degrees, 0.75 at 60
    page = Page(width=200.0, height=200.0, margin=0.0)
    weights = []
    for deg in range(0, 181, 5):
        a = np.radians(deg + 0.3)  # off the axes by a little: no exact ties
        end = 80 * np.array([np.cos(a), np.sin(a)])
        d = Drawing(strokes=(_stroke([-end, end], width=2 / 3),), page=page,
                    window=(-100.0, -100.0, 100.0, 100.0))  # fmt: skip
        img, _ = png.render_image(d, dpi=72, gray=True)
        assert img.mode == "L" and png.render_image(d, dpi=72)[0].size == img.size
        ink = (255 - np.asarray(img, dtype=float)).sum() / 255
        weights.append(ink / 160)
    assert 0.6 < min(weights) and max(weights) < 0.8
    assert max(weights) / min(weights) < 1.15
