"""The Sphinx documentation builds without warnings and its examples run.

Both builds use ``-W`` (warnings are errors), as CI does, and the html build
is nitpicky (``-n``: every cross-reference must resolve); the html build here
skips rendering the gallery (``lgraph_gallery_build=0``; ``test_gallery.py``
covers the builder) except for one figure, to check the embedding.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

import lgraph

pytest.importorskip("sphinx", reason="Sphinx is not installed (pip install -e '.[docs]')")

DOCS = Path(__file__).resolve().parent.parent / "docs"


def _sphinx(builder: str, out: Path, *extra: str) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q", "-b", builder,
           *extra, str(DOCS), str(out)]  # fmt: skip
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300)


def test_html_build(tmp_path: Path) -> None:
    out = tmp_path / "html"
    res = _sphinx("html", out, "-n", "-D", "lgraph_gallery_only=extra_hidden_dashed")
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    for page in ("index", "getting_started", "concepts", "tutorial_surface", "notebooks",
                 "mathematics", "gallery", "limits", "api", "plotters_latex",
                 "architecture"):  # fmt: skip
        assert (out / f"{page}.html").exists(), page
    gallery_page = (out / "gallery.html").read_text(encoding="utf-8")
    assert 'src="gallery/extra_hidden_dashed.png"' in gallery_page
    assert (out / "gallery" / "extra_hidden_dashed.png").exists()
    assert (out / "gallery" / "index.html").exists()
    assert (out / "gallery" / "extra_hidden_dashed.pdf").read_bytes().startswith(b"%PDF")


def test_doctest_build(tmp_path: Path) -> None:
    res = _sphinx("doctest", tmp_path / "doctest")
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    summary = (tmp_path / "doctest" / "output.txt").read_text(encoding="utf-8")
    m = re.search(r"Doctest summary\s*=+\s*(\d+) tests", summary)
    assert m and int(m.group(1)) >= 20, summary[-2000:]
    assert "0 failures in tests" in summary


def test_api_reference_lists_every_public_name() -> None:
    api = (DOCS / "api.rst").read_text(encoding="utf-8")
    documented = set(re.findall(r"^\.\. auto(?:class|function|data|exception):: lgraph\.(\w+)",
                                api, re.M))  # fmt: skip
    missing = sorted(set(lgraph.__all__) - documented)
    assert not missing, f"add these public names to docs/api.rst: {missing}"


def test_api_reference_has_the_scene_file_format_and_the_plugins() -> None:
    api = (DOCS / "api.rst").read_text(encoding="utf-8")
    assert ".. automodule:: lgraph.scenefile" in api
    assert ".. automodule:: lgraph.plugins" in api
    import lgraph.scenefile as sf

    # the format in the module docstring names every table and key the parser allows
    for key in (*sf._TOP, *sf._OBJECT, *sf._STYLE, "hidden_lines", "tolerance", "hidden_style",
                "preset", "landscape", "margin", "kind", "eye", "target", "direction"):  # fmt: skip
        assert re.search(rf"\b{key}\b", sf.__doc__), key
