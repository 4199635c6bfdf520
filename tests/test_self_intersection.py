"""Lines of self-intersection and visibility on self-intersecting surfaces,
checked against closed forms and an exact brute-force ray test (the Whitney
umbrella is the cubic x^2 = y^2 z: a ray meets it where a cubic vanishes)."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph.families.self_intersection import self_intersection_points


def _umbrella(u_range=(-1.0, 1.0)):
    return lg.ParametricSurface(
        lambda u, v: np.stack(np.broadcast_arrays(u * v, u, v * v), -1),
        u_range,
        (-1.0, 1.0),
        derivatives_func=lambda u, v: (
            np.stack(np.broadcast_arrays(v, 1 + 0 * u, 0 * v), -1),
            np.stack(np.broadcast_arrays(u, 0 * u, 2 * v), -1),
        ),
    )


def _tube():
    """A tube of radius 0.3 + 0.08 sin u about the lemniscate (2 cos u, sin 2u, 0):
    where the centre curve crosses itself the thin part (u = 3 pi/2) pierces
    the thick one (u = pi/2), in two closed curves."""

    def centre(u):
        return np.stack(np.broadcast_arrays(2 * np.cos(u), np.sin(2 * u), 0 * u), -1)

    def point(u, v):
        u, v = np.broadcast_arrays(u, v)
        d = np.stack([-2 * np.sin(u), 2 * np.cos(2 * u), 0 * u], -1)
        d = d / np.linalg.norm(d, axis=-1, keepdims=True)
        n = np.stack([-d[..., 1], d[..., 0], 0 * u], -1)
        b = np.stack([0 * u, 0 * u, 1 + 0 * u], -1)
        r = (0.3 + 0.08 * np.sin(u))[..., None]
        return centre(u) + r * (np.cos(v)[..., None] * n + np.sin(v)[..., None] * b)

    return lg.ParametricSurface(point, (0, 2 * np.pi), (0, 2 * np.pi), periodic=(True, True))


def _evaluate(batches, n=101):
    out = []
    for b in batches:
        for k in range(len(b)):
            t = np.linspace(b.t0[k], b.t1[k], n)
            xyz, uv = b.evaluate(np.full(n, k), t)
            out.append((xyz, uv, b.closed[k]))
    return out


@pytest.mark.parametrize("u_range", [(-1.0, 1.0), (-1.0, 1.1)], ids=["on-grid", "off-grid"])
def test_whitney_umbrella_self_intersection_is_its_handle(u_range):
    s = _umbrella(u_range)
    pts = self_intersection_points(s)
    a, b = pts["a"], pts["b"]
    assert len(a) > 25  # one crossing per grid row of the kept preimage
    # two parameter pairs, one point
    assert np.abs(s.points(a) - s.points(b)).max() < 1e-9
    assert np.linalg.norm(a - b, axis=1).min() > 1e-3
    batches = lg.SelfIntersection().batches(s, None)
    (curve,) = _evaluate(batches)
    xyz, uv, closed = curve
    assert not closed
    # the segment x = y = 0, 0 < z <= 1, drawn once, up to the patch edge
    assert np.abs(xyz[:, :2]).max() < 1e-9 and np.abs(uv[:, 0]).max() < 1e-9
    assert xyz[:, 2].max() > 1 - 1e-9 and xyz[:, 2].min() < 0.01
    # the other preimage (0, -v) of every drawn point (from the formula)
    assert np.abs(s.point(0 * uv[:, 1], -uv[:, 1]) - xyz).max() < 1e-9
    assert np.all(np.abs(uv[:, 1]) > 1e-3)


def test_self_intersection_of_a_tube_across_its_periodic_seams():
    s = _tube()
    pts = self_intersection_points(s)
    a, b = pts["a"], pts["b"]
    assert len(a) > 50
    assert np.abs(s.points(a) - s.points(b)).max() < 1e-9
    # the two preimages lie on the two branches through the crossing (u near pi/2, 3 pi/2)
    da = np.abs(np.angle(np.exp(1j * (a[:, 0] - b[:, 0]))))
    assert np.all(da > 1.0)
    curves = _evaluate(lg.SelfIntersection().batches(s, None), 101)
    assert len(curves) == 2
    grid_u, grid_v = np.meshgrid(np.linspace(0, 2 * np.pi, 801), np.linspace(0, 2 * np.pi, 201))
    dense = s.point(grid_u, grid_v).reshape(-1, 3)
    dense_uv = np.stack([grid_u.ravel(), grid_v.ravel()], 1)
    for xyz, uv, closed in curves:
        assert closed
        assert np.abs(s.points(uv) - xyz).max() < 1e-12
        # a second preimage on the other branch: nearest dense sample off the
        # first branch, then Gauss-Newton on x(b) = xyz (an independent solver)
        far = np.abs(np.angle(np.exp(1j * (dense_uv[None, :, 0] - uv[:, None, 0])))) > 1.0
        dist = np.where(far, np.linalg.norm(dense[None] - xyz[:, None], axis=2), np.inf)
        b = dense_uv[np.argmin(dist, axis=1)]
        h = 1e-7
        for _ in range(8):
            g = s.points(b) - xyz
            j1 = (s.point(b[:, 0] + h, b[:, 1]) - s.point(b[:, 0] - h, b[:, 1])) / (2 * h)
            j2 = (s.point(b[:, 0], b[:, 1] + h) - s.point(b[:, 0], b[:, 1] - h)) / (2 * h)
            J = np.stack([j1, j2], axis=2)
            b = (
                b
                - np.linalg.lstsq(J[0], g[0], rcond=None)[0] * 0
                + np.stack([np.linalg.lstsq(J[k], -g[k], rcond=None)[0] for k in range(len(b))])
            )
        assert np.abs(s.points(b) - xyz).max() < 1e-9
        assert np.abs(np.angle(np.exp(1j * (b[:, 0] - uv[:, 0])))).min() > 1.0


def _umbrella_hidden(points, projector, eps=1e-7):
    """Exact brute force: rays toward the viewer against x^2 = y^2 z, |y| <= 1,
    0 <= z <= 1.  Returns (hidden, clear): clear is False where the answer is
    fragile (a root near the origin, the far end, the patch edge, or a double root)."""
    v, smax = projector.rays(points)
    o = points
    ox, oy, oz = o.T
    vx, vy, vz = v.T
    c3 = -vy * vy * vz
    c2 = vx * vx - 2 * oy * vy * vz - vy * vy * oz
    c1 = 2 * ox * vx - oy * oy * vz - 2 * oy * vy * oz
    c0 = ox * ox - oy * oy * oz
    n = len(o)
    roots = np.full((n, 3), np.nan + 0j)
    cubic = np.abs(c3) > 1e-12
    if cubic.any():
        comp = np.zeros((cubic.sum(), 3, 3))
        comp[:, 1, 0] = comp[:, 2, 1] = 1.0
        comp[:, :, 2] = -np.stack([c0, c1, c2], 1)[cubic] / c3[cubic, None]
        roots[cubic] = np.linalg.eigvals(comp)
    q = ~cubic
    with np.errstate(all="ignore"):
        disc = np.sqrt((c1 * c1 - 4 * c2 * c0).astype(complex))
        roots[q, 0] = ((-c1 - disc) / (2 * c2))[q]
        roots[q, 1] = ((-c1 + disc) / (2 * c2))[q]
    real = np.abs(roots.imag) < 1e-7
    s = roots.real
    p = o[:, None, :] + s[..., None] * v[:, None, :]
    inpatch = (np.abs(p[..., 1]) <= 1) & (p[..., 2] >= 0) & (p[..., 2] <= 1)
    hit = real & inpatch & (s > eps) & (s < smax[:, None])
    hidden = hit.any(axis=1)
    other = real & (np.abs(s) > 1e-6)  # not the point's own root
    edge = (np.abs(np.abs(p[..., 1]) - 1) < 1e-3) | (np.abs(p[..., 2] - 1) < 1e-3)
    edge |= np.abs(p[..., 2]) < 1e-3
    near_double = np.abs(roots.imag) < 1e-2
    fragile = other & ((np.abs(s) < 1e-3) | edge | (np.abs(s - smax[:, None]) < 1e-3))
    fragile |= ~real & near_double
    return hidden, ~fragile.any(axis=1)


@pytest.mark.parametrize(
    "projector",
    [lg.ParallelProjector.from_angles(-50, 25), lg.CentralProjector(eye=(3.0, -4.0, 2.5))],
    ids=["parallel", "central"],
)
def test_visibility_on_the_self_intersecting_umbrella_matches_brute_force(projector):
    s = _umbrella()
    scene = lg.Scene()
    scene.add(s, lg.ParameterLines(9, 9), lg.SelfIntersection())
    drawing = scene.render(projector, hidden_lines=True)
    pts, vis = [], []
    for st in drawing.strokes:
        m = len(st.xyz)
        if m < 8:
            continue
        keep = slice(2, m - 2)  # transitions are at stroke ends
        pts.append(st.xyz[keep])
        vis.append(np.full(len(st.xyz[keep]), st.visible))
    P, visible = np.concatenate(pts), np.concatenate(vis)
    hidden, clear = _umbrella_hidden(P, projector)
    assert clear.sum() > 0.8 * len(P)
    assert visible[clear].any() and (~visible[clear]).any()
    bad = clear & (hidden == visible)
    assert not bad.any(), P[bad][:5]


def test_figure_eight_klein_bottle_meets_itself_in_a_circle():
    """The figure-8 immersion of the Klein bottle: its cross-section's double
    point (v = 0 and v = pi) sweeps the circle of radius R in the plane z = 0."""
    R = 2.0

    def klein(u, v):
        u, v = np.broadcast_arrays(u, v)
        w = R + np.cos(u / 2) * np.sin(v) - np.sin(u / 2) * np.sin(2 * v)
        z = np.sin(u / 2) * np.sin(v) + np.cos(u / 2) * np.sin(2 * v)
        return np.stack([w * np.cos(u), w * np.sin(u), z], -1)

    s = lg.ParametricSurface(klein, (0, 2 * np.pi), (0, 2 * np.pi), periodic=(False, True))
    pts = self_intersection_points(s)
    assert np.abs(s.points(pts["a"]) - s.points(pts["b"])).max() < 1e-9
    (curve,) = _evaluate(lg.SelfIntersection().batches(s, None), 301)
    xyz, uv, _ = curve
    assert np.abs(np.hypot(xyz[:, 0], xyz[:, 1]) - R).max() < 1e-9
    assert np.abs(xyz[:, 2]).max() < 1e-9
    # the whole circle: u runs over the full range, on one of the sheets v = 0 or pi
    assert np.ptp(uv[:, 0]) > 2 * np.pi - 0.1
    vv = np.mod(uv[:, 1], np.pi)
    assert np.minimum(vv, np.pi - vv).max() < 1e-9
