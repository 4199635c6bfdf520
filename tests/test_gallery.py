"""The gallery builder (``lgraph gallery``) and every gallery script."""

from __future__ import annotations

import io
import re
import shutil
import subprocess
import textwrap
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import lgraph
import lgraph as lg
from lgraph import gallery
from lgraph.cli import main as cli_main

GALLERY = Path(__file__).resolve().parent.parent / "gallery"
SCRIPTS = sorted(p for p in GALLERY.glob("*.py") if not p.name.startswith("_"))
SUBSET = ["extra_hidden_dashed", "extra_parallel_vs_central"]


class _Links(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.imgs: list[str] = []
        self.hrefs: list[str] = []
        self.ids: list[str] = []
        self.text: list[str] = []

    def handle_starttag(self, tag: str, attrs: list) -> None:
        a = dict(attrs)
        if tag == "img":
            self.imgs.append(a["src"])
        if tag == "a" and "href" in a:
            self.hrefs.append(a["href"])
        if tag == "figure":
            self.ids.append(a["id"])

    def handle_data(self, data: str) -> None:
        self.text.append(data)


def _parse(index: Path) -> _Links:
    p = _Links()
    p.feed(index.read_text(encoding="utf-8"))
    return p


def _assert_pdf(path: Path, tmp_path: Path) -> None:
    data = path.read_bytes()
    assert data.startswith(b"%PDF-"), path
    assert b"%%EOF" in data[-64:], path
    if shutil.which("pdftoppm"):  # the PDF must be readable by an independent reader
        out = tmp_path / f"ppm_{path.stem}"
        subprocess.run(
            ["pdftoppm", "-png", "-r", "20", "-singlefile", str(path), str(out)],
            check=True,
            capture_output=True,
            timeout=60,
        )
        img = np.asarray(Image.open(f"{out}.png").convert("L"))
        assert (img < 128).any(), f"{path.name}: pdftoppm rendered a blank page"


def _assert_line_drawing(path: Path) -> None:
    img = np.asarray(Image.open(path).convert("L"), dtype=float)
    assert min(img.shape) >= 100
    white = (img > 240).mean()
    dark = (img < 110).mean()
    assert white > 0.7, f"{path.name}: only {white:.0%} white: not a line drawing"
    assert dark > 0.003, f"{path.name}: only {dark:.2%} dark pixels: nearly empty"


def test_build_subset(tmp_path: Path) -> None:
    out = io.StringIO()
    rc = gallery.build_gallery(tmp_path / "site", jobs=2, only=SUBSET, tolerance=1e-3, stream=out)
    log = out.getvalue()
    assert rc == 0, log
    site = tmp_path / "site"
    for stem in SUBSET:
        _assert_pdf(site / f"{stem}.pdf", tmp_path)
        _assert_line_drawing(site / f"{stem}.png")
        assert (site / "src" / f"{stem}.py").read_bytes() == (GALLERY / f"{stem}.py").read_bytes()
        assert re.search(rf"^\[[12]/2\] {stem}  \d+\.\d s$", log, re.M), log
    # nothing else was built
    assert sorted(p.stem for p in site.glob("*.pdf")) == sorted(SUBSET)
    page = _parse(site / "index.html")
    text = " ".join(page.text)
    for stem in SUBSET:
        assert f"{stem}.png" in page.imgs
        assert f"{stem}.pdf" in page.hrefs
        assert f"src/{stem}.py" in page.hrefs
        caption = gallery.script_caption(GALLERY / f"{stem}.py")
        assert caption and caption[:40] in text
    assert page.ids == SUBSET


def _write(folder: Path, name: str, body: str) -> None:
    (folder / name).write_text(textwrap.dedent(body), encoding="utf-8")


GOOD = """
    import lgraph as lg
    CAPTION = "A sphere."
    def build():
        scene = lg.Scene()
        scene.add(lg.Sphere(1), lg.ParameterLines(4, 6))
        return scene, lg.ParallelProjector(direction=(1, 1, 1))
"""


@pytest.mark.parametrize("jobs", [1, 2])
def test_failures_are_reported_and_the_rest_build(tmp_path: Path, jobs: int) -> None:
    src = tmp_path / "scripts"
    src.mkdir()
    _write(src, "fig_1_1_good.py", GOOD)
    _write(src, "extra_broken.py", 'CAPTION = "Broken."\ndef build():\n    return 1 / 0\n')
    _write(src, "extra_no_import.py", "import lgraph_no_such_module\n")
    _write(src, "extra_no_build.py", 'CAPTION = "No build."\n')
    _write(src, "_helper.py", "raise RuntimeError('helpers are not figures')\n")
    out = io.StringIO()
    rc = gallery.build_gallery(tmp_path / "site", jobs=jobs, source_dir=src, stream=out)
    log = out.getvalue()
    assert rc == 1
    assert "Traceback" in log and "ZeroDivisionError" in log
    assert "ModuleNotFoundError" in log and "defines no build()" in log
    assert "3 failed" in log and "_helper" not in log
    site = tmp_path / "site"
    _assert_pdf(site / "fig_1_1_good.pdf", tmp_path)
    _assert_line_drawing(site / "fig_1_1_good.png")
    assert not (site / "extra_broken.pdf").exists()
    page = _parse(site / "index.html")
    assert page.ids == ["fig_1_1_good", "extra_broken", "extra_no_build", "extra_no_import"]
    assert page.imgs == ["fig_1_1_good.png"]
    html = (site / "index.html").read_text(encoding="utf-8")
    assert html.count('class="failed"') == 3
    assert "Broken." in html  # caption read from the source of the failing script


def test_no_match_and_missing_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out = io.StringIO()
    assert gallery.build_gallery(tmp_path, only=["no-such-figure"], stream=out) == 2
    with pytest.raises(FileNotFoundError, match="does not exist"):
        gallery.build_gallery(tmp_path, source_dir=tmp_path / "nowhere")
    fake = tmp_path / "site-packages" / "lgraph" / "__init__.py"
    monkeypatch.setattr(lgraph, "__file__", str(fake))
    with pytest.raises(FileNotFoundError, match="pip install -e"):
        gallery.default_gallery_dir()


def test_cli_gallery(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    rc = cli_main(["gallery", str(tmp_path), "-j", "1", "--only", "extra_hidden_dashed"])
    assert rc == 0
    assert "[1/1] extra_hidden_dashed" in capsys.readouterr().out
    assert (tmp_path / "extra_hidden_dashed.pdf").exists()
    assert (tmp_path / "index.html").exists()


def test_panels_side_by_side() -> None:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(2, 1, 1), lg.ParameterLines(3, 5))
    one = gallery.render_figure((scene, lg.ParallelProjector(direction=(1, 2, 1))))
    two = gallery.render_figure(
        [
            (scene, lg.ParallelProjector(direction=(1, 2, 1))),
            (scene, lg.CentralProjector(eye=(3, 6, 3)), {"hidden_lines": True}),
        ]
    )
    n1 = len(one.strokes)
    assert len(two.strokes) > 2 * n1  # the second panel adds hidden parts
    left = np.concatenate([s.xy for s in two.strokes[:n1]])
    right = np.concatenate([s.xy for s in two.strokes[n1:]])
    assert left[:, 0].max() < right[:, 0].min()
    # equal heights
    h1 = np.ptp(left[:, 1])
    h2 = np.ptp(right[:, 1])
    assert h1 == pytest.approx(h2, rel=1e-9)
    assert all(s.visible for s in two.strokes[:n1])  # hidden parts only in panel two
    assert not all(s.visible for s in two.strokes[n1:])
    with pytest.raises(TypeError, match="build\\(\\) must return"):
        gallery.render_figure("nonsense")
    with pytest.raises(TypeError, match="panel 0"):
        gallery.render_figure([(scene,)])


def test_run_script_main(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    script = GALLERY / "extra_composition.py"
    module = gallery._load_module(script)
    paths = gallery.run_script_main(str(script), module.build)
    assert sorted(p.name for p in paths) == ["extra_composition.pdf", "extra_composition.png"]
    _assert_pdf(tmp_path / "extra_composition.pdf", tmp_path)


def test_script_caption_and_titles(tmp_path: Path) -> None:
    _write(tmp_path, "a.py", 'CAPTION: str = "x" "y"\n')
    _write(tmp_path, "b.py", "CAPTION = f'{1}'\n")
    _write(tmp_path, "c.py", "def (\n")
    assert gallery.script_caption(tmp_path / "a.py") == "xy"
    assert gallery.script_caption(tmp_path / "b.py") == ""
    assert gallery.script_caption(tmp_path / "c.py") == ""
    assert gallery.figure_title("fig_4_1_ruled") == "Figure 4.1: ruled"
    stems = [p.stem for p in gallery.discover_scripts(GALLERY)]
    figs = [s for s in stems if s.startswith("fig_")]
    assert stems[: len(figs)] == figs  # paper figures first


# -- every gallery script ---------------------------------------------------------
def test_gallery_has_scripts() -> None:
    assert len(SCRIPTS) >= 3


@pytest.mark.parametrize("script", SCRIPTS, ids=[p.stem for p in SCRIPTS])
def test_gallery_script(script: Path) -> None:
    assert re.fullmatch(r"(fig_\d+_\d+|extra)_[a-z0-9_]+", script.stem), script.stem
    module = gallery._load_module(script)
    assert isinstance(module.CAPTION, str) and len(module.CAPTION) > 40
    assert gallery.script_caption(script) in ("", module.CAPTION)
    source = script.read_text(encoding="utf-8")
    assert re.search(r"^if __name__ == .__main__.:", source, re.M), "runs on its own"
    drawing = gallery.render_figure(module.build(), tolerance=1e-3)
    assert len(drawing.strokes) > 0
    for s in drawing.strokes:
        assert np.all(np.isfinite(s.xy)), f"{script.stem}: non-finite points"
