"""Plotter-clean drawings (lgraph.output.plotter): checked by distances on the page,
by exhaustive search for the order, and against the original vertices."""

from __future__ import annotations

import importlib.util
import itertools
import re
from pathlib import Path

import attrs
import numpy as np
import pytest

import lgraph as lg
from lgraph.gallery import render_figure
from lgraph.output.backends._common import finite_runs
from lgraph.output.drawing import Drawing, Page, Stroke, Style
from lgraph.output.units import length_pt

GALLERY = Path(__file__).resolve().parent.parent / "gallery"


def stroke(points, **kw) -> Stroke:
    xy = np.asarray(points, float)
    return Stroke(xy=xy, xyz=np.c_[xy, np.arange(len(xy), dtype=float)], **kw)


def page(*strokes: Stroke) -> Drawing:
    """Projection coordinates equal page points: a 100 x 100 pt frame plus the strokes."""
    frame = (stroke([[0, 0], [100, 0]], family="frame"), stroke([[0, 100], [100, 100]]))
    return Drawing(strokes=frame + strokes, page=Page(margin=0, extent=100))


def segment_distance(points: np.ndarray, runs: list[np.ndarray]) -> np.ndarray:
    """Distance of every point to the nearest segment of the polylines ``runs``."""
    a = np.concatenate([r[:-1] for r in runs])
    b = np.concatenate([r[1:] for r in runs])
    ab = b - a
    out = np.empty(len(points))
    for k in range(0, len(points), 400):
        p = points[k : k + 400, None, :]
        t = np.clip(((p - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0, 1)
        out[k : k + 400] = np.linalg.norm(p - (a + t[..., None] * ab), axis=-1).min(axis=1)
    return out


def page_runs(d: Drawing) -> list[np.ndarray]:
    return [r for pts, _ in d.page_strokes() for r in finite_runs(pts)]


def travel(runs: list[np.ndarray]) -> float:
    return float(sum(np.linalg.norm(b[0] - a[-1]) for a, b in zip(runs, runs[1:])))


def gallery_drawing(name: str) -> Drawing:
    spec = importlib.util.spec_from_file_location(name, GALLERY / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return render_figure(module.build())


# -- the gallery ----------------------------------------------------------------------
@pytest.mark.parametrize(
    "name", ["fig_4_3_normal_curvature_torus", "extra_hidden_dashed", "fig_4_5_general_cones"]
)
def test_gallery_figures_keep_every_point_within_tol(name: str) -> None:
    d = gallery_drawing(name)
    tol = 0.3  # pt
    clean = d.for_plotter(merge=tol, min_length=0)
    assert clean.page_size() == d.page_size()
    before, after = page_runs(d), page_runs(clean)
    assert len(after) < len(before)
    # every point of the original within tol of the result (and nothing new: every
    # vertex of the result is a vertex of the original, with its own xyz)
    dist = segment_distance(np.concatenate(before), after)
    assert dist.max() <= tol * (1 + 1e-9), dist.max()
    orig = {tuple(p) for s in d.strokes for p in np.c_[s.xy, s.xyz].tolist()}
    new = {tuple(p) for s in clean.strokes for p in np.c_[s.xy, s.xyz].tolist()}
    assert new <= orig
    assert clean.pen_up_length() < 0.7 * d.pen_up_length()
    # the default tolerances keep it within 0.1 mm as well
    default = d.for_plotter()
    dist = segment_distance(
        np.concatenate([r for r in before if np.linalg.norm(np.diff(r, axis=0), axis=1).sum()
                        >= length_pt("0.3mm")]),
        page_runs(default),
    )  # fmt: skip
    assert dist.max() <= length_pt("0.1mm") * (1 + 1e-9)


# -- duplicates, merging, fragments ---------------------------------------------------
def test_the_same_curve_added_twice_is_drawn_once() -> None:
    helix = lg.Curve(lambda t: np.stack([np.cos(t), np.sin(t), 0.2 * t], axis=-1), 0, 12)
    scene = lg.Scene()
    scene.add(helix)
    scene.add(helix)
    d = scene.render(lg.ParallelProjector.from_angles(30, 20))
    assert len(d.strokes) == 2
    clean = d.for_plotter()
    assert len(clean.strokes) == 1
    np.testing.assert_array_equal(
        np.sort(clean.strokes[0].xy, axis=0), np.sort(d.strokes[0].xy, axis=0)
    )


def test_overlapping_ends_are_trimmed_and_crossings_kept() -> None:
    long = stroke([[10, 50], [90, 50]])
    overlap = stroke([[60, 50], [80, 50], [80, 80]])  # its first 20 pt lie on `long`
    cross = stroke([[50, 20], [50, 80]])  # crosses `long`: stays whole
    d = page(long, overlap, cross)
    clean = d.for_plotter(merge=0.5, min_length=0, sort=False)
    got = {tuple(map(tuple, s.xy)) for s in clean.strokes}
    assert ((50.0, 20.0), (50.0, 80.0)) in got
    assert ((80.0, 50.0), (80.0, 80.0)) in got  # the trimmed overlap
    assert ((10.0, 50.0), (90.0, 50.0)) in got
    dist = segment_distance(np.concatenate(page_runs(d)), page_runs(clean))
    assert dist.max() <= 0.5


def test_pieces_of_a_closed_curve_become_one_closed_path() -> None:
    t = np.linspace(0, 2 * np.pi, 201)
    circle = np.c_[50 + 30 * np.cos(t), 50 + 30 * np.sin(t)]
    circle[-1] = circle[0] + [0.0, 0.05]  # ends meet within the tolerance, not exactly
    pieces = [
        stroke(circle[:70], family="contour"),
        stroke(circle[69:140][::-1], family="contour"),  # reversed
        stroke(circle[139:], family="contour"),
    ]
    clean = page(*pieces).for_plotter(merge=0.1, min_length=0)
    contour = [s for s in clean.strokes if s.family == "contour"]
    assert len(contour) == 1
    xy = contour[0].xy
    np.testing.assert_array_equal(xy[0], xy[-1])  # closed exactly
    assert len(xy) == 202  # 201 vertices (the shared ones once), plus the closing point
    r = np.linalg.norm(xy - 50, axis=1)
    assert np.abs(r - 30).max() < 0.06
    # consecutive points stay neighbours on the circle (one pass around)
    step = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    assert step.max() < 2 * 30 * np.sin(np.pi / 200) + 0.06
    # xyz travelled with xy
    orig = {tuple(p) for s in pieces for p in np.c_[s.xy, s.xyz].tolist()}
    assert {tuple(p) for p in np.c_[xy, contour[0].xyz].tolist()[:-1]} <= orig


def test_strokes_of_different_families_or_styles_are_not_merged() -> None:
    a = stroke([[10, 50], [30, 50]], family="u1")
    b = stroke([[30, 50], [50, 50]], family="u2")
    c = stroke([[50, 50], [70, 50]], family="u2", style=Style(width=2))
    clean = page(a, b, c).for_plotter(min_length=0)
    assert len(clean.strokes) == 5


def test_a_path_over_two_surfaces_has_no_surface() -> None:
    a, b = lg.Sphere(1), lg.Sphere(2)
    uv = np.zeros((2, 2))
    one = stroke([[10, 50], [30, 50]], family="u1", surface=a, uv=uv)
    two = stroke([[50, 50], [30, 50]], family="u1", surface=b, uv=uv)
    same = stroke([[10, 60], [30, 60]], family="u1", surface=a, uv=uv)
    same2 = stroke([[30, 60], [50, 60]], family="u1", surface=a, uv=uv + 1)
    clean = page(one, two, same, same2).for_plotter(min_length=0)
    merged = {s.xy[:, 1][0]: s for s in clean.strokes if s.family == "u1"}
    assert len(merged) == 2
    assert merged[50.0].surface is None and merged[50.0].uv is None
    assert merged[60.0].surface is a
    np.testing.assert_array_equal(np.abs(merged[60.0].xy[:, 0] - 30), [20, 0, 20])
    assert merged[60.0].uv.shape == (3, 2)


def test_fragments_shorter_than_min_length_are_dropped() -> None:
    tiny = stroke([[50, 50], [50.5, 50]])  # 0.5 pt
    short = stroke([[20, 50], [22, 50]])  # 2 pt
    d = page(tiny, short)
    assert len(d.for_plotter(min_length=1).strokes) == 3
    assert len(d.for_plotter(min_length="1mm").strokes) == 2  # 2.83 pt
    assert len(d.for_plotter(min_length=0).strokes) == 4


# -- order ----------------------------------------------------------------------------
def best_travel(runs: list[np.ndarray]) -> float:
    """Exhaustive: the least pen-up travel over all orders and orientations."""
    best = np.inf
    for order in itertools.permutations(range(len(runs))):
        for flips in itertools.product((False, True), repeat=len(runs)):
            seq = [runs[i][::-1] if f else runs[i] for i, f in zip(order, flips)]
            best = min(best, travel(seq))
    return best


def nearest_neighbour_travel(runs: list[np.ndarray]) -> float:
    """Greedy from the first path, entering each next path at its nearer end."""
    left = list(range(1, len(runs)))
    seq = [runs[0]]
    while left:
        end = seq[-1][-1]
        d = [(min(np.linalg.norm(runs[i][0] - end), np.linalg.norm(runs[i][-1] - end)), i)
             for i in left]  # fmt: skip
        _, i = min(d)
        left.remove(i)
        r = runs[i]
        seq.append(r if np.linalg.norm(r[0] - end) <= np.linalg.norm(r[-1] - end) else r[::-1])
    return travel(seq)


def test_order_of_parallel_lines_is_the_zigzag() -> None:
    rng = np.random.default_rng(3)
    ys = rng.permutation(np.arange(5) * 15.0 + 10)
    lines = [stroke([[10, y], [90, y]], family="u1") for y in ys]
    d = Drawing(strokes=lines, page=Page(margin=0, extent=80))
    clean = d.for_plotter(merge=0.01, min_length=0)
    runs = page_runs(clean)
    assert travel(runs) == pytest.approx(best_travel(page_runs(d)))
    assert travel(runs) == pytest.approx(clean.pen_up_length())


@pytest.mark.parametrize("seed", range(6))
def test_order_is_no_worse_than_nearest_neighbour_and_near_the_optimum(seed: int) -> None:
    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 100, (4, 2, 2))
    d = Drawing(
        strokes=[stroke(p, family="u1") for p in pts] + [stroke([[0, 0], [100, 100]], family="u1")],
        page=Page(margin=0, extent=100),
    )
    original = page_runs(d)
    got = d.for_plotter(merge=0.01, min_length=0).pen_up_length()
    assert got <= nearest_neighbour_travel(original) + 1e-9
    assert got <= 1.25 * best_travel(original) + 1e-9


def test_pen_up_length_by_hand_and_units() -> None:
    d = Drawing(
        strokes=[
            stroke([[0, 0], [10, 0]], family="u1"),
            stroke([[10, 3], [0, 3]], family="u2"),  # another layer: no travel to it
            stroke([[10, 4], [20, 4]], family="u1"),
        ],
        page=Page(margin=0, extent=20),
    )
    assert d.pen_up_length() == pytest.approx(4.0)
    assert d.pen_up_length(layers=None) == pytest.approx(3.0 + np.hypot(10, 1))
    assert d.pen_up_length("mm") == pytest.approx(4.0 * 25.4 / 72)
    with pytest.raises(ValueError, match="unit must be one of pt, in, cm, mm"):
        d.pen_up_length("px")


def test_bad_options_are_refused() -> None:
    d = page()
    for kw, msg in [
        ({"merge": -1}, "merge must be a length >= 0"),
        ({"merge": "0.1 furlong"}, "merge must be a length >= 0"),
        ({"min_length": float("nan")}, "min_length must be a length >= 0"),
        ({"sort": "yes"}, "sort must be True or False"),
        ({"layers": "pens"}, "layers must be 'family', 'surface', 'occlusion' or None"),
    ]:
        with pytest.raises(ValueError, match=msg):
            d.for_plotter(**kw)


def test_tolerances_on_the_plotted_page() -> None:
    tiny = stroke([[50, 50], [51, 50]])  # 1 pt = 0.353 mm on the drawing's 100 pt page
    d = page(tiny)
    assert len(d.for_plotter(min_length="0.3mm").strokes) == 3  # kept
    assert len(d.for_plotter(min_length="0.3mm", width="20mm").strokes) == 2  # 0.2 mm: dropped
    assert len(d.for_plotter(min_length="0.3mm", width="200mm").strokes) == 3  # 2 mm: kept
    with pytest.raises(ValueError, match="for_plotter: width must be a positive length"):
        d.for_plotter(width="-2mm")


def test_nan_breaks_and_empty_drawings() -> None:
    broken = stroke([[10, 10], [20, 10], [np.nan, np.nan], [30, 10], [40, 10]])
    clean = page(broken).for_plotter(min_length=0)
    assert all(np.isfinite(s.xy).all() for s in clean.strokes)
    assert len(clean.strokes) == 4
    assert len(Drawing(strokes=()).for_plotter().strokes) == 0
    assert Drawing(strokes=()).pen_up_length() == 0.0


def test_command_line_plotter_flag(tmp_path) -> None:  # noqa: ANN001
    from lgraph.cli import main

    scene = tmp_path / "fig.toml"
    scene.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 30\nelevation = 20\n'
        "[render]\nhidden_lines = true\n"
        '[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
        'families = [{ name = "parameter_lines", n1 = 4, n2 = 6 }]\n'
    )
    assert main(["render", str(scene), "-o", str(tmp_path / "raw.svg")]) == 0
    assert main(["render", str(scene), "-o", str(tmp_path / "clean.svg"), "--plotter"]) == 0
    raw = (tmp_path / "raw.svg").read_text()
    clean = (tmp_path / "clean.svg").read_text()
    assert clean.count("<polyline") < raw.count("<polyline")
    assert clean.count("inkscape:groupmode") == raw.count("inkscape:groupmode") == 4
    labels = re.compile(r'inkscape:label="([^"]*)"')
    assert labels.findall(clean) == labels.findall(raw)  # same layer numbers and names
    out = tmp_path / "sized.svg"
    assert main(["render", str(scene), "-o", str(out), "--plotter", "--width", "120mm"]) == 0
    assert 'width="120mm"' in out.read_text()


def test_layers_keep_their_numbers_and_names(tmp_path) -> None:  # noqa: ANN001
    from lgraph.output.layers import drawing_layers

    d = gallery_drawing("extra_hidden_dashed")
    styled = [
        attrs.evolve(s, style=Style(width=1.0)) if i % 3 == 0 and s.visible else s
        for i, s in enumerate(d.strokes)
    ]  # two styles per family: layers u1 and u1-2, ...
    d = attrs.evolve(d, strokes=styled)
    clean = d.for_plotter()
    before = [(g.label, g.style) for g in drawing_layers(d)]
    assert [(g.label, g.style) for g in drawing_layers(clean)] == before
    assert len(before) > 4
