"""Property-based fuzzing (hypothesis) of the public surface of lgraph.

Every call either succeeds with a finite result or raises ValueError /
TypeError whose message names its owner and a parameter; failed saves leave
no file; visible strokes are the same with and without hidden lines.  Kept
small (a few dozen examples per property, no deadline) so that the whole
file runs in well under a minute on a 2-core machine.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis", reason="the fuzz suite needs hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import lgraph as lg  # noqa: E402
from lgraph.scenefile import SceneFileError, load_scene_file  # noqa: E402

FAST = settings(
    max_examples=100,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
    derandomize=True,
)
SLOW = settings(FAST, max_examples=25)

#: anything a user might pass where a number is expected
odd_numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-1e3, max_value=1e3),
    st.integers(min_value=-(10**6), max_value=10**6),
    st.sampled_from([0, -1, 1e-320, 1e300, True, False, None, "1", [1], np.int64(3),
                     np.float32(0.5), np.float64(np.nan), np.int8(-2)]),
)  # fmt: skip


def _names_parameter(exc: Exception, owner: str, params: tuple[str, ...]) -> bool:
    msg = str(exc)
    return msg.startswith(owner) and any(re.search(rf"\b{p}\b", msg) for p in params)


CONSTRUCTORS = {
    "Sphere": (lg.Sphere, ("r",)),
    "Ellipsoid": (lg.Ellipsoid, ("a", "b", "c")),
    "HyperboloidOneSheet": (lg.HyperboloidOneSheet, ("a", "b", "c")),
    "EllipticCylinder": (lg.EllipticCylinder, ("a", "b")),
    "EllipticParaboloid": (lg.EllipticParaboloid, ("a", "b")),
    "Torus": (lg.Torus, ("R", "r")),
    "DupinCyclide": (lg.DupinCyclide, ("a", "b", "d")),
}


@FAST
@given(
    name=st.sampled_from(sorted(CONSTRUCTORS)), values=st.lists(odd_numbers, min_size=3, max_size=3)
)
def test_constructors_accept_or_name_the_parameter(name, values) -> None:
    cls, params = CONSTRUCTORS[name]
    args = values[: len(params)]
    try:
        s = cls(*args)
    except (ValueError, TypeError) as e:
        assert _names_parameter(e, name, params), str(e)
        return
    lo, hi = s.bounds()
    assert np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))
    p = s.point(np.array([0.3, 1.1]), np.array([0.7, 2.0]))
    assert np.all(np.isfinite(p))


@FAST
@given(d=st.lists(odd_numbers, min_size=3, max_size=3))
def test_parallel_projectors_are_orthonormal_or_refused(d) -> None:
    try:
        p = lg.ParallelProjector(direction=d)
    except (ValueError, TypeError) as e:
        assert _names_parameter(e, "ParallelProjector", ("direction",)), str(e)
        return
    frame = np.array(p.frame)
    assert np.all(np.isfinite(frame))
    assert np.allclose(frame @ frame.T, np.eye(3), atol=1e-12)


@FAST
@given(az=odd_numbers, el=odd_numbers, dist=odd_numbers)
def test_projectors_from_angles(az, el, dist) -> None:
    try:
        p = lg.CentralProjector.from_angles(az, el, dist)
    except (ValueError, TypeError) as e:
        assert _names_parameter(e, "", ("azimuth", "elevation", "distance")), str(e)
        return
    assert np.all(np.isfinite(p.eye)) and p.distance > 0


@FAST
@given(args=st.lists(odd_numbers, min_size=4, max_size=4), kind=st.sampled_from(["t", "r", "s"]))
def test_transforms(args, kind) -> None:
    try:
        if kind == "t":
            t = lg.translate(*args[:3])
        elif kind == "r":
            t = lg.rotate(args[:3], args[3])
        else:
            t = lg.scale(*args[:3])
    except (ValueError, TypeError) as e:
        assert re.match(r"^\w+: ", str(e)), str(e)
        return
    x = t.apply(np.array([[1.0, 2.0, 3.0]]))
    assert np.all(np.isfinite(x))
    if kind == "r":  # a rotation: orthonormal, determinant 1
        m = t.matrix
        assert np.allclose(m @ m.T, np.eye(3), atol=1e-12) and np.linalg.det(m) > 0


@FAST
@given(width=odd_numbers, dash=st.one_of(st.none(), st.lists(odd_numbers, max_size=3)),
       color=st.one_of(st.sampled_from(["black", "grey", "#12ab34", "#zzzzzz", "", 3]),
                       st.lists(odd_numbers, min_size=3, max_size=3)))  # fmt: skip
def test_styles(width, dash, color) -> None:
    try:
        s = lg.Style(color=color, width=width, dash=dash)
    except (ValueError, TypeError) as e:
        assert _names_parameter(e, "Style", ("color", "width", "dash")), str(e)
        return
    assert s.width > 0 and math.isfinite(s.width)


BASE = """
[projector]
kind = "parallel"
direction = [1, 2, 3]

