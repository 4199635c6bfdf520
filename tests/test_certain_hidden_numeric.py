"""Certain hidden lines on numeric surfaces that hide parts of themselves
(issue #24): a user-written Enneper patch (extent 2, self-intersecting) and a
helicoid seen from above, in random views.  Between every two samples of a
visible stroke, points of the same parameter line are asked of the
surface's own ray test (``Surface.hits``, independent of the renderer's
sampling): none may be hidden, except within a small band of the stroke's
ends (the transitions themselves, located to 1e-12 of the span).

The helicoid's pieces hidden beside a cusp of its contour (contour and line
nearly parallel, 1e-4 apart in the image, the polylines not crossing) are
found by the near-miss refinement of
:func:`lgraph.render.crossings.seed_net_crossings`; the pieces of Enneper's
lines hidden across the patch's self-intersection curve are found when that
curve is drawn (``SelfIntersection``), which puts it into the net.  Two
mutation checks show that each of these is needed: without it, pieces
escape."""

from __future__ import annotations

import numpy as np
import pytest
from user_surfaces import enneper

import lgraph as lg
from lgraph._own import ON


def helicoid(u, v):
    return np.stack(np.broadcast_arrays(u * np.cos(v), u * np.sin(v), 0.5 * v), -1)


SURFACES = {
    "enneper": lg.ParametricSurface(enneper, (-2.0, 2.0), (-2.0, 2.0)),
    "helicoid": lg.ParametricSurface(helicoid, (0.2, 1.5), (0.0, 4 * np.pi)),
}


def _views(seed):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(2):
        az, el = rng.uniform(0, 360), rng.uniform(20, 80)
        out.append(lg.ParallelProjector.from_angles(az, el))
    return out


def _eye_rays(projector, x):
    if isinstance(projector, lg.CentralProjector):
        d = projector.eye - x
        return d, np.ones(len(x))
    return np.broadcast_to(projector.direction, x.shape), np.full(len(x), np.inf)


def _escaped(name, seed, self_intersection, views=None):
    """For each of the seed's views (or those at ``views``): how many points of the parameter lines,
    between two samples of a visible stroke and away from its ends, the
    surface's own ray test finds hidden."""
    surface = SURFACES[name]
    scene = lg.Scene()
    families = [lg.ParameterLines(10, 10)]
    if self_intersection:
        families.append(lg.SelfIntersection())
    scene.add(surface, *families)
    size = surface.size
    out = []
    chosen = _views(seed)
    for projector in chosen if views is None else [chosen[k] for k in views]:
        drawing = scene.render(projector, hidden_lines=True)
        lines = [s for s in drawing.strokes if s.family in ("u1", "u2") and s.visible]
        assert lines
        uv, ends = [], []
        for s in lines:
            a, b = s.uv[:-1], s.uv[1:]
            for f in (0.25, 0.5, 0.75):  # points of the line between two samples
                uv.append(a + f * (b - a))
            ends.append(s.xyz[[0, -1]])
        uv = np.concatenate(uv)
        ends = np.concatenate(ends)
        x = surface.point(uv[:, 0], uv[:, 1])
        d, smax = _eye_rays(projector, x)
        hidden = surface.hits(x, np.array(d), smax, np.full(len(x), ON, dtype=np.int8))
        # near a transition (the stroke's end) the ray grazes: not asked
        far = np.min(np.linalg.norm(x[:, None] - ends[None], axis=2), axis=1) > 1e-3 * size
        out.append(int((hidden & far).sum()))
    return out


@pytest.mark.parametrize("name", ["helicoid", "enneper"])
@pytest.mark.parametrize("seed", range(2))
def test_no_hidden_piece_between_two_visible_samples(name, seed):
    """Enneper's patch passes through itself: drawn with its
    ``SelfIntersection``, that curve is part of the net."""
    escaped = _escaped(name, seed, self_intersection=name == "enneper")
    assert escaped == [0, 0], f"hidden points drawn visible, per view: {escaped}"


