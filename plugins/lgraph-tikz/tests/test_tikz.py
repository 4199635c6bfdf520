"""Tests of the TikZ backend: parse the file back and compare with the drawing;
compile it with pdflatex (standalone and \\input into an article) where TeX is installed."""

from __future__ import annotations

import importlib.metadata as md
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from lgraph_tikz import write_tikz

import lgraph as lg
from lgraph.output.drawing import Drawing, Stroke
from lgraph.output.layers import drawing_layers
from lgraph.output.units import UNITS, length_pt

DRAW = re.compile(r"\\draw\[lgraph/(?P<name>[^\]]*)\] (?P<coords>.*);")
STYLE = re.compile(r"\\lgraphstyle\{(?P<name>[^}]*)\}\{(?P<opts>.*)\}$", re.M)
CM = UNITS["cm"]


def parse(text: str) -> list[tuple[str, np.ndarray]]:
    out = []
    for m in DRAW.finditer(text):
        pts = np.array(re.findall(r"\(([-\d.]+),([-\d.]+)\)", m.group("coords")), float)
        out.append((m.group("name"), pts))
    return out


def stroke(points, **kw) -> Stroke:
    xy = np.asarray(points, float)
    return Stroke(xy=xy, xyz=np.zeros((len(xy), 3)), **kw)


def rendered() -> Drawing:
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(4, 6))
    return scene.render(lg.ParallelProjector.from_angles(30, 20), hidden_lines=True)


def test_round_trip_in_cm_with_one_named_style_per_layer(tmp_path: Path) -> None:
    d = rendered()
    path = tmp_path / "s.tex"
    write_tikz(d, path, precision=4)
    text = path.read_text()
    assert text.count("\\begin{tikzpicture}") == 1
    assert text.rstrip().endswith("\\end{tikzpicture}%")
    assert "\\documentclass" not in text
    layers = drawing_layers(d)
    styles = {m.group("name"): m.group("opts") for m in STYLE.finditer(text)}
    assert list(styles) == [g.name for g in layers]
    assert sorted(styles) == ["contour", "hidden", "u1", "u2"]
    for g in layers:
        assert f"line width={g.style.width:g}bp" in styles[g.name]
        assert ("dash pattern=on 2bp off 1.5bp" in styles[g.name]) == (g.name == "hidden")
    draws = parse(text)
    expected = [(g.name, pts) for g in layers for pts, _ in g.runs]
    assert [n for n, _ in draws] == [n for n, _ in expected]
    for (_, got), (_, want) in zip(draws, expected):
        assert got.shape == want.shape
        assert np.abs(got * CM - want).max() <= 0.5e-4 * CM + 1e-9
    w, h = d.page_size()
    assert f"\\useasboundingbox (0,0) rectangle ({w / CM:.4f}".rstrip("0") in text


def test_width_as_save_gives_it_line_widths_kept(tmp_path: Path) -> None:
    d = rendered()
    write_tikz(d, tmp_path / "a.tex", precision=5)
    write_tikz(d, tmp_path / "b.tex", precision=5, width="8.5cm")
    a, b = (tmp_path / "a.tex").read_text(), (tmp_path / "b.tex").read_text()
    sized = d.sized(width="8.5cm")
    want = np.concatenate([pts for g in drawing_layers(sized) for pts, _ in g.runs]) / CM
    got = np.concatenate([p for _, p in parse(b)])
    np.testing.assert_allclose(got, want, atol=6e-6)
    assert "rectangle (8.5," in b
    assert dict(m.groups() for m in STYLE.finditer(a)) == dict(
        m.groups() for m in STYLE.finditer(b)
    )
    if registered():  # Drawing.save(width=...) gives the same file
        d.save(tmp_path / "c.tex", precision=5, width="8.5cm")
        assert (tmp_path / "c.tex").read_text() == b


