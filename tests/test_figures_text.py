"""Real text (issue #27): ``save(..., text="text")`` writes PDF labels as
base-font text that ``pdftotext`` finds and SVG labels as escaped
``<text>``; the default stays glyph outlines."""

from __future__ import annotations

import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

import lgraph as lg

SVG = "{http://www.w3.org/2000/svg}"


def _drawing() -> lg.Drawing:
    sc = lg.Scene()
    sc.add(lg.Torus(2, 0.7), lg.ParameterLines(4, 8))
    sc.add(lg.Label(r"point $\kappa_n = \frac{L}{E}$", at=(0, -2.7, 0), always=True, size=12))
    sc.add(lg.Label("a < b & c", at=(2.7, 0, 0), anchor="w", always=True))
    return sc.render(lg.ParallelProjector.from_angles(-60, 35))


def _pdftotext(path: Path) -> str:
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext (poppler-utils) is not installed")
    return subprocess.run(["pdftotext", str(path), "-"], capture_output=True, text=True,
                          timeout=60, check=True).stdout  # fmt: skip


def test_pdftotext_finds_the_labels_with_real_text(tmp_path: Path):
    d = _drawing()
    found = _pdftotext(d.save(tmp_path / "t.pdf", text="text"))
    # (pdftotext decides the spaces between words itself, from the glyph positions)
    flat = re.sub(r"\s", "", found)
    assert "pointκn=" in flat and "a<b&c" in flat
    assert "L" in flat and "E" in flat
    # the default: outlines, nothing to find
    assert not _pdftotext(d.save(tmp_path / "o.pdf")).strip()


def test_svg_labels_are_escaped_text_elements(tmp_path: Path):
    d = _drawing()
    path = d.save(tmp_path / "t.svg", text="text")
    raw = path.read_text()
    assert "a &lt; b &amp; c" in raw
    root = ET.parse(path).getroot()  # well-formed
    texts = ["".join(t.itertext()) for t in root.iter(SVG + "text")]
    assert "a < b & c" in texts
    assert any(t.replace(" ", "").startswith("pointκn=") for t in texts)
    # the fraction bar is a rectangle; the default has no text at all
    assert root.find(f".//{SVG}g[@class='label']/{SVG}rect") is not None
    assert "<text" not in d.save(tmp_path / "o.svg").read_text()


def test_real_text_sits_where_the_outlines_do(tmp_path: Path):
    """Each glyph of the real text starts inside the label's (outline) ink box,
    within a fraction of the font size: the same layout, other fonts."""
    d = _drawing().sized(width="10cm")
    path = d.save(tmp_path / "t.svg", text="text")
    root = ET.parse(path).getroot()
    ph = float(root.get("viewBox").split()[3])
    boxes = d.label_boxes()
    groups = root.findall(f".//{SVG}g[@class='label']")
    for g, (x0, y0, x1, y1), lab in zip(groups, boxes, d.labels):
        slack = 0.3 * lab.size
        for span in g.iter(SVG + "tspan"):
            x, y = float(span.get("x")), ph - float(span.get("y"))
            assert x0 - slack <= x <= x1 + slack and y0 - slack <= y <= y1 + slack


def test_a_label_beyond_the_base_fonts_stays_outlines_in_pdf(tmp_path: Path):
    sc = lg.Scene()
    sc.add(lg.Label("$\\aleph \\hbar$ x", at=(0, 0, 0)))
    d = sc.render(lg.ParallelProjector(direction=(0, 0, 1)))
    data = d.save(tmp_path / "a.pdf", text="text", compress=False).read_bytes()
    assert b"h\nf\n" in data  # filled outlines
    assert not re.search(rb"\(.*\) Tj", data)


def test_bad_text_option_is_refused(tmp_path: Path):
    with pytest.raises(ValueError, match="write_pdf: text must be 'outlines' or 'text'"):
        _drawing().save(tmp_path / "x.pdf", text="glyphs")
    assert not (tmp_path / "x.pdf").exists()


def test_glyph_styles_follow_the_mathematics():
    pytest.importorskip("matplotlib")
    from lgraph.output._text import text_glyphs

    g = text_glyphs(r"$\mathbf{x}_1 + y$ and", 10.0).glyphs
    styles = {c: st for _, _, c, st, _ in g if c.strip()}
    assert styles["x"] == "bold" and styles["1"] == "roman" and styles["y"] == "italic"
    assert styles["a"] == "roman"  # text outside $ is upright
    sizes = {c: z for _, _, c, _, z in g}
    assert sizes["1"] < sizes["x"]  # the subscript is smaller
