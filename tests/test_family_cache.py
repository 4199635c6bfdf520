"""The cache of view-independent geometry (lgraph.families.cache)."""

from __future__ import annotations

import attrs
import numpy as np
import pytest

import lgraph as lg
from lgraph.families import Family
from lgraph.families import cache as family_cache

VIEWS = [
    lg.ParallelProjector.from_angles(30, 25),
    lg.CentralProjector.from_angles(-70, 40, 14),
    lg.ParallelProjector.from_angles(160, -10),
]


@pytest.fixture(autouse=True)
def fresh_cache():
    family_cache.clear()
    family_cache.set_max_entries(family_cache.MAX_ENTRIES)
    yield
    family_cache.clear()
    family_cache.set_max_entries(family_cache.MAX_ENTRIES)


def _same(a: lg.Drawing, b: lg.Drawing) -> None:
    assert len(a.strokes) == len(b.strokes)
    for s, t in zip(a.strokes, b.strokes):
        assert (s.family, s.visible, s.style, s.surface) == (
            t.family,
            t.visible,
            t.style,
            t.surface,
        )
        assert np.array_equal(s.xy, t.xy) and np.array_equal(s.xyz, t.xyz)
        assert (s.uv is None) == (t.uv is None)
        if s.uv is not None:
            assert np.array_equal(s.uv, t.uv)


def _scene() -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(6, 7))
    scene.add(lg.Torus(1.5, 0.5), lg.ParameterLines(6, 12), transform=lg.translate(0, 0, 2.2))
    scene.add(lg.HyperboloidOneSheet(1, 1, 1), lg.AsymptoticLines(4, 4),
              transform=lg.translate(0, 4.5, 0))  # fmt: skip
    scene.add(lg.Curve(lambda t: np.stack([np.cos(t), np.sin(t), t / 3], -1), 0, 6))
    return scene


def test_cached_and_uncached_renders_give_identical_strokes():
    scene = _scene()
    cached = [scene.render(v, hidden_lines=True) for v in VIEWS]
    info = family_cache.info()
    assert info["misses"] == 3 and info["hits"] == 6  # three families, three views
    family_cache.set_max_entries(0)  # off: every render computes everything
    family_cache.clear()
    for v, d in zip(VIEWS, cached):
        _same(d, scene.render(v, hidden_lines=True))
    assert family_cache.info()["hits"] == family_cache.info()["misses"] == 0


def test_numeric_lines_of_curvature_are_cached_and_identical():
    scene = lg.Scene()
    scene.add(lg.Helicoid(), lg.LinesOfCurvature(2, 2))
    first = [scene.render(v, tolerance=1e-2) for v in VIEWS[:2]]
    assert family_cache.info()["misses"] == 1 and family_cache.info()["hits"] == 1
    assert any(s.family == "curvature" for s in first[1].strokes)
    family_cache.set_max_entries(0)  # the second view came from the cache
    _same(first[1], scene.render(VIEWS[1], tolerance=1e-2))


@attrs.frozen
class Counting(Family):
    """Parameter lines that count how often they are computed."""

    calls: list = attrs.field(factory=list, eq=False)
    view_dependent = False

    def batches(self, surface, projector):
        self.calls.append(projector)
        return lg.ParameterLines(3, 3).batches(surface, projector)


@attrs.frozen
class CountingView(Counting):
    view_dependent = True


def test_view_independent_families_are_computed_once_view_dependent_ones_every_time():
    fixed, moving = Counting(), CountingView()
    scene = lg.Scene()
    scene.add(lg.Sphere(1), fixed, moving)
    for v in VIEWS:
        scene.render(v)
    assert len(fixed.calls) == 1
    assert len(moving.calls) == len(VIEWS)
    assert family_cache.is_view_dependent(lg.Contour())
    assert not family_cache.is_view_dependent(lg.LinesOfCurvature())


