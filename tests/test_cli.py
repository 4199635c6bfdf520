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


def test_unwritable_output_is_a_clear_error(tmp_path, capsys):
    missing = tmp_path / "nope" / "deeper"
    assert main(["demo", str(missing)]) == 1
    assert "does not exist" in capsys.readouterr().err
