"""Exact curves at any size (issue #27): ``save(..., curves="bezier",
precision=...)`` writes cubic Bézier segments whose distance from the exact
projected curve -- evaluated here independently, densely, from the curve
batch, the node's transform and the projector -- is within the precision at
A0 width, with stroke ends (visibility transitions) exact, smooth joints,
in PDF, SVG and TikZ, read by vpype."""

from __future__ import annotations

import re
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from page_curves import deviation, flatten

import lgraph as lg
from lgraph.output.backends._common import page_runs
from lgraph.output.bezier import page_curve_runs
from lgraph.output.units import length_pt

SVG = "{http://www.w3.org/2000/svg}"
A0 = "841mm"
PRECISION = length_pt("0.01mm")


def _ellipsoid() -> lg.Drawing:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(6, 8))
    return scene.render(lg.CentralProjector.from_angles(35, 25, 16), hidden_lines=True)


def _bumpy_torus() -> lg.Drawing:
    """A parametric surface with the numeric contour (marching squares and Newton)."""

    def f(u, v):
        r = 0.6 + 0.12 * np.sin(5 * v)
        return np.stack([(2 + r * np.cos(u)) * np.cos(v), (2 + r * np.cos(u)) * np.sin(v),
                         r * np.sin(u)], axis=-1)  # fmt: skip

    s = lg.ParametricSurface(f, (0, 2 * np.pi), (0, 2 * np.pi), periodic=(True, True))
    scene = lg.Scene()
    scene.add(s, lg.ParameterLines(6, 10))
    return scene.render(lg.ParallelProjector.from_angles(-50, 40), hidden_lines=True)


@pytest.fixture(scope="module", params=["ellipsoid", "bumpy torus"])
def sized(request) -> lg.Drawing:
    d = _ellipsoid() if request.param == "ellipsoid" else _bumpy_torus()
    return d.sized(width=A0)


def test_bezier_deviation_from_the_exact_curve_at_a0(sized: lg.Drawing):
    scale, offset, _, _ = sized._layout()
    runs = [r for r in page_curve_runs(sized, PRECISION) if r[2]]
    assert len(runs) >= 10
    worst = 0.0
    for ctrl, stroke, _ in runs:
        # both ways: the true curve near the Bézier and the Bézier near the true curve
        worst = max(worst, deviation(ctrl, stroke, True, scale, offset))
        # ends exact: the stroke's first and last samples (visibility transitions)
        assert np.allclose(ctrl[0], stroke.xy[0] * scale + offset, atol=1e-9, rtol=0)
        assert np.allclose(ctrl[-1], stroke.xy[-1] * scale + offset, atol=1e-9, rtol=0)
    assert worst <= 1.02 * PRECISION  # dense sampling of the true curve: within 2 %


