"""Gluings: periodic and twisted parameters (Domain), the cover, and every
line family drawn across a twisted seam as one stroke.

Independent checks: the parametrizations' own formulas continued past the
rectangle (``x(u + 2 pi, v) = x(u, -v)`` for the Moebius strip, say) against
``Domain.wrap``; strokes checked in space (no gap where their parameters jump
across the seam), by the defining equation of their family at the points
next to the seam (Rodrigues' formula for lines of curvature, zero normal
curvature for asymptotic lines, a normal acceleration for geodesics, the
level for level lines, ``N . w = 0`` for the contour).
"""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph.surfaces._domain import Domain

VIEW = lg.ParallelProjector(direction=(0.3, 0.2, 1.0))


# -- Domain ----------------------------------------------------------------
@pytest.mark.parametrize("bad", [("no", False), "yes", (2, False), (False, "twist"), (None, True)])
def test_periodic_refuses_anything_but_false_true_twisted(bad):
    allowed = r"Domain: periodic.* must be False, True(,| or) 'twisted'"
    with pytest.raises(ValueError, match=allowed):
        Domain((0, 1), (0, 1), periodic=bad)
    with pytest.raises(ValueError, match="ParametricSurface: periodic"):
        lg.ParametricSurface(
            lambda u, v: np.stack(np.broadcast_arrays(u, v, u), -1), (0, 1), (0, 1), periodic=bad
        )


def test_periodic_values_and_comparisons():
    assert Domain((0, 1), (0, 1), periodic=(True, False)).periodic == (True, False)
    assert Domain((0, 1), (0, 1), periodic=True).periodic == (True, True)
    d = Domain((0, 1), (0, 2), periodic=("twisted", True))
    assert d.periodic == ("twisted", True)
    assert d.glued == (True, True) and d.twisted == (True, False)
    assert len(d.ends(0)) == 0 and len(d.ends(1)) == 0


def _moebius_natural(u, v):
    """The Moebius formula evaluated anywhere (it continues the gluing by itself)."""
    r = 1 + v * np.cos(u / 2)
    return np.stack([r * np.cos(u), r * np.sin(u), v * np.sin(u / 2)], -1)


@pytest.mark.parametrize(
    "surface",
    [lg.MoebiusStrip(), lg.KleinBottle(form="figure8"), lg.RomanSurface(), lg.BoySurface()],
    ids=["moebius", "klein8", "roman", "boy"],
)
def test_wrap_agrees_with_the_formula_continued(surface):
    d = surface.domain
    rng = np.random.default_rng(4)
    lo = np.array([d.u1[0], d.u2[0]])
    span = np.array([d.span(0), d.span(1)])
    k = rng.integers(-3, 4, (400, 2)) * np.array(d.glued)
    c = lo + rng.uniform(0, 1, (400, 2)) * span + k * span
    base = d.wrap(c, clip=False)
    assert (base >= lo - 1e-12).all() and (base <= lo + span + 1e-12).all()
    # the classes' formulas are natural: evaluated outside they continue the surface
    inner = getattr(surface, "_inner", None)
    f = inner.func if inner is not None else None
    if isinstance(surface, lg.MoebiusStrip):
        f = _moebius_natural
    if f is None:  # Boy: numpy function of the sphere's point, defined everywhere
        from lgraph.surfaces.classical.onesided import _bryant_kusner as f
    x_cover = np.asarray(f(c[:, 0], c[:, 1]), float)
    np.testing.assert_allclose(surface.points(base), x_cover, atol=1e-12)


def test_deck_maps_and_continuous_polylines():
    for per in [("twisted", "twisted"), ("twisted", True), (False, "twisted"), (True, True)]:
        d = Domain((0, 1), (0, 2), periodic=per)
        t = np.linspace(0, 1, 500)[:, None]
        line = np.array([0.1, 0.3]) + t * np.array([3.7, 5.3]) * np.array(d.glued)
        wrapped = d.wrap(line, clip=False)
        np.testing.assert_allclose(d.continuous(wrapped), line, atol=1e-12)
        np.testing.assert_allclose(d.nearest_image(line + 1e-3, wrapped), line, atol=1e-12)


