"""The command line: ``lgraph demo`` and ``--help`` everywhere."""

from __future__ import annotations

import subprocess
import sys

import pytest
from PIL import Image

from lgraph.cli import main


def test_demo_writes_pdf_and_png(tmp_path, capsys):
    assert main(["demo", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    pdf, png = tmp_path / "lgraph-demo.pdf", tmp_path / "lgraph-demo.png"
    assert pdf.read_bytes().startswith(b"%PDF")
    assert str(pdf.resolve()) in out and str(png.resolve()) in out
    with Image.open(png) as im:
        gray = im.convert("L")
        hist = gray.histogram()
    dark = sum(hist[:128])
    assert 0.005 < dark / sum(hist) < 0.3  # a line drawing: mostly paper, some ink
    # nothing but the two figures (atomic writes leave no temporary files)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["lgraph-demo.pdf", "lgraph-demo.png"]


def test_demo_in_current_folder_via_module(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "lgraph", "demo"], cwd=tmp_path, capture_output=True, text=True
    )
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "lgraph-demo.pdf").exists()


@pytest.mark.parametrize("argv", [[], ["demo"], ["render"], ["gallery"], ["plugins"]])
def test_help_everywhere(argv, capsys):
    with pytest.raises(SystemExit) as e:
        main([*argv, "--help"])
    assert e.value.code == 0
    assert "usage: lgraph" in capsys.readouterr().out


def test_no_command_prints_help(capsys):
    assert main([]) == 2
    assert "usage: lgraph" in capsys.readouterr().out


def test_demo_creates_its_folder_like_gallery(tmp_path, capsys):
    missing = tmp_path / "nope" / "deeper"
    assert main(["demo", str(missing)]) == 0
    assert (missing / "lgraph-demo.pdf").exists()


def test_demo_into_a_file_is_an_input_error(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    assert main(["demo", str(f)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("lgraph demo: error:") and "is not a folder" in err


def test_version(capsys):
    import lgraph

    with pytest.raises(SystemExit) as e:
        main(["--version"])
    assert e.value.code == 0
    assert capsys.readouterr().out.strip() == f"lgraph {lgraph.__version__}"


@pytest.mark.parametrize("jobs", ["0", "-3", "two"])
def test_gallery_jobs_must_be_at_least_one(jobs, tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        main(["gallery", str(tmp_path), "-j", jobs])
    assert e.value.code == 2
    assert "expected an integer >= 1" in capsys.readouterr().err


def test_render_help_lists_the_backend_suffixes(capsys):
    from lgraph.output.backends import backend_suffixes

    with pytest.raises(SystemExit):
        main(["render", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    for suffix in backend_suffixes():
        assert suffix in out


SCENE = """
[projector]
kind = "parallel"
direction = [1, 2, 3]

[[object]]
surface = "sphere"
params = { r = 1 }
"""


def _scene(tmp_path, extra=""):
    path = tmp_path / "s.toml"
    path.write_text(SCENE + extra)
    return path


def _no_part_files(folder):
    return not [p for p in folder.rglob("*") if p.name.endswith(".part")]


def test_render_checks_output_before_rendering(tmp_path, capsys, monkeypatch):
    import lgraph.render as vis

    def boom(*a, **k):
        raise AssertionError("rendered although the output is wrong")

    monkeypatch.setattr(vis, "render", boom)
    path = _scene(tmp_path)
    assert main(["render", str(path), "-o", str(tmp_path / "x.doc")]) == 2
    assert "unknown file suffix '.doc'" in capsys.readouterr().err
    assert main(["render", str(path), "-o", str(tmp_path)]) == 2  # a folder
    err = capsys.readouterr().err
    assert "is a folder" in err or "unknown file suffix" in err
    # [save] keys are checked against the backend of the output suffix
    bad = _scene(tmp_path, "\n[save]\ndpi = 200\ntitle = 3\n")
    assert main(["render", str(bad), "-o", str(tmp_path / "f.pdf")]) == 2
    err = capsys.readouterr().err
    assert f"{bad}:11: save.dpi: unknown option 'dpi' for .pdf output" in err
    assert f"{bad}:12: save.title: expected a string" in err  # every problem at once
    assert "Traceback" not in err


def test_render_creates_a_missing_output_folder(tmp_path, capsys):
    path = _scene(tmp_path, "\n[save]\ndpi = 40\n")
    out = tmp_path / "a" / "b" / "fig.png"
    assert main(["render", str(path), "-o", str(out)]) == 0
    assert out.exists() and _no_part_files(tmp_path)


def test_scene_file_with_bom_renders(tmp_path, capsys):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + SCENE.encode())
    assert main(["render", str(path), "-o", str(tmp_path / "bom.svg")]) == 0


def test_deep_nesting_and_huge_widths_give_no_traceback(tmp_path, capsys):
    deep = tmp_path / "deep.toml"
    deep.write_text(SCENE + "\n[render]\nhidden_lines = " + "[" * 5000 + "]" * 5000 + "\n")
    assert main(["render", str(deep), "-o", str(tmp_path / "d.svg")]) == 2
    assert "nested too deeply" in capsys.readouterr().err
    wide = _scene(tmp_path, "style = { width = 1e300 }\n[save]\ndpi = 30\n")
    with pytest.warns(UserWarning, match="covers the whole image"):
        assert main(["render", str(wide), "-o", str(tmp_path / "w.png")]) == 0
    assert _no_part_files(tmp_path)


def test_tiny_tolerance_in_a_scene_file_is_refused_before_rendering(tmp_path, capsys):
    path = _scene(tmp_path, "\n[render]\ntolerance = 1e-300\n")
    assert main(["render", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{path}:11: render.tolerance: expected a fraction" in err


def test_debug_shows_the_traceback(tmp_path):
    path = _scene(tmp_path, "\n[render]\ntolerance = 1e-300\n")
    with pytest.raises(Exception, match="render.tolerance"):
        main(["--debug", "render", str(path)])


def test_a_bad_width_is_reported_before_rendering(tmp_path, capsys, monkeypatch):
    import lgraph.render as vis

    def boom(*a, **k):
        raise AssertionError("rendered although --width is wrong")

    monkeypatch.setattr(vis, "render", boom)
    path = _scene(tmp_path)
    assert main(["render", str(path), "--width", "8.5 parsecs"]) == 2
    assert "--width:" in capsys.readouterr().err
