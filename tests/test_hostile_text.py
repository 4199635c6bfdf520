r"""Hostile label text and scene-file values ("Faults and hostile input, third round").

Four mechanisms, each tested here on the inputs that broke it:

1. control characters are refused when a Label is made, and the SVG writer
   escapes every string it writes, so any SVG lgraph writes is well-formed XML;
2. length and nesting limits (``MAX_LABEL_LENGTH``, ``MAX_LABEL_DEPTH``) are
   checked before anything parses the text, and mathtext's RecursionError and
   MemoryError become ValueErrors;
3. TeX that reaches files or the shell, defines commands or changes how TeX
   reads text is refused when a Label is made (and again by the TikZ writer);
4. scene-file messages quote values escaped and cut (``_show``).
"""

from __future__ import annotations

import re
import time
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path
from unittest import mock

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import lgraph as lg
from lgraph.output import _text
from lgraph.output._text import (
    MAX_LABEL_DEPTH,
    MAX_LABEL_LENGTH,
    check_tex,
    check_text,
    quote,
    text_shape,
)
from lgraph.output.backends.svg import write_svg
from lgraph.output.drawing import Drawing, PlacedLabel, Stroke
from lgraph.output.page import Page
from lgraph.scenefile import SceneFileError, load_scene_file
from lgraph.scenefile._locate import _show

SVG = "{http://www.w3.org/2000/svg}"
#: what a message must never contain: C0 (but the line breaks between
#: problems), DEL and C1 controls
RAW_CONTROL = re.compile("[\x00-\x09\x0b-\x1f\x7f-\x9f]")
#: every character, lone surrogates and controls included
ANY_CHAR = st.characters(exclude_categories=())


def _drawing(text: str, family: str = "u1") -> Drawing:
    s = Stroke(xy=np.array([[0.0, 0.0], [2.0, 1.0]]), xyz=np.zeros((2, 3)), family=family)
    lab = PlacedLabel(text, np.array([1.0, 0.5]), np.zeros(3))
    return Drawing(strokes=(s,), page=Page(margin=0, extent=72), labels=(lab,))


def _svg_root(drawing: Drawing, path: Path) -> ET.Element:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # glyphs missing from the fonts
        write_svg(drawing, path)
    return ET.parse(path).getroot()


# -- 1. control characters ------------------------------------------------------------
@pytest.mark.parametrize(
    "text, char, position",
    [
        ("bell\x07", "\\x07", 4),
        ("\x00", "\\x00", 0),
        ("\x1b[31mred", "\\x1b", 0),
        ("a\x0bb", "\\x0b", 1),
        ("two\nlines", "\\n", 3),
        ("tab\there", "\\t", 3),
        ("del\x7f", "\\x7f", 3),
        ("c1 \x85", "\\x85", 3),
        ("csi \x9b31m", "\\x9b", 4),
        ("half \ud800", "\\ud800", 5),
        ("$x$\ufffe", "\\ufffe", 3),
    ],
)
def test_a_label_refuses_control_characters_naming_them_and_where(text, char, position):
    with pytest.raises(ValueError, match="Label: text must not contain control characters") as e:
        lg.Label(text, at=(0, 0, 0))
    msg = str(e.value)
    assert f"got '{char}' at position {position}" in msg
    assert not RAW_CONTROL.search(msg) and "\n" not in msg


def test_a_label_is_one_line_since_mathtext_draws_no_line_break():
    # mathtext sets "\n" as a missing glyph, the PDF fallback as nothing: refused
    with pytest.raises(ValueError, match=r"one line .*got '\\n'"):
        lg.Label("$x$\n$y$", at=(0, 0, 0))


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.text(ANY_CHAR, min_size=1, max_size=12))
def test_the_svg_of_any_label_the_label_accepts_parses(tmp_path_factory, text):
    try:
        lab = lg.Label(text, at=(0, 0, 0))
    except (ValueError, TypeError):
        assume(False)
    path = tmp_path_factory.mktemp("svg") / "l.svg"
    root = _svg_root(_drawing(lab.text), path)
    labels = [g for g in root.iter(f"{SVG}g") if g.get("class") == "label"]
    assert [g.get("data-text") for g in labels] == [text]  # the text survives exactly


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.text(ANY_CHAR.filter(lambda c: c != "$"), min_size=1, max_size=12),
    st.text(ANY_CHAR, min_size=1, max_size=12),
)
def test_the_svg_writer_escapes_what_no_label_would_hold(tmp_path_factory, text, family):
    # a drawing built by hand skips Label's checks; its SVG still parses: the
    # native <text> of plain labels (no matplotlib), data-text, data-family and
    # the layer names all go through the writer's escaping
    path = tmp_path_factory.mktemp("svg") / "h.svg"
    text_shape.cache_clear()
    try:
        with mock.patch.object(_text, "_mpl_available", return_value=False):
            root = _svg_root(_drawing(text, family), path)
    finally:
        text_shape.cache_clear()
    (native,) = root.iter(f"{SVG}text")
    assert native.text is not None
    assert {p.get("data-family") for p in root.iter(f"{SVG}polyline")} != set()


