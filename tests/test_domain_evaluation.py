"""lgraph never evaluates a user's surface outside its declared domain (issue #25).

A surface whose ``point`` raises for any parameter outside the rectangle
(beyond rounding: 1e-12 of the span) renders every family, with hidden lines
on and off, in parallel and central views; glued parameters reach the user's
function mapped back into the rectangle.  Finite differences at the edges are
one-sided (checked against exact derivatives), and NaN from the user's
function is an error naming the surface and the parameters.
"""

from __future__ import annotations

import numpy as np
import pytest
from user_surfaces import dini

import lgraph as lg


class Outside(ValueError):
    """Raised by the test surfaces for a parameter outside their rectangle."""


def strict(func, r1, r2, calls=None):
    """``func`` that raises :class:`Outside` beyond 1e-12 of the spans (and
    records the range of the parameters of each call in ``calls``: ``(u
    min, v min, u max, v max)``, not the parameters themselves, which would
    take gigabytes)."""
    t1, t2 = 1e-12 * (r1[1] - r1[0]), 1e-12 * (r2[1] - r2[0])

    def f(u, v):
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        bad = (u < r1[0] - t1) | (u > r1[1] + t1) | (v < r2[0] - t2) | (v > r2[1] + t2)
        if np.any(bad):
            i = np.flatnonzero(bad.ravel())[0]
            raise Outside(f"outside the domain: u = {u.ravel()[i]!r}, v = {v.ravel()[i]!r}")
        if calls is not None and u.size:
            calls.append((u.min(), v.min(), u.max(), v.max()))
        return func(u, v)

    return f


def _stack(*c):
    return np.stack(np.broadcast_arrays(*c), -1)


def saddle(u, v):
    return _stack(u, v, u**3 - 3 * u * v * v)


def umbrella(u, v):  # Whitney's umbrella: a self-intersection ending at a pinch point
    return _stack(u * v, v, u * u)


def torus(u, v):
    return _stack((2 + np.cos(v)) * np.cos(u), (2 + np.cos(v)) * np.sin(u),
                  np.sin(v) + 0.3 * np.cos(2 * u))  # fmt: skip


def moebius(u, v):
    w = 1 + v / 2 * np.cos(u / 2)
    return _stack(w * np.cos(u), w * np.sin(u), v / 2 * np.sin(u / 2))


CASES = {
    "dini": (dini, (0, 4 * np.pi), (0.3, 1.4), (False, False)),
    "saddle": (saddle, (-1, 1), (-1, 1), (False, False)),
    "umbrella": (umbrella, (-1, 1), (-1, 1), (False, False)),
    "torus": (torus, (0, 2 * np.pi), (0, 2 * np.pi), (True, True)),
    "moebius": (moebius, (0, 2 * np.pi), (-0.5, 0.5), ("twisted", False)),
}


def _families(r1, r2):
    start = (0.7 * r1[0] + 0.3 * r1[1], 0.6 * r2[0] + 0.4 * r2[1])
    return [
        lg.ParameterLines(5, 5),
        lg.LinesOfCurvature(4, 4),
        lg.LinesOfCurvature(4, 4, spacing="even"),
        lg.AsymptoticLines(3, 3),
        lg.Geodesic(start, (1, 0.3), length=20, both_ways=True),
        lg.LevelLines(5),
        lg.ParabolicLines(),
        lg.SelfIntersection(),
        lg.Umbilics(),
    ]


VIEWS = [
    (lg.ParallelProjector(direction=(1, 0.6, 0.8)), False),
    (lg.ParallelProjector(direction=(1, 0.6, 0.8)), True),
    (lg.CentralProjector(eye=(6, 4, 5), target=(0, 0, 0)), True),
]


