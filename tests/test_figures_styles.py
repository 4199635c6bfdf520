"""Styles where users expect them (issue #27): arrows in a family of their
own, page backgrounds (transparent or a colour), and the CSS/matplotlib
colour names with their exact values."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import lgraph as lg
from lgraph.scene.colors import COLORS, CSS_COLORS, parse_color

VIEW = lg.ParallelProjector.from_angles(30, 20)


def _arrow_scene(style=None) -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 4), style=style)
    scene.add(lg.Arrow((0, 0, 1), (0, 0, 2.2), label="$N$"), style=style)
    return scene


def test_an_arrow_added_with_default_families_draws_only_its_outline_as_family_arrow():
    d = _arrow_scene().render(VIEW, hidden_lines=True)
    arrow = [s for s in d.strokes if isinstance(s.surface, lg.Arrow)]
    assert arrow and {s.family for s in arrow} == {"arrow"}
    assert "boundary" not in {s.family for s in d.strokes}
    # the arrow's outline keeps the outline width (1.6 x the default 0.5 pt)
    assert all(s.style.width == pytest.approx(0.8) for s in arrow if s.visible)


def test_the_arrow_style_key_restyles_arrows_and_nothing_else():
    red = lg.Style(color="red", width=1.2)
    thick = lg.Style(width=2.0)
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 4), style={"contour": thick})
    scene.add(lg.Arrow((0, 0, 1), (0, 0, 2.2)), style={"arrow": red, "contour": thick})
    d = scene.render(VIEW)
    by_family = {}
    for s in d.strokes:
        by_family.setdefault(s.family, set()).add(s.style)
    assert by_family["arrow"] == {red}
    assert by_family["contour"] == {thick}


def test_arrow_outlines_still_hide_like_contours():
    # an arrow in front of the sphere (the eye at -y): the sphere's lines are
    # cut behind its shaft (the arrow's outline is in the net of visibility
    # changes, whatever its family's name)
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(12, 12))
    scene.add(lg.Arrow((-2, -1.5, 0), (2, -1.5, 0), shaft_radius=0.15, head_radius=0.3))
    d = scene.render(lg.ParallelProjector(direction=(0, -1, 0)))
    sphere = [s for s in d.strokes if isinstance(s.surface, lg.Sphere)]
    pts = np.concatenate([s.xyz for s in sphere])
    behind = (np.abs(pts[:, 2]) < 0.15 * (1 - 1e-6)) & (np.abs(pts[:, 0]) < 1.5)
    assert not behind.any()
    # and they do reach the shaft's edges
    near = np.abs(np.abs(pts[:, 2]) - 0.15) < 1e-6
    assert near.sum() >= 8


def test_tikz_gets_an_arrow_style_of_its_own(tmp_path: Path):
    pytest.importorskip("lgraph_tikz")
    d = _arrow_scene().render(VIEW)
    tex = d.save(tmp_path / "a.tex").read_text()
    assert "\\lgraphstyle{arrow}" in tex and "\\draw[lgraph/arrow]" in tex


# -- colour names ------------------------------------------------------------------
@pytest.mark.parametrize(
    "name, hex_",
    # published values (CSS Color Module Level 4, section 6.1)
    [("red", "#ff0000"), ("green", "#008000"), ("blue", "#0000ff"), ("grey", "#808080"),
     ("rebeccapurple", "#663399"), ("cornflowerblue", "#6495ed"), ("darkgoldenrod", "#b8860b")],
)  # fmt: skip
def test_css_names_have_their_published_values(name: str, hex_: str):
    assert COLORS[name] == hex_
    assert lg.Style(color=name).color == parse_color(hex_)


def test_the_tables_equal_matplotlibs():
    colors = pytest.importorskip("matplotlib.colors")
    assert CSS_COLORS == {k: v.lower() for k, v in colors.CSS4_COLORS.items()}
    for table in (colors.BASE_COLORS, colors.TABLEAU_COLORS):
        for name, value in table.items():
            assert parse_color(name) == pytest.approx(colors.to_rgb(value), abs=0.5 / 255)


def test_names_ignore_case_and_spaces_and_short_hex_is_accepted():
    assert parse_color("Dark Slate Grey") == parse_color("darkslategrey")
    assert parse_color("#f0c") == parse_color("#ff00cc")


def test_an_unknown_name_is_refused_naming_what_is_allowed():
    with pytest.raises(ValueError, match=r"Style: color must be a CSS or matplotlib colour name"):
        lg.Style(color="reddish")


def test_the_core_names_work_without_matplotlib(monkeypatch):
    import builtins

    real = builtins.__import__

    def no_mpl(name, *args, **kwargs):
        if name.startswith("matplotlib"):
            raise ImportError(name)
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_mpl)
    assert parse_color("tab:orange") == parse_color("#ff7f0e")


# -- backgrounds -------------------------------------------------------------------
def _plain() -> lg.Drawing:
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 4))
    return scene.render(VIEW)


def test_png_background_none_is_transparent_outside_the_ink(tmp_path: Path):
    from PIL import Image

    img = Image.open(_plain().save(tmp_path / "t.png", background=None, dpi=72))
    assert img.mode == "RGBA"
    a = np.asarray(img)
    assert a[0, 0, 3] == 0  # the page corner: nothing
    assert a[..., 3].max() == 255  # the lines are opaque


def test_png_background_colour_fills_the_page(tmp_path: Path):
    from PIL import Image

    img = Image.open(_plain().save(tmp_path / "c.png", background="tab:blue", dpi=72))
    assert tuple(np.asarray(img.convert("RGB"))[0, 0]) == (0x1F, 0x77, 0xB4)


def test_svg_and_pdf_paint_a_colour_and_nothing_for_none(tmp_path: Path):
    d = _plain()
    svg = d.save(tmp_path / "c.svg", background="lavender").read_text()
    assert '<rect x="0" y="0"' in svg and 'fill="#e6e6fa"' in svg
    assert "<rect" not in d.save(tmp_path / "n.svg", background=None).read_text()
    pdf = d.save(tmp_path / "c.pdf", background="#ff0000", compress=False).read_bytes()
    assert re.search(rb"1 0 0 rg 0 0 [\d.]+ [\d.]+ re f", pdf)
    pdf = d.save(tmp_path / "n.pdf", background="transparent", compress=False).read_bytes()
    assert b" re f" not in pdf


def test_a_bad_background_is_refused_before_writing(tmp_path: Path):
    with pytest.raises(ValueError, match="Drawing.save: background must be a colour or None"):
        _plain().save(tmp_path / "x.png", background="mauvish")
    assert not (tmp_path / "x.png").exists()