def test_the_svg_writer_replaces_characters_xml_cannot_hold(tmp_path):
    root = _svg_root(_drawing("ok", family="fam\x07ily\ud800"), tmp_path / "f.svg")
    (line,) = root.iter(f"{SVG}polyline")
    assert line.get("data-family") == "fam\ufffdily\ufffd"


# -- 2. length and nesting ------------------------------------------------------------
def test_the_limits_have_their_documented_values():
    assert (MAX_LABEL_LENGTH, MAX_LABEL_DEPTH) == (1000, 10)


def test_a_megabyte_label_is_refused_at_once_with_a_short_message():
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=r"at most 1000 characters long \(MAX_LABEL_LENGTH\)"):
        lg.Label("x" * 1_000_000, at=(0, 0, 0))
    assert time.perf_counter() - t0 < 1.0
    with pytest.raises(ValueError) as e:
        lg.Label("$" + "\\alpha" * 200_000 + "$", at=(0, 0, 0), size=-1)
    assert len(str(e.value)) < 300 and "(1200002 characters)" in str(e.value)


@pytest.mark.parametrize(
    "opening, closing",
    [(r"\sqrt{", "}"), ("{", "}"), ("x^{", "}"), (r"\left(", r"\right)"), (r"\sqrt[", "]{x}")],
    ids=["sqrt", "braces", "superscripts", "left-right", "sqrt-root"],
)
@pytest.mark.parametrize("deep", [MAX_LABEL_DEPTH + 1, 30, 500])
def test_deep_nesting_is_refused_before_mathtext_sees_it(opening, closing, deep):
    text = "$" + opening * deep + "x" + closing * deep + "$"
    with mock.patch.object(_text, "_outline", side_effect=AssertionError("parsed")):
        with pytest.raises(ValueError) as e:
            lg.Label(text, at=(0, 0, 0))
    msg = str(e.value)
    if len(text) > MAX_LABEL_LENGTH:
        assert "MAX_LABEL_LENGTH" in msg
    else:
        assert f"more than {MAX_LABEL_DEPTH} deep (MAX_LABEL_DEPTH), got {deep}" in msg


@pytest.mark.parametrize(
    "opening, closing", [(r"\sqrt{", "}"), (r"\hat{", "}"), (r"\frac{", "}{y}"), ("x^{", "}")]
)
def test_nesting_at_the_limit_typesets_even_from_a_deep_stack(opening, closing):
    text = "$" + opening * MAX_LABEL_DEPTH + "x" + closing * MAX_LABEL_DEPTH + "$"

    def deep(n: int) -> lg.Label:  # callers' frames: the scene file reader, a notebook
        return deep(n - 1) if n else lg.Label(text, at=(0, 0, 0))

    assert deep(300).text == text
    assert text_shape(text, 7.5).codes is not None


def test_recursion_in_mathtext_becomes_a_value_error():
    chain = "$" + r"\hat " * 150 + "x$"  # no group at all: a chain of accents
    # a Label does not typeset (TeX may do it, for TikZ); lgraph does where it
    # draws the glyphs: there the RecursionError is a ValueError.  Whether 150
    # accents exhaust the recursion limit depends on how deep the caller's
    # stack already is (a pytest-xdist worker's varies; CI once typeset the
    # chain): the limit is set to 300 frames above this test's own depth
    import inspect
    import sys

    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(len(inspect.stack(0)) + 300)
    try:
        with pytest.raises(ValueError, match="nests too deeply for mathtext") as e:
            text_shape(chain, 10.0)
        assert e.type is ValueError and e.value.__suppress_context__  # no RecursionError shown
        with pytest.raises(ValueError, match="nests too deeply for mathtext"):
            check_text("Label", chain)
    finally:
        sys.setrecursionlimit(limit)
    assert lg.Label("$\\hat{x}_1$", at=(0, 0, 0)).text  # mathtext still works afterwards


