"""Tests of the vpype command: the document it builds is compared with lgraph's
own rendering of the same scene file, and written/read back through vpype."""

from __future__ import annotations

import importlib.metadata as md
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

vp = pytest.importorskip("vpype", reason="vpype is not installed (pip install vpype)")
vpype_cli = pytest.importorskip("vpype_cli", reason="vpype is not installed (pip install vpype)")

from vpype_lgraph import PX_PER_PT, drawing_to_document, lgraph  # noqa: E402

from lgraph.output.drawing import dash_polyline  # noqa: E402
from lgraph.output.layers import drawing_layers  # noqa: E402
from lgraph.scenefile import load_scene_file  # noqa: E402

SCENE = """
[projector]
kind = "parallel"
azimuth = 30
elevation = 20

[[object]]
surface = "ellipsoid"
params = { a = 3, b = 2, c = 1.3 }
families = [{ name = "lines_of_curvature", n1 = 5, n2 = 6 }]

[[object]]
surface = "sphere"
params = { r = 1 }
families = [{ name = "parameter_lines", n1 = 3, n2 = 4 }]
transform = [{ translate = [4, 0, 0] }]
"""


def installed() -> bool:
    return any(ep.name == "lgraph" for ep in md.entry_points(group="vpype.plugins"))


@pytest.fixture(scope="module", autouse=True)
def registered():  # noqa: ANN201
    """The command, through its entry point when installed, else added by hand."""
    if not installed() and "lgraph" not in vpype_cli.cli.commands:
        vpype_cli.cli.add_command(lgraph)
    yield


@pytest.fixture
def scene(tmp_path: Path) -> Path:
    path = tmp_path / "fig.toml"
    path.write_text(SCENE)
    return path


def lgraph_drawing(path: Path, hidden: bool):  # noqa: ANN201
    scn, projector, _ = load_scene_file(path)
    return scn.render(projector, hidden_lines=hidden)


def to_px(pts: np.ndarray, page_height: float) -> np.ndarray:
    return (pts[:, 0] + 1j * (page_height - pts[:, 1])) * PX_PER_PT


def test_layers_match_lgraph_rendering(scene: Path) -> None:
    doc = vpype_cli.execute(f"lgraph --hidden --no-dashes '{scene}'")
    d = lgraph_drawing(scene, hidden=True)
    layers = drawing_layers(d)
    assert sorted(doc.layers) == [layer.number for layer in layers]
    _, ph = d.page_size()
    for layer in layers:
        got = doc.layers[layer.number]
        assert got.property("vp_name") == layer.label
        assert got.property("vp_pen_width") == pytest.approx(layer.style.width * PX_PER_PT)
        rgb = tuple(round(255 * c) for c in layer.style.color)
        assert (got.property("vp_color").red, got.property("vp_color").green,
                got.property("vp_color").blue) == rgb  # fmt: skip
        assert len(got) == len(layer.runs)
        for line, (pts, _) in zip(got.lines, layer.runs):
            np.testing.assert_allclose(line, to_px(pts, ph), atol=1e-9)
    pw, ph = d.page_size()
    assert doc.page_size == pytest.approx((pw * PX_PER_PT, ph * PX_PER_PT))
    assert [doc.layers[k].property("vp_name") for k in sorted(doc.layers)] == [
        "1 hidden", "2 curvature", "3 contour", "4 u1", "5 u2"
    ]  # fmt: skip


def test_hidden_lines_are_split_into_dashes(scene: Path) -> None:
    doc = vpype_cli.execute(f"lgraph --hidden '{scene}'")
    hidden = drawing_layers(lgraph_drawing(scene, hidden=True))[0]
    assert hidden.name == "hidden" and hidden.style.dash
    dashes = [p for pts, _ in hidden.runs for p in dash_polyline(pts, hidden.style.dash)]
    assert len(doc.layers[1]) == len(dashes) > len(hidden.runs)
    on, off = hidden.style.dash
    ink = sum(np.abs(np.diff(line)).sum() for line in doc.layers[1].lines) / PX_PER_PT
    total = sum(np.linalg.norm(np.diff(p, axis=0), axis=1).sum() for p, _ in hidden.runs)
    assert ink == pytest.approx(total * on / (on + off), rel=0.1)


def test_surface_layers_and_no_hidden(scene: Path) -> None:
    doc = vpype_cli.execute(f"lgraph --layers surface '{scene}'")
    names = [doc.layers[k].property("vp_name") for k in sorted(doc.layers)]
    assert names == ["1 ellipsoid", "2 ellipsoid-contour", "3 sphere", "4 sphere-contour"]