# -- strokes across the seam -----------------------------------------------
def _render(surface, *families, view=VIEW):
    """Visible parts only (``hidden_lines=False``): strokes break where they
    become hidden, never at a seam."""
    sc = lg.Scene()
    sc.add(surface, *families)
    return sc.render(view, hidden_lines=False)


def _crossings(stroke, d):
    """Indices i where the stroke's parameters jump across a glued seam between samples i, i+1."""
    jump = np.abs(np.diff(stroke.uv, axis=0)) / np.array([d.span(0), d.span(1)])
    return np.flatnonzero((jump > 0.5).any(axis=1))


def _check_one_stroke_across(drawing, surface, family):
    """Strokes of ``family``: continuous in space where their parameters jump
    (one stroke across the seam), none ending on a twisted seam (away from
    the boundary), and at least one crossing a twisted seam.  Returns the
    crossing samples ``(stroke, i)``."""
    d = surface.domain
    strokes = [s for s in drawing.strokes if s.family == family]
    assert strokes, family
    found = []
    size = surface.size
    for s in strokes:
        step = np.linalg.norm(np.diff(s.xyz, axis=0), axis=1)
        assert step.max() < 0.1 * size
        for i in _crossings(s, d):
            # no gap at the seam: the chord there is like its neighbours (the
            # renderer samples unevenly: densely near contours and flips)
            near = step[max(i - 3, 0) : i + 4]
            assert step[i] <= 5 * np.median(near) + 1e-9 * size
            found.append((s, i))
        for end in (s.uv[0], s.uv[-1]):
            for k in (0, 1):
                if not d.twisted[k]:
                    continue
                on_seam = min(abs(end[k] - e) for e in d.range(k)) < 1e-7 * d.span(k)
                other = 1 - k
                on_edge = (not d.glued[other]) and (
                    min(abs(end[other] - e) for e in d.range(other)) < 1e-7 * d.span(other)
                )
                assert not (on_seam and not on_edge), (family, end)
    twisted_jumps = [
        (s, i) for s, i in found
        if any(d.twisted[k] and abs(s.uv[i + 1, k] - s.uv[i, k]) > 0.5 * d.span(k) for k in (0, 1))
    ]  # fmt: skip
    assert twisted_jumps, f"no {family} stroke crosses a twisted seam"
    return twisted_jumps


@pytest.mark.parametrize(
    "surface", [lg.MoebiusStrip(), lg.KleinBottle(form="figure8"), lg.RomanSurface()],
    ids=["moebius", "klein8", "roman"],
)  # fmt: skip
def test_parameter_lines_cross_the_seam_as_one_stroke(surface):
    d = surface.domain
    drawing = _render(surface, lg.ParameterLines(6, 6))
    fam = "u2" if d.twisted[0] else "u1"  # the lines running along the twisted parameter
    for s, i in _check_one_stroke_across(drawing, surface, fam):
        k = 0 if d.twisted[0] else 1  # across the seam the other parameter is mirrored
        j = 1 - k
        a, b = s.uv[i, j], s.uv[i + 1, j]
        mirrored = d.mirror(j, a)
        if d.glued[j]:
            gap = (b - mirrored) / d.span(j)
            gap -= np.round(gap)
        else:
            gap = (b - mirrored) / d.span(j)
        assert abs(gap) < 0.02


