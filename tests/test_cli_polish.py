"""CLI polish: ``--debug`` after the command, ``lgraph plugins`` listing the
names, several ``-o`` outputs of one rendering (options of only some of their
backends are warnings), and the scene-file examples of the docs run as written."""

from __future__ import annotations

import os
import re
import sys
import textwrap
from pathlib import Path

import pytest

import lgraph as lg
import lgraph.render as vis
from lgraph import plugins
from lgraph.cli import build_parser, main
from lgraph.scenefile import SceneFileError, load_scene_file

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent

SCENE = """\
[projector]
kind = "parallel"
direction = [1, 2, 3]

[[object]]
surface = "sphere"
params = { r = 1 }
families = [{ name = "parameter_lines", n1 = 4, n2 = 6 }]
"""


def _scene(folder: Path, extra: str = "", name: str = "s.toml") -> Path:
    path = folder / name
    path.write_text(SCENE + extra, encoding="utf-8")
    return path


def _line_of(path: Path, start: str) -> int:
    """The 1-based number of the first line of ``path`` starting with ``start``."""
    lines = path.read_text(encoding="utf-8").splitlines()
    return next(n for n, line in enumerate(lines, 1) if line.startswith(start))


@pytest.fixture
def renders(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Count the renderings (calls of ``lgraph.render.render``)."""
    calls: list[int] = []
    original = vis.render

    def counting(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)

    monkeypatch.setattr(vis, "render", counting)
    return calls


@pytest.fixture
def saves(monkeypatch: pytest.MonkeyPatch) -> list[tuple[str, dict]]:
    """Record ``(file name, options)`` of every ``Drawing.save``."""
    calls: list[tuple[str, dict]] = []
    original = lg.Drawing.save

    def recording(self, path, **options):
        calls.append((Path(path).name, dict(options)))
        return original(self, path, **options)

    monkeypatch.setattr(lg.Drawing, "save", recording)
    return calls


@pytest.fixture
def no_render(monkeypatch: pytest.MonkeyPatch) -> None:
    def boom(*args, **kwargs):
        raise AssertionError("rendered although the command line is wrong")

    monkeypatch.setattr(vis, "render", boom)


# -- 1. --debug before or after the command -----------------------------------------
@pytest.mark.parametrize(
    "argv",
    [["demo"], ["render", "s.toml"], ["animate", "s.toml"], ["gallery", "out"], ["plugins"]],
)
def test_debug_is_accepted_before_and_after_every_command(argv: list[str]) -> None:
    parser = build_parser()
    assert parser.parse_args([*argv, "--debug"]).debug is True
    assert parser.parse_args(["--debug", *argv]).debug is True  # not reset by the command
    assert parser.parse_args(argv).debug is False


def test_debug_after_the_command_shows_the_traceback(tmp_path: Path, capsys) -> None:
    path = _scene(tmp_path, "\n[render]\ntolerance = 1e-300\n")
    assert main(["render", str(path)]) == 2  # without --debug: a message only
    assert "Traceback" not in capsys.readouterr().err
    for argv in (["render", str(path), "--debug"], ["--debug", "render", str(path)]):
        with pytest.raises(Exception, match="render.tolerance"):
            main(argv)


# -- 2. lgraph plugins lists the names ----------------------------------------------
def _name_groups(text: str) -> dict[str, tuple[int, list[str]]]:
    """``{"surfaces": (count, names), ...}`` from the wrapped name lists."""
    joined = re.sub(r"\n {4}", " ", text)
    groups = {}
    for m in re.finditer(r"^(surfaces|families|backends) \((\d+)\): (.*)$", joined, re.M):
        groups[m.group(1)] = (int(m.group(2)), m.group(3).split(", "))
    return groups


def test_plugins_lists_the_names_of_surfaces_families_and_backends(capsys) -> None:
    from lgraph.output.backends import backend_suffixes

    assert main(["plugins"]) == 0
    out = capsys.readouterr().out
    groups = _name_groups(out)
    assert set(groups) == {"surfaces", "families", "backends"}
    for kind, expected in (
        ("surfaces", plugins.surface_names()),
        ("families", plugins.family_names()),
        ("backends", backend_suffixes()),
    ):
        count, names = groups[kind]
        assert names == expected and count == len(expected), kind
    assert {"ellipsoid", "sphere", "torus"} <= set(groups["surfaces"][1])
    assert {"contour", "parameter_lines", "lines_of_curvature"} <= set(groups["families"][1])
    assert {".pdf", ".png", ".svg"} <= set(groups["backends"][1])
    lines = out.splitlines()
    assert lines[-1].startswith("built-in: ")  # the count of built-ins stays last
    assert all(len(line) <= 79 for line in lines if line.startswith(("surfaces", "    ")))
    # the plugin table (or the note that there is none) still comes first
    assert lines[0].split()[:2] == ["NAME", "KIND"] or lines[0].startswith("no plugins")


def test_plugins_lists_names_registered_at_run_time(monkeypatch, capsys) -> None:
    from lgraph.output._backend_table import BACKENDS

    monkeypatch.setitem(plugins._registered_surfaces, "polish_ball", lg.Sphere)
    monkeypatch.setitem(BACKENDS, ".polish", lambda drawing, path: None)
    assert main(["plugins"]) == 0
    groups = _name_groups(capsys.readouterr().out)
    assert "polish_ball" in groups["surfaces"][1]
    assert ".polish" in groups["backends"][1]


# -- 3. several outputs --------------------------------------------------------------
def test_several_outputs_are_rendered_once_and_saved_to_each(
    tmp_path: Path, capsys, renders: list[int]
) -> None:
    path = _scene(tmp_path)
    outs = [tmp_path / "fig.pdf", tmp_path / "sub" / "fig.png", tmp_path / "fig.svg"]
    assert main(["render", str(path), *[a for o in outs for a in ("-o", str(o))]]) == 0
    assert len(renders) == 1
    captured = capsys.readouterr()
    assert captured.err == ""
    assert captured.out.splitlines() == [f"wrote {o.resolve()}" for o in outs]
    assert outs[0].read_bytes().startswith(b"%PDF")
    assert outs[1].read_bytes().startswith(b"\x89PNG")
    assert b"<svg" in outs[2].read_bytes()


def test_an_option_of_only_some_backends_is_a_warning(
    tmp_path: Path, capsys, saves: list[tuple[str, dict]]
) -> None:
    path = _scene(tmp_path, '\n[save]\ntitle = "Sphere"\ndpi = 40\n')
    title, dpi = _line_of(path, "title"), _line_of(path, "dpi")
    pdf, png, svg = tmp_path / "fig.pdf", tmp_path / "fig.png", tmp_path / "fig.svg"
    assert main(["render", str(path), "-o", str(pdf), "-o", str(png), "-o", str(svg)]) == 0
    err = capsys.readouterr().err.splitlines()
    warn = "lgraph render: warning:"
    assert err == [
        f"{warn} {path}:{dpi}: save.dpi: not an option of the .pdf backend; ignored for {pdf}",
        f"{warn} {path}:{title}: save.title: not an option of the .png backend; ignored for {png}",
        f"{warn} {path}:{title}: save.title: not an option of the .svg backend; ignored for {svg}",
        f"{warn} {path}:{dpi}: save.dpi: not an option of the .svg backend; ignored for {svg}",
    ]
    # each backend gets its own options only
    assert saves == [("fig.pdf", {"title": "Sphere"}), ("fig.png", {"dpi": 40}), ("fig.svg", {})]
    assert all(p.exists() for p in (pdf, png, svg))


def test_an_option_no_chosen_backend_takes_is_still_an_error(
    tmp_path: Path, capsys, no_render: None
) -> None:
    path = _scene(tmp_path, "\n[save]\nlayers = 'family'\nfoo = 1\ndpi = [40]\n")
    pdf, png = tmp_path / "fig.pdf", tmp_path / "fig.png"
    assert main(["render", str(path), "-o", str(pdf), "-o", str(png)]) == 2
    err = capsys.readouterr().err
    foo = _line_of(path, "foo")
    assert (
        f"{path}:{foo}: save.foo: unknown option 'foo' for .pdf and .png output; allowed: " in err
    )
    assert (
        "background, compress, curves, dpi, height, margin, precision, size, supersample, text, "
        "title, width" in err
    )
    assert f"{path}:{foo + 1}: save.dpi: expected a number" in err  # every problem at once
    assert "save.layers: unknown option 'layers'" in err  # .svg takes it, not chosen here
    assert "warning" not in err and "Traceback" not in err
    assert not pdf.exists() and not png.exists()


def test_with_one_output_an_unknown_option_is_an_error_as_before(
    tmp_path: Path, capsys, no_render: None
) -> None:
    path = _scene(tmp_path, '\n[save]\ntitle = "Sphere"\n')
    assert main(["render", str(path), "-o", str(tmp_path / "fig.png")]) == 2
    err = capsys.readouterr().err
    line = _line_of(path, "title")
    assert err.startswith(f"lgraph render: error: {path}:{line}: save.title: unknown option")
    assert (
        "for .png output; allowed: background, dpi, height, margin, size, supersample, width" in err
    )
    # two outputs of the same backend: no other backend takes it, still an error
    argv = ["render", str(path), "-o", str(tmp_path / "a.png"), "-o", str(tmp_path / "b.png")]
    assert main(argv) == 2
    assert "save.title: unknown option 'title' for .png output" in capsys.readouterr().err


def test_width_and_height_of_the_command_line_apply_to_every_output(
    tmp_path: Path, capsys, saves: list[tuple[str, dict]], renders: list[int]
) -> None:
    path = _scene(tmp_path, '\n[save]\nwidth = "3cm"\nprecision = 2\n')
    argv = ["render", str(path), "-o", str(tmp_path / "f.svg"), "-o", str(tmp_path / "f.pdf")]
    assert main([*argv, "--width", "5cm", "--height", "4cm"]) == 0
    assert saves == [
        ("f.svg", {"width": "5cm", "precision": 2, "height": "4cm"}),
        ("f.pdf", {"width": "5cm", "precision": 2, "height": "4cm"}),
    ]
    assert len(renders) == 1
    saves.clear()
    assert main([*argv, "--plotter"]) == 0  # one cleaned drawing for both
    assert [options["width"] for _, options in saves] == [pytest.approx(85.03937)] * 2


def test_every_output_is_checked_before_any_work(tmp_path: Path, capsys, no_render: None) -> None:
    path = _scene(tmp_path)
    ok = tmp_path / "ok.pdf"
    assert main(["render", str(path), "-o", str(ok), "-o", str(tmp_path / "x.doc")]) == 2
    assert "unknown file suffix '.doc'" in capsys.readouterr().err
    assert not ok.exists()


def test_an_output_that_is_the_scene_file_is_refused(
    tmp_path: Path, capsys, no_render: None
) -> None:
    path = _scene(tmp_path)
    before = path.read_bytes()
    assert main(["render", str(path), "-o", str(tmp_path / "f.pdf"), "-o", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"output {str(path)!r} is the scene file itself" in err
    # a scene file named like a figure: the default output would be the file itself
    odd = _scene(tmp_path, name="figure.pdf")
    assert main(["render", str(odd)]) == 2
    assert "is the scene file itself" in capsys.readouterr().err
    # the same file under another name: by identity, not by name
    link = tmp_path / "link.svg"
    try:
        os.link(path, link)
    except OSError:  # pragma: no cover - no hard links here
        pytest.skip("hard links not supported")
    assert main(["render", str(path), "-o", str(link)]) == 2
    assert f"output {str(link)!r} is the scene file itself" in capsys.readouterr().err
    assert path.read_bytes() == before and odd.read_bytes() == SCENE.encode()


def test_an_animation_over_its_scene_file_is_refused(tmp_path: Path, capsys) -> None:
    odd = _scene(tmp_path, name="turn.gif")
    assert main(["animate", str(odd), "--frames", "1"]) == 2
    assert "is the scene file itself" in capsys.readouterr().err
    assert odd.read_text(encoding="utf-8") == SCENE


def test_an_output_given_twice_is_refused(tmp_path: Path, capsys, no_render: None) -> None:
    path = _scene(tmp_path)
    (tmp_path / "sub").mkdir()
    same = tmp_path / "sub" / ".." / "fig.pdf"
    argv = ["render", str(path), "-o", str(tmp_path / "fig.pdf"), "-o", str(same)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"output {str(same)!r} is given twice (also as {str(tmp_path / 'fig.pdf')!r})" in err
    assert main(["render", str(path), "-o", "fig.svg", "-o", "fig.svg"]) == 2
    assert "output 'fig.svg' is given twice; give each once" in capsys.readouterr().err
    assert not (tmp_path / "fig.pdf").exists()


def test_load_scene_file_with_several_outputs(tmp_path: Path) -> None:
    path = _scene(tmp_path, '\n[save]\ntitle = "Sphere"\nwidth = "2in"\n')
    line = _line_of(path, "title")
    with pytest.warns(UserWarning) as record:
        scene, projector, options = load_scene_file(path, output=["a.pdf", Path("b.PNG")])
    assert [str(w.message) for w in record] == [
        f"{path}:{line}: save.title: not an option of the .png backend; ignored for b.PNG"
    ]
    assert options["save"] == [{"title": "Sphere", "width": 144.0}, {"width": 144.0}]
    assert len(scene) == 1 and set(options) == {"render", "save"}
    # one output: the return shape of before (a dict), an unknown option is an error
    assert load_scene_file(path, output="a.pdf")[2]["save"] == {"title": "Sphere", "width": 144.0}
    with pytest.raises(SceneFileError, match="unknown option 'title' for .png output"):
        load_scene_file(path, output="b.png")
    # a sequence of one: a list of one, same checks as one output
    with pytest.raises(SceneFileError, match="unknown option 'title' for .svg output"):
        load_scene_file(path, output=["c.svg"])
    # no [save] table: empty options for each output
    bare = _scene(tmp_path, name="bare.toml")
    assert load_scene_file(bare, output=["a.pdf", "b.svg"])[2]["save"] == [{}, {}]
    with pytest.raises(ValueError, match="expected one or more files"):
        load_scene_file(path, output=[])


# -- 4. the scene-file examples, tested as written -----------------------------------
def _docstring_example() -> str:
    """The indented block after ``The format::`` of :mod:`lgraph.scenefile`."""
    import lgraph.scenefile

    lines = lgraph.scenefile.__doc__.splitlines()
    start = lines.index("The format::") + 1
    block = []
    for line in lines[start:]:
        if line.strip() and not line.startswith(" "):
            break
        block.append(line)
    return textwrap.dedent("\n".join(block)).strip() + "\n"


def test_the_format_example_of_the_scene_file_docstring_loads_and_renders(
    tmp_path: Path, capsys
) -> None:
    text = _docstring_example()
    assert text.startswith("[projector]") and "[[group.object]]" in text
    data = tomllib.loads(text)  # valid TOML (it once declared [save] twice)
    assert {"projector", "page", "render", "save", "object", "labels", "points", "group"} <= set(
        data
    )
    path = tmp_path / "example.toml"
    path.write_text(text, encoding="utf-8")
    scene, projector, options = load_scene_file(path)
    assert options["save"] == {"title": "Ellipsoid", "width": pytest.approx(240.9449, abs=1e-3)}
    assert options["render"]["hidden_lines"] is True
    out = tmp_path / "example.pdf"
    assert main(["render", str(path), "-o", str(out)]) == 0
    assert out.read_bytes().startswith(b"%PDF")
    drawing = scene.render(projector, **options["render"])
    families = {s.family for s in drawing.strokes}
    assert {"contour", "curvature", "intersection", "point"} <= families  # group cuts it
    assert len(drawing.labels) == 1  # the label at the top is visible


def _doc_examples() -> list[tuple[str, str]]:
    """Every TOML block of docs/*.rst and README.md that is a scene file."""
    found = []
    for doc in [*sorted((ROOT / "docs").glob("*.rst")), ROOT / "README.md"]:
        text = doc.read_text(encoding="utf-8")
        blocks = [
            textwrap.dedent(m.group(1))
            for m in re.finditer(r"^\.\. code-block:: toml\n\n((?:(?: {3,}.*)?\n)+)", text, re.M)
        ]
        blocks += re.findall(r"^```toml\n(.*?)^```", text, re.M | re.S)
        n = 0
        for block in blocks:
            if re.search(r"^\[projector\]", block, re.M):
                n += 1
                found.append((f"{doc.name}-{n}", block))
    return found


DOC_EXAMPLES = _doc_examples()


def test_the_docs_have_scene_file_examples() -> None:
    assert "plugins.rst-1" in [name for name, _ in DOC_EXAMPLES]  # the extraction works


@pytest.mark.parametrize("text", [t for _, t in DOC_EXAMPLES], ids=[n for n, _ in DOC_EXAMPLES])
def test_a_scene_file_example_of_the_docs_renders_as_written(
    text: str, tmp_path: Path, capsys
) -> None:
    data = tomllib.loads(text)
    needed = {o["surface"] for o in data.get("object", [])} - set(plugins.surface_names())
    families = {
        f["name"] if isinstance(f, dict) else f
        for o in data.get("object", [])
        for f in o.get("families", [])
    }
    needed |= families - set(plugins.family_names())
    if needed:
        pytest.skip(f"needs plugins for {sorted(needed)}")
    path = tmp_path / "example.toml"
    path.write_text(text, encoding="utf-8")
    load_scene_file(path)
    out = tmp_path / "example.pdf"
    assert main(["render", str(path), "-o", str(out)]) == 0, capsys.readouterr().err
    assert out.read_bytes().startswith(b"%PDF")


def test_an_arrow_with_a_label_in_a_scene_file(tmp_path):
    """``params.label`` of an arrow is its text (not a formula), and an arrow
    draws its outline only, as in Python (its class's default families)."""
    import lgraph as lg

    path = tmp_path / "arrow.toml"
    path.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 30\nelevation = 25\n'
        '[[object]]\nsurface = "arrow"\n'
        'params = { tail = [0, 0, 0], tip = [1, 0, 0], label = "$N$" }\n',
        encoding="utf-8",
    )
    scene, projector, _ = lg.load_scene_file(path)
    drawing = scene.render(projector)
    assert [lab.text for lab in drawing.labels] == ["$N$"]
    assert {s.family for s in drawing.strokes} == {"arrow"}  # its outline, no boundary