def test_surface_styles_and_labels(tmp_path: Path) -> None:
    d = rendered()
    write_tikz(d, tmp_path / "s.tex", layers="surface")
    names = [m.group("name") for m in STYLE.finditer((tmp_path / "s.tex").read_text())]
    assert sorted(names) == ["hidden", "sphere", "sphere-contour"]

    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(2, 4))
    scene.add(lg.Label("$\\kappa_n N$", at=(0, 0, 1.4), anchor="ne", color="#cc0000"))
    scene.add(lg.Label("$P$", at=(0, 0, 0), anchor="sw", offset=(3, 2)))  # hidden by the sphere
    labelled = scene.render(lg.ParallelProjector(direction=(1, 0, 0.2)), hidden_lines=True)
    write_tikz(labelled, tmp_path / "l.tex", width="6cm")
    text = (tmp_path / "l.tex").read_text()
    nodes = re.findall(r"\\node\[anchor=([a-z ]+), text=\{rgb,255:red,(\d+);green,(\d+);"
                       r"blue,(\d+)\}, (lgraph/[a-z-]+)\] at \(([-\d.]+),([-\d.]+)\) \{(.*)\};",
                       text)  # fmt: skip
    sized = labelled.sized(width="6cm")
    assert [(n[0], n[4], n[7]) for n in nodes] == [
        (lab_anchor, style, lab.text)
        for lab, lab_anchor, style in zip(
            sized.labels, ("north east", "south west"), ("lgraph/label", "lgraph/hidden-label")
        )
    ]
    assert tuple(map(int, nodes[0][1:4])) == (204, 0, 0)
    at = np.array([[float(n[5]), float(n[6])] for n in nodes]) * CM
    np.testing.assert_allclose(at, sized.label_positions(), atol=0.6e-3 * CM)
    assert "font" not in text
    assert "\\lgraphstyle{label}{}" in text and "\\lgraphstyle{hidden-label}{}" in text


@pytest.mark.parametrize(
    "kw, msg",
    [
        ({"width": "-2cm"}, "width must be a positive length"),
        ({"width": "2 furlongs"}, "width must be a positive length"),
        ({"width": 0}, "width must be a positive length"),
        ({"standalone": "yes"}, "standalone must be True or False"),
        ({"layers": "pens"}, "layers must be 'family' or 'surface'"),
        ({"precision": 9}, "precision must be an integer"),
    ],
)
def test_bad_options_write_nothing(tmp_path: Path, kw: dict, msg: str) -> None:
    path = tmp_path / "x.tex"
    with pytest.raises(ValueError, match=msg):
        write_tikz(rendered(), path, **kw)
    assert not path.exists()


