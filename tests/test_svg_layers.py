"""Layered SVG in mm, read back by XML and by vpype (the pen-plotter tool)."""

from __future__ import annotations

import importlib.util
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import lgraph as lg
from lgraph.gallery import render_figure
from lgraph.output.backends._common import finite_runs
from lgraph.output.drawing import Drawing, Page, Stroke, Style
from lgraph.output.layers import drawing_layers
from lgraph.output.units import length_pt

SVG = "{http://www.w3.org/2000/svg}"
INK = "{http://www.inkscape.org/namespaces/inkscape}"
GALLERY = Path(__file__).resolve().parent.parent / "gallery"
PX_PER_MM = 96 / 25.4


def two_surfaces() -> Drawing:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(5, 6))
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 4), transform=lg.translate(4, 0, 0))
    return scene.render(lg.ParallelProjector.from_angles(30, 20), hidden_lines=True)


def layers_of(path: Path) -> list[ET.Element]:
    return ET.parse(path).getroot().findall(SVG + "g")


def points(el: ET.Element) -> np.ndarray:
    return np.array([p.split(",") for p in el.get("points").split()], float)


def test_one_layer_per_family_with_one_style_each(tmp_path: Path) -> None:
    d = two_surfaces()
    path = d.save(tmp_path / "fig.svg")
    groups = layers_of(path)
    labels = [g.get(INK + "label") for g in groups]
    assert labels == ["1 hidden", "2 curvature", "3 contour", "4 u1", "5 u2"]
    assert [g.get("id") for g in groups] == [f"layer{k}" for k in range(1, 6)]
    assert all(g.get(INK + "groupmode") == "layer" for g in groups)
    families = {s.family for s in d.strokes if s.visible}
    assert {lab.split()[1] for lab in labels} == families | {"hidden"}
    for g in groups:  # the style is the layer's: no polyline overrides it
        name = g.get(INK + "label").split()[1]
        members = [s for s in d.strokes if (not s.visible if name == "hidden" else
                   s.visible and s.family == name)]  # fmt: skip
        assert g.get("stroke-width") == f"{members[0].style.width:g}"
        assert len({s.style for s in members}) == 1
        lines = g.findall(SVG + "polyline")
        assert all(line.get("stroke") is None for line in lines)
        assert len(lines) == sum(len(finite_runs(s.xy)) for s in members)
    assert (g.get("stroke-dasharray") for g in groups).__next__() == "2 1.5"  # hidden: dashed


def test_layers_per_surface_and_styles_split(tmp_path: Path) -> None:
    d = two_surfaces()
    labels = [g.get(INK + "label") for g in layers_of(d.save(tmp_path / "s.svg", layers="surface"))]
    # the contour is drawn wider than the lines on the surface: a layer of its own
    assert labels == ["1 hidden", "2 ellipsoid", "3 ellipsoid-contour", "4 sphere",
                      "5 sphere-contour"]  # fmt: skip
    red = Style(color="#ff0000")
    strokes = [Stroke(xy=np.array([[0.0, k], [1.0, k]]), xyz=np.zeros((2, 3)), family="u1",
                      style=red if k % 2 else Style()) for k in range(4)]  # fmt: skip
    groups = layers_of(Drawing(strokes=strokes).save(tmp_path / "r.svg"))
    assert [(g.get(INK + "label"), g.get("stroke"), len(g)) for g in groups] == [
        ("1 u1", "#000000", 2),
        ("2 u1-2", "#ff0000", 2),
    ]
    none = ET.parse(d.save(tmp_path / "n.svg", layers=None)).getroot()
    assert none.find(SVG + "g") is None
    assert len(none.findall(SVG + "polyline")) == sum(len(finite_runs(s.xy)) for s in d.strokes)


def test_width_in_mm_scales_the_page_not_the_lines(tmp_path: Path) -> None:
    d = two_surfaces()
    root = ET.parse(d.save(tmp_path / "w.svg", width="200mm")).getroot()
    sized = d.sized(width="200mm")  # what save(width=...) draws (lgraph.Drawing.sized)
    pw, ph = sized.page_size()
    assert pw == pytest.approx(length_pt("200mm"))
    assert root.get("width") == "200mm"
    assert float(root.get("height")[:-2]) == pytest.approx(ph / length_pt("1mm"), abs=1e-4)
    vb = [float(x) for x in root.get("viewBox").split()]
    assert vb[:2] == [0, 0] and vb[2] == pytest.approx(pw, abs=1e-4)
    assert vb[3] == pytest.approx(ph, abs=1e-4)
    # the points are the page points of the sized drawing, y flipped
    got = np.concatenate([points(el) for el in root.iter(SVG + "polyline")])
    want = np.concatenate([r for g in drawing_layers(sized) for r, _ in g.runs])
    np.testing.assert_allclose(got, want * (1, -1) + (0, ph), atol=1e-3)
    # and the figure is larger than on the default page, the lines are not wider
    assert np.ptp(got[:, 0]) > 1.05 * np.ptp(np.concatenate([r for r, _ in d.page_strokes()])[:, 0])
    assert {g.get("stroke-width") for g in root.findall(SVG + "g")} == {"0.3", "0.5", "0.8"}
    # both: the figure fits inside (aspect kept)
    root = ET.parse(d.save(tmp_path / "b.svg", width="10cm", height="10cm")).getroot()
    w, h = (float(root.get(k)[:-2]) for k in ("width", "height"))
    assert max(w, h) == pytest.approx(100, abs=1e-3) and min(w, h) <= 100


