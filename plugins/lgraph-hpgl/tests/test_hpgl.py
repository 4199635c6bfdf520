"""Tests of the HPGL backend: parse the file back and compare with the drawing."""

from __future__ import annotations

import importlib.metadata as md
import re

import numpy as np
import pytest
from lgraph_hpgl import UNITS_PER_PT, write_hpgl

import lgraph as lg
from lgraph.output.drawing import Drawing, Page, Stroke, Style


def parse(text: str) -> list[tuple[int, np.ndarray]]:
    """(pen, points in plotter units) for every PU..PD polyline."""
    out, pen = [], 0
    for cmd in text.replace("\n", "").split(";"):
        if cmd.startswith("SP"):
            pen = int(cmd[2:])
        elif cmd.startswith("PU") and len(cmd) > 2:
            start = [int(x) for x in cmd[2:].split(",")]
            out.append((pen, [start]))
        elif cmd.startswith("PD"):
            nums = [int(x) for x in cmd[2:].split(",")]
            out[-1][1].extend(np.reshape(nums, (-1, 2)).tolist())
    return [(p, np.array(pts)) for p, pts in out]


def stroke(points, **kw):
    xy = np.asarray(points, float)
    return Stroke(xy=xy, xyz=np.zeros((len(xy), 3)), **kw)


def test_round_trip_of_a_rendered_scene(tmp_path):
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(5, 8))
    d = scene.render(lg.ParallelProjector.from_angles(30, 20))
    path = tmp_path / "s.hpgl"
    d.save(path) if "lgraph-hpgl" in _installed() else write_hpgl(d, path)
    text = path.read_text(encoding="ascii")
    assert text.startswith("IN;") and text.rstrip().endswith("PU;SP0;")
    assert re.fullmatch(r"[A-Z0-9,;\n-]*", text)
    lines = parse(text)
    expected = [pts for pts, _ in d.page_strokes()]
    assert len(lines) == len(expected)
    for (_pen, got), want in zip(lines, expected):
        # rounded to whole plotter units; repeated points are dropped
        assert np.abs(got[0] - want[0] * UNITS_PER_PT).max() <= 0.5
        assert np.abs(got[-1] - want[-1] * UNITS_PER_PT).max() <= 0.5
        w, h = d.page_size()
        assert got.min() >= 0 and got[:, 0].max() <= w * UNITS_PER_PT + 1


def test_pens_follow_colours_and_dashes_are_split(tmp_path):
    red = Style(color="#ff0000")
    d = Drawing(
        strokes=(
            stroke([[0, 0], [72, 0]]),
            stroke([[0, 10], [72, 10]], style=red),
            stroke([[0, 20], [72, 20]]),
            stroke([[0, 30], [72, 30]], style=Style(dash=(6, 6))),
        ),
        page=Page(margin=0, extent=72),
    )
    path = tmp_path / "p.hpgl"
    write_hpgl(d, path, pens=2)
    lines = parse(path.read_text())
    pens = [p for p, _ in lines]
    assert pens[:3] == [1, 2, 1]
    dashes = lines[3:]
    assert len(dashes) == 6  # 72 pt with 6 on / 6 off
    lengths = [np.linalg.norm(pts[-1] - pts[0]) / UNITS_PER_PT for _, pts in dashes]
    assert np.allclose(lengths, 6, atol=0.1)


class _Broken:
    """A drawing whose one stroke has a break (non-finite points)."""

    def page_strokes(self):
        pts = np.array([[0, 0], [10, 0], [np.nan, np.nan], [20, 0], [30, 5]], float)
        yield pts, stroke(pts)


def test_breaks_split_strokes_and_bad_options(tmp_path):
    path = tmp_path / "b.hpgl"
    write_hpgl(_Broken(), path)
    lines = parse(path.read_text())
    assert [len(p) for _, p in lines] == [2, 2]
    d = Drawing(strokes=(stroke([[0, 0], [1, 1]]),))
    with pytest.raises(ValueError, match="pens must be an integer"):
        write_hpgl(d, path, pens=0)


def _installed() -> set[str]:
    return {dist.metadata["Name"] for dist in md.distributions()}


def test_registered_as_the_hpgl_backend(tmp_path):
    if "lgraph-hpgl" not in _installed():  # pragma: no cover
        pytest.fail("lgraph-hpgl is not installed: run pip install -e plugins/lgraph-hpgl")
    from lgraph.output.backends import backend_suffixes

    assert ".hpgl" in backend_suffixes()
    d = Drawing(strokes=(stroke([[0, 0], [1, 1]]),))
    d.save(tmp_path / "x.hpgl")
    assert (tmp_path / "x.hpgl").read_text().startswith("IN;")


def test_labels_plain_in_the_stroke_font_math_left_out_with_a_warning(tmp_path):
    import warnings

    from lgraph_hpgl import write_hpgl

    import lgraph as lg

    scene = lg.Scene()
    scene.add(lg.Label("P", at=(0, 0, 0)))
    scene.add(lg.Label("$\\kappa$", at=(1, 1, 0)))
    d = scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    path = tmp_path / "a.hpgl"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        write_hpgl(d, path)
    assert any("TeX mathematics left out" in str(w.message) for w in caught)
    text = path.read_text()
    assert "LBP\x03" in text and "kappa" not in text


def test_no_control_character_of_a_hand_built_label_reaches_the_plotter(tmp_path):
    """A drawing built by hand may hold any label text; ESC (a device command)
    and ETX (the end of a label) must not reach the HP-GL stream."""
    import attrs
    from lgraph_hpgl import write_hpgl

    import lgraph as lg

    scene = lg.Scene()
    scene.add(lg.Label("P", at=(0, 0, 0)))
    d = scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    bad = attrs.evolve(d.labels[0], text="P\x1b.(\x03IN;\x07Q")
    d = attrs.evolve(d, labels=(bad,))
    path = tmp_path / "a.hpgl"
    write_hpgl(d, path)
    text = path.read_text()
    assert "\x1b" not in text and "\x07" not in text
    assert "LBP.(IN;Q\x03" in text and text.count("\x03") == 1
