"""Drawings in notebooks: inline reprs, file objects, to_svg, the matplotlib bridge."""

from __future__ import annotations

import io
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from PIL import Image

import lgraph as lg
from lgraph.notebook import display
from lgraph.output.backends import backend_suffixes

SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def drawing() -> lg.Drawing:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(5, 6))
    proj = lg.ParallelProjector.from_angles(30, 25)
    return scene.render(proj, hidden_lines=True)


def _polylines(svg_text: str) -> list:
    root = ET.fromstring(svg_text.encode("utf-8"))
    assert root.tag == SVG + "svg"
    return list(root.iter(SVG + "polyline"))  # inside layer groups


def test_repr_svg_is_valid_svg_with_every_stroke(drawing):
    text = drawing._repr_svg_()
    assert isinstance(text, str)
    lines = _polylines(text)
    # one polyline per stroke here (no stroke holds a break)
    assert len(lines) == len(drawing.strokes)
    hidden = sum(1 for p in lines if p.get("data-visible") == "false")
    assert hidden == sum(1 for s in drawing.strokes if not s.visible) > 0
    # the coordinates are the page coordinates of the strokes
    pts = np.array([float(v) for v in re.split(r"[ ,]", lines[-1].get("points"))]).reshape(-1, 2)
    page = dict((id(s), p) for p, s in drawing.page_strokes())
    stroke = [s for s in sorted(drawing.strokes, key=lambda s: s.visible)][-1]
    ph = drawing.page_size()[1]
    np.testing.assert_allclose(pts, page[id(stroke)] * (1, -1) + (0, ph), atol=1e-3)


def test_repr_png_is_a_png_of_the_page(drawing):
    data = drawing._repr_png_()
    assert isinstance(data, bytes) and data.startswith(b"\x89PNG\r\n\x1a\n")
    im = Image.open(io.BytesIO(data))
    pw, ph = drawing.page_size()
    scale = display.REPR_PNG_DPI / 72
    assert abs(im.size[0] - pw * scale) <= 1 and abs(im.size[1] - ph * scale) <= 1
    gray = np.asarray(im.convert("L"))
    assert 0.002 < (gray < 128).mean() < 0.3  # ink on paper


@pytest.mark.parametrize("suffix", backend_suffixes())
def test_save_to_a_file_object_equals_the_file(drawing, tmp_path, suffix):
    path = drawing.save(tmp_path / f"a{suffix}")
    buf = io.BytesIO(b"head:")
    buf.seek(5)
    assert drawing.save(buf, format=suffix.lstrip(".")) is buf
    got, want = buf.getvalue()[5:], path.read_bytes()
    assert buf.getvalue()[:5] == b"head:"
    if suffix == ".pdf":  # the creation date and document id differ
        strip = re.compile(
            rb"/(CreationDate|ModDate) \(D:[^)]*\)|/ID\s*\[[^\]]*\]|% ReportLab[^\n]*"
        )
        got, want = strip.sub(b"", got), strip.sub(b"", want)
    assert got == want
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"a{suffix}"]


def test_save_to_a_real_binary_file_and_format_from_its_name(drawing, tmp_path):
    with open(tmp_path / "x.svg", "wb") as f:
        drawing.save(f)  # format from the file's name
    assert _polylines((tmp_path / "x.svg").read_text(encoding="utf-8"))
    with open(tmp_path / "y.bin", "wb") as f:
        drawing.save(f, format="png")
    assert (tmp_path / "y.bin").read_bytes().startswith(b"\x89PNG")


def test_format_overrides_the_suffix(drawing, tmp_path):
    p = drawing.save(tmp_path / "figure.out", format="svg")
    assert p.read_text(encoding="utf-8").startswith("<?xml")


def test_file_object_errors_are_clear(drawing):
    with pytest.raises(ValueError, match="needs format="):
        drawing.save(io.BytesIO())
    with pytest.raises(ValueError, match="unknown file suffix '.doc'"):
        drawing.save(io.BytesIO(), format="doc")
    with pytest.raises(TypeError, match="binary mode"):
        drawing.save(io.StringIO(), format="svg")


def test_to_svg_matches_the_saved_file(drawing, tmp_path):
    assert drawing.to_svg() == drawing.save(tmp_path / "a.svg").read_text(encoding="utf-8")
    assert drawing.to_svg(precision=1) != drawing.to_svg()


def test_short_reprs(drawing):
    r = repr(drawing)
    assert r.startswith("<Drawing: ") and f"{len(drawing.strokes)} strokes" in r
    assert len(r) < 100
    scene = lg.Scene()
    scene.add(lg.Sphere(1))
    assert repr(scene) == "<Scene: 1 nodes>"


def test_scene_displays_itself_from_the_default_view():
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.ParameterLines(4, 6))
    expected = scene.render(lg.ParallelProjector.from_angles(*display.DEFAULT_VIEW))
    lines = _polylines(scene._repr_svg_())
    assert len(lines) == len(expected.strokes)
    assert scene._repr_svg_() == expected.to_svg()
    assert scene._repr_png_() == expected._repr_png_()
    # adding a node changes what is shown
    scene.add(lg.Sphere(0.5), transform=lg.translate(0, 0, 3))
    assert len(_polylines(scene._repr_svg_())) > len(lines)


# -- matplotlib ---------------------------------------------------------------------
def _segments(ax) -> list:
    from matplotlib.collections import LineCollection

    return [c for c in ax.collections if isinstance(c, LineCollection)]


def test_plot_draws_every_stroke_with_its_style(drawing):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax = drawing.plot()
    try:
        cols = _segments(ax)
        segs = [s for c in cols for s in c.get_segments()]
        assert len(segs) == len(drawing.strokes)
        got = sorted(np.concatenate(segs).round(9).tolist())
        want = sorted(np.concatenate([s.xy for s in drawing.strokes]).round(9).tolist())
        assert got == want
        styles = {(s.style.width, s.style.dash, s.style.color) for s in drawing.strokes}
        # one collection per family, visibility and style (a legend by family)
        assert len(cols) == len({(s.family, s.visible, s.style) for s in drawing.strokes})
        for c in cols:
            width = float(c.get_linewidths()[0])
            [(w, dash, color)] = [t for t in styles if t[0] == width]
            np.testing.assert_allclose(c.get_colors()[0][:3], color)
            offset, pattern = c.get_dashes()[0]
            if dash is None:
                assert pattern is None
            else:  # matplotlib scales dashes by the width; what it draws is in pt
                np.testing.assert_allclose(pattern, dash)
        assert ax.get_aspect() == 1.0
        hidden = [c for c in cols if c.get_label().endswith(" (hidden)")]
        visible = [c for c in cols if not c.get_label().endswith(" (hidden)")]
        assert hidden and visible
        assert max(c.get_zorder() for c in hidden) < min(c.get_zorder() for c in visible)
        x0, y0, x1, y1 = drawing.bounds()
        lo, hi = ax.get_xlim()
        assert lo < x0 and hi > x1
        buf = io.BytesIO()
        ax.figure.savefig(buf, format="png")
        assert buf.getvalue().startswith(b"\x89PNG")
    finally:
        plt.close("all")


def test_plot_into_given_axes_of_subplots(drawing):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2)
    try:
        assert drawing.plot(b, axis=True) is b
        assert not _segments(a) and _segments(b)
        assert b.axison
    finally:
        plt.close(fig)


def test_plot_without_matplotlib_is_a_clear_error(drawing, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(ImportError, match="pip install matplotlib"):
        drawing.plot()