@pytest.mark.parametrize("name", sorted(CASES))
def test_every_family_stays_inside_the_domain(name):
    func, r1, r2, periodic = CASES[name]
    calls: list = []
    s = lg.ParametricSurface(strict(func, r1, r2, calls), r1, r2, periodic=periodic)
    glued = periodic != (False, False)
    # every family once (their curves do not depend on the view); the ray
    # tests and contours of hidden lines in parallel and central views with
    # parameter lines (glued patches, whose numeric contours are slower: the
    # families that cross seams, hidden lines in one view)
    families = _families(r1, r2)
    if glued:
        families = [f for f in families if not isinstance(f, (lg.ParabolicLines, lg.Umbilics))]
    # Dini's numeric contour is the slowest: its hidden lines in the central
    # view only (finite rays, the stricter case)
    views = VIEWS[1:2] if glued else [VIEWS[0], VIEWS[2]] if name == "dini" else VIEWS
    for k, (projector, hidden) in enumerate(views):
        scene = lg.Scene()
        scene.add(s, *(families if k == 0 else [lg.ParameterLines(4, 4)]))
        drawing = scene.render(projector, hidden_lines=hidden)
        assert drawing.strokes
        if hidden:
            assert not all(st.visible for st in drawing.strokes)
    ranges = np.array(calls)
    for k, (lo, hi) in enumerate((r1, r2)):
        slack = 1e-12 * (hi - lo)
        assert lo - slack <= ranges[:, k].min() and ranges[:, k + 2].max() <= hi + slack


def test_intersection_with_a_sphere_stays_inside():
    func, r1, r2, _ = CASES["saddle"]
    s = lg.ParametricSurface(strict(func, r1, r2), r1, r2)
    scene = lg.Scene()
    scene.add(s, lg.ParameterLines(4, 4))
    scene.add(lg.Sphere(0.7), lg.ParameterLines(3, 3))
    drawing = scene.render(lg.ParallelProjector(direction=(1, 0.6, 0.8)), hidden_lines=True)
    assert any(st.family == "intersection" for st in drawing.strokes)


def test_dini_lines_of_curvature_end_on_the_edge():
    """Dini's surface (v <= 1.4, where log tan(v/2) is fine beyond): the
    integrator used to try v up to 3.17; now every line of curvature stays in
    the patch and the lines that leave it end on its edge."""
    func, r1, r2, _ = CASES["dini"]
    s = lg.ParametricSurface(strict(func, r1, r2), r1, r2)
    scene = lg.Scene()
    scene.add(s, lg.LinesOfCurvature(6, 6), contour=False)  # the contour is checked above
    drawing = scene.render(lg.ParallelProjector(direction=(1, 0.5, 0.4)))
    curv = [st for st in drawing.strokes if st.family == "curvature"]
    assert curv
    uv = np.concatenate([st.uv for st in curv])
    assert uv[:, 1].min() >= r2[0] - 1e-12 and uv[:, 1].max() <= r2[1] + 1e-12
    # the lines that leave the patch end exactly on its edges v = 0.3, v = 1.4
    ends = np.concatenate([st.uv[[0, -1], 1] for st in curv])
    on_edge = np.minimum(np.abs(ends - r2[0]), np.abs(ends - r2[1])) < 1e-9
    assert on_edge.sum() >= 6
    # and they are lines of curvature: chords along principal directions
    # (Dini's surface has K = -1, no umbilics), up to the chords' own bend
    for st in curv:
        t = np.diff(st.xyz, axis=0)
        t /= np.linalg.norm(t, axis=1, keepdims=True)
        mid = 0.5 * (st.uv[1:] + st.uv[:-1])
        e1, e2 = s.principal_directions(mid[:, 0], mid[:, 1])
        off = np.minimum(np.linalg.norm(np.cross(t, e1), axis=1),
                         np.linalg.norm(np.cross(t, e2), axis=1))  # fmt: skip
        assert off.max() < 2e-2