def test_moebius_lines_pair_and_boundary_is_one_curve():
    m = lg.MoebiusStrip(width=1.0)
    (b,) = m.parameter_lines(0, 6)
    # six values of v = +-c: three closed lines of two turns
    assert len(b) == 3 and b.closed.all()
    np.testing.assert_allclose(b.t1 - b.t0, 4 * np.pi)
    (edge,) = m.boundary()
    assert len(edge) == 1 and edge.closed[0]
    t = np.linspace(edge.t0[0], edge.t1[0], 801)
    x, uv = edge.evaluate(np.zeros(len(t), int), t)
    np.testing.assert_allclose(x[0], x[-1], atol=1e-12)  # closes after two turns
    assert np.linalg.norm(np.diff(x, axis=0), axis=1).max() < 0.03
    # both edges v = -w/2 and v = w/2 are this one curve; the glued edge u = 0 is none
    np.testing.assert_allclose(np.abs(uv[:, 1]), 0.5, atol=1e-12)
    assert (uv[:, 1] > 0).any() and (uv[:, 1] < 0).any()
    drawing = _render(m, lg.ParameterLines(4, 0))
    for s in (s for s in drawing.strokes if s.family == "boundary"):
        np.testing.assert_allclose(np.abs(s.uv[:, 1]), 0.5, atol=1e-12)


def test_no_seam_is_drawn_on_glued_surfaces():
    for s in (lg.KleinBottle(), lg.KleinBottle(form="figure8"), lg.RomanSurface()):
        assert s.boundary() == []


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _oriented_normals(surface, uv):
    n = surface.normal(uv[:, 0], uv[:, 1])
    sign = np.sign(np.einsum("ij,ij->i", n[1:], n[:-1]))
    return n * np.concatenate([[1.0], np.cumprod(sign)])[:, None]


def _near_crossing(s, i, k=6):
    a, b = max(i - k, 0), min(i + k + 2, len(s.xyz))
    return s.xyz[a:b], s.uv[a:b]


def test_lines_of_curvature_cross_the_seam():
    m = lg.MoebiusStrip()
    drawing = _render(m, lg.LinesOfCurvature(4, 4))
    for s, i in _check_one_stroke_across(drawing, m, "curvature"):
        x, uv = _near_crossing(s, i)
        n = _oriented_normals(m, d_wrap(m, uv))
        dx, dn = np.diff(x, axis=0), np.diff(n, axis=0)
        # Rodrigues: dN is parallel to dx along a line of curvature
        sine = np.linalg.norm(np.cross(_unit(dx), dn), axis=1) / np.linalg.norm(dn, axis=1)
        assert sine.max() < 2e-2


def d_wrap(surface, uv):
    return surface.domain.wrap(uv, clip=False)


def test_asymptotic_lines_cross_the_seam():
    m = lg.MoebiusStrip()
    drawing = _render(m, lg.AsymptoticLines(3, 3))
    for s, i in _check_one_stroke_across(drawing, m, "asymptotic"):
        x, uv = _near_crossing(s, i)
        n = m.normal(uv[1:-1, 0], uv[1:-1, 1])
        # normal curvature ~ 0: second differences (in arc length) normal to N
        t = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(x, axis=0), axis=1))])
        dd = (
            np.diff(np.diff(x, axis=0) / np.diff(t)[:, None], axis=0)
            / (0.5 * (t[2:] - t[:-2]))[:, None]
        )
        assert np.abs(np.einsum("ij,ij->i", dd, n)).max() < 2e-2


def test_geodesic_crosses_the_seam():
    m = lg.MoebiusStrip(width=1.6)
    drawing = _render(m, lg.Geodesic((5.8, 0.05), (1.0, 0.02), length=3.0))
    for s, i in _check_one_stroke_across(drawing, m, "geodesic"):
        x, uv = _near_crossing(s, i)
        n = m.normal(uv[1:-1, 0], uv[1:-1, 1])
        t = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(x, axis=0), axis=1))])
        dd = (
            np.diff(np.diff(x, axis=0) / np.diff(t)[:, None], axis=0)
            / (0.5 * (t[2:] - t[:-2]))[:, None]
        )
        tangential = dd - np.einsum("ij,ij->i", dd, n)[:, None] * n
        assert np.linalg.norm(tangential, axis=1).max() < 2e-2


