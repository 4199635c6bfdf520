"""normal() follows the parametrization (inward on spheres and ellipsoids, as
the paper's N = x1 x x2 / |x1 x x2|); outward_normal() points out of the solid,
checked against the gradient of the implicit equation and the torus's tube."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg

U1 = np.linspace(-1.45, 1.45, 9)[:, None]
U2 = np.linspace(0.0, 6.2, 11)[None, :]


@pytest.mark.parametrize("surface", [lg.Sphere(1.7), lg.Ellipsoid(3, 2, 1.3)])
def test_ellipsoid_normal_is_inward_and_outward_normal_is_the_gradient(surface):
    x = surface.point(U1, U2)
    axes = np.array(surface.axes, float)
    grad = x / axes**2  # gradient of x^2/a^2 + y^2/b^2 + z^2/c^2 - 1, outward
    grad /= np.linalg.norm(grad, axis=-1, keepdims=True)
    np.testing.assert_allclose(surface.outward_normal(U1, U2), grad, atol=1e-9)
    np.testing.assert_allclose(surface.normal(U1, U2), -grad, atol=1e-9)


def test_torus_outward_normal_points_away_from_the_tube_centre():
    R, r = 3.0, 1.1
    torus = lg.Torus(R, r)
    u1, u2 = np.linspace(0, 6.2, 13)[:, None], np.linspace(0, 6.2, 7)[None, :]
    x = torus.point(u1, u2)
    rho = np.hypot(x[..., 0], x[..., 1])
    centre = np.stack([R * x[..., 0] / rho, R * x[..., 1] / rho, np.zeros_like(rho)], -1)
    expect = (x - centre) / r  # the tube's radius direction
    np.testing.assert_allclose(torus.outward_normal(u1, u2), expect, atol=1e-9)


def test_open_surfaces_have_no_outward_normal():
    with pytest.raises(ValueError, match="outward_normal needs a closed surface"):
        lg.HyperbolicParaboloid(1, 1).outward_normal(0.0, 0.0)