def test_mathtext_out_of_memory_becomes_a_value_error():
    with mock.patch("matplotlib.textpath.TextPath", side_effect=MemoryError):
        with pytest.raises(ValueError, match="Label: text needs more memory than mathtext"):
            text_shape("$x_{memory}$", 10.0)


def test_text_that_skipped_the_label_is_limited_where_it_is_laid_out():
    with pytest.raises(ValueError, match="MAX_LABEL_LENGTH"):
        text_shape("$x$" * 400, 10.0)
    with pytest.raises(ValueError, match="MAX_LABEL_DEPTH"):
        text_shape("$" + "{" * 40 + "x" + "}" * 40 + "$", 10.0)


def test_messages_quote_label_text_cut_and_escaped():
    assert quote("$x$") == "'$x$'"
    assert quote("it's") == '"it\'s"'  # as repr for short text
    long = quote("\x1b" + "y" * 5000)
    assert long.startswith("'\\x1by") and long.endswith("'... (5001 characters)")
    assert len(long) < 100
    with pytest.raises(ValueError, match=r"anchor must be") as e:
        lg.Label("z" * 900, at=(0, 0, 0), anchor="up")
    assert len(str(e.value)) < 250  # the label is named by a cut quote


# -- 3. TeX that reaches files or the shell --------------------------------------------
DENIED = [
    (r"\input{/etc/passwd}", r"\input"),
    (r"$\input{x}$", r"\input"),
    (r"\immediate\write18{rm -rf ~}", r"\immediate"),
    (r"\write18{ls}", r"\write"),
    (r"\openin1=secret", r"\openin"),
    (r"\openout1=x.tex", r"\openout"),
    (r"\read1 to\x", r"\read"),
    (r"\readline1 to\x", r"\readline"),
    (r"\include{chapter}", r"\include"),
    (r"\usepackage{shellesc}", r"\usepackage"),
    (r"\catcode`\|=0", r"\catcode"),
    (r"\csname input\endcsname{x}", r"\csname"),
    (r"\def\x{y}", r"\def"),
    (r"\edef\x{y}", r"\edef"),
    (r"\let\x=\relax", r"\let"),
    (r"\newcommand{\x}{y}", r"\newcommand"),
    (r"\renewcommand{\x}{y}", r"\renewcommand"),
    (r"\NewDocumentCommand\x{}{y}", r"\NewDocumentCommand"),
    (r"\scantokens{x}", r"\scantokens"),
    (r"\string\i nput", r"\string"),
    (r"\detokenize{x}", r"\detokenize"),
    (r"\meaning\relax", r"\meaning"),
    (r"\makeatletter", r"\makeatletter"),
    (r"\ExplSyntaxOn", r"\ExplSyntaxOn"),
    (r"\UseName{input}{x}", r"\UseName"),
    (r"\@@input x", r"\@@input"),
    (r"\directlua{os.execute('ls')}", r"\directlua"),
    (r"\luaexec{x}", r"\luaexec"),
    (r"\ShellEscape{ls}", r"\ShellEscape"),
    (r"\pdfobj file{secret}", r"\pdfobj"),
    (r"\XeTeXpdffile secret", r"\XeTeXpdffile"),
    (r"\tikz\draw plot file{secret};", r"\tikz"),
    (r"\pgfplothandlerrecord{x}", r"\pgfplothandlerrecord"),
    (r"\includegraphics{secret.pdf}", r"\includegraphics"),
    (r"\lstinputlisting{secret}", r"\lstinputlisting"),
    (r"\special{! (x) run}", r"\special"),
    (r"\begin{filecontents}{x.tex}", r"\begin{filecontents}"),
    (r"\begin {filecontents*}{x.tex}", r"\begin{filecontents*}"),
    (r"\end{luacode}", r"\end{luacode}"),
    (r"\begin{fil\empty econtents}", r"\begin"),
    (r"\begin\x", r"\begin"),
]


@pytest.mark.parametrize("text, command", DENIED, ids=[c for _, c in DENIED])
def test_a_label_refuses_tex_that_reaches_files_or_the_shell(text, command):
    with pytest.raises(ValueError) as e:
        lg.Label(text, at=(0, 0, 0))
    msg = str(e.value)
    assert msg.startswith(f"Label: text must not use the TeX command {command} (it ")
    assert "at position" in msg