[render]
hidden_lines = false

[[object]]
surface = "ellipsoid"
params = {{ a = {a}, b = 1, c = 0.5 }}
families = [{{ name = "parameter_lines", n1 = {n1}, n2 = 4 }}]
style = {{ width = {w} }}
"""

toml_values = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False, min_value=-1e6, max_value=1e6).map(repr),
    st.integers(min_value=-5, max_value=50).map(str),
    st.sampled_from(['"x"', "true", "[1, 2]", "nan", "inf", "-0.0", "1e-300", "[]", "{}"]),
)


@SLOW
@given(a=toml_values, n1=toml_values, w=toml_values)
def test_scene_files_load_or_report_every_problem(tmp_path_factory, a, n1, w) -> None:
    folder = tmp_path_factory.mktemp("scene")
    path = folder / "s.toml"
    path.write_text(BASE.format(a=a, n1=n1, w=w))
    try:
        scene, projector, options = load_scene_file(path, output=folder / "s.svg")
    except SceneFileError as e:
        lines = str(e).splitlines()
        assert len(lines) == len(e.errors) >= 1
        for line in lines:
            assert re.match(rf"^{re.escape(str(path))}(:\d+)?: ", line), line
        return
    d = scene.render(projector, **options["render"])
    assert all(np.isfinite(s.xy).all() for s in d.strokes)


save_options = st.fixed_dictionaries(
    {},
    optional={
        "dpi": odd_numbers,
        "precision": odd_numbers,
        "supersample": odd_numbers,
        "title": st.sampled_from(["t", 3]),
        "bogus": st.just(1),
    },
)


@pytest.fixture(scope="module")
def small_drawing() -> lg.Drawing:
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(3, 5))
    return sc.render(lg.ParallelProjector(direction=(1, 2, 3)), tolerance=1e-3)


@SLOW
@given(suffix=st.sampled_from([".pdf", ".png", ".svg", ".doc", ""]), options=save_options)
def test_saves_write_a_file_or_leave_nothing(
    tmp_path_factory, small_drawing, suffix, options
) -> None:
    folder = tmp_path_factory.mktemp("save")
    target = folder / f"fig{suffix}"
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            small_drawing.save(target, **options)
    except (ValueError, TypeError) as e:
        assert re.match(r"^[\w.]+: ", str(e)), str(e)
        assert list(folder.iterdir()) == []
        return
    assert [p.name for p in folder.iterdir()] == [target.name]
    assert target.stat().st_size > 0


@SLOW
@given(
    d=st.lists(st.floats(min_value=-1, max_value=1), min_size=3, max_size=3).filter(
        lambda v: np.linalg.norm(v) > 0.1
    ),
    shift=st.lists(st.floats(min_value=-1.5, max_value=1.5), min_size=3, max_size=3),
)
def test_visible_strokes_do_not_depend_on_hidden_lines(d, shift) -> None:
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(4, 6))
    sc.add(lg.Ellipsoid(1, 0.6, 0.4), lg.ParameterLines(3, 5), transform=lg.translate(*shift))
    p = lg.ParallelProjector(direction=d)
    plain = sc.render(p, tolerance=1e-3)
    both = sc.render(p, tolerance=1e-3, hidden_lines=True)
    visible = [s for s in both.strokes if s.visible]
    assert all(np.isfinite(s.xy).all() for s in both.strokes)

    def length(strokes) -> float:
        return sum(float(np.hypot(*np.diff(s.xy, axis=0).T).sum()) for s in strokes)

    # the same visible set: same total length and the same stroke ends
    assert length(visible) == pytest.approx(length(plain.strokes), rel=1e-3, abs=1e-9)
    ends = lambda ss: np.concatenate([s.xy[[0, -1]] for s in ss]) if ss else np.empty((0, 2))  # noqa: E731
    ea, eb = ends(plain.strokes), ends(visible)
    if len(ea) and len(eb):
        gap = np.linalg.norm(ea[:, None] - eb[None], axis=-1)
        assert gap.min(axis=1).max() < 1e-3 * 4
