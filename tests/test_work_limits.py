"""Small input, huge work: every family parameter that multiplies the work has
a limit, checked before the work, with a ValueError naming the parameter
(docs/limits.rst).  The time bounds (5 s) only catch runaway work: every
refusal here takes well under a second."""

from __future__ import annotations

import itertools
import time
import tracemalloc
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import lgraph
import lgraph as lg
from lgraph import _tolerance as tol

ROOT = Path(__file__).resolve().parents[1]
QUICK = 5.0  # seconds: generous, only against runaway work


class _Timer:
    def __enter__(self) -> _Timer:
        self.t0 = time.perf_counter()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.seconds = time.perf_counter() - self.t0


def _saddle() -> lg.ParametricSurface:
    """A surface without closed forms whose parameter lines are not its lines
    of curvature (they are integrated) and with K < 0 (asymptotic lines)."""

    def f(u: Any, v: Any) -> np.ndarray:
        u, v = np.broadcast_arrays(u, v)
        return np.stack([u, v, 0.3 * u**3 - u * v * v + 0.2 * u * v], -1)

    return lg.ParametricSurface(f, (-1, 1), (-1, 1))


# -- level lines and parabolic lines ---------------------------------------------------
@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: lg.LevelLines(5, grid=4097), r"LevelLines: grid must be an integer from 9 to"),
        (lambda: lg.ParabolicLines(grid=4097), r"ParabolicLines: grid must be an integer from 9"),
        (lambda: lg.LevelLines(100000), r"LevelLines: n must be an integer from 0 to 1000,"),
        (
            lambda: lg.LevelLines(values=np.linspace(0, 1, 5000)),
            r"LevelLines: values must be a list of at most 1000 numbers, got 5000",
        ),
        (
            lambda: lg.LevelLines(1000, grid=1025),
            r"LevelLines: grid must be at most 201 with 1000 levels .* got 1025",
        ),
        (
            lambda: lg.LevelLines(values=np.linspace(0, 1, 100), grid=1025),
            r"LevelLines: grid must be at most 633 with 100 levels .* got 1025",
        ),
    ],
)
def test_level_line_limits_are_refused_at_construction(make: Any, message: str) -> None:
    with _Timer() as t, pytest.raises(ValueError, match=message):
        make()
    assert t.seconds < QUICK


def test_level_line_limits_allow_what_figures_use() -> None:
    lg.LevelLines(15)
    lg.LevelLines(9, grid=193)
    lg.LevelLines(1000)  # 1000 levels on the default grid: within MAX_LEVEL_CELLS
    lg.LevelLines(1000, grid=201)
    lg.LevelLines(values=[0.5], grid=tol.MAX_LEVEL_GRID)
    lg.ParabolicLines(grid=97)
    lg.ParabolicLines(grid=tol.MAX_LEVEL_GRID)
    with pytest.raises(ValueError, match="grid must be at most 201 with 1000 levels"):
        lg.LevelLines(1000, grid=202)


def test_level_batches_checks_its_budget_before_evaluating() -> None:
    from lgraph.families.level import level_batches

    calls = []

    def f(u1: Any, u2: Any) -> np.ndarray:
        calls.append(np.shape(u1))
        return np.asarray(u1, float)

    torus = lg.Torus(2, 0.8)
    with pytest.raises(ValueError, match=r"level_batches: grid must be an integer from 2 to 1025"):
        level_batches(torus, f, [0.0], 1.0, grid=4097)
    with pytest.raises(ValueError, match=r"level_batches: grid must be at most 201 with 1000"):
        level_batches(torus, f, np.linspace(-1, 1, 1000), 1.0, grid=1025)
    with pytest.raises(ValueError, match=r"level_batches: values must be at most 1000 levels"):
        level_batches(torus, f, np.zeros(1001), 1.0)
    assert not calls


def test_the_traced_function_is_evaluated_in_bounded_chunks() -> None:
    """On a fine grid the function sees at most LEVEL_CHUNK_NODES nodes at
    once (its working memory stays bounded); the lines are those of one call."""
    from lgraph.families.level import _on_grid
    from lgraph.surfaces.parametric._zero_set import grid_parameters

    torus = lg.Torus(2, 0.8)
    sizes = []

    def f(x: np.ndarray) -> np.ndarray:
        sizes.append(x[..., 0].size)
        return x[..., 0] + 0.5 * x[..., 2]

    (b,) = lg.LevelLines(function=f, values=[0.3], grid=513).batches(torus, None)
    assert len(b) >= 1
    assert max(sizes) <= tol.LEVEL_CHUNK_NODES
    U1, U2 = grid_parameters(torus, 513)

    def g(u1: Any, u2: Any) -> np.ndarray:
        return torus.point(u1, u2) @ np.array([1.0, 0.0, 0.5])

    np.testing.assert_allclose(_on_grid(g, U1, U2), g(U1, U2), rtol=0, atol=1e-13)
    # the default grid is evaluated in one call, as before
    U1, U2 = grid_parameters(torus, 193)
    sizes.clear()
    _on_grid(lambda u1, u2: f(torus.point(u1, u2)), U1, U2)
    assert sizes == [193 * 193]