def test_a_changed_scene_is_recomputed():
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(4, 4))
    before = scene.render(VIEWS[0])
    # a node added after a render: drawn, and it hides part of the first
    ball = scene.add(lg.Sphere(1.5), lg.LinesOfCurvature(3, 3), transform=lg.translate(0, 0, 1.5))
    after = scene.render(VIEWS[0])
    fresh = lg.Scene()
    fresh.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(4, 4))
    fresh.add(lg.Sphere(1.5), lg.LinesOfCurvature(3, 3), transform=lg.translate(0, 0, 1.5))
    family_cache.set_max_entries(0)
    _same(after, fresh.render(VIEWS[0]))
    assert any(s.surface is ball.item for s in after.strokes)
    assert len(after.strokes) != len(before.strokes)
    # an equal-looking scene with other parameters shares nothing
    family_cache.set_max_entries(10)
    other = lg.Scene()
    other.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(5, 4))
    n = family_cache.info()["misses"]
    d = other.render(VIEWS[0])
    assert family_cache.info()["misses"] == n + 1
    assert len([s for s in d.strokes if s.family == "curvature"]) > len(
        [s for s in before.strokes if s.family == "curvature"]
    )


def test_memory_is_bounded():
    family_cache.set_max_entries(2)
    scene = lg.Scene()
    for k in range(5):
        scene.add(lg.Sphere(1), lg.ParameterLines(2 + k, 3), transform=lg.translate(3 * k, 0, 0))
    scene.render(VIEWS[0])
    assert family_cache.info()["entries"] == 2
    family_cache.set_max_entries(10)
    scene.render(VIEWS[0])
    assert family_cache.info()["entries"] == 5
    family_cache.set_max_entries(3)  # lowering the bound evicts at once
    assert family_cache.info()["entries"] == 3
    family_cache.clear()
    assert family_cache.info()["entries"] == 0
    with pytest.raises(ValueError, match="non-negative integer"):
        family_cache.set_max_entries(1.5)


def test_groups_share_the_cache_and_equal_uncached_renders():
    inner = lg.Scene()
    inner.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(4, 5))
    outer = lg.Scene()
    outer.add(inner, transform=lg.translate(0, 0, 1) @ lg.rotate("z", 30))
    outer.add(inner, transform=lg.translate(7, 0, 0))  # the same surface twice
    cached = [outer.render(v) for v in VIEWS]
    info = family_cache.info()
    assert info["misses"] == 1 and info["hits"] == 2 * len(VIEWS) - 1
    family_cache.set_max_entries(0)
    for v, d in zip(VIEWS, cached):
        _same(d, outer.render(v))


@attrs.frozen
class Unhashable(Family):
    """A family with a list field: attrs cannot hash it."""

    values: list = attrs.field(factory=lambda: [3, 3])
    view_dependent = False

    def batches(self, surface, projector):
        return lg.ParameterLines(*self.values).batches(surface, projector)


def test_unhashable_families_are_cached_by_identity():
    fam = Unhashable()
    with pytest.raises(TypeError):
        hash(fam)
    scene = lg.Scene()
    scene.add(lg.Sphere(1), fam)
    a = scene.render(VIEWS[0])
    scene.render(VIEWS[1])
    assert family_cache.info()["hits"] == 1
    family_cache.set_max_entries(0)
    _same(a, scene.render(VIEWS[0]))


def test_new_view_independent_families_are_cached():
    for fam in (lg.LevelLines(5), lg.ParabolicLines(), lg.SelfIntersection()):
        assert not family_cache.is_view_dependent(fam), fam


@attrs.frozen
class CountingPoints(Family):
    """Parameter lines whose batches count the points they evaluate."""

    points: list = attrs.field(factory=list, eq=False)
    view_dependent = False

    def batches(self, surface, projector):
        out = []
        for b in lg.ParameterLines(3, 4).batches(surface, projector):

            def evaluate(idx, t, f=b.evaluate):
                self.points.append(len(t))
                return f(idx, t)

            out.append(attrs.evolve(b, evaluate=evaluate))
        return out