def test_round_trip_through_vpype_write_and_read(scene: Path, tmp_path: Path) -> None:
    out = tmp_path / "out.svg"
    doc = vpype_cli.execute(f"lgraph --hidden '{scene}' linemerge linesort write '{out}'")
    back = vpype_cli.execute(f"read '{out}'")
    assert [back.layers[k].property("vp_name") for k in sorted(back.layers)] == [
        doc.layers[k].property("vp_name") for k in sorted(doc.layers)
    ]
    assert back.page_size == pytest.approx(doc.page_size, abs=1e-3)
    for k in doc.layers:
        assert len(back.layers[k]) == len(doc.layers[k])
        for a, b in zip(doc.layers[k].lines, back.layers[k].lines):
            assert len(a) == len(b) and np.abs(a - b).max() < 1e-2
    # linemerge + linesort shortened the travel of what lgraph emitted
    raw = vpype_cli.execute(f"lgraph --hidden '{scene}'")

    def travel(d) -> float:  # noqa: ANN001
        return sum(layer.pen_up_length()[0] for layer in d.layers.values())

    assert travel(doc) < travel(raw)


def test_clean_removes_duplicates_and_travel(scene: Path) -> None:
    raw = vpype_cli.execute(f"lgraph --no-dashes '{scene}'")
    clean = vpype_cli.execute(f"lgraph --no-dashes --clean '{scene}'")
    d = lgraph_drawing(scene, hidden=False)
    want = d.for_plotter()
    assert sum(map(len, clean.layers.values())) == len(want.strokes) < len(d.strokes)

    def travel(doc) -> float:  # noqa: ANN001
        return sum(layer.pen_up_length()[0] for layer in doc.layers.values())

    assert travel(clean) == pytest.approx(want.pen_up_length() * PX_PER_PT)
    assert travel(clean) < travel(vpype_cli.execute("linemerge linesort", raw))


def test_python_api_adds_layers_after_existing_ones(scene: Path) -> None:
    d = lgraph_drawing(scene, hidden=False)
    doc = drawing_to_document(d)
    doc = drawing_to_document(d, document=doc)
    n = len(drawing_layers(d))
    assert sorted(doc.layers) == list(range(1, 2 * n + 1))
    assert doc.layers[n + 1].property("vp_name") == f"{n + 1} curvature"


def test_a_bad_scene_file_is_a_clear_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENE.replace("a = 3", 'a = "three"'))
    with pytest.raises(Exception, match=r"bad\.toml:\d+: object\[0\]\.params\.a"):
        vpype_cli.execute(f"lgraph '{bad}'")


def test_command_line(scene: Path, tmp_path: Path) -> None:
    """``vpype lgraph ...`` in a fresh process (the same Python as the tests)."""
    if not installed():
        pytest.skip(
            "this plugin's entry point is not installed (pip install -e plugins/vpype-lgraph)"
        )
    out = tmp_path / "cli.svg"
    cmd = [sys.executable, "-m", "vpype_cli", "lgraph", str(scene), "linemerge", "linesort",
           "write", str(out)]  # fmt: skip
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    back = vpype_cli.execute(f"read '{out}'")
    assert [back.layers[k].property("vp_name") for k in sorted(back.layers)] == [
        "1 curvature", "2 contour", "3 u1", "4 u2"
    ]  # fmt: skip


def test_a_scene_file_with_formulas(tmp_path: Path) -> None:
    """Surfaces and curves written as formulas (no Python) reach vpype as
    lgraph draws them."""
    path = tmp_path / "moebius.toml"
    path.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 25\nelevation = 40\n'
        "[constants]\nw = 0.5\n"
        '[[object]]\nsurface = "parametric"\n'
        'x = "(1 + v*cos(u/2)) * cos(u)"\ny = "(1 + v*cos(u/2)) * sin(u)"\nz = "v*sin(u/2)"\n'
        'u = [0, "2*pi"]\nv = ["-w", "w"]\n'
        'families = [{ name = "parameter_lines", n1 = 12, n2 = 4 }]\n'
        '[[curve]]\nx = "cos(t)"\ny = "sin(t)"\nz = "0"\nt = [0, "2*pi"]\nclosed = true\n'
    )
    doc = vpype_cli.execute(f"lgraph --no-dashes '{path}'")
    layers = drawing_layers(lgraph_drawing(path, hidden=False))
    assert sum(map(len, doc.layers.values())) == sum(len(layer.runs) for layer in layers) > 16