def test_mutation_without_near_misses_the_helicoid_shows_hidden_pieces(monkeypatch):
    """Mutation check: with the near-miss refinement off (testing at the
    samples and at crossings of the polylines only), pieces the helicoid
    hides beside its contour's cusps are drawn visible."""
    import lgraph.render.crossings as crossings

    monkeypatch.setattr(crossings, "NEAR_PASSES", 0)
    assert sum(_escaped("helicoid", 0, self_intersection=False, views=[1])) > 0


def test_mutation_without_the_self_intersection_in_the_net_pieces_escape(monkeypatch):
    """Mutation check: the self-intersection curve drawn but left out of the
    net, pieces of Enneper's lines hidden across it are drawn visible (as
    they are when ``SelfIntersection`` is not drawn: docs/mathematics.rst)."""
    import lgraph.render.crossings as crossings

    monkeypatch.setattr(crossings, "SELF_MEETING_FAMILY", "not a family")
    assert sum(_escaped("enneper", 0, self_intersection=True, views=[0])) > 0


def test_sagittas_bound_the_distance_of_a_circle_from_its_chords():
    """The chords' sagitta estimates of near-miss detection against the exact
    sagitta of a circle's chords (r (1 - cos(h/2)))."""
    from types import SimpleNamespace

    from lgraph.render.crossings import _sagittas

    t = np.linspace(0, np.pi, 21)
    xy = np.column_stack([np.cos(t), np.sin(t)])
    s = SimpleNamespace(t=t, xy=xy, cid=np.zeros(21, dtype=int), view=np.zeros(1, dtype=int))
    sag = _sagittas(s, np.array([1.0]))[:-1]
    exact = 1 - np.cos((t[1] - t[0]) / 2)
    assert np.all(sag >= exact) and np.all(sag <= 8 * exact)


R_TORUS, r_TORUS = 2.0, 0.7


def _torus(u, v):
    w = R_TORUS + r_TORUS * np.cos(v)
    return np.stack(np.broadcast_arrays(w * np.cos(u), w * np.sin(u), r_TORUS * np.sin(v)), -1)


def _hidden_by_the_torus(x, eye):
    """Exact: whether the segment from each point to the eye meets the torus
    (the real roots of its quartic along the segment, from the eigenvalues
    of the companion matrices; the point's own root at 0 left out)."""
    d = eye - x
    length = np.linalg.norm(d, axis=1)
    d = d / length[:, None]
    a1, a0 = 2 * np.einsum("ij,ij->i", x, d), np.einsum("ij,ij->i", x, x)
    c = a0 + R_TORUS**2 - r_TORUS**2
    q2 = d[:, 0] ** 2 + d[:, 1] ** 2
    q1 = 2 * (x[:, 0] * d[:, 0] + x[:, 1] * d[:, 1])
    q0 = x[:, 0] ** 2 + x[:, 1] ** 2
    k = 4 * R_TORUS**2
    # (s^2 + a1 s + c)^2 - k (q2 s^2 + q1 s + q0): monic, coefficients of s^3 .. s^0
    coef = np.stack([2 * a1, a1**2 + 2 * c - k * q2, 2 * a1 * c - k * q1, c**2 - k * q0], 1)
    companion = np.zeros((len(x), 4, 4))
    companion[:, 0, :] = -coef
    companion[:, [1, 2, 3], [0, 1, 2]] = 1.0
    roots = np.linalg.eigvals(companion)
    real = np.abs(roots.imag) < 1e-9
    s = roots.real
    return np.any(real & (s > 1e-6) & (s < length[:, None]), axis=1)