def test_one_sided_differences_at_the_edges():
    """The default derivatives are exact to about 1e-9 (first) and 1e-6
    (second, third order at the edges) on the edges and corners of the patch,
    where a central stencil would leave it."""
    f = lambda u, v: _stack(np.sin(u) * np.exp(v), u * u * v, np.cos(u + 2 * v))  # noqa: E731
    s = lg.ParametricSurface(strict(f, (0, 1), (0, 2)), (0, 1), (0, 2))
    u = np.array([0, 5e-4, 1e-3, 1.5e-3, 2e-3, 0.5, 0.999, 1.0])
    v = np.array([2, 1.999, 0, 1e-3, 0.5, 1, 3e-3, 2.0])
    x1, x2 = s.derivatives(u, v)
    x11, x12, x22 = s.second_derivatives(u, v)
    e, c, sn = np.exp(v), np.cos(u + 2 * v), np.sin(u + 2 * v)
    exact = [
        (x1, _stack(np.cos(u) * e, 2 * u * v, -sn)),
        (x2, _stack(np.sin(u) * e, u * u, -2 * sn)),
        (x11, _stack(-np.sin(u) * e, 2 * v, -c)),
        (x12, _stack(np.cos(u) * e, 2 * u, -2 * c)),
        (x22, _stack(np.sin(u) * e, 0 * u, -4 * c)),
    ]
    for k, (got, want) in enumerate(exact):
        assert np.abs(got - want).max() < (1e-9 if k < 2 else 5e-6)
    # away from the edges: the classical central stencils, unchanged
    a, b = s.derivatives(0.5, 1.0)
    h = 1e-3
    central = (f(0.5 - 2 * h, 1.0) - 8 * f(0.5 - h, 1.0) + 8 * f(0.5 + h, 1.0)
               - f(0.5 + 2 * h, 1.0)) / (12 * h)  # fmt: skip
    assert np.abs(a - central).max() < 1e-12


def test_glued_parameters_are_mapped_back():
    """Past a seam the user's function is called with the glued equivalent;
    a twisted seam reflects the other parameter (and the derivatives' signs)."""
    calls: list = []
    s = lg.ParametricSurface(strict(moebius, (0, 2 * np.pi), (-0.5, 0.5), calls),
                             (0, 2 * np.pi), (-0.5, 0.5), periodic=("twisted", False))  # fmt: skip
    p = s.point(2 * np.pi + 0.3, 0.2)
    assert np.allclose(p, moebius(np.array(0.3), np.array(-0.2)), atol=1e-14)
    assert np.allclose(p, moebius(np.array(2 * np.pi + 0.3), np.array(0.2)), atol=1e-12)
    x1, x2 = s.derivatives(2 * np.pi + 0.3, 0.2)
    h = 1e-6  # the cover's derivative, by differences of the unwrapped formula
    ref2 = (moebius(np.array(2 * np.pi + 0.3), np.array(0.2 + h))
            - moebius(np.array(2 * np.pi + 0.3), np.array(0.2 - h))) / (2 * h)  # fmt: skip
    assert np.abs(x2 - ref2).max() < 1e-7
    g = lambda u, v: _stack(u, v, u * v)  # noqa: E731
    d1 = lambda u, v: (_stack(1 + 0 * u, 0 * u, v), _stack(0 * u, 1 + 0 * u, u))  # noqa: E731
    t = lg.ParametricSurface(g, (0, 1), (-1, 1), periodic=("twisted", False), derivatives_func=d1)
    a1, a2 = t.derivatives(1.25, 0.5)  # the point (0.25, -0.5) of the rectangle, u2 reversed
    assert np.allclose(a1, [1, 0, -0.5]) and np.allclose(a2, [0, -1, -0.25])


def test_nan_inside_the_domain_names_surface_and_parameters():
    f = lambda u, v: _stack(u, v, np.log(u))  # noqa: E731 - -inf at u = 0
    s = lg.ParametricSurface(f, (0.5, 1), (0, 1))
    with np.errstate(divide="ignore"):
        with pytest.raises(ValueError, match=r"ParametricSurface: func returned NaN or inf .*"
                           r"\(u1, u2\) = \(.*0\.0.*0\.25"):  # fmt: skip
            s.point(np.array([0.75, 0.0]), np.array([0.5, 0.25]))
    # NaN parameters (a failed search upstream) are not blamed on the function
    assert np.isnan(s.point(np.nan, 0.5)[0])