@pytest.mark.parametrize("text", ["^^5cinput{x}", "$x^^5c$", "^^^^005cinput", "^^M"])
def test_a_label_refuses_tex_caret_notation(text):
    with pytest.raises(ValueError, match=r"Label: text must not contain '\^\^'"):
        lg.Label(text, at=(0, 0, 0))


@pytest.mark.parametrize(
    "text",
    [
        r"$\vx_1 + \tfrac12$",  # document macros (for TikZ output)
        r"\in put",  # \in, then letters
        r"\\input",  # a line break, then letters
        r"\inputx \writer \defined",  # other control words
        r"$\kappa_n \leftarrow \mathbf{x}\{u\}$",
        r"Mr.\@ Smith",
        r"\begin{pmatrix} a \end{pmatrix}",
        "x^2 ^ ^",
    ],
)
def test_mathematics_and_document_macros_stay_allowed(text):
    assert check_tex("Label", text) == text


def test_allowed_tex_makes_labels():
    for text in [r"$\kappa_n N$", r"\in put", "$x^{2}_{1}$", "50% of $\\Omega$"]:
        assert lg.Label(text, at=(0, 0, 0)).text == text


# -- 4. scene-file messages --------------------------------------------------------------
SCENE = """\
[projector]
kind = "parallel"
direction = [{big}]

[[object]]
surface = "sphere"
params = {{ r = 1 }}

[[labels]]
text = "\\u001b[31mred\\u0007"
at = [0, 0, 0]

[[labels]]
text = "fine"
at = [0, 0, 0]
anchor = ["\\u001b[31m", "\\u009b2J"]
"""


def _scene_error(tmp_path: Path, text: str) -> str:
    path = tmp_path / "s.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(SceneFileError) as e:
        load_scene_file(path)
    return str(e.value).replace(str(path), "s.toml")  # lengths without the temporary path


def test_scene_file_messages_have_no_control_characters_and_stay_short(tmp_path):
    big = ", ".join(["1"] * 200_000)
    msg = _scene_error(tmp_path, SCENE.format(big=big))
    lines = msg.splitlines()
    assert len(lines) == 3, msg
    assert not RAW_CONTROL.search(msg), repr(msg)
    assert len(msg) < 500, msg
    assert "direction: expected an array of 3 numbers, got an array [1, 1, 1," in lines[0]
    assert lines[0].endswith(", ...] (200000 items)")
    assert "'\\x1b[31mred\\x07'" in msg  # the label's text, escaped
    assert "an array ['\\x1b[31m', '\\x9b2J']" in msg


def test_scene_file_keys_with_control_characters_are_escaped(tmp_path):
    text = SCENE.format(big="1, 1, 1").replace("anchor = ", '"\\u001b[31mkey" = 1\nanchor = ')
    assert not RAW_CONTROL.search(_scene_error(tmp_path, text))


def test_a_half_megabyte_label_in_a_scene_file_gives_a_short_message(tmp_path):
    text = f'[[labels]]\ntext = "{"x" * 500_000}"\nat = [0, 0, 0]\n'
    msg = _scene_error(tmp_path, text)
    assert "MAX_LABEL_LENGTH" in msg and len(msg) < 400, msg[:1000]


@pytest.mark.parametrize(
    "value, shown",
    [
        ("\x1b[31m", "a string '\\x1b[31m'"),
        ("\u202eevil", "a string '\\u202eevil'"),  # bidirectional override
        ("s" * 10_000, "a string '" + "s" * 58 + "'... (10000 characters)"),
        ([1, 2.5, True, "x", [3], {}], "an array [1, 2.5, true, 'x', [...], {...}]"),
        ([], "an array []"),
        ({"a": 1}, "a table"),
        (False, "a boolean (false)"),
        (1e300, "1e+300"),
    ],
)
def test_show_quotes_values_escaped_and_cut(value, shown):
    assert _show(value) == shown


@given(st.recursive(st.text(ANY_CHAR) | st.integers() | st.floats(), st.lists, max_leaves=50))
def test_show_of_any_value_is_short_and_printable(value):
    s = _show(value)
    assert s.isprintable() and len(s) < 120
    big = _show([value] * 100_000)
    assert big.isprintable() and len(big) < 120