def _torus_flip_errors(angles):
    """Distances (relative to the scene) of the ends of visible strokes on a
    user-written torus (a ParametricSurface: the numeric ray test) from the
    exact transitions along their lines, found by bisection on the torus's
    quartic within 1e-3 of the line's span of each end (all ends at once)."""
    surface = lg.ParametricSurface(_torus, (0, 2 * np.pi), (0, 2 * np.pi), periodic=(True, True))
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(12, 12))
    projector = lg.CentralProjector.from_angles(*angles, 15.0)
    drawing = scene.render(projector, hidden_lines=True)
    eye = np.asarray(projector.eye, float)
    size = 2 * (R_TORUS + r_TORUS)
    start, axis, t_end, out = [], [], [], []
    for s in drawing.strokes:
        if not s.visible or s.family not in ("u1", "u2") or len(s.uv) < 3:
            continue
        ax = 1 if s.family == "u1" else 0  # the parameter that runs along the line
        for end, inner in ((0, 1), (-1, -2)):
            t = s.uv[end, ax]
            if min(t % (2 * np.pi), -t % (2 * np.pi)) < 1e-9:
                continue  # the closed line's seam, not a transition
            start.append(s.uv[end])
            axis.append(ax)
            t_end.append(t)
            out.append(np.sign(t - s.uv[inner, ax]) * 1e-3 * 2 * np.pi)
    assert len(start) > 20
    start, axis, t_end, out = map(np.array, (start, axis, t_end, out))
    rows = np.arange(len(start))

    def point(t):
        uv = start.copy()
        uv[rows, axis] = t
        return surface.point(uv[:, 0], uv[:, 1])

    a, b = t_end - out, t_end + out
    assert not _hidden_by_the_torus(point(a), eye).any()  # visible inside the strokes
    assert _hidden_by_the_torus(point(b), eye).all()  # hidden past them
    for _ in range(40):
        m = 0.5 * (a + b)
        hidden = _hidden_by_the_torus(point(m), eye)
        a, b = np.where(hidden, a, m), np.where(hidden, m, b)
    return np.linalg.norm(point(0.5 * (a + b)) - point(t_end), axis=1) / size


@pytest.mark.parametrize("angles", [(30, 25), (140, 40), (250, 15)])
def test_flips_at_a_numeric_surfaces_own_contour_are_exact(angles):
    """A flip where a line passes its own surface's contour lies at the zero
    of ``N . ray`` (confirmed by ray tests beside it).  The numeric ray test
    takes a fold's root within about 1e-5 of the scene for the point's own, so
    a K-section on it alone put 16-24 of about 40 transitions per view more
    than 1e-6 of the scene past the contour (up to 5e-5); now at most one (a
    sample itself so close to the contour that the ray test classifies it
    wrongly: docs/mathematics.rst), against the torus's exact quartic."""
    errors = _torus_flip_errors(angles)
    assert np.sum(errors > 1e-6) <= 2
    assert errors.max() < 2e-5


def test_mutation_flips_by_k_section_alone_miss_the_own_contour(monkeypatch):
    from lgraph.render import flips

    monkeypatch.setattr(flips, "_own_guided", lambda *args: None)
    assert np.mean(_torus_flip_errors((30, 25)) > 1e-6) > 0.3


