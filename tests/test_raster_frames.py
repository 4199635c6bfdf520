"""Cheaper raster frames, the same pixels: ``render_image`` (strokes drawn on
the rows that hold ink only, coordinates handed to pillow as truncated float32
arrays, only the inked columns box-reduced) against the straightforward way in
``tests/raster_reference.py``, pixel for pixel."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import raster_reference as ref
from PIL import Image, ImageDraw

import lgraph as lg
import lgraph.backends.png as png
from lgraph.drawing import Drawing, Page, Stroke, Style


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
    for size in (97, 240, 401):  # odd sizes: the rows and columns at every phase
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
    # the bound behind the rows that are drawn (png._ink_box): pillow's own
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
def test_bands_of_ink_at_every_phase_of_the_rows(supersample):
    # short strokes in a band of the page: the drawn rows start inside the
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
