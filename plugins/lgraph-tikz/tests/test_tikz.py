"""Tests of the TikZ backend: parse the file back and compare with the drawing."""

from __future__ import annotations

import importlib.metadata as md
import re
import shutil
import subprocess

import numpy as np
import pytest
from lgraph_tikz import write_tikz

import lgraph as lg
from lgraph.drawing import Drawing, Page, Stroke, Style

DRAW = re.compile(r"\\draw\[(?P<opts>[^\]]*)\] (?P<coords>.*);")


def parse(text):
    out = []
    for m in DRAW.finditer(text):
        pts = np.array(re.findall(r"\(([-\d.]+),([-\d.]+)\)", m.group("coords")), float)
        out.append((m.group("opts"), pts))
    return out


def stroke(points, **kw):
    xy = np.asarray(points, float)
    return Stroke(xy=xy, xyz=np.zeros((len(xy), 3)), **kw)


def test_round_trip_of_a_rendered_scene(tmp_path):
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(4, 6))
    d = scene.render(lg.ParallelProjector.from_angles(30, 20), hidden_lines=True)
    path = tmp_path / "s.tex"
    write_tikz(d, path, precision=3)
    text = path.read_text()
    assert text.count("\\begin{tikzpicture}") == 1 and text.rstrip().endswith("\\end{tikzpicture}")
    draws = parse(text)
    expected = list(d.page_strokes())
    assert len(draws) == len(expected)
    for (opts, got), (want, s) in zip(draws, expected):
        assert got.shape == want.shape
        assert np.abs(got - want).max() <= 0.5e-3 + 1e-9
        assert f"line width={s.style.width:g}pt" in opts
        assert ("dash pattern" in opts) == bool(s.style.dash)


def test_colours_dashes_and_standalone(tmp_path):
    d = Drawing(
        strokes=(
            stroke([[0, 0], [72, 0]], style=Style(color="#ff0000", dash=(2, 1.5))),
            stroke([[0, 10], [72, 10]]),
        ),
        page=Page(margin=0, extent=72),
    )
    path = tmp_path / "c.tex"
    write_tikz(d, path, standalone=True)
    text = path.read_text()
    assert "\\definecolor{lgc0}{rgb}{1,0,0}" in text
    assert "\\definecolor{lgc1}{rgb}{0,0,0}" in text
    assert "dash pattern=on 2pt off 1.5pt" in text
    assert text.startswith("% lgraph") and "\\documentclass{standalone}" in text
    assert text.rstrip().endswith("\\end{document}")
    with pytest.raises(ValueError, match="precision must be an integer"):
        write_tikz(d, path, precision=9)


def test_standalone_file_compiles_when_latex_is_present(tmp_path):
    d = Drawing(strokes=(stroke([[0, 0], [72, 36]], style=Style(dash=(3, 2))),))
    path = tmp_path / "fig.tex"
    write_tikz(d, path, standalone=True)
    latex = shutil.which("pdflatex")
    if latex is None:
        # no TeX here: check the structure TeX needs instead
        text = path.read_text()
        assert text.count("{") == text.count("}")
        assert text.index("\\begin{document}") < text.index("\\begin{tikzpicture}")
        return
    r = subprocess.run(
        [latex, "-interaction=nonstopmode", "-halt-on-error", path.name],
        cwd=tmp_path, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert r.returncode == 0, r.stdout[-2000:]
    assert (tmp_path / "fig.pdf").stat().st_size > 0


def test_registered_as_the_tex_backend(tmp_path):
    names = {dist.metadata["Name"] for dist in md.distributions()}
    if "lgraph-tikz" not in names:  # pragma: no cover
        pytest.fail("lgraph-tikz is not installed: run pip install -e plugins/lgraph-tikz")
    from lgraph.backends import backend_suffixes

    assert ".tex" in backend_suffixes()
    d = Drawing(strokes=(stroke([[0, 0], [1, 1]]),))
    d.save(tmp_path / "x.tex", standalone=True)
    assert "\\documentclass{standalone}" in (tmp_path / "x.tex").read_text()


def test_label_nodes_carry_the_raw_tex_and_the_anchor(tmp_path):
    from lgraph_tikz import write_tikz

    import lgraph as lg

    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(2, 4))
    scene.add(lg.Label("$\\kappa_n N$", at=(0, 0, 1.4), anchor="ne", color="#cc0000"))
    d = scene.render(lg.ParallelProjector(direction=(1, 0, 0.2)))
    path = tmp_path / "a.tex"
    write_tikz(d, path)
    text = path.read_text()
    (node,) = [ln for ln in text.splitlines() if ln.startswith("\\node")]
    assert "anchor=north east" in node and node.endswith("{$\\kappa_n N$};")
    assert "font" not in node
    import re

    at = [float(v) for v in re.search(r"at \(([-\d.]+),([-\d.]+)\)", node).groups()]
    np.testing.assert_allclose(at, d.label_positions()[0], atol=1e-4)
