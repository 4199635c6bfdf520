"""Scene files: the same strokes as the Python scene; one clear line per error."""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import lgraph as lg
from lgraph.scenefile import SceneFileError, _Locator, load_scene_file

FIG_7_2 = """\
# The paper's Figure 7.2: an ellipsoid drawn by its lines of curvature.
[projector]
kind = "central"
azimuth = 35
elevation = 25
distance = 16

[[object]]
surface = "ellipsoid"
params = { a = 3, b = 2, c = 1.3 }
families = [{ name = "lines_of_curvature", n1 = 14, n2 = 18 }]
"""

TWO_OBJECTS = """\
[projector]
kind = "central"
eye = [9, -7, 6]
target = [0, 0, 0]

[render]
hidden_lines = true
tolerance = 2e-4

[page]
width = 400
height = 300
margin = 12

[save]
dpi = 150

[[object]]
surface = "ellipsoid"
params = { a = 3, b = 2, c = 1.5 }
families = [{ name = "parameter_lines", n1 = 8, n2 = 12 }]
transform = [{ rotate = { axis = "z", degrees = 30 } }, { translate = [0.5, 0, 0] }]
style = { color = "#000000", width = 0.5 }

[[object]]
surface = "sphere"
params = { r = 1 }
families = ["parameter_lines"]
transform = [{ scale = 0.8 }, { translate = [2.5, 1, 1] }]
[object.style]
default = { color = "blue", width = 0.4 }
contour = { width = 1.2, dash = [3, 1] }
"""


def write(tmp_path: Path, text: str, name: str = "scene.toml") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def same_strokes(a: lg.Drawing, b: lg.Drawing) -> None:
    assert len(a.strokes) == len(b.strokes) > 0
    for s, t in zip(a.strokes, b.strokes):
        assert s.family == t.family and s.visible == t.visible and s.style == t.style
        np.testing.assert_array_equal(s.xy, t.xy)


