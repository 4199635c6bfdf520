"""The document's TeX for TikZ (issue #27): label text goes to TeX as
written -- document macros allowed, mathtext used only where lgraph draws
glyphs itself -- and labels from scene files cannot reach files or the shell
when the figure is compiled.  Compiled with pdflatex where it is installed
(.ci/plugins.sh installs Debian's texlive-latex-base and texlive-pictures)."""

from __future__ import annotations

import io
import os
import shutil
import subprocess
from pathlib import Path

import pytest

import lgraph as lg

pytest.importorskip("lgraph_tikz")

MACROS = r"$\vx_1 + \tfrac{1}{2}\,\vx_2$"


def _pdflatex(folder: Path, source: str) -> subprocess.CompletedProcess:
    exe = shutil.which("pdflatex")
    if exe is None:
        pytest.skip("pdflatex is not installed (Debian: apt-get install texlive-latex-base "
                    "texlive-pictures; .ci/plugins.sh installs them)")  # fmt: skip
    env = {**os.environ, "openout_any": "p", "openin_any": "p", "shell_escape": "f"}
    return subprocess.run(
        [exe, "-no-shell-escape", "-interaction=nonstopmode", "-halt-on-error", source],
        cwd=folder, capture_output=True, text=True, timeout=300, env=env,
    )  # fmt: skip


def _scene(text: str) -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 6))
    scene.add(lg.Label(text, at=(0, 0, 1.2), anchor="s", always=True))
    return scene


def _document(folder: Path, figure: str) -> None:
    (folder / "doc.tex").write_text(
        "\\documentclass{article}\n\\usepackage{amsmath}\n\\usepackage{tikz}\n"
        "\\newcommand\\vx{\\mathbf{x}}\n\\pagestyle{empty}\n"
        f"\\begin{{document}}\n\\input{{{figure}}}\n\\end{{document}}\n"
    )


def test_document_macros_pass_to_tex_and_compile(tmp_path: Path):
    d = _scene(MACROS).render(lg.ParallelProjector.from_angles(30, 20))
    tex = d.save(tmp_path / "fig.tex", width="6cm").read_text()
    assert "{" + MACROS + "};" in tex  # as written
    _document(tmp_path, "fig.tex")
    r = _pdflatex(tmp_path, "doc.tex")
    assert r.returncode == 0, r.stdout[-2000:]
    assert "Undefined control sequence" not in r.stdout
    if shutil.which("pdftotext"):
        text = subprocess.run(["pdftotext", str(tmp_path / "doc.pdf"), "-"],
                              capture_output=True, text=True, timeout=60).stdout  # fmt: skip
        assert "x" in text and "1" in text and "2" in text


def test_where_lgraph_draws_the_glyphs_unknown_tex_is_refused_before_writing(tmp_path: Path):
    pytest.importorskip("matplotlib")
    d = _scene(MACROS).render(lg.ParallelProjector.from_angles(30, 20))
    for suffix in (".pdf", ".svg", ".png"):
        with pytest.raises(ValueError, match=r"unknown TeX .* the TikZ backend \(\.tex\)"):
            d.save(tmp_path / f"fig{suffix}")
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="unknown TeX"):
        d.save(io.BytesIO(), format="pdf")


HOSTILE = [
    r"\input{/etc/passwd}",
    r"$x$ \immediate\write18{touch pwned}",
    r"\openout5=pwned.tex",
    r"\catcode`\^=7",
    r"\csname input\endcsname{/etc/passwd}",
    r"\begin{filecontents}{pwned.tex}",
    r"\special{ps: pwned}",
    r"\read16 to \x",
]


@pytest.mark.parametrize("text", HOSTILE)
def test_hostile_scene_file_labels_are_refused_at_load(tmp_path: Path, text: str):
    path = tmp_path / "s.toml"
    quoted = text.replace("\\", "\\\\")
    path.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 30\nelevation = 20\n'
        '[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
        f'[[labels]]\ntext = "{quoted}"\nat = [0, 0, 1.2]\n'
    )
    with pytest.raises(lg.SceneFileError, match=r"labels\[0\].*must not use the TeX command"):
        lg.load_scene_file(path)


def test_a_scene_file_figure_compiles_without_touching_other_files(tmp_path: Path):
    """Labels a scene file may have (document macros, escaped characters)
    compile with the shell closed, and the compile writes only its own files."""
    path = tmp_path / "s.toml"
    path.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 30\nelevation = 20\n'
        '[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
        '[[labels]]\ntext = "$\\\\vx_1$ 50\\\\% \\\\{u\\\\}"\nat = [0, 0, 1.2]\nalways = true\n'
    )
    scene, projector = lg.load_scene_file(path)[:2]
    d = scene.render(projector)
    d.save(tmp_path / "fig.tex", width="5cm")
    _document(tmp_path, "fig.tex")
    before = {p.name for p in tmp_path.iterdir()}
    r = _pdflatex(tmp_path, "doc.tex")
    assert r.returncode == 0, r.stdout[-2000:]
    made = {p.name for p in tmp_path.iterdir()} - before
    assert made <= {"doc.aux", "doc.log", "doc.pdf"}, made