def test_initial_samples_of_cached_batches_are_evaluated_once():
    fam = CountingPoints()
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), fam, transform=lg.rotate("x", 20))
    first = scene.render(VIEWS[0])
    initial = fam.points[0]  # the first call: every curve's initial samples
    assert initial == 7 * lg._tolerance.INITIAL_SAMPLES
    for v in VIEWS[1:]:
        n = len(fam.points)
        scene.render(v)
        # later views evaluate only refinement and flip points, never all of them again
        assert len(fam.points) > n and initial not in fam.points[n:]
    # the kept samples are those an uncached render computes: identical strokes
    family_cache.set_max_entries(0)
    _same(first, scene.render(VIEWS[0]))
    for v in VIEWS[1:]:
        family_cache.set_max_entries(family_cache.MAX_ENTRIES)
        cached = scene.render(v)
        family_cache.set_max_entries(0)
        _same(cached, scene.render(v))


def test_derived_data_lives_and_dies_with_its_entry():
    calls = []

    def compute():
        calls.append(1)
        return len(calls)

    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(2, 3))
    scene.add(lg.Sphere(1), lg.ParameterLines(4, 3), transform=lg.translate(3, 0, 0))
    node = scene.nodes[0]
    (batch,) = family_cache.family_batches(node, 0, node.families[0], None)
    assert family_cache.derived(batch, "k", compute) == 1
    assert family_cache.derived(batch, "k", compute) == 1  # kept
    assert family_cache.derived(batch, "other", compute) == 2  # keys apart
    # a batch the cache does not hold (a contour, a copy): computed every time
    copy = attrs.evolve(batch)
    assert family_cache.derived(copy, "k", compute) == 3
    assert family_cache.derived(copy, "k", compute) == 4
    # evicted with its entry
    family_cache.set_max_entries(1)
    other = scene.nodes[1]
    family_cache.family_batches(other, 0, other.families[0], None)
    assert family_cache.derived(batch, "k", compute) == 5
    family_cache.set_max_entries(10)
    (batch,) = family_cache.family_batches(node, 0, node.families[0], None)
    family_cache.derived(batch, "k", compute)
    family_cache.clear()  # and with clear()
    assert family_cache.derived(batch, "k", compute) == 7


def test_equal_surfaces_of_several_nodes_share_batches_and_keep_their_own_surface():
    # equal spheres in different nodes: one cached entry, one batch object;
    # every stroke still names its own node's surface, and the render equals
    # the uncached one (which evaluates every node on its own)
    spheres = [lg.Sphere(0.4) for _ in range(3)]
    scene = lg.Scene()
    for k, s in enumerate(spheres):
        scene.add(s, lg.ParameterLines(3, 4), transform=lg.translate(k, 0.5 * k, 0))
    p = lg.CentralProjector.from_angles(30, 25, 12)
    batches = [scene.batches(node, p)[0] for node in scene.nodes]
    assert batches[0] is batches[1] is batches[2]
    assert family_cache.info()["entries"] == 1
    cached = scene.render(p, hidden_lines=True)
    owners = {id(s) for s in spheres}
    assert {id(st.surface) for st in cached.strokes} == owners
    for st in cached.strokes:  # on its own sphere, at that node's place
        k = next(i for i, s in enumerate(spheres) if s is st.surface)
        centre = np.array([k, 0.5 * k, 0.0])
        assert np.allclose(np.linalg.norm(st.xyz - centre, axis=1), 0.4, atol=1e-12)
    family_cache.set_max_entries(0)
    _same(cached, scene.render(p, hidden_lines=True))
    assert not (lg.Sphere(0.4) == lg.Ellipsoid(0.4, 0.4, 0.4))  # no sharing across classes
    # their exact contours share one evaluation kernel (one call for all nodes)
    kernels = {id(s.contour(p)[0].kernel[0]) for s in spheres}
    assert len(kernels) == 1
