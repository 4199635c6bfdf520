"""Raster frames of animations: one grey channel where it loses nothing, exact grey GIFs."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

import lgraph as lg
from lgraph.animation.writers import GifWriter
from lgraph.output.backends.png import render_image


def _drawing(style: lg.Style | None = None) -> lg.Drawing:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(5, 6), style=style)
    return scene.render(
        lg.ParallelProjector.from_angles(30, 25), hidden_lines=True, page=(240, 180)
    )


@pytest.mark.parametrize("supersample", [1, 3])
def test_grey_drawings_come_as_one_channel_with_the_rgb_pixels(supersample):
    d = _drawing()  # black lines, grey dashed hidden lines, white background
    rgb, dpi = render_image(d, size=320, supersample=supersample)
    grey, dpi_grey = render_image(d, size=320, supersample=supersample, gray=True)
    assert (rgb.mode, grey.mode) == ("RGB", "L") and dpi == dpi_grey
    a = np.asarray(rgb, dtype=int)
    assert np.array_equal(a[..., 0], a[..., 1]) and np.array_equal(a[..., 0], a[..., 2])
    assert np.array_equal(np.asarray(grey, dtype=int), a[..., 0])
    assert (a < 128).sum() > 100  # something is drawn


def test_colour_labels_and_transparency_keep_rgb():
    colour = _drawing(lg.Style(color="red"))
    assert render_image(colour, size=320, gray=True)[0].mode == "RGB"
    clear = lg.Drawing(strokes=_drawing().strokes, page=(240, 180), background=None)
    assert render_image(clear, size=320, gray=True)[0].mode == "RGBA"
    scene = lg.Scene()
    scene.add(lg.Sphere(1))
    scene.add(lg.Label("P", at=(0, 0, 1)))
    labelled = scene.render(lg.ParallelProjector.from_angles(30, 25))
    assert render_image(labelled, size=320, gray=True)[0].mode == "RGB"


def _gif_frames(path) -> list[np.ndarray]:
    im = Image.open(path)
    out = []
    for k in range(im.n_frames):
        im.seek(k)
        out.append(np.asarray(im.convert("RGB"), dtype=int))
    return out


def test_gif_keeps_grey_frames_exactly_and_quantizes_colour_ones(tmp_path):
    rng = np.random.default_rng(1)
    grey = [Image.fromarray(rng.integers(0, 256, (30, 40), dtype=np.uint8)) for _ in range(3)]
    colour = Image.fromarray(rng.integers(0, 256, (30, 40, 3), dtype=np.uint8))
    w = GifWriter(tmp_path / "a.gif", n_frames=4, fps=10)
    for im in grey:
        w.add(im)
    buf = io.BytesIO()
    colour.save(buf, "PNG")
    w.add(buf.getvalue())  # PNG bytes, as frames come back from worker processes
    got = _gif_frames(w.close())
    assert len(got) == 4
    for g, im in zip(got, grey):  # all 256 grey levels fit the frame's palette
        assert np.array_equal(g, np.repeat(np.asarray(im, dtype=int)[..., None], 3, axis=2))
    assert np.abs(got[3] - np.asarray(colour, dtype=int)).mean() < 40  # a palette of 256


def _image_descriptors(data: bytes) -> list[bytes]:
    """The 10-byte image descriptors of a GIF, read block by block."""

    def skip_sub_blocks(pos: int) -> int:
        while data[pos]:
            pos += data[pos] + 1
        return pos + 1

    flags, pos, out = data[10], 13, []
    if flags & 0x80:
        pos += 3 << ((flags & 7) + 1)
    while data[pos] != 0x3B:
        if data[pos] == 0x21:  # an extension: label, then sub-blocks
            pos = skip_sub_blocks(pos + 2)
            continue
        assert data[pos] == 0x2C
        desc = data[pos : pos + 10]
        out.append(desc)
        pos += 10
        if desc[9] & 0x80:
            pos += 3 << ((desc[9] & 7) + 1)
        pos = skip_sub_blocks(pos + 1)  # the LZW minimum code size, then the data
    return out


def test_gif_frames_are_not_interlaced(tmp_path):
    rng = np.random.default_rng(2)
    w = GifWriter(tmp_path / "b.gif", n_frames=3, fps=10)
    for _ in range(2):  # grey frames, the second only within its changed box
        w.add(Image.fromarray(rng.integers(0, 256, (30, 40), dtype=np.uint8)))
    w.add(Image.fromarray(rng.integers(0, 256, (30, 40, 3), dtype=np.uint8)))
    descriptors = _image_descriptors(w.close().read_bytes())
    assert len(descriptors) == 3
    assert all(d[9] & 0x40 == 0 for d in descriptors)  # rows in order
    assert all(d[9] & 0x80 for d in descriptors)  # each with its local colour table
