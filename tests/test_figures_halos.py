"""Halos (issue #27): the lines under a label's ink box plus a gap, and around
a point mark, are cut geometrically -- checked in the files every backend
writes (PDF, SVG, PNG, HPGL, plotter-cleaned SVG): no stroke point and no
piece of a segment inside the padded box -- and the cutting itself against
dense sampling of the original polylines."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import lgraph as lg
from lgraph.output.halos import cut_polylines

SVG = "{http://www.w3.org/2000/svg}"
VIEW = lg.ParallelProjector.from_angles(-60, 35)
WIDTH = "10cm"


def _scene(**scene_options) -> lg.Scene:
    sc = lg.Scene(**scene_options)
    sc.add(lg.Torus(2, 0.7), lg.ParameterLines(12, 24))
    sc.add(lg.Label("$\\kappa_n = \\frac{L}{E}$", at=(0, -2.0, 0.7), always=True, size=12))
    sc.add(lg.Label("$P$", at=(2.7, 0, 0), anchor="w", offset=(1, 0)))
    sc.add(lg.Point((0, -2.7, 0), size=4, always=True))
    return sc


@pytest.fixture(scope="module")
def drawing() -> lg.Drawing:
    return _scene(halo=True).render(VIEW, hidden_lines=True)


def _segments_inside(polylines: list[np.ndarray], boxes, discs, shrink: float) -> int:
    """How many sample points of the polylines' segments (20 per segment,
    ends included) lie inside a box or disc shrunk by ``shrink``."""
    bad = 0
    f = np.linspace(0, 1, 20)[:, None, None]
    for p in polylines:
        if len(p) < 2:
            continue
        q = (p[:-1] + f * (p[1:] - p[:-1])).reshape(-1, 2)
        x, y = q[:, 0], q[:, 1]
        for x0, y0, x1, y1 in boxes:
            bad += int(
                (
                    (x > x0 + shrink) & (x < x1 - shrink) & (y > y0 + shrink) & (y < y1 - shrink)
                ).sum()
            )
        for cx, cy, r in discs:
            bad += int((np.hypot(x - cx, y - cy) < r - shrink).sum())
    return bad


def _touching(polylines: list[np.ndarray], boxes, tol: float) -> int:
    """Stroke points within ``tol`` of a box's edge (the cut ends)."""
    n = 0
    for p in polylines:
        for x0, y0, x1, y1 in boxes:
            x, y = p[:, 0], p[:, 1]
            inx = (x > x0 - tol) & (x < x1 + tol)
            iny = (y > y0 - tol) & (y < y1 + tol)
            edge = (np.abs(x - x0) < tol) | (np.abs(x - x1) < tol)
            edge |= (np.abs(y - y0) < tol) | (np.abs(y - y1) < tol)
            n += int((inx & iny & edge).sum())
    return n


def _svg_polylines(path: Path) -> tuple[list[np.ndarray], float]:
    root = ET.parse(path).getroot()
    ph = float(root.get("viewBox").split()[3])
    out = []
    for pl in root.iter(SVG + "polyline"):
        if pl.get("data-family") == "point":
            continue
        p = np.array(re.split(r"[ ,]", pl.get("points")), float).reshape(-1, 2)
        out.append(p * (1, -1) + (0, ph))  # back to page coordinates, y up
    return out, ph


def test_cut_polylines_removes_exactly_the_inside_parts():
    rng = np.random.default_rng(7)
    pts = rng.uniform(0, 10, (400, 2))
    ends = [100, 250, 400]
    boxes = np.array([[2.0, 3.0, 5.0, 6.5], [6.0, 1.0, 9.0, 2.0]])
    discs = np.array([[7.0, 7.0, 1.5]])
    out, new_ends = cut_polylines(pts, ends, boxes, discs)
    assert len(new_ends) == 3
    starts = [0, *new_ends[:-1]]
    kept = [out[a:b] for a, b in zip(starts, new_ends)]
    runs = [r for p in kept for r in np.split(p, np.flatnonzero(np.isnan(p[:, 0])))]
    runs = [r[np.isfinite(r[:, 0])] for r in runs]
    assert _segments_inside(runs, boxes, discs, 1e-9) == 0
    # dense samples of the original: those well outside every region lie on
    # a kept segment, those well inside on none
    f = np.linspace(0, 1, 7)[1:-1, None, None]
    orig = [pts[a:b] for a, b in zip([0, *ends[:-1]], ends)]
    samples = np.concatenate([(p[:-1] + f * (p[1:] - p[:-1])).reshape(-1, 2) for p in orig])
    x, y = samples[:, 0], samples[:, 1]
    dist_in = np.full(len(samples), -np.inf)  # > 0 inside some region (depth)
    for x0, y0, x1, y1 in boxes:
        dist_in = np.maximum(dist_in, np.minimum.reduce([x - x0, x1 - x, y - y0, y1 - y]))
    for cx, cy, r in discs:
        dist_in = np.maximum(dist_in, r - np.hypot(x - cx, y - cy))
    segs = np.concatenate([np.stack([r[:-1], r[1:]], axis=1) for r in runs if len(r) > 1])

    def on_kept(q: np.ndarray) -> np.ndarray:
        a, b = segs[:, 0], segs[:, 1]
        d = b - a
        t = np.clip(np.einsum("ij,kij->ki", d, q[:, None] - a) / np.einsum("ij,ij->i", d, d), 0, 1)
        near = a + t[..., None] * d
        return np.hypot(*(near - q[:, None]).transpose(2, 0, 1)).min(axis=1) < 1e-9

    assert on_kept(samples[dist_in < -1e-6]).all()
    assert not on_kept(samples[dist_in > 1e-6]).any()


