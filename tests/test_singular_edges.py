"""Singular edges and points of user-written parametrizations (issue #25).

Cuspidal edges (Dini's surface at ``v = pi/2``, the pseudosphere's rim), a
pinch point (Whitney's umbrella), an edge that collapses to a point (Apery's
Boy surface at ``v = pi/2``, a sphere chart without declared poles): each
renders at the default tolerance, its contour points satisfy ``N . w = 0``
(``N`` from the surface's exact derivatives, written here), its cuspidal
edges are drawn as edges, and the visibility of sampled points agrees with
rays cast against a fine triangle mesh (tests/bruteforce.py).

Before the normal was declared undefined at singular points, the
finite-difference normal on the pseudosphere's rim (noise) had zeros there:
spurious contour pieces with ``|N . w|`` up to 0.5 whose sampling took 6214
points at elevation 3 degrees and did not end at 0.5 degrees.
"""

from __future__ import annotations

import numpy as np
import pytest
from bruteforce import MeshCaster, even_stations
from user_surfaces import boy, dini, stack

import lgraph as lg
from lgraph.surfaces.parametric._singular_edges import singular_curves


def pseudosphere(u, t):
    return stack(np.cos(u) / np.cosh(t), np.sin(u) / np.cosh(t), t - np.tanh(t))


def pseudosphere_normal(u, t):  # x_u x x_t, exact
    s, th = 1 / np.cosh(t), np.tanh(t)
    xu = stack(-np.sin(u) * s, np.cos(u) * s, 0 * u)
    xt = stack(-np.cos(u) * s * th, -np.sin(u) * s * th, th**2)
    return np.cross(xu, xt)


def dini_normal(u, v, a=1.0, b=0.2):
    xu = stack(-a * np.sin(u) * np.sin(v), a * np.cos(u) * np.sin(v), b + 0 * u)
    xv = stack(a * np.cos(u) * np.cos(v), a * np.sin(u) * np.cos(v), a * (np.cos(v) / np.tan(v)))
    return np.cross(xu, xv)


def whitney(u, v):
    return stack(u * v, u, v**2)


def whitney_normal(u, v):
    return stack(2 * v, -2 * v**2, -u)


def _contour_residual(drawing, normal, projector):
    """Largest ``|N . w|`` (unit vectors) over the contour's points, and their
    number; points where the normal vanishes (a pinch point, where the
    contour ends) have no ``N`` and are left out."""
    uv = np.concatenate([s.uv for s in drawing.strokes if s.family == "contour"])
    n = normal(uv[:, 0], uv[:, 1])
    length = np.linalg.norm(n, axis=1)
    regular = length > 1e-9 * length.max()
    n = n[regular] / length[regular, None]
    w = np.asarray(projector.frame[2])
    return float(np.abs(n @ w).max()), len(uv)


def _check_visibility(drawing, caster, delta, spacing):
    """Every sampled point (evenly along each stroke) whose brute-force
    visibility is reliable agrees with the drawing; returns how many were
    checked."""
    uv, vis = [], []
    for s in drawing.strokes:
        if s.uv is None:
            continue
        k = even_stations(s.xy, spacing)
        uv.append(s.uv[k])
        vis.append(np.full(len(k), s.visible))
    uv, vis = np.concatenate(uv), np.concatenate(vis)
    hidden, reliable = caster.robust_hidden(uv, delta)
    wrong = reliable & (hidden == vis)
    assert not wrong.any(), uv[wrong][:5]
    return int(reliable.sum())


def _contour_samples(surface, projector):
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(0, 0))
    return scene.render(projector)


@pytest.mark.parametrize("elevation", [3.0, 0.5])
def test_contour_beside_the_pseudosphere_rim(elevation):
    """Seen from just above the rim, the contour turns ``asinh(tan e)`` from
    the rim (0.052 and 0.0087): it is found on the contour to the accuracy of
    the finite differences, with no piece on the rim itself, and down to that
    turn -- or, at 0.5 degrees, where the turn lies within the grid's first
    cell (0.0104) of the rim, to that cell (the rest moves the image by the
    square of 0.0104 at most)."""
    p = lg.ParallelProjector.from_angles(20, elevation)
    rim = lg.ParametricSurface(pseudosphere, (0, 2 * np.pi), (0.0, 2.0), periodic=(True, False))
    (b,) = rim.contour(p)
    assert len(b) <= 2  # one curve, or its two sides of the rim's first cell; none on the rim
    k = np.repeat(np.arange(len(b)), 2001)
    t = np.concatenate([np.linspace(b.t0[i], b.t1[i], 2001) for i in range(len(b))])
    _, uv = b.evaluate(k, t)
    n = pseudosphere_normal(uv[:, 0], uv[:, 1])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    assert np.abs(n @ p.frame[2]).max() < 1e-7
    turn = np.arcsinh(np.tan(np.radians(elevation)))
    assert uv[:, 1].min() == pytest.approx(max(turn, 2.0 / 192), abs=1e-6)