def test_joints_are_smooth_and_segments_fewer_than_samples(sized: lg.Drawing):
    runs = [r for r in page_curve_runs(sized, PRECISION) if r[2]]
    segments = sum((len(c) - 1) // 3 for c, _, _ in runs)
    samples = sum(len(s.xy) - 1 for _, s, _ in runs)
    assert segments < samples  # at A0 and 0.01 mm, still fewer than the 1e-4 chords
    cosines = []
    for ctrl, _, _ in runs:
        into = ctrl[3:-1:3] - ctrl[2:-2:3]
        out = ctrl[4::3] - ctrl[3:-1:3]
        n = np.linalg.norm(into, axis=1) * np.linalg.norm(out, axis=1)
        ok = n > 1e-12
        cosines.extend((np.einsum("ij,ij->i", into, out)[ok] / n[ok]).tolist())
    assert np.median(cosines) > 1 - 1e-9 and np.quantile(cosines, 0.99) > 0.9999


def test_every_vector_backend_writes_the_same_curves(tmp_path: Path):
    d = _ellipsoid()
    sized = d.sized(width="8cm")
    runs = page_curve_runs(sized, PRECISION)
    n_curves = sum((len(c) - 1) // 3 for c, _, b in runs if b)
    # SVG: <path d="M.. C.."> with the same control points (3 decimals)
    svg = d.save(tmp_path / "b.svg", width="8cm", curves="bezier", precision="0.01mm")
    root = ET.parse(svg).getroot()
    paths = [p for p in root.iter(SVG + "path") if p.get("data-family")]
    assert sum(p.get("d").count("C") for p in paths) == n_curves
    ph = float(root.get("viewBox").split()[3])
    got = sorted(
        tuple(np.round(np.array(re.findall(r"-?[\d.]+", p.get("d")), float)[:2] * (1, -1)
                       + (0, ph), 2)) for p in paths
    )  # fmt: skip
    want = sorted(tuple(np.round(c[0], 2)) for c, _, b in runs if b)
    assert np.allclose(got, want, atol=0.011)
    # PDF: "c" operators
    pdf = d.save(tmp_path / "b.pdf", width="8cm", curves="bezier", compress=False).read_bytes()
    assert len(re.findall(rb" c\n", pdf)) == n_curves
    # TikZ: ".. controls (a) and (b) .."
    pytest.importorskip("lgraph_tikz")
    tex = d.save(tmp_path / "b.tex", width="8cm", curves="bezier").read_text()
    assert tex.count(".. controls") == n_curves
    # polylines are the default: no curves
    plain = d.save(tmp_path / "p.svg", width="8cm").read_text()
    assert " C" not in plain and "<polyline" in plain


def test_vpype_reads_the_bezier_svg_and_its_lengths_agree(tmp_path: Path):
    vpype = pytest.importorskip("vpype")
    d = _ellipsoid()
    path = d.save(tmp_path / "v.svg", width=A0, curves="bezier")
    # the command line reads it ...
    out = subprocess.run(["vpype", "read", str(path), "stat"], capture_output=True,
                         text=True, timeout=300)  # fmt: skip
    assert out.returncode == 0 and "Path count" in out.stdout, out.stderr
    # ... and the layers it flattens are as long as the exact curves: a little
    # longer than the polylines' chords (px = 1/96 in, pt = 1/72 in)
    doc = vpype.read_multilayer_svg(str(path), quantization=0.1)
    total = sum(layer.length() for layer in doc.layers.values()) * 72 / 96
    poly = sum(
        np.linalg.norm(np.diff(p, axis=0), axis=1).sum() for p, _ in page_runs(d.sized(width=A0))
    )
    assert poly <= total <= poly * 1.001


def test_halos_cut_the_curves_where_they_cross_the_edges(tmp_path: Path):
    scene = lg.Scene(halo=True)
    scene.add(lg.Sphere(1), lg.ParameterLines(16, 24))
    scene.add(lg.Label("$\\kappa_n = \\frac{L}{E}$", at=(0, 0, 0), always=True, size=14))
    d = scene.render(lg.ParallelProjector(direction=(0.3, -1, 0.4))).sized(width="6cm")
    (box,), _ = d.halo_regions()
    runs = [r for r in page_curve_runs(d, PRECISION) if r[2]]
    flat = np.concatenate([flatten(c) for c, _, _ in runs])
    x, y = flat[:, 0], flat[:, 1]
    e = 1e-6
    assert not ((x > box[0] + e) & (x < box[2] - e) & (y > box[1] + e) & (y < box[3] - e)).any()
    ends = np.concatenate([[c[0], c[-1]] for c, _, _ in runs])
    on_edge = np.minimum.reduce([abs(ends[:, 0] - box[0]), abs(ends[:, 0] - box[2]),
                                 abs(ends[:, 1] - box[1]), abs(ends[:, 1] - box[3])])  # fmt: skip
    assert (on_edge < 1e-9).sum() >= 4  # cut ends lie on the box's edge, to bisection accuracy


def test_strokes_without_their_curve_stay_polylines():
    s = lg.Stroke(xy=np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]), xyz=np.zeros((3, 3)))
    runs = page_curve_runs(lg.Drawing((s,)), PRECISION)
    assert [(len(p), b) for p, _, b in runs] == [(3, False)]
    # so do plotter-cleaned drawings (merged paths have no one curve parameter)
    d = _ellipsoid().for_plotter()
    assert not any(b for _, _, b in page_curve_runs(d, PRECISION))


def test_bad_curve_options_are_refused(tmp_path: Path):
    d = _ellipsoid()
    with pytest.raises(ValueError, match="write_svg: curves must be 'polyline' or 'bezier'"):
        d.save(tmp_path / "x.svg", curves="splines")
    with pytest.raises(ValueError, match="a length is the deviation of curves='bezier'"):
        d.save(tmp_path / "x.pdf", precision="0.01mm")
    with pytest.raises(ValueError, match="precision must be a positive length"):
        d.save(tmp_path / "x.pdf", curves="bezier", precision="0mm")
    assert not list(tmp_path.iterdir())


def test_drawings_still_pickle_and_then_draw_polylines():
    import pickle

    d = _ellipsoid()
    back = pickle.loads(pickle.dumps(d))
    assert len(back.strokes) == len(d.strokes) and all(s.curve is None for s in back.strokes)
    assert not any(b for _, _, b in page_curve_runs(back, PRECISION))


def test_scene_files_and_the_command_line_take_the_new_save_keys(tmp_path: Path):
    path = tmp_path / "b.toml"
    path.write_text(
        '[projector]\nkind = "parallel"\ndirection = [1, 1, 1]\n\n'
        '[save]\ncurves = "bezier"\nprecision = "0.02mm"\ntext = "text"\nmargin = "1mm"\n'
        'background = "none"\n\n[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
    )
    save = lg.load_scene_file(path)[2]["save"]
    assert save["curves"] == "bezier" and save["precision"] == "0.02mm"
    assert save["margin"] == pytest.approx(length_pt("1mm"))
    from lgraph.cli import main

    assert main(["render", str(path), "-o", str(tmp_path / "b.svg")]) in (0, None)
    svg = (tmp_path / "b.svg").read_text()
    assert "<path" in svg and " C" in svg
    path.write_text(path.read_text().replace('"0.02mm"', '"0.02 parsecs"'))
    with pytest.raises(lg.SceneFileError, match="save.precision"):
        lg.load_scene_file(path)


def test_png_names_the_formats_that_take_curves_and_text(tmp_path):
    """PNG is pixels: ``curves=``/``text=`` are refused with a message that
    says which formats take them, and nothing is written."""
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(2, 4))
    d = scene.render(lg.ParallelProjector(direction=(1, 2, 3)))
    with pytest.raises(TypeError, match=r"curves= belong to the vector formats \(PDF, SVG, TikZ\)"):
        d.save(tmp_path / "f.png", curves="bezier")
    with pytest.raises(TypeError, match="curves= and text= belong"):
        d.save(tmp_path / "f.png", curves="bezier", text="text")
    assert list(tmp_path.iterdir()) == []