# -- numeric lines of curvature and asymptotic lines ------------------------------------
@pytest.mark.parametrize(
    ("family", "message"),
    [
        (
            lg.LinesOfCurvature(100000, 100000),
            r"LinesOfCurvature: n1 must be an integer from 0 to 500 for lines integrated "
            r"numerically with spacing='complete', got 100000",
        ),
        (lg.LinesOfCurvature(3, 501), r"LinesOfCurvature: n2 must be an integer from 0 to 500"),
        (
            lg.LinesOfCurvature(3, 101, spacing="even"),
            r"LinesOfCurvature: n2 must be an integer from 0 to 100 .*spacing='even', got 101",
        ),
        (lg.AsymptoticLines(1000, 3), r"AsymptoticLines: n1 must be an integer from 0 to 500"),
        (
            lg.AsymptoticLines(101, 3, spacing="even"),
            r"AsymptoticLines: n1 must be an integer from 0 to 100",
        ),
    ],
)
def test_numeric_field_lines_are_refused_before_integrating(family: Any, message: str) -> None:
    surface = _saddle()
    with _Timer() as t, pytest.raises(ValueError, match=message):
        family.batches(surface, None)
    assert t.seconds < QUICK


def test_closed_forms_and_parameter_lines_keep_the_curve_limit() -> None:
    """Lines that are not integrated (closed forms; Enneper's parameter lines
    are its lines of curvature) are only limited by MAX_CURVES and, when
    rendered, by the sample budget MAX_POINTS: refused quickly either way."""
    for surface in (lg.Ellipsoid(3, 2, 1.3), lg.Enneper()):
        fam = lg.LinesOfCurvature(100000, 100000)
        with _Timer() as t:
            batches = fam.batches(surface, None)
        assert sum(len(b) for b in batches) == 200000 and t.seconds < QUICK
        sc = lg.Scene()
        sc.add(surface, fam)
        with _Timer() as t, pytest.raises(ValueError, match="the limit is 4000000"):
            sc.render(lg.ParallelProjector(direction=(1, 2, 3)))
        assert t.seconds < QUICK


def test_numeric_lines_within_the_limits_still_draw() -> None:
    (b,) = lg.LinesOfCurvature(3, 0).batches(_saddle(), None)
    assert len(b) == 3


# -- geodesics ----------------------------------------------------------------------------
def test_a_geodesic_both_ways_counts_twice_its_length() -> None:
    torus = lg.Torus(3, 1)
    length = 0.6 * tol.MAX_GEODESIC_TURNS * torus.size  # one way within the limit
    fam = lg.Geodesic((0.1, 0.2), (1.0, 0.7), length=length, both_ways=True)
    with _Timer() as t, pytest.raises(ValueError, match=r"Geodesic: length .* run both ways"):
        fam.batches(torus, None)
    assert t.seconds < QUICK
    with pytest.raises(ValueError, match=r"Geodesic: length .* exceeds the limit"):
        lg.Geodesic((0.1, 0.2), (1.0, 0.7), length=2 * length).batches(torus, None)


# -- scene files: the limits name the key ------------------------------------------------
_HEAD = """
[projector]
kind = "parallel"
azimuth = 30
elevation = 20

[[object]]
"""
_TORUS = 'surface = "torus"\nparams = { R = 2, r = 0.8 }\n'
_SADDLE = """surface = "parametric"
x = "u"
y = "v"
z = "0.3*u^3 - u*v^2 + 0.2*u*v"
u = [-1, 1]
v = [-1, 1]
"""


@pytest.mark.parametrize(
    ("family", "key", "message"),
    [
        (
            '{ name = "level_lines", n = 5, grid = 4097 }',
            "object[0].families[0].grid",
            "grid must be an integer from 9 to 1025, got 4097",
        ),
        (
            '{ name = "level_lines", n = 100000 }',
            "object[0].families[0].n",
            "n must be an integer from 0 to 1000, got 100000",
        ),
        (
            '{ name = "level_lines", n = 1000, grid = 1025 }',
            "object[0].families[0].grid",
            "grid must be at most 201 with 1000 levels",
        ),
        (
            '{ name = "parabolic_lines", grid = 100000 }',
            "object[0].families[0].grid",
            "grid must be an integer from 9 to 1025",
        ),
    ],
)
def test_scene_file_work_limits_name_the_key(
    tmp_path: Path, family: str, key: str, message: str
) -> None:
    path = tmp_path / "huge.toml"
    path.write_text(_HEAD + _TORUS + f"families = [{family}]\n", encoding="utf-8")
    with _Timer() as t, pytest.raises(lgraph.SceneFileError) as info:
        lgraph.load_scene_file(path)
    assert t.seconds < QUICK
    assert info.value.key == key
    assert message in str(info.value)


