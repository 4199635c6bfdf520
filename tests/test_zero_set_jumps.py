"""Zero sets skip the sign changes that are jumps (lgraph.surfaces.parametric._zero_set).

The contour function of a parametrization that folds over a degenerate line
(the normal flips with the orientation) changes sign there without a zero:
Apery's parametrization of Boy's surface maps its line ``v = pi/2`` to one
point.  Taken for a zero, that line made the contour jump back and forth
between it and the true contour, and its sampling ran into the point budget
(issue #25)."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.surfaces.parametric._zero_set import zero_set


def _surface():
    return lg.ParametricSurface(
        lambda u, v: np.stack(np.broadcast_arrays(u, v, 0 * u), -1), (0.0, 1.0), (0.0, 1.0)
    )


def test_a_jump_is_no_zero_and_a_zero_beside_it_is_kept():
    """A step across ``v = 0.41`` times ``u + 1`` only jumps; times ``u - 0.3`` it
    also has a true zero, the line ``u = 0.3``, which is kept."""
    s = _surface()

    def jump(u, v):
        return np.where(v < 0.41, -1.0, 1.0) * (u + 1)

    assert zero_set(s, jump, grid=41) == []

    def both(u, v):  # zero on u = 0.3; a jump across v = 0.41 changes no sign of the zero
        return np.where(v < 0.41, -1.0, 1.0) * (u - 0.3)

    curves = zero_set(s, both, grid=41)
    assert curves
    pts = np.concatenate([p for p, _ in curves])
    assert np.allclose(pts[:, 0], 0.3, atol=1e-12)  # only points of the true zero
    # the jump line itself contributes nothing: no point off u = 0.3
    assert len(pts) >= 30


def test_nan_nodes_make_no_zero():
    """A node where the function is undefined (0/0) counts as 0 on the grid;
    the sign changes next to it are not zeros."""
    s = _surface()

    def f(u, v):
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(np.abs(v - 0.5) < 1e-9, np.nan, -1.0 - u)

    assert zero_set(s, f, grid=41) == []


def _apery(u, v):
    d = 2 - np.sqrt(2) * np.sin(3 * u) * np.sin(2 * v)
    c2 = np.cos(v) ** 2
    x = (np.sqrt(2) * c2 * np.cos(2 * u) + np.cos(u) * np.sin(2 * v)) / d
    y = (np.sqrt(2) * c2 * np.sin(2 * u) - np.sin(u) * np.sin(2 * v)) / d
    z = 3 * c2 / d
    return np.stack(np.broadcast_arrays(x, y, z), -1)


def test_the_contour_of_aperys_boy_surface_does_not_jump():
    """Every contour curve of Apery's parametrization is continuous in the
    image (no step longer than 2 % of the figure between points 1/2000 of the
    curve apart) and lies on the contour (``N . w`` small where ``N`` is
    defined); its sampling stays far below the point budget."""
    surface = lg.ParametricSurface(_apery, (0.0, np.pi), (0.0, np.pi))
    projector = lg.CentralProjector.from_angles(30, 25, 8)
    (batch,) = lg.Contour().batches(surface, projector)
    pts = []
    for i in range(len(batch)):
        t = np.linspace(batch.t0[i], batch.t1[i], 2001)
        x, uv = batch.evaluate(np.full(len(t), i), t)
        xy = projector.project(np.asarray(x).reshape(-1, 3))
        pts.append((xy, np.asarray(uv).reshape(-1, 2)))
    allxy = np.concatenate([xy for xy, _ in pts])
    size = np.ptp(allxy, axis=0).max()
    for xy, uv in pts:
        step = np.linalg.norm(np.diff(xy, axis=0), axis=1)
        assert step.max() < 0.02 * size
        x1, x2 = surface.derivatives(uv[:, 0], uv[:, 1])
        n = np.cross(x1, x2)
        w = projector.eye - surface.point(uv[:, 0], uv[:, 1])
        cos = np.einsum("ij,ij->i", n, w) / (np.linalg.norm(n, axis=1) * np.linalg.norm(w, axis=1))
        assert np.nanmax(np.abs(cos)) < 1e-6
    scene = lg.Scene()
    scene.add(surface, lg.ParameterLines(12, 12))
    drawing = scene.render(projector)
    assert 1000 < drawing.n_points < 100_000