def _line_behind_torus_errors(monkeypatch, angles):
    """Straight lines behind a user-written torus, seen from ``angles``: the
    distances (relative to the scene) of their visible strokes' inner ends
    from the exact transitions (bisection on the torus's quartic), and how
    many flips the net's crossing located (``flips._guided``)."""
    from lgraph.render import flips

    located = []
    guided = flips._guided

    def spy(s, fl, vis, whole, meetings):
        before = fl.open(whole)
        guided(s, fl, vis, whole, meetings)
        located.append(int((before & ~fl.open(whole)).sum()))

    monkeypatch.setattr(flips, "_guided", spy)
    surface = lg.ParametricSurface(_torus, (0, 2 * np.pi), (0, 2 * np.pi), periodic=(True, True))
    projector = lg.CentralProjector.from_angles(*angles, 15.0)
    eye = np.asarray(projector.eye, float)
    w = eye / np.linalg.norm(eye)
    e1 = np.cross(w, [0.0, 0.0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(w, e1)
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(2, 2))
    offsets = np.linspace(-1.3, 1.3, 7)
    for y0 in offsets:
        base = y0 * e2 - 2.5 * w

        def line(t, base=base):
            return base + np.asarray(t)[..., None] * e1

        scene.add(lg.Curve(line, -4.0, 4.0))
    drawing = scene.render(projector, hidden_lines=True)
    size = 2 * (R_TORUS + r_TORUS)
    ends, inner = [], []
    for s in drawing.strokes:
        if not s.visible or s.family != "curve":
            continue
        for end, nxt in ((0, 1), (-1, -2)):
            if np.abs(np.abs(s.xyz[end] @ e1) - 4.0) > 1e-9:  # not the line's own end
                ends.append(s.xyz[end])
                inner.append(s.xyz[end] - s.xyz[nxt])
    assert len(ends) >= 8
    ends, inner = np.array(ends), np.array(inner)
    step = 1e-3 * np.sign(inner @ e1)[:, None] * e1  # outward along the line
    a, b = ends - step, ends + step
    assert not _hidden_by_the_torus(a, eye).any()
    assert _hidden_by_the_torus(b, eye).all()
    for _ in range(45):
        m = 0.5 * (a + b)
        hidden = _hidden_by_the_torus(m, eye)[:, None]
        a, b = np.where(hidden, a, m), np.where(hidden, m, b)
    return np.linalg.norm(0.5 * (a + b) - ends, axis=1) / size, sum(located)


@pytest.mark.parametrize("angles", [(30, 25), (200, 50)])
def test_flips_behind_a_numeric_contour_lie_on_it(monkeypatch, angles):
    """A line passing behind a numeric surface's contour flips where its
    image crosses the contour's: each such flip is taken on that crossing of
    the exact curves (two ray tests beside it confirm it), not by a K-section
    from 1e-7 of the span on: all of them here, within 1e-9 of the scene of
    the exact transition (measured: 4e-13, the final bracket's half width)."""
    errors, located = _line_behind_torus_errors(monkeypatch, angles)
    assert located >= len(errors)
    assert errors.max() < 1e-9


def _enneper_self_crossings(fixed):
    """Where a parameter line of Enneper's surface through ``fixed`` (the
    other parameter) meets the self-intersection: the points ``(u, v)`` and
    ``(-u, v)`` have one image where ``u^2 = 3 (1 + v^2)`` (in the plane x = 0),
    ``(u, v)`` and ``(u, -v)`` where ``v^2 = 3 (1 + u^2)`` (y = 0): the running
    parameter's values there (the surface is symmetric in u and v)."""
    with np.errstate(invalid="ignore"):
        r = np.array([np.sqrt(3 * (1 + fixed**2)), np.sqrt(fixed**2 / 3 - 1)])
    r = r[np.isfinite(r)]
    return np.concatenate([r, -r])


def _enneper_flip_errors(hidden=False):
    """Distances (relative to the scene) of the ends of visible strokes
    (``hidden``: of hidden ones, split where their depth changes) of
    parameter lines on the self-intersecting Enneper patch (extent 2) that
    lie at its self-intersection from the exact crossings there, seen from
    (30, 25)."""
    surface = SURFACES["enneper"]
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(12, 12))
    drawing = scene.render(lg.CentralProjector.from_angles(30, 25, 20.0), hidden_lines=True)
    grid = surface.point(*np.meshgrid(*[np.linspace(-2, 2, 41)] * 2)).reshape(-1, 3)
    size = np.ptp(grid, axis=0).max()
    errors = []
    for s in drawing.strokes:
        if s.visible == hidden or s.family not in ("u1", "u2"):
            continue
        ax = 1 if s.family == "u1" else 0  # the running parameter
        for end in (0, -1):
            uv = s.uv[end]
            exact = _enneper_self_crossings(uv[1 - ax])
            if not len(exact):
                continue
            t = exact[np.argmin(np.abs(exact - uv[ax]))]
            if abs(t - uv[ax]) > 1e-3:
                continue  # an end elsewhere (contour, boundary)
            at = uv.copy()
            at[ax] = t
            errors.append(np.linalg.norm(surface.point(*at) - surface.point(*uv)) / size)
    return np.array(errors)


@pytest.mark.parametrize("hidden", [False, True], ids=["flips", "depths"])
def test_changes_where_a_line_passes_through_another_sheet_are_exact(hidden):
    """Enneper's patch of extent 2 hides its lines beyond its self-intersection
    (not drawn here, so not in the net), and the depth of hidden ones changes
    there: the ray's root on the other sheet reaches the line's point.  Each
    change is taken on that root of the followed ``s`` (lgraph.render.sheets),
    not by K-section on the ray test, which takes a root within about 1e-5 of
    the scene for the origin's own and so ended strokes up to that far off
    (measured: 9 visible and 21 hidden ends, all within 4e-13)."""
    errors = _enneper_flip_errors(hidden)
    assert len(errors) >= (16 if hidden else 8)
    assert errors.max() < 1e-9