def test_scene_file_numeric_lines_are_refused_quickly(tmp_path: Path) -> None:
    """The numeric budget needs the surface, so it is checked when the loader
    first draws the family: a SceneFileError naming the family's place, at
    once, where it ran without end before."""
    path = tmp_path / "huge.toml"
    family = '{ name = "lines_of_curvature", n1 = 100000, n2 = 100000 }'
    path.write_text(_HEAD + _SADDLE + f"families = [{family}]\n", encoding="utf-8")
    with _Timer() as t, pytest.raises(lgraph.SceneFileError) as info:
        lgraph.load_scene_file(path)
    assert t.seconds < QUICK
    assert "n1 must be an integer from 0 to 500" in str(info.value)
    assert info.value.key == "object[0].families[0]"


# -- animation views ----------------------------------------------------------------------
def _scene() -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.Sphere(1))
    return scene


def test_a_billion_views_from_a_generator_are_refused_quickly_in_little_memory(
    tmp_path: Path,
) -> None:
    view = lg.ParallelProjector.from_angles(10, 20)
    refused = r"animate: frames must be an integer from 1 to 100000, got more than 100000"
    tracemalloc.start()
    try:
        with _Timer() as t, pytest.raises(ValueError, match=refused):
            lg.animate(_scene(), itertools.repeat(view, 10**9), tmp_path / "x.gif", progress=False)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert t.seconds < QUICK
    assert peak < 50e6  # one reference per view read, up to the limit: about 1 MB
    assert not list(tmp_path.iterdir())


def test_a_generator_is_read_only_one_view_past_the_limit(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setattr(tol, "MAX_FRAMES", 5)
    read = []

    def views() -> Iterator[lg.ParallelProjector]:
        for k in itertools.count():
            read.append(k)
            yield lg.ParallelProjector.from_angles(10 * k, 20)

    with pytest.raises(ValueError, match=r"animate: frames must be an integer from 1 to 5, got"):
        lg.animate(_scene(), views(), tmp_path / "x.gif", progress=False)
    assert len(read) == 6


def test_a_sequence_is_measured_not_read(tmp_path: Path) -> None:
    class Huge(Sequence):
        def __len__(self) -> int:
            return 10**9

        def __getitem__(self, k: Any) -> Any:
            raise AssertionError("the views were read")

    with _Timer() as t, pytest.raises(ValueError, match=r"got 1000000000"):
        lg.animate(_scene(), Huge(), tmp_path / "x.gif", progress=False)
    with pytest.raises(ValueError, match=r"got more than 100000 views"):
        lg.animate(_scene(), range(10**20), tmp_path / "x.gif", progress=False)  # len() overflows
    assert t.seconds < QUICK


def test_a_short_generator_still_animates(tmp_path: Path) -> None:
    from PIL import Image

    out = lg.animate(
        _scene(),
        (v for v in lg.orbit(elevation=20, frames=3)),
        tmp_path / "turn.gif",
        width=64,
        progress=False,
    )
    with Image.open(out) as im:
        assert im.n_frames == 3
    with pytest.raises(ValueError, match="views is empty"):
        lg.animate(_scene(), iter(()), tmp_path / "none.gif", progress=False)


# -- the docs page --------------------------------------------------------------------------
def test_the_limits_page_lists_the_work_limits() -> None:
    page = (ROOT / "docs" / "limits.rst").read_text(encoding="utf-8")
    for name in (
        "MAX_LEVELS",
        "MAX_LEVEL_GRID",
        "MAX_LEVEL_CELLS",
        "LEVEL_CHUNK_NODES",
        "MAX_FIELD_LINES",
        "MAX_EVEN_FIELD_LINES",
    ):
        assert f"``{name}" in page, name
        assert f"``{getattr(tol, name)}``" in page, name
    assert "Formulas" in page


def test_the_point_budget_names_the_family_and_node_that_cost(monkeypatch):
    """A render over the point budget says which family of which node needs
    the samples (issue #25: a numeric contour's cost was blamed on "the
    lines"), before sampling it."""
    from lgraph import _tolerance
    from lgraph.render.sampling import PointBudgetError

    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(2, 2))
    wiggle = lg.Curve(lambda t: np.stack([t, 0.05 * np.sin(377 * t), 2 + 0 * t], -1), -1.0, 1.0)
    scene.add(wiggle)
    monkeypatch.setattr(_tolerance, "MAX_POINTS", 1500)  # the wiggle needs about 2200
    with pytest.raises(PointBudgetError) as info:
        scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    message = str(info.value)
    assert "family 'curve' of node 1" in message and "raise tolerance" in message
