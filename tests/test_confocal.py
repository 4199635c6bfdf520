"""Confocal quadrics and triply orthogonal systems: members lie on the right
implicit equation, meet at right angles along their intersection curves."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg


def g(a, b, c, lam, x):
    """Paper (7.1): x^2/(a^2-l) + y^2/(b^2-l) + z^2/(c^2-l) - 1 and its gradient."""
    den = np.array([a * a, b * b, c * c], float) - lam
    return (x * x / den).sum(-1) - 1.0, 2 * x / den


@pytest.mark.parametrize(
    "lam,kind",
    [
        (-1.0, "ellipsoid"),
        (2.0, "hyperboloid of one sheet"),
        (6.0, "hyperboloid of two sheets"),
        (0.5, "ellipsoid"),
    ],
)
def test_member_kind_and_equation(lam, kind):
    m = lg.ConfocalQuadric(1, 2, 3, lam)
    assert m.kind == kind
    d = m.domain
    u1, u2 = np.meshgrid(np.linspace(*d.u1, 31), np.linspace(*d.u2, 37), indexing="ij")
    x = m.point(u1.ravel(), u2.ravel())
    val, _ = g(1, 2, 3, lam, x)
    assert np.max(np.abs(val)) < 1e-12
    # the member's own coefficients describe the same quadric
    A, b, dd = m.coefficients
    F = np.einsum("ni,ij,nj->n", x, A, x) + x @ b + dd
    assert np.max(np.abs(F)) < 1e-12
    # lines of curvature and contour lie on it too
    for bt in m.lines_of_curvature(4, 5) + m.contour(lg.ParallelProjector(direction=(1, 2, 0.5))):
        t = np.linspace(bt.t0, bt.t1, 50).T.ravel()
        xs, uv = bt.evaluate(np.repeat(np.arange(len(bt)), 50), t)
        assert np.max(np.abs(g(1, 2, 3, lam, xs)[0])) < 1e-11
        assert np.allclose(m.point(uv[:, 0], uv[:, 1]), xs, atol=1e-9)


def test_invalid_parameters():
    for args in [(1, 2, 3, 1.0), (1, 2, 3, 4.0), (1, 2, 3, 9.0), (1, 2, 3, 10.0), (2, 1, 3, 0.0)]:
        with pytest.raises(ValueError, match="ConfocalQuadric"):
            lg.ConfocalQuadric(*args)


def test_one_sheet_member_hides_like_its_equation():
    """Rays against the (rotated) one-sheeted member: analytic roots of (7.1)
    with the patch |x| <= height agree with hits()."""
    m = lg.ConfocalQuadric(1, 2, 3, 2.0, height=1.5)
    rng = np.random.default_rng(3)
    o = rng.uniform(-6, 6, (4000, 3))
    v = rng.normal(size=(4000, 3))
    den = 1 / (np.array([1.0, 4.0, 9.0]) - 2.0)
    qa = (v * v * den).sum(1)
    qb = 2 * (o * v * den).sum(1)
    qc = (o * o * den).sum(1) - 1
    disc = qb * qb - 4 * qa * qc
    expect = np.zeros(len(o), bool)
    with np.errstate(invalid="ignore"):
        for sg in (-1, 1):
            s = (-qb + sg * np.sqrt(disc)) / (2 * qa)
            p = o + s[:, None] * v
            expect |= (disc >= 0) & (s > 1e-9) & (np.abs(p[:, 0]) <= 1.5)
    got = m.hits(o, v, np.full(len(o), np.inf), np.zeros(len(o), np.int8))
    assert np.mean(got == expect) > 0.999


@pytest.mark.parametrize("lams", [(-1.0, 2.0, 6.0), (0.3, 1.5, 5.0), (-4.0, 3.5, 8.5)])
def test_members_meet_at_right_angles(lams):
    a, b, c = 1.0, 2.0, 3.0
    system = lg.TripleOrthogonalSystem.confocal(a, b, c, lams, height=4.0)
    assert len(system.members) == 3
    pairs_seen = 0
    for curve in system.curves:
        t = np.linspace(curve.t0, curve.t1, 400)
        x = curve(t)
        on = []
        grads = []
        for m in system.members:
            val, grad = g(a, b, c, m.lam, x)
            if np.max(np.abs(val)) < 1e-9:
                on.append(m)
                grads.append(grad)
                assert np.all(m.patch_margin(x) >= -1e-9)
        assert len(on) == 2  # every curve lies on exactly two members
        n1, n2 = grads
        cosang = np.abs((n1 * n2).sum(1)) / (
            np.linalg.norm(n1, axis=1) * np.linalg.norm(n2, axis=1)
        )
        assert np.max(cosang) < 1e-9
        pairs_seen += 1
    assert pairs_seen >= 6


def test_intersection_curves_are_continuous_and_complete():
    system = lg.TripleOrthogonalSystem.confocal(1, 2, 3, (-1.0, 2.0, 6.0))
    for curve in system.curves:
        x = curve(np.linspace(curve.t0, curve.t1, 3001))
        step = np.linalg.norm(np.diff(x, axis=0), axis=1)
        assert step.max() < 0.01 * step.sum()
        if curve.closed:
            assert np.allclose(x[0], x[-1], atol=1e-9)


def test_spherical_system():
    system = lg.TripleOrthogonalSystem.spherical(2.0, 50.0, 20.0)
    sphere, cone, plane = system.members
    k = np.tan(np.radians(50))
    n_plane = np.array([-np.sin(np.radians(20)), np.cos(np.radians(20)), 0])
    for curve in system.curves:
        t = np.linspace(curve.t0, curve.t1, 200)[1:-1]
        x = curve(t)
        on_s = np.abs((x * x).sum(1) - 4.0) < 1e-9
        on_c = np.abs(x[:, 0] ** 2 + x[:, 1] ** 2 - k * k * x[:, 2] ** 2) < 1e-9
        on_p = np.abs(x @ n_plane) < 1e-12
        assert int(on_s.all()) + int(on_c.all()) + int(on_p.all()) == 2
        grads = []
        if on_s.all():
            grads.append(2 * x)
        if on_c.all():
            grads.append(np.stack([2 * x[:, 0], 2 * x[:, 1], -2 * k * k * x[:, 2]], 1))
        if on_p.all():
            grads.append(np.broadcast_to(n_plane, x.shape))
        n1, n2 = grads
        cosang = np.abs((n1 * n2).sum(1)) / (
            np.linalg.norm(n1, axis=1) * np.linalg.norm(n2, axis=1)
        )
        assert np.max(cosang) < 1e-9
    d = system.scene(hides=False).render(lg.ParallelProjector(direction=(2, 1.2, 1)))
    assert {"contour", "curve"} <= {s.family for s in d.strokes}


def test_system_scene_renders_with_lines_of_curvature():
    system = lg.TripleOrthogonalSystem.confocal(1, 2, 3, (-1.0, 2.0, 6.0))
    d = system.scene(lg.LinesOfCurvature(4, 4)).render(
        lg.CentralProjector(eye=(14, 9, 7)), hidden_lines=True
    )
    fams = {s.family for s in d.strokes}
    assert {"curvature", "contour", "curve"} <= fams
    for s in d.strokes:
        assert np.isfinite(s.xy).all()
