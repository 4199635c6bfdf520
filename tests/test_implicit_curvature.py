"""Lines of curvature of implicit surfaces against independent checks:
Rodrigues' formula dN || dx with the closed-form normals of an ellipsoid,
and the torus's lines of curvature (meridians and parallels)."""

from __future__ import annotations

import numpy as np

import lgraph as lg
from lgraph.surfaces.implicit import ImplicitSurface


def _points(batch, k, n=400):
    t = np.linspace(batch.t0[k], batch.t1[k], n)
    return batch.evaluate(np.full(n, k), t)[0]


def test_ellipsoid_lines_satisfy_rodrigues():
    a, b, c = 2.0, 1.0, 1.5
    s = lg.AlgebraicSurface(f"x^2/{a * a} + y^2/{b * b} + z^2/{c * c} - 1", radius=3)
    (batch,) = lg.LinesOfCurvature(6, 6).batches(s, None)
    assert batch.family == "curvature" and len(batch) == 12
    sines = []
    for k in range(len(batch)):
        x = _points(batch, k)
        assert np.abs(s.implicit(x)).max() < 1e-14
        g = x / np.array([a * a, b * b, c * c])  # the closed-form normal
        N = g / np.linalg.norm(g, axis=1, keepdims=True)
        dx, dN = np.diff(x, axis=0), np.diff(N, axis=0)
        cross = np.linalg.norm(np.cross(dx, dN), axis=1)
        sines.append(cross / np.linalg.norm(dx, axis=1) / np.linalg.norm(dN, axis=1))
    sines = np.concatenate(sines)
    # the angle between dx and dN: the integration's error (near the umbilics
    # the directions turn fast and the bound is looser)
    assert np.median(sines) < 1e-4
    assert sines.max() < 5e-3


def test_torus_lines_are_meridians_and_parallels():
    R, r = 2.0, 0.7

    def F(x, y, z):
        q = x**2 + y**2 + z**2 + R * R - r * r
        return q**2 - 4 * R * R * (x**2 + y**2)

    s = ImplicitSurface(F, radius=2.8)  # numeric derivatives
    (batch,) = s.lines_of_curvature(4, 4)
    kinds = []
    for k in range(len(batch)):
        x = _points(batch, k, 200)
        # a parallel lies in a plane z = const; a meridian in a plane through the z axis
        flat = np.ptp(x[:, 2]) < 1e-4
        phi = np.arctan2(x[:, 1], x[:, 0])
        meridian = np.ptp(np.unwrap(2 * phi)) < 2e-4  # phi or phi + pi
        assert flat or meridian, k
        kinds.append("parallel" if flat else "meridian")
    assert set(kinds) == {"parallel", "meridian"}
