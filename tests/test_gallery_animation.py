"""The gallery's animated figure: a script with ANIMATION gets a turntable GIF."""

from __future__ import annotations

import io
import textwrap
from pathlib import Path

import numpy as np
from PIL import Image

from lgraph import gallery

GALLERY = Path(__file__).resolve().parent.parent / "gallery"


def test_the_gallery_shows_an_animated_gif(tmp_path: Path) -> None:
    spec = gallery.script_animation(GALLERY / "extra_turntable.py")
    assert spec and spec["frames"] >= 12
    out = io.StringIO()
    assert gallery.build_gallery(tmp_path, jobs=1, only=["extra_turntable"], stream=out) == 0
    im = Image.open(tmp_path / "extra_turntable.gif")
    assert im.n_frames == spec["frames"] and im.size[0] == spec["width"]
    first = np.asarray(im.convert("L"))
    im.seek(spec["frames"] // 4)
    quarter = np.asarray(im.convert("L"))
    assert (first < 128).mean() > 0.005 and not np.array_equal(first, quarter)
    index = (tmp_path / "index.html").read_text(encoding="utf-8")
    assert 'class="thumbnail" src="extra_turntable.gif"' in index
    assert (tmp_path / "extra_turntable.pdf").exists()  # the still figure too


def test_script_animation_reads_only_literals(tmp_path: Path) -> None:
    f = tmp_path / "a.py"
    f.write_text(textwrap.dedent("""
        ANIMATION = {"frames": 4, "elevation": 10}
    """), encoding="utf-8")  # fmt: skip
    assert gallery.script_animation(f) == {"frames": 4, "elevation": 10}
    f.write_text("ANIMATION = dict(frames=4)\n", encoding="utf-8")
    assert gallery.script_animation(f) is None
    f.write_text("CAPTION = 'x'\n", encoding="utf-8")
    assert gallery.script_animation(f) is None