@pytest.mark.parametrize(
    "kw, msg",
    [
        ({"width": "-3mm"}, "width must be a positive length"),
        ({"width": "3 furlongs"}, "width must be a positive length"),
        ({"height": 0}, "height must be a positive length"),
        ({"layers": "pen"}, "layers must be 'family', 'surface', 'occlusion' or None"),
    ],
)
def test_bad_options_write_nothing(tmp_path: Path, kw: dict, msg: str) -> None:
    d = Drawing(strokes=(Stroke(xy=np.eye(2), xyz=np.zeros((2, 3))),), page=Page())
    with pytest.raises(ValueError, match=msg):
        d.save(tmp_path / "x.svg", **kw)
    assert list(tmp_path.iterdir()) == []


# -- vpype reads it -------------------------------------------------------------------
def test_vpype_reads_the_layers_and_the_page_size(tmp_path: Path) -> None:
    vpype_cli = pytest.importorskip(
        "vpype_cli", reason="vpype is not installed (pip install vpype)"
    )
    d = two_surfaces()
    path = d.save(tmp_path / "fig.svg", width="200mm")
    doc = vpype_cli.execute(f"read '{path}'")
    names = [doc.layers[k].property("vp_name") for k in sorted(doc.layers)]
    assert names == ["1 hidden", "2 curvature", "3 contour", "4 u1", "5 u2"]
    w, h = doc.page_size
    assert w / PX_PER_MM == pytest.approx(200, abs=1e-3)
    assert h / PX_PER_MM == pytest.approx(
        d.sized(width="200mm").page_size()[1] / length_pt("1mm"), abs=1e-3
    )
    widths = {k: doc.layers[k].property("vp_pen_width") for k in doc.layers}
    assert widths[1] == pytest.approx(0.3 * 96 / 72, rel=1e-5)  # hidden lines: 0.3 pt
    assert sum(len(layer) for layer in doc.layers.values()) == sum(
        len(finite_runs(s.xy)) for s in d.strokes
    )


@pytest.mark.parametrize("name", ["fig_7_2_ellipsoid", "extra_hidden_dashed"])
def test_travel_no_longer_than_vpype_linemerge_linesort(tmp_path: Path, name: str) -> None:
    vpype_cli = pytest.importorskip(
        "vpype_cli", reason="vpype is not installed (pip install vpype)"
    )
    spec = importlib.util.spec_from_file_location(name, GALLERY / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    d = render_figure(module.build())
    raw = d.save(tmp_path / "raw.svg", width="200mm")
    cleaned = d.for_plotter(merge="0.05mm", width="200mm")
    clean = cleaned.save(tmp_path / "clean.svg", width="200mm")

    def travel(doc) -> float:  # noqa: ANN001
        return sum(layer.pen_up_length()[0] for layer in doc.layers.values())

    theirs = vpype_cli.execute(f"read '{raw}' linemerge linesort")
    ours = vpype_cli.execute(f"read '{clean}'")
    assert travel(ours) <= travel(theirs)
    assert sum(map(len, ours.layers.values())) <= sum(map(len, theirs.layers.values()))
    # and our own measure agrees with vpype's (px -> pt)
    assert travel(ours) * 72 / 96 == pytest.approx(
        cleaned.sized(width="200mm").pen_up_length(),
        rel=1e-5,  # SVG keeps 3 decimals
    )


def test_labels_never_start_with_axidraw_command_characters(tmp_path: Path) -> None:
    strokes = [Stroke(xy=np.eye(2) * (k + 1), xyz=np.zeros((2, 3)), family=name)
               for k, name in enumerate(["%pause", "!skip", "two words", "%"])]  # fmt: skip
    labels = [
        g.get(INK + "label") for g in layers_of(Drawing(strokes=strokes).save(tmp_path / "a.svg"))
    ]
    assert labels == ["1 pause", "2 skip", "3 two-words", "4 layer"]
    assert all(not lab.split(" ", 1)[1].startswith(("%", "!")) for lab in labels)