@pytest.mark.parametrize(
    "surface",
    [lg.MoebiusStrip(), lg.KleinBottle(form="figure8"), lg.RomanSurface()],
    ids=["moebius", "klein8", "roman"],
)
def test_level_lines_cross_the_seam(surface):
    w = np.array([1.0, 0.3, 0.2])
    drawing = _render(surface, lg.LevelLines(7, direction=w))
    _check_one_stroke_across(drawing, surface, "level")
    for s in (s for s in drawing.strokes if s.family == "level"):
        f = s.xyz @ (w / np.linalg.norm(w))
        assert np.ptp(f) < 1e-9


@pytest.mark.parametrize(
    ("surface", "view"),
    [
        (lg.MoebiusStrip(), lg.ParallelProjector(direction=(1.0, 1.0, 0.1))),
        (lg.KleinBottle(form="figure8"), lg.ParallelProjector(direction=(0.2, 1.0, 0.4))),
    ],
    ids=["moebius", "klein8"],
)
def test_contour_continuous_across_the_seam(surface, view):
    drawing = _render(surface, view=view)
    _check_one_stroke_across(drawing, surface, "contour")
    w = _unit(np.asarray(view.direction, float))
    for s in (s for s in drawing.strokes if s.family == "contour"):
        n = surface.normal(s.uv[:, 0], s.uv[:, 1])
        assert np.abs(n @ w).max() < 1e-6


def test_scene_file_takes_twisted(tmp_path):
    text = """
[projector]
kind = "parallel"
direction = [0.3, 0.2, 1]

[[object]]
surface = "parametric"
x = "(1 + v/2*cos(u/2))*cos(u)"
y = "(1 + v/2*cos(u/2))*sin(u)"
z = "v/2*sin(u/2)"
u = [0, "2*pi"]
v = [-0.5, 0.5]
periodic = ["twisted", false]
"""
    path = tmp_path / "m.toml"
    path.write_text(text)
    scene, _projector, _options = lg.load_scene_file(path)
    surfaces = [n.surface for n in scene.nodes if getattr(n, "surface", None) is not None]
    assert surfaces[0].domain.periodic == ("twisted", False)
    path.write_text(text.replace('["twisted", false]', '["no", false]'))
    with pytest.raises(lg.SceneFileError, match="twisted"):
        lg.load_scene_file(path)


def test_deck_maps_at_the_seam_to_the_last_bit():
    # a point one unit in the last place outside the twisted edge and one on
    # it are the same point: the map between them is the identity
    d = lg.RomanSurface().domain
    lo = d.u2[0]
    p = np.array([0.4706261, np.nextafter(lo, -1.0)])
    q = np.array([0.4706261, lo])
    S, t = d.deck(p, q)
    np.testing.assert_allclose(S * q + t, p, atol=1e-15)


def test_roman_surface_contour_lies_on_the_contour():
    s = lg.RomanSurface()
    view = lg.ParallelProjector(direction=(1.0, 0.8, 0.6))
    w = _unit(np.array([1.0, 0.8, 0.6]))
    for b in s.contour(view):
        for k in range(len(b)):
            t = np.linspace(b.t0[k], b.t1[k], 1000)
            x, uv = b.evaluate(np.full(len(t), k), t)
            # the pieces end on the pinch points, where the normal is undefined
            x1, x2 = s.derivatives(uv[:, 0], uv[:, 1])
            regular = np.linalg.norm(np.cross(x1, x2), axis=1) > 1e-9
            assert regular.sum() >= len(t) - 2
            assert np.abs(s.normal(uv[regular, 0], uv[regular, 1]) @ w).max() < 1e-6
            assert np.linalg.norm(np.diff(x, axis=0), axis=1).max() < 0.02 * s.size
