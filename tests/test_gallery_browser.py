"""The gallery page in a real browser: headless Chromium loads ``index.html``,
takes a screenshot, and every thumbnail must have loaded.

The page itself marks each ``img.thumbnail`` with ``data-loaded="1"`` (or
``"0"``) once the window's load event has fired, checking ``naturalWidth > 0``;
Chromium's ``--dump-dom`` prints the DOM after the page has settled.
"""

from __future__ import annotations

import io
import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from lgraph import gallery

SUBSET = ["extra_hidden_dashed", "extra_composition"]


def _chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return "/usr/bin/chromium" if os.path.exists("/usr/bin/chromium") else None


CHROMIUM = _chromium()
pytestmark = pytest.mark.skipif(
    CHROMIUM is None,
    reason="Chromium is not installed (Debian: apt-get install chromium); "
    "the gallery page cannot be checked in a browser",
)


def _run(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    profile = tmp_path / "profile"
    cmd = [
        str(CHROMIUM),
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-dev-shm-usage",
        f"--user-data-dir={profile}",
        "--virtual-time-budget=10000",
        *args,
    ]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("gallery") / "site"
    log = io.StringIO()
    assert gallery.build_gallery(out, jobs=2, only=SUBSET, tolerance=1e-3, stream=log) == 0
    return out


def test_every_thumbnail_loads(site: Path, tmp_path: Path) -> None:
    url = (site / "index.html").as_uri()
    res = _run(tmp_path, "--dump-dom", url)
    assert res.returncode == 0, res.stderr[-2000:]
    dom = res.stdout
    marks = re.findall(r'<img[^>]*class="thumbnail"[^>]*>', dom)
    assert len(marks) == len(SUBSET), dom[:2000]
    for tag in marks:
        assert 'data-loaded="1"' in tag, f"thumbnail did not load: {tag}"
    assert f'data-thumbnails="{len(SUBSET)}/{len(SUBSET)}"' in dom


def test_missing_thumbnail_is_detected(site: Path, tmp_path: Path) -> None:
    # the check itself must be able to fail: break one thumbnail
    broken = tmp_path / "broken"
    shutil.copytree(site, broken)
    (broken / f"{SUBSET[0]}.png").unlink()
    res = _run(tmp_path, "--dump-dom", (broken / "index.html").as_uri())
    assert res.returncode == 0, res.stderr[-2000:]
    assert f'data-thumbnails="{len(SUBSET) - 1}/{len(SUBSET)}"' in res.stdout
    assert 'data-loaded="0"' in res.stdout


def test_screenshot(site: Path, tmp_path: Path) -> None:
    shot = tmp_path / "shot.png"
    res = _run(
        tmp_path, "--window-size=1200,900", f"--screenshot={shot}", (site / "index.html").as_uri()
    )
    assert res.returncode == 0 and shot.exists(), res.stderr[-2000:]
    img = np.asarray(Image.open(shot).convert("L"), dtype=float)
    assert img.shape == (900, 1200)
    # the page is light with dark text and drawings: it rendered, it is not blank
    assert (img > 200).mean() > 0.5
    assert (img < 100).mean() > 0.002