def test_svg_and_pdf_lines_stay_out_of_the_padded_boxes(drawing: lg.Drawing, tmp_path: Path):
    sized = drawing.sized(width=WIDTH)
    boxes, discs = sized.halo_regions()
    assert len(boxes) == 2 and len(discs) == 1
    # the boxes are the labels' ink boxes grown by 1.5 pt
    assert np.allclose(boxes - sized.label_boxes(), [-1.5, -1.5, 1.5, 1.5])
    lines, _ = _svg_polylines(drawing.save(tmp_path / "h.svg", width=WIDTH))
    assert _segments_inside(lines, boxes, discs, 2e-3) == 0
    assert _touching(lines, boxes, 2e-3) >= 4  # lines do end on the halos' edges
    # without halos, lines do cross the boxes (the test means something)
    plain = _scene().render(VIEW, hidden_lines=True)
    lines, _ = _svg_polylines(plain.save(tmp_path / "p.svg", width=WIDTH))
    assert _segments_inside(lines, boxes, discs, 2e-3) > 0
    # PDF: the stroked path coordinates (integers in 1e-3 pt under a cm matrix)
    data = drawing.save(tmp_path / "h.pdf", width=WIDTH, compress=False).read_bytes()
    stream = re.search(rb"stream\r?\n(.*?)endstream", data, re.S).group(1).decode()
    body = stream.split("0.001 0 0 0.001 0 0 cm", 1)[1].split("\nQ", 1)[0]
    paths, cur = [], []
    for line in body.splitlines():
        parts = line.split()
        if parts and parts[-1] in ("m", "l"):
            cur.append([float(parts[0]) / 1000, float(parts[1]) / 1000])
        elif parts == ["S"]:
            paths.append(np.array(cur))
            cur = []
    assert len(paths) > 50
    lines = [p for p in paths if len(p) > 2 or np.ptp(p, axis=0).max() > 0]  # not the dot
    assert _segments_inside(lines, boxes, discs, 2e-3) == 0


def test_png_has_no_line_ink_in_the_padded_boxes(drawing: lg.Drawing, tmp_path: Path):
    from PIL import Image

    red = lg.Scene(halo=True)
    red.add(lg.Torus(2, 0.7), lg.ParameterLines(12, 24))
    red.add(lg.Label("$\\kappa_n$", at=(0, -2.0, 0.7), always=True, size=14, color="red"))
    d = red.render(VIEW, hidden_lines=True)
    dpi = 300
    img = np.asarray(Image.open(d.save(tmp_path / "h.png", width=WIDTH, dpi=dpi)).convert("RGB"))
    sized = d.sized(width=WIDTH)
    ((x0, y0, x1, y1),) = sized.halo_regions()[0]
    ph = sized.page_size()[1]
    k = dpi / 72
    # shrink by the widest line's half width (0.8 pt) and 1.5 px of anti-aliasing
    s = 0.4 + 1.5 / k
    cols = slice(int(np.ceil((x0 + s) * k)), int((x1 - s) * k))
    rows = slice(int(np.ceil((ph - y1 + s) * k)), int((ph - y0 - s) * k))
    patch = img[rows, cols].astype(int)
    assert patch.size
    assert (patch[..., 0] > 200).all()  # red text on white: red stays high; black lines do not
    assert (patch[..., 1] < 128).any()  # the text is there