def test_rim_contour_samples():
    """At elevation 0.5 degrees the rim's contour takes about as many samples
    as the same view of a patch that stops short of the rim (at most 3 times:
    the turn adds length, the rim nothing)."""
    p = lg.ParallelProjector.from_angles(20, 0.5)
    rim = lg.ParametricSurface(pseudosphere, (0, 2 * np.pi), (0.0, 2.0), periodic=(True, False))
    short = lg.ParametricSurface(pseudosphere, (0, 2 * np.pi), (0.3, 2.0), periodic=(True, False))
    d, d0 = _contour_samples(rim, p), _contour_samples(short, p)
    res, n = _contour_residual(d, pseudosphere_normal, p)
    _, n0 = _contour_residual(d0, pseudosphere_normal, p)
    assert res < 1e-7
    assert n <= 3 * n0


def test_rim_between_two_sheets_is_an_edge():
    """Across the rim (``t`` in ``[-1.5, 1.5]``) the normal flips: the rim is
    found as one closed singular curve at ``t = 0``, drawn as an edge (family
    boundary, on the rim to 1e-12), and hidden lines agree with brute force."""
    s = lg.ParametricSurface(pseudosphere, (0, 2 * np.pi), (-1.0, 1.0), periodic=(True, False))
    ((curve, closed),) = singular_curves(s)
    assert closed and np.abs(curve[:, 1]).max() < 1e-12
    p = lg.ParallelProjector.from_angles(30, 25)
    scene = lg.Scene()
    scene.add(s, lg.ParameterLines(4, 3))
    d = scene.render(p, hidden_lines=True)
    rim = [st for st in d.strokes if st.family == "boundary" and abs(st.uv[0, 1]) < 0.5]
    assert rim and max(np.abs(st.uv[:, 1]).max() for st in rim) < 1e-12
    assert any(st.visible for st in rim) and not all(st.visible for st in rim)
    res, _ = _contour_residual(d, pseudosphere_normal, p)
    assert res < 1e-7
    caster = MeshCaster(pseudosphere, (0, 2 * np.pi), (-1.0, 1.0), 400, 300, p, (True, False))
    assert _check_visibility(d, caster, (0.02, 0.007), 0.02) > 200


def test_dini_across_its_cuspidal_edge():
    """Dini's surface over ``v`` in ``[0.3, 2.8]``: the helix ``v = pi/2`` is one
    open singular curve from ``u = 0`` to ``u = pi``, drawn; the contour and
    the hidden lines are right."""
    s = lg.ParametricSurface(dini, (0, np.pi), (0.3, 2.8))
    ((curve, closed),) = singular_curves(s)
    assert not closed and np.abs(curve[:, 1] - np.pi / 2).max() < 1e-10
    assert np.ptp(curve[:, 0]) == pytest.approx(np.pi, abs=1e-9)
    p = lg.ParallelProjector.from_angles(30, 25)
    scene = lg.Scene()
    scene.add(s, lg.ParameterLines(3, 3))
    d = scene.render(p, hidden_lines=True)
    res, _ = _contour_residual(d, dini_normal, p)
    assert res < 1e-7
    caster = MeshCaster(dini, (0, np.pi), (0.3, 2.8), 400, 400, p)
    assert _check_visibility(d, caster, (0.02, 0.02), 0.02) > 150


def test_pinch_point_and_collapsed_edge_draw_no_edge():
    """A pinch point (Whitney's umbrella) and an edge collapsed to a point
    (Apery's Boy surface, ``v = pi/2``) are no singular curves: nothing is
    drawn there; the umbrella's hidden lines agree with brute force."""
    w = lg.ParametricSurface(whitney, (-1, 1), (-1, 1))
    b = lg.ParametricSurface(boy, (0, np.pi), (0, np.pi))
    assert singular_curves(w) == [] and singular_curves(b) == []
    p = lg.ParallelProjector.from_angles(30, 25)
    scene = lg.Scene()
    scene.add(w, lg.ParameterLines(4, 4))
    d = scene.render(p, hidden_lines=True)
    res, _ = _contour_residual(d, whitney_normal, p)
    assert res < 1e-7
    caster = MeshCaster(whitney, (-1, 1), (-1, 1), 300, 300, p)
    assert _check_visibility(d, caster, (0.01, 0.01), 0.02) > 200


def sphere(u, v):
    return stack(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v))


def test_sphere_with_undeclared_poles():
    """A sphere chart whose collapsed ends ``v = 0, pi`` are not declared
    poles, seen along the equator: its contour is a great circle through both
    poles, found whole (two meridians of length pi) and on the unit circle of
    the view, where the grid once ran through the poles' undefined normals
    (non-finite contour points: a ValueError)."""
    s = lg.ParametricSurface(sphere, (0, 2 * np.pi), (0, np.pi), periodic=(True, False))
    p = lg.ParallelProjector(direction=(1.0, 0.3, 0.0))
    d = _contour_samples(s, p)
    contour = [st for st in d.strokes if st.family == "contour"]
    length = sum(np.linalg.norm(np.diff(st.xyz, axis=0), axis=1).sum() for st in contour)
    assert length == pytest.approx(2 * np.pi, rel=2e-3)  # chords; a cell missing at a pole: 1e-2
    xyz = np.concatenate([st.xyz for st in contour])
    assert np.abs(xyz @ p.frame[2]).max() < 1e-7