@pytest.mark.parametrize("module", ["flips", "depth"])
def test_mutation_without_followed_sheets_the_self_crossings_are_off(monkeypatch, module):
    from lgraph.render import depth, flips

    mod = {"flips": flips, "depth": depth}[module]
    monkeypatch.setattr(mod, "through_sheets", lambda *args: (np.zeros(0, dtype=int), np.zeros(0)))
    assert _enneper_flip_errors(module == "depth").max() > 1e-8


def _torus_depth_errors(angles):
    """Distances (relative to the scene) of the depth changes of hidden
    parameter lines on the user-written torus (two hidden strokes of one
    line meeting, of different occlusion) from the exact ones, found by
    bisection on the count of the torus's quartic within 1e-3 of the span."""
    surface = lg.ParametricSurface(_torus, (0, 2 * np.pi), (0, 2 * np.pi), periodic=(True, True))
    exact = lg.Torus(R_TORUS, r_TORUS)
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(12, 12))
    projector = lg.CentralProjector.from_angles(*angles, 15.0)
    strokes = [
        s
        for s in scene.render(projector, hidden_lines=True).strokes
        if s.family in ("u1", "u2") and not s.visible
    ]
    start, axis, before, after = [], [], [], []
    for a, b in zip(strokes, strokes[1:]):
        if a.family == b.family and a.occlusion != b.occlusion:
            if np.linalg.norm(a.xyz[-1] - b.xyz[0]) < 1e-12:  # one line, a change of depth
                start.append(b.uv[0])
                axis.append(1 if a.family == "u1" else 0)
                before.append(a.occlusion)
                after.append(b.occlusion)
    start, axis, before, after = map(np.array, (start, axis, before, after))
    rows = np.arange(len(start))

    def count(t):
        uv = start.copy()
        uv[rows, axis] = t
        x = exact.point(uv[:, 0], uv[:, 1])
        return exact.hit_count(x, *projector.rays(x), np.full(len(t), ON, np.int8)), x

    t0 = start[rows, axis]
    lo, hi = t0 - 1e-3, t0 + 1e-3
    ok = (count(lo)[0] == before) & (count(hi)[0] == after)  # else not one change here
    for _ in range(45):
        m = 0.5 * (lo + hi)
        same = count(m)[0] == before
        lo, hi = np.where(same, m, lo), np.where(same, hi, m)
    size = 2 * (R_TORUS + r_TORUS)
    err = np.linalg.norm(count(0.5 * (lo + hi))[1] - count(t0)[1], axis=1) / size
    return err[ok]


def _no_guidance_for_depth(monkeypatch):
    from lgraph.render import depth

    def none(*args):
        return np.zeros(0, int), np.zeros(0)

    monkeypatch.setattr(depth, "through_sheets", none)
    monkeypatch.setattr(depth, "own_contour_zeros", none)


@pytest.mark.parametrize("guided", [True, False], ids=["guided", "mutation"])
def test_depth_changes_at_a_numeric_surfaces_own_contour(monkeypatch, guided):
    """Where a hidden line on a user-written torus passes its own contour, its
    depth changes at the zero of ``N . ray``, confirmed by counts beside it
    (the count errs within about 1e-5 of the scene of a fold).  K-section on
    the count alone put 21 of 41 such changes in two views more than 1e-8 of
    the scene off; now none (measured: at most 8e-10; one is allowed, a
    sample itself that close to a fold counted wrongly)."""
    if not guided:
        _no_guidance_for_depth(monkeypatch)
    errors = np.concatenate([_torus_depth_errors(a) for a in ((30, 25), (250, 15))])
    assert len(errors) >= 30
    off = np.sum(errors > 1e-8)
    assert (off <= 1) if guided else (off > len(errors) // 4)