def test_plotter_outputs_keep_the_gaps(drawing: lg.Drawing, tmp_path: Path):
    sized = drawing.sized(width=WIDTH)
    boxes, discs = sized.halo_regions()
    # for_plotter (merged, sorted paths) then SVG: the cut happens on the page
    # (the page of the cleaned drawing is laid out from its own strokes)
    plotted = drawing.for_plotter(width=WIDTH)
    lines, _ = _svg_polylines(plotted.save(tmp_path / "p.svg", width=WIDTH))
    assert _segments_inside(lines, *plotted.sized(width=WIDTH).halo_regions(), 2e-3) == 0
    # HPGL (plotter units of 1/40 mm, rounded: 0.036 pt)
    pytest.importorskip("lgraph_hpgl")
    with pytest.warns(UserWarning, match="TeX mathematics left out"):  # its stroke font
        text = drawing.save(tmp_path / "h.hpgl", width=WIDTH).read_text()
    unit = 1016 / 72
    paths = []
    for m in re.finditer(r"PU(-?\d+),(-?\d+);PD([-\d,]+);", text):
        p = np.array([m.group(1), m.group(2), *m.group(3).split(",")], float).reshape(-1, 2)
        paths.append(p / unit)
    lines = [p for p in paths if np.ptp(p, axis=0).max() > 0]
    assert len(lines) > 50
    assert _segments_inside(lines, boxes, discs, 0.05) == 0


def test_vpype_reads_the_cut_svg(drawing: lg.Drawing, tmp_path: Path):
    vpype = pytest.importorskip("vpype")
    path = drawing.save(tmp_path / "v.svg", width=WIDTH)
    doc = vpype.read_multilayer_svg(str(path), quantization=0.01)
    sized = drawing.sized(width=WIDTH)
    boxes, discs = sized.halo_regions()
    ph = sized.page_size()[1]
    px_per_pt = 96 / 72  # vpype works in CSS pixels
    lines = []
    for layer in doc.layers.values():
        if str(layer.property("vp_name")).endswith((" labels", " point")):
            continue  # the glyph outlines, and the dot inside its own halo
        for line in layer:
            p = np.column_stack([line.real, line.imag]) / px_per_pt
            lines.append(p * (1, -1) + (0, ph))
    assert len(lines) > 50
    assert _segments_inside(lines, boxes, discs, 0.02) == 0


def test_halo_per_label_overrides_the_scene_default():
    sc = lg.Scene(halo=2.0)
    sc.add(lg.Sphere(1), lg.ParameterLines(4, 8))
    sc.add(lg.Label("A", at=(0, 0, 1), always=True))
    sc.add(lg.Label("B", at=(0, 1, 0), always=True, halo=False))
    sc.add(lg.Label("C", at=(1, 0, 0), always=True, halo=0.5))
    sc.add(lg.Point((0, -1, 0), always=True))
    d = sc.render(lg.ParallelProjector(direction=(1, 1, 1)))
    assert [lab.halo for lab in d.labels] == [2.0, None, 0.5]
    assert [s.halo for s in d.strokes if s.family == "point"] == [2.0]
    plain = lg.Scene()
    plain.add(lg.Label("A", at=(0, 0, 1), halo=True))
    assert plain.render(lg.ParallelProjector(direction=(1, 1, 1))).labels[0].halo == 1.5


def test_bad_halos_are_refused_naming_the_class():
    with pytest.raises(ValueError, match="Label 'A': halo must be True, False, None or a gap"):
        lg.Label("A", at=(0, 0, 0), halo=-1)
    with pytest.raises(ValueError, match="Point: halo must be"):
        lg.Point((0, 0, 0), halo="wide")
    with pytest.raises(ValueError, match="Scene: halo must be"):
        lg.Scene(halo=float("nan"))


def test_scene_files_give_labels_and_points_halos(tmp_path: Path):
    path = tmp_path / "s.toml"
    path.write_text(
        '[projector]\nkind = "parallel"\ndirection = [1, 1, 1]\n\n'
        '[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n\n'
        '[[labels]]\ntext = "$P$"\nat = [0, 0, 1]\nhalo = 2\n\n'
        "[[points]]\nat = [1, 0, 0]\nhalo = true\n"
    )
    scene = lg.load_scene_file(path)[0]
    assert [lab.halo for lab in scene.labels] == [2.0]
    assert [p.halo for p in scene.points] == [1.5]
    path.write_text(path.read_text().replace("halo = 2", 'halo = "wide"'))
    with pytest.raises(lg.SceneFileError, match="labels"):
        lg.load_scene_file(path)