# -- TeX --------------------------------------------------------------------------------
def pdflatex(folder: Path, source: str) -> Path:
    """Compile ``source`` (a file name in ``folder``) uncompressed; return the PDF."""
    exe = shutil.which("pdflatex")
    if exe is None:
        pytest.skip("pdflatex is not installed (Debian: apt-get install texlive-latex-base "
                    "texlive-pictures; .ci/plugins.sh does it)")  # fmt: skip
    stem = Path(source).stem
    r = subprocess.run(
        [exe, "-interaction=nonstopmode", "-halt-on-error", f"-jobname={stem}",
         f"\\pdfcompresslevel=0\\pdfobjcompresslevel=0\\input{{{source}}}"],
        cwd=folder, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert r.returncode == 0, r.stdout[-3000:]
    return folder / f"{stem}.pdf"


def media_boxes(pdf: Path) -> list[list[float]]:
    data = pdf.read_bytes().decode("latin-1")
    return [[float(x) for x in m.split()] for m in re.findall(r"/MediaBox\s*\[([^\]]*)\]", data)]


def test_standalone_compiles_to_a_page_of_the_requested_width(tmp_path: Path) -> None:
    d = rendered()
    write_tikz(d, tmp_path / "fig.tex", standalone=True, width="8.5cm")
    pdf = pdflatex(tmp_path, "fig.tex")
    (box,) = media_boxes(pdf)
    w = length_pt("8.5cm")
    assert box[0] == 0 and box[1] == 0
    assert box[2] == pytest.approx(w, abs=0.01)
    assert box[3] == pytest.approx(w * d.page_size()[1] / d.page_size()[0], abs=0.01)
    assert "1 0 0 RG" not in pdf.read_bytes().decode("latin-1")


def test_input_into_an_article_restyled_from_the_preamble(tmp_path: Path) -> None:
    d = rendered()
    write_tikz(d, tmp_path / "body.tex", width="6cm")
    (tmp_path / "doc.tex").write_text(
        "\\documentclass{article}\n\\usepackage{tikz}\n"
        "\\tikzset{lgraph/contour/.style={draw=red, line width=2pt}}\n"
        "\\begin{document}\nFigure 1:\n\n\\input{body.tex}\n\n"
        "Figure 2: \\input{body.tex}\n\\end{document}\n"
    )
    pdf = pdflatex(tmp_path, "doc.tex")
    assert len(media_boxes(pdf)) == 1  # one page
    content = pdf.read_bytes().decode("latin-1")
    assert content.count("1 0 0 RG") >= 2  # the document's red contour, in both figures
    assert "0.35" in content or "0.349" in content  # the file's own grey for hidden lines


# -- registration and the command line -------------------------------------------------
def registered() -> bool:
    return "lgraph-tikz" in {dist.metadata["Name"] for dist in md.distributions()}


def test_registered_as_the_tex_backend(tmp_path: Path) -> None:
    if not registered():
        pytest.skip("lgraph-tikz is not installed: pip install -e plugins/lgraph-tikz")
    from lgraph.output.backends import backend_suffixes

    assert ".tex" in backend_suffixes()
    d = Drawing(strokes=(stroke([[0, 0], [1, 1]]),))
    d.save(tmp_path / "x.tex", standalone=True, width="3cm")
    text = (tmp_path / "x.tex").read_text()
    assert "\\documentclass{article}" in text and "rectangle (3,3)" in text
    with pytest.raises(ValueError, match="width must be a positive length"):
        d.save(tmp_path / "y.tex", width="-3cm")
    assert not (tmp_path / "y.tex").exists()


SPHERE_SCENE = (
    '[projector]\nkind = "parallel"\nazimuth = 30\nelevation = 20\n'
    '[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
)


def _render(tmp_path: Path, scene_text: str) -> tuple[subprocess.CompletedProcess, Path]:
    """``lgraph render fig.toml -o fig.tex`` in a child process."""
    if not registered():
        pytest.skip("lgraph-tikz is not installed: pip install -e plugins/lgraph-tikz")
    scene, out = tmp_path / "fig.toml", tmp_path / "fig.tex"
    scene.write_text(scene_text)
    r = subprocess.run([sys.executable, "-m", "lgraph", "render", str(scene), "-o", str(out)],
                       capture_output=True, text=True, timeout=300)  # fmt: skip
    return r, out


def test_lgraph_render_writes_tikz(tmp_path: Path) -> None:
    r, out = _render(
        tmp_path, SPHERE_SCENE + 'families = [{ name = "parameter_lines", n1 = 3, n2 = 4 }]\n'
    )
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    assert "\\begin{tikzpicture}" in text
    assert sorted(m.group("name") for m in STYLE.finditer(text)) == ["contour", "u1", "u2"]


def test_scene_file_save_options_reach_the_tikz_writer(tmp_path: Path) -> None:
    """``[save] standalone = true, width = "6cm"`` of a scene file: checked
    against the options the TikZ writer declares, then passed to it."""
    save = '[save]\nstandalone = true\nwidth = "6cm"\n'
    r, out = _render(tmp_path, SPHERE_SCENE + save)
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    assert text.count("\\documentclass") == 1 and "\\end{document}" in text
    assert "6 x 6 cm" in text
    r, _ = _render(tmp_path, SPHERE_SCENE + save + "standalone_typo = 1\n")
    assert r.returncode == 2 and "standalone_typo" in r.stderr
