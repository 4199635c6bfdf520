"""Physical sizes mean what they say (issue #27): with ``save(width=/height=)``
the figure's ink -- strokes with their line widths, and labels -- spans
exactly that size, measured in the written files, plus ``margin=`` when
asked for."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import lgraph as lg

SVG = "{http://www.w3.org/2000/svg}"
MM = 72 / 25.4


def _scene(labels: bool = True) -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.Torus(2, 0.7), lg.ParameterLines(6, 10), style=lg.Style(width=0.6))
    if labels:
        # a label sticking out to the right of the torus, one to the top
        scene.add(lg.Label("$\\kappa_n = \\frac{L}{E}$", at=(2.7, 0, 0), anchor="w", offset=(4, 0)))
        scene.add(lg.Label("$P$", at=(0, 0, 0.7), anchor="s", always=True))
    return scene


def _drawing(labels: bool = True) -> lg.Drawing:
    return _scene(labels).render(lg.ParallelProjector.from_angles(-60, 25))


def _svg_ink(path: Path) -> tuple[float, float, float, float, float, float]:
    """Ink box ``x0, y0, x1, y1`` of the SVG's polylines (points widened by
    half the stroke width of their layer) and label paths (every coordinate
    of their outlines), and the page size from the viewBox."""
    root = ET.parse(path).getroot()
    _, _, pw, ph = (float(v) for v in root.get("viewBox").split())
    lo, hi = [np.inf, np.inf], [-np.inf, -np.inf]

    def grow(pts: np.ndarray, pad: float) -> None:
        lo[:] = np.minimum(lo, pts.min(axis=0) - pad)
        hi[:] = np.maximum(hi, pts.max(axis=0) + pad)

    for layer in root.iter(SVG + "g"):
        width = float(layer.get("stroke-width") or 0)
        for pl in layer.findall(SVG + "polyline"):
            pts = np.array(re.split(r"[ ,]", pl.get("points")), float).reshape(-1, 2)
            grow(pts, width / 2)
    for p in root.iter(SVG + "path"):
        nums = np.array(re.findall(r"-?\d+(?:\.\d+)?", p.get("d")), float).reshape(-1, 2)
        grow(nums, 0.0)
    return (*lo, *hi, pw, ph)


def _pdf_media_and_ink(path: Path) -> tuple[list[float], tuple[float, float, float, float]]:
    """The MediaBox and the stroked ink box of an uncompressed PDF written by
    lgraph (integer coordinates under one ``k 0 0 k 0 0 cm`` matrix)."""
    data = path.read_bytes()
    box = [float(x) for x in re.search(rb"/MediaBox \[\s*([\d.\s-]+)\]", data).group(1).split()]
    stream = re.search(rb"stream\r?\n(.*?)endstream", data, re.S).group(1).decode()
    # reportlab's own "1 0 0 1 0 0 cm" first, then lgraph's scaling of the strokes
    m = [m for m in re.finditer(r"([\d.]+) 0 0 [\d.]+ 0 0 cm", stream) if m.group(1) != "1"][0]
    k = float(m.group(1))
    body = stream[m.end() :].split("\nQ", 1)[0]
    lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
    width = 0.0
    for line in body.splitlines():
        parts = line.split()
        if parts and parts[-1] == "w":
            width = float(parts[0]) * k
        elif parts and parts[-1] in ("m", "l"):
            p = np.array(parts[:2], float) * k
            lo, hi = np.minimum(lo, p - width / 2), np.maximum(hi, p + width / 2)
    return box, (*lo, *hi)


@pytest.mark.parametrize("labels", [False, True])
def test_svg_ink_spans_the_asked_width(tmp_path: Path, labels: bool) -> None:
    d = _drawing(labels)
    path = d.save(tmp_path / "f.svg", width="8cm")
    x0, y0, x1, y1, pw, ph = _svg_ink(path)
    assert pw == pytest.approx(80 * MM, abs=2e-3)
    # precision 3 decimals: the ink touches all four sides of the page
    assert x0 == pytest.approx(0, abs=2e-3) and x1 == pytest.approx(pw, abs=2e-3)
    assert y0 == pytest.approx(0, abs=2e-3) and y1 == pytest.approx(ph, abs=2e-3)
    root = ET.parse(path).getroot()
    assert root.get("width") == "80mm"


def test_pdf_media_box_and_stroke_ink_match_the_asked_height(tmp_path: Path) -> None:
    d = _drawing(labels=False)
    path = d.save(tmp_path / "f.pdf", height="5cm", compress=False)
    box, (x0, y0, x1, y1) = _pdf_media_and_ink(path)
    assert box[3] - box[1] == pytest.approx(50 * MM, abs=1e-3)
    assert (x0, y0) == pytest.approx((0, 0), abs=2e-3)
    assert (x1, y1) == pytest.approx((box[2], box[3]), abs=2e-3)


def test_margin_in_physical_units_surrounds_the_ink(tmp_path: Path) -> None:
    d = _drawing()
    path = d.save(tmp_path / "m.svg", width="8cm", margin="2mm")
    x0, y0, x1, y1, pw, ph = _svg_ink(path)
    assert pw == pytest.approx(80 * MM, abs=2e-3)
    for v in (x0, y0, pw - x1, ph - y1):
        assert v == pytest.approx(2 * MM, abs=2e-3)
    # a number is pt
    x0, _, x1, _, pw, _ = _svg_ink(d.save(tmp_path / "n.svg", width=200, margin=10))
    assert (x0, pw - x1, pw) == pytest.approx((10, 10, 200), abs=2e-3)


def test_both_sizes_fit_inside_and_one_of_them_is_met(tmp_path: Path) -> None:
    d = _drawing()
    w, h = d.sized(width="8cm", height="3cm").page_size()
    assert w <= 80 * MM + 1e-9 and h <= 30 * MM + 1e-9
    assert max(w / (80 * MM), h / (30 * MM)) == pytest.approx(1, abs=1e-9)


def test_png_pixels_follow_the_physical_size(tmp_path: Path) -> None:
    from PIL import Image

    d = _drawing(labels=False)
    img = Image.open(d.save(tmp_path / "f.png", width="2in", dpi=100))
    assert img.size[0] == 200
    ink = np.asarray(img.convert("L")) < 250
    cols = np.flatnonzero(ink.any(axis=0))
    assert cols[0] <= 1 and cols[-1] >= 198  # ink from edge to edge


def test_bad_margins_are_refused_naming_the_parameter(tmp_path: Path) -> None:
    d = _drawing(labels=False)
    with pytest.raises(ValueError, match="margin must be a non-negative length"):
        d.save(tmp_path / "a.svg", width="8cm", margin="-1mm")
    with pytest.raises(ValueError, match="width must exceed twice the margin"):
        d.save(tmp_path / "a.svg", width="8mm", margin="4mm")
    assert not (tmp_path / "a.svg").exists()