def _gallery_build(stem):
    import importlib.util

    path = Path(__file__).resolve().parents[1] / "gallery" / f"{stem}.py"
    spec = importlib.util.spec_from_file_location(f"gallery_{stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.build()


def test_figure_7_2_scene_file_renders_the_gallery_script(tmp_path):
    """The scene file of the paper's Figure 7.2 gives exactly the strokes of
    gallery/fig_7_2_ellipsoid.py."""
    scene, projector, options = load_scene_file(write(tmp_path, FIG_7_2))
    assert options == {"render": {}, "save": {}}
    ref, ref_proj = _gallery_build("fig_7_2_ellipsoid")
    np.testing.assert_allclose(projector.eye, ref_proj.eye)
    got = scene.render(projector)
    same_strokes(got, ref.render(ref_proj))
    assert {s.family for s in got.strokes} == {"curvature", "contour"}


def test_transforms_styles_page_and_options(tmp_path):
    scene, projector, options = load_scene_file(write(tmp_path, TWO_OBJECTS), output="fig.png")
    ref = lg.Scene()
    ref.add(
        lg.Ellipsoid(3, 2, 1.5),
        lg.ParameterLines(8, 12),
        transform=lg.translate(0.5, 0, 0) @ lg.rotate("z", 30),  # listed order: rotate first
        style=lg.Style(color="#000000", width=0.5),
    )
    ref.add(
        lg.Sphere(1),
        lg.ParameterLines(),
        transform=lg.translate(2.5, 1, 1) @ lg.scale(0.8),
        style={
            "default": lg.Style(color="blue", width=0.4),
            "contour": lg.Style(width=1.2, dash=(3, 1)),
        },
    )
    ref_proj = lg.CentralProjector(eye=(9, -7, 6), target=(0, 0, 0))
    render = options["render"]
    assert render["hidden_lines"] is True and render["tolerance"] == 2e-4
    assert render["page"] == lg.Page(400, 300, 12)
    assert options["save"] == {"dpi": 150}
    kw = {"hidden_lines": True, "tolerance": 2e-4, "page": lg.Page(400, 300, 12)}
    same_strokes(scene.render(projector, **render), ref.render(ref_proj, **kw))


@pytest.mark.parametrize(
    ("projector", "expected"),
    [
        (
            'kind = "parallel"\ndirection = [1, -1, 0.7]',
            lg.ParallelProjector(direction=(1, -1, 0.7)),
        ),
        (
            'kind = "parallel"\nazimuth = 30\nelevation = 20',
            lg.ParallelProjector.from_angles(30, 20),
        ),
        (
            'kind = "central"\nazimuth = 30\nelevation = 20\ndistance = 12\ntarget = [1, 0, 0]',
            lg.CentralProjector.from_angles(30, 20, 12, target=(1, 0, 0)),
        ),
    ],
)
def test_projector_forms(tmp_path, projector, expected):
    text = f"[projector]\n{projector}\n[[object]]\nsurface = 'sphere'\nparams = {{ r = 1 }}\n"
    _, got, _ = load_scene_file(write(tmp_path, text))
    assert type(got) is type(expected)
    for a, b in zip(got.frame, expected.frame):
        np.testing.assert_allclose(a, b, atol=1e-15)


def test_page_preset(tmp_path):
    text = FIG_7_2 + '[page]\npreset = "a4"\nlandscape = true\n'
    _, _, options = load_scene_file(write(tmp_path, text))
    page = options["render"]["page"]
    assert page.width > page.height and abs(page.width - 841.8898) < 1e-3


# -- errors: one line naming file, line and key ------------------------------------
BASE = """\
[projector]
kind = "parallel"
direction = [1, -1, 0.7]

[[object]]
surface = "ellipsoid"
params = { a = 3, b = 2, c = 1.3 }
families = [{ name = "parameter_lines", n1 = 4, n2 = 6 }]
"""

BAD = {  # case: ((text replaced, by), line, key, words in the message)
    "unknown surface": (
        ('surface = "ellipsoid"', 'surface = "elipsoid"'),
        6,
        "object[0].surface",
        "unknown surface 'elipsoid'",
    ),
    "python code string": (
        ("a = 3", "a = \"__import__('os').system('x')\""),
        7,
        "object[0].params.a",
        "attributes are not allowed",
    ),
    "bad formula": (("b = 2", 'b = "2 +"'), 7, "object[0].params.b", "syntax error"),
    "non-constant formula": (("b = 2", 'b = "2*u"'), 7, "object[0].params.b", "unknown name 'u'"),
    "negative count": (
        ("n1 = 4", "n1 = -4"),
        8,
        "object[0].families[0].n1",
        "n1 must be an integer",
    ),
    "float count": (("n2 = 6", "n2 = 6.5"), 8, "object[0].families[0].n2", "n2 must be an integer"),
    "missing key": (('kind = "parallel"\n', ""), 1, "projector", "missing required key 'kind'"),
    "missing parameter": (("b = 2, ", ""), 7, "object[0].params", "missing required parameter 'b'"),
    "unknown parameter": (
        ("c = 1.3", "c = 1.3, d = 1"),
        7,
        "object[0].params.d",
        "unknown parameter 'd'",
    ),
    "bad value": (
        ("a = 3", "a = -3"),
        7,
        "object[0].params.a",
        "a must be a positive finite number",
    ),
    "wrong type": (
        ("[1, -1, 0.7]", '"up"'),
        3,
        "projector.direction",
        "expected an array of 3 numbers",
    ),
    "unknown family": (
        ('"parameter_lines"', '"parameter_line"'),
        8,
        "object[0].families[0].name",
        "unknown line family",
    ),
    "unknown top-level key": (
        ("[[object]]", "[objects]\nx = 1\n[[object]]"),
        5,
        "objects",
        "unknown key 'objects'",
    ),
    "bad colour": (
        ("n2 = 6 }]", 'n2 = 6 }]\nstyle = { color = "#12" }'),
        9,
        "object[0].style.color",
        "color must be",
    ),
    "syntax error": (("a = 3,", "a = 3,,"), 7, "params", "invalid TOML"),
}


@pytest.mark.parametrize("case", list(BAD), ids=list(BAD))
def test_bad_files_give_one_clear_line(tmp_path, case):
    (old, new), line, key, words = BAD[case]
    assert old in BASE
    path = write(tmp_path, BASE.replace(old, new, 1), "bad.toml")
    with pytest.raises(SceneFileError) as info:
        load_scene_file(path)
    msg = str(info.value)
    assert "\n" not in msg
    assert msg.startswith(f"{path}:{line}: {key}: "), msg
    assert words in msg
    assert info.value.line == line and info.value.path == str(path)


def test_a_python_expression_is_never_evaluated(tmp_path):
    marker = tmp_path / "evaluated"
    code = f"__import__('pathlib').Path({str(marker)!r}).touch()"
    text = BASE.replace("a = 3", "a = '" + code.replace("'", '"') + "'")
    path = write(tmp_path, text)
    with pytest.raises(SceneFileError, match="not allowed"):
        load_scene_file(path)
    assert not marker.exists()


def test_a_partially_valid_file_builds_nothing(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(lg.Scene, "render", lambda *a, **k: calls.append(1))
    text = BASE + '\n[[object]]\nsurface = "sphere"\nparams = { r = "1 +" }\n'
    with pytest.raises(SceneFileError, match=r":12: object\[1\]\.params\.r: "):
        load_scene_file(write(tmp_path, text))
    assert not calls


def test_missing_file(tmp_path):
    with pytest.raises(SceneFileError, match="cannot read the scene file"):
        load_scene_file(tmp_path / "nope.toml")


def test_locator_finds_keys_in_inline_tables_arrays_and_subtables():
    text = textwrap.dedent(
        """\
        [projector]
        kind = "central"   # comment with = sign
        [[object]]
        surface = "a"
        [[object]]
        surface = 'b'
        families = [
            "x",
            { name = "y", n1 = 3 },
        ]
        [object.params]
        r = 1
        s = "has } and ] inside"
        t = 2
        """
    )
    loc = _Locator(text)
    assert loc.line_of(("projector", "kind")) == 2
    assert loc.line_of(("object", 0, "surface")) == 4
    assert loc.line_of(("object", 1, "surface")) == 6
    assert loc.line_of(("object", 1, "families", 0)) == 8
    assert loc.line_of(("object", 1, "families", 1, "n1")) == 9
    assert loc.line_of(("object", 1, "params", "t")) == 14
    assert loc.line_of(("object", 1, "params", "missing")) == 11  # nearest enclosing key


def test_lgraph_render_exits_2_without_traceback(tmp_path):
    path = write(tmp_path, BASE.replace("a = 3", "a = \"__import__('os').system('x')\""))
    out = tmp_path / "figure.svg"
    r = subprocess.run(
        [sys.executable, "-m", "lgraph", "render", str(path), "-o", str(out)],
        capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert r.returncode == 2
    assert "Traceback" not in r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and f"{path}:7: object[0].params.a:" in lines[0]
    assert not out.exists()


def test_lgraph_render_writes_the_figure(tmp_path):
    path = write(tmp_path, BASE)
    out = tmp_path / "figure.svg"
    r = subprocess.run(
        [sys.executable, "-m", "lgraph", "render", str(path), "-o", str(out)],
        capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert out.read_text().count("<polyline") >= 5


def test_save_options_of_a_registered_backend_are_checked_and_passed(tmp_path, monkeypatch):
    """Backend writers declare their options (keyword parameters, or an
    ``lgraph_options`` dict); ``[save]`` is checked against them and passed on."""
    from lgraph.output import backends

    got = {}

    def write_fake(drawing, path, *, standalone=False, precision=2):
        got.update(standalone=standalone, precision=precision)
        Path(path).write_text("fake")

    def write_declared(drawing, path, **options):
        got.update(options)
        Path(path).write_text("declared")

    write_declared.lgraph_options = {"pens": 1}
    monkeypatch.setitem(backends._BACKENDS, ".fake", write_fake)
    monkeypatch.setitem(backends._BACKENDS, ".decl", write_declared)
    ok = write(tmp_path, BASE + "\n[save]\nstandalone = true\n")
    scene, projector, options = load_scene_file(ok, output=tmp_path / "f.fake")
    assert options["save"] == {"standalone": True}
    scene.render(projector).save(tmp_path / "f.fake", **options["save"])
    assert got == {"standalone": True, "precision": 2}
    bad = write(tmp_path, BASE + "\n[save]\nstandalone = 1\nprecision = 1.5\npens = 3\n")
    with pytest.raises(SceneFileError) as e:
        load_scene_file(bad, output="f.fake")
    assert len(e.value.errors) == 3
    assert "save.standalone: expected true or false" in str(e.value)
    assert (
        "save.pens: unknown option 'pens' for .fake output; "
        "allowed: background, height, margin, precision, standalone, width" in str(e.value)
    )
    pens = write(tmp_path, BASE + "\n[save]\npens = 4\n")
    assert load_scene_file(pens, output="f.decl")[2]["save"] == {"pens": 4}
    with pytest.raises(SceneFileError, match="unknown option 'pens' for .svg output"):
        load_scene_file(pens, output="f.svg")


def test_every_problem_of_a_file_is_reported_at_once(tmp_path):
    text = (
        BASE.replace("a = 3", "a = -3") + '\n[render]\nhidden_lines = "yes"\n[page]\nmargin = "x"\n'
    )
    text += '\n[[object]]\nsurface = "no-such-surface"\n'
    path = write(tmp_path, text)
    with pytest.raises(SceneFileError) as e:
        load_scene_file(path)
    keys = [k for _, k, _ in e.value.errors]
    assert "render.hidden_lines" in keys and "page.margin" in keys and "object[1].surface" in keys
    assert any(k.startswith("object[0].params") for k in keys)
    assert len(str(e.value).splitlines()) == len(e.value.errors) >= 4
    lines = [ln for ln, _, _ in e.value.errors]
    assert lines == sorted(lines) and all(isinstance(ln, int) for ln in lines)


def test_an_eye_inside_an_object_is_reported_before_rendering(tmp_path):
    text = BASE.replace('kind = "parallel"', 'kind = "central"')
    text = re.sub(r"direction = \[[^\]]*\]", "eye = [0.5, 0, 0]", text)
    path = write(tmp_path, text)
    with pytest.raises(SceneFileError) as e:
        load_scene_file(path)
    assert "projector.eye: object[0]" in str(e.value) and "behind the eye" in str(e.value)
    far = write(tmp_path, re.sub(r"eye = \[0.5, 0, 0\]", "eye = [20, 5, 3]", text))
    scene, projector, _ = load_scene_file(far)
    assert scene.render(projector).strokes


def test_tikz_plugin_options_pass_from_save(tmp_path, monkeypatch):
    """The example TikZ plugin declares ``standalone`` as a keyword parameter;
    ``[save] standalone = true`` reaches it (registered here by hand, as its
    entry point would)."""
    from lgraph.output import backends

    monkeypatch.syspath_prepend(
        str(Path(__file__).resolve().parents[1] / "plugins/lgraph-tikz/src")
    )
    lgraph_tikz = pytest.importorskip("lgraph_tikz")
    monkeypatch.setitem(backends._BACKENDS, ".tex", lgraph_tikz.write_tikz)
    path = write(tmp_path, BASE + "\n[save]\nstandalone = true\n")
    scene, projector, options = load_scene_file(path, output=tmp_path / "f.tex")
    assert options["save"] == {"standalone": True}
    out = scene.render(projector).save(tmp_path / "f.tex", **options["save"])
    assert "\\documentclass" in out.read_text()


def test_every_unknown_key_of_a_table_is_reported_with_its_line(tmp_path):
    text = BASE.replace('surface = "ellipsoid"', 'surface = "ellipsoid"\ncolour = 1\nhide = true')
    path = write(tmp_path, text + "\n[page]\nwidht = 10\nmargn = 2\n")
    with pytest.raises(SceneFileError) as e:
        load_scene_file(path)
    found = {key: line for line, key, _ in e.value.errors}
    assert found == {"object[0].colour": 7, "object[0].hide": 8, "page.widht": 13, "page.margn": 14}
