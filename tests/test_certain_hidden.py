"""Hidden pieces shorter than a chord: tiny occluders in front of lines,
checked against the analytic shadow of each sphere (issue #24)."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
import lgraph.render as render_pkg


def _line_scene(spheres, y0=0.0):
    sc = lg.Scene()
    sc.add(lg.Curve(lambda t: np.stack([t, y0 + 0 * t, 0 * t], -1), -10.0, 10.0))
    for cx, cy, cz, r in spheres:
        sc.add(lg.Sphere(r), lg.ParameterLines(2, 4), transform=lg.translate(cx, cy, cz))
    return sc


def _hidden_intervals(drawing):
    """x ranges of the hidden strokes of the free curve, sorted; strokes
    that touch (split where the number of sheets in front changes) merged."""
    out = sorted(
        (s.xyz[:, 0].min(), s.xyz[:, 0].max())
        for s in drawing.strokes
        if s.family == "curve" and not s.visible
    )
    merged = []
    for a, b in out:
        if merged and a <= merged[-1][1] + 1e-9 * 20:  # both ends of a located change
            merged[-1] = (merged[-1][0], max(merged[-1][1], b))
        else:
            merged.append((a, b))
    return merged


def _shadow(spheres, y0=0.0):
    """The union of the x intervals that spheres (above the line, seen from
    +z) cover on the line y = y0, z = 0: |x - cx|^2 + |y0 - cy|^2 < r^2."""
    iv = []
    for cx, cy, _, r in spheres:
        h2 = r * r - (y0 - cy) ** 2
        if h2 > 0:
            a, b = max(cx - np.sqrt(h2), -10.0), min(cx + np.sqrt(h2), 10.0)
            if a < b:  # clipped to the line's ends
                iv.append((a, b))
    iv.sort()
    merged = []
    for a, b in iv:
        if merged and a <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(merged[-1][1], b))
        else:
            merged.append((a, b))
    return merged


def test_the_sphere_between_two_samples_hides_its_piece():
    dr = _line_scene([(0.11, 0.0, 1.0, 0.05)]).render(
        lg.ParallelProjector(direction=(0, 0, 1)), hidden_lines=True
    )
    ((a, b),) = _hidden_intervals(dr)
    assert a == pytest.approx(0.06, abs=1e-7) and b == pytest.approx(0.16, abs=1e-7)
    visible = [s for s in dr.strokes if s.family == "curve" and s.visible]
    assert len(visible) == 2


@pytest.mark.parametrize("seed", range(6))
def test_random_tiny_spheres_in_front_of_a_line(seed):
    # radii from 1e-3 to 1e-1 of the scene (the line is 20 long), offsets
    # across the line so that some shadows are much shorter than the sphere
    rng = np.random.default_rng(seed)
    n = 6
    r = 20 * 10 ** rng.uniform(-3, -1, n)
    cx = rng.uniform(-9, 9, n)
    cy = rng.uniform(-0.9, 0.9, n) * r
    cz = rng.uniform(0.5, 2.0, n) + r
    spheres = list(zip(cx, cy, cz, r))
    dr = _line_scene(spheres).render(lg.ParallelProjector(direction=(0, 0, 1)), hidden_lines=True)
    got = _hidden_intervals(dr)
    want = _shadow(spheres)
    assert len(got) == len(want)
    for (a, b), (c, d) in zip(got, want):
        assert a == pytest.approx(c, abs=1e-6) and b == pytest.approx(d, abs=1e-6)


def test_sample_only_testing_misses_the_piece(monkeypatch):
    # the mutation check: without the net crossings the same scene draws the
    # whole line visible, so the test above depends on them
    monkeypatch.setattr(render_pkg, "seed_net_crossings", lambda s, vis, near=None: 0)
    dr = _line_scene([(0.11, 0.0, 1.0, 0.05)]).render(
        lg.ParallelProjector(direction=(0, 0, 1)), hidden_lines=True
    )
    assert _hidden_intervals(dr) == []


def test_a_tiny_sphere_in_front_of_a_circle_in_a_central_view():
    # the circle x^2 + y^2 = 4 in z = 0, seen from high above its centre;
    # a sphere of radius 0.02 near the eye's ray to the point at angle 1: the hidden arc
    # is where the ray to the circle's point meets the sphere (brute force
    # over a fine set of angles)
    eye = np.array([0.0, 0.0, 30.0])
    centre, r = np.array([1.8 * np.cos(1.0), 1.8 * np.sin(1.0), 3.0]), 0.02
    sc = lg.Scene()
    sc.add(lg.Curve(lambda t: np.stack([2 * np.cos(t), 2 * np.sin(t), 0 * t], -1), 0.0, 2 * np.pi))
    sc.add(lg.Sphere(r), lg.ParameterLines(2, 4), transform=lg.translate(*centre))
    dr = sc.render(lg.CentralProjector(eye=tuple(eye), target=(0, 0, 0)), hidden_lines=True)
    hidden = [s for s in dr.strokes if s.family == "curve" and not s.visible]
    assert len(hidden) == 1
    ang = np.arctan2(hidden[0].xyz[:, 1], hidden[0].xyz[:, 0])
    t = np.linspace(0.95, 1.05, 200001)
    p = np.stack([2 * np.cos(t), 2 * np.sin(t), 0 * t], -1)
    d = eye - p
    d /= np.linalg.norm(d, axis=1)[:, None]
    w = p - centre
    b = np.einsum("ij,ij->i", w, d)
    disc = b * b - (np.einsum("ij,ij->i", w, w) - r * r)
    shadow = t[(disc > 0) & (-b > 0)]
    step = t[1] - t[0]
    assert ang.min() == pytest.approx(shadow.min(), abs=2 * step)
    assert ang.max() == pytest.approx(shadow.max(), abs=2 * step)


def _random_ellipsoids(rng, n):
    sc = lg.Scene()
    for _ in range(n):
        axes = rng.uniform(0.3, 2.0, 3)
        tr = lg.translate(*rng.uniform(-4, 4, 3)) @ lg.rotate(rng.normal(size=3), rng.uniform(0, 3))
        sc.add(lg.Ellipsoid(*axes), lg.ParameterLines(2, 2), transform=tr)
    return sc


@pytest.mark.parametrize("central", [False, True])
def test_outline_conics_vanish_on_the_contours(central):
    # the exact outline of every grouped ellipsoid: zero on its (sampled)
    # contour, positive at the image of its centre, negative far away; its
    # tight box is the contour's extent
    from lgraph.render.occlusion import Occlusion

    rng = np.random.default_rng(3 + central)
    sc = _random_ellipsoids(rng, 4)
    p = (
        lg.CentralProjector.from_angles(40, 30, 30)
        if central
        else lg.ParallelProjector.from_angles(-70, 35)
    )
    vis = Occlusion(sc.nodes, p)
    C, box, origin = vis.outlines(0), vis.outline_boxes(0), vis.image_origin(0)
    dr = sc.render(p, tolerance=1e-7, hidden_lines=True)
    contours = [s for s in dr.strokes if s.family == "contour"]
    by_node = {}
    for s in contours:  # each contour stroke lies on exactly one outline
        y = np.column_stack([s.xy - origin, np.ones(len(s.xy))])
        vals = np.abs(np.einsum("ni,kij,nj->kn", y, C, y))
        k = int(np.argmin(vals.max(axis=1)))
        assert vals[k].max() < 1e-9
        by_node.setdefault(k, []).append(s.xy)
    assert sorted(by_node) == [0, 1, 2, 3]
    for k, xys in by_node.items():
        xy = np.concatenate(xys)
        size = np.ptp(xy, axis=0).max()
        assert np.allclose(box[k, :2], xy.min(axis=0), atol=1e-5 * size)
        assert np.allclose(box[k, 2:], xy.max(axis=0), atol=1e-5 * size)
    centres = np.array([n.transform.apply(np.zeros((1, 3)))[0] for n in sc.nodes])
    y = np.column_stack([p.project(centres) - origin, np.ones(4)])
    assert (np.einsum("ni,nij,nj->n", y, C, y) > 0).all()
    far = np.array([1e3, -1e3, 1.0])
    assert (np.einsum("i,nij,j->n", far, C, far) < 0).all()


def test_a_tiny_sphere_hides_a_short_piece_of_a_big_spheres_line():
    # chords on an ellipsoid are crossed with the outlines of the ellipsoids
    # whose outline meets theirs: a sphere of radius 0.003 above a point of a
    # parameter line of the unit sphere (seen from +z) hides a piece of it
    # shorter than its chord, ends at distance r from the point in the image
    view = lg.ParallelProjector(direction=(0, 0, 1))
    big = lg.Scene()
    big.add(lg.Sphere(1.0), lg.ParameterLines(5, 8))
    lines = [s for s in big.render(view).strokes if s.family != "contour"]
    # the meridians: great circles, whose normalized chord midpoints lie on them
    strokes = [s for s in lines if abs(np.linalg.det(s.xyz[[0, len(s.xyz) // 2, -1]])) < 1e-12]
    others = [np.concatenate([t.xy for t in lines if t is not s]) for s in strokes]

    def mid(s):  # the point of the meridian half-way between two samples
        m = len(s.xyz) // 2
        q = s.xyz[m] + s.xyz[m + 1]
        return q / np.linalg.norm(q)

    best = max(
        range(len(strokes)),
        key=lambda i: np.linalg.norm(others[i] - mid(strokes[i])[:2], axis=1).min(),
    )
    p = mid(strokes[best])
    assert p[2] > 0.2  # seen from +z, in front
    r = 0.003
    assert np.linalg.norm(others[best] - p[:2], axis=1).min() > 10 * r
    sc = lg.Scene()
    sc.add(lg.Sphere(1.0), lg.ParameterLines(5, 8))
    sc.add(lg.Sphere(r), lg.ParameterLines(2, 2), transform=lg.translate(p[0], p[1], p[2] + 0.5))
    dr = sc.render(view, hidden_lines=True)
    hidden = [s for s in dr.strokes if s.surface is sc.nodes[0].surface and not s.visible]
    hidden = [s for s in hidden if np.linalg.norm(s.xy - p[:2], axis=1).max() < 2 * r]
    # the front piece behind the tiny sphere's two sheets; the back of the same
    # meridian (the same image) lies behind one more sheet, the big sphere's front
    assert sorted(s.occlusion for s in hidden) == [2, 3]
    hidden = [s for s in hidden if s.xyz[:, 2].min() > 0]
    assert len(hidden) == 1
    d = np.linalg.norm(hidden[0].xy - p[:2], axis=1)
    assert d.max() <= r + 1e-9
    assert d[0] == pytest.approx(r, abs=1e-7) and d[-1] == pytest.approx(r, abs=1e-7)
    # and the piece is shorter than a chord of the line drawn alone
    line = strokes[best].xy
    assert np.ptp(hidden[0].xy, axis=0).max() < np.linalg.norm(np.diff(line, axis=0), axis=1).max()
