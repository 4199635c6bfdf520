"""Numeric line families (lgraph.families.fieldlines): complete, exact where the
parameter lines are the lines, free of corners at singular points, and the
same on every machine.

Every check here is independent of the integrator: surfaces of revolution
(lines of curvature are meridians and parallels), the triaxial ellipsoid
(each line of curvature lies on one confocal quadric), the monkey saddle
(fundamental forms written out here for the graph z = c (x^3 - 3 x y^2)).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import lgraph as lg
from lgraph.curvature import asymptotic_field, principal_field
from lgraph.families.fieldlines import trace
from lgraph.families.numeric import field_line_batches


def revolution(rho, z, u_range, poles):
    """A user-written surface of revolution: ``point`` and a domain, nothing else."""

    def point(u, v):
        r = rho(u)
        return np.stack(np.broadcast_arrays(r * np.cos(v), r * np.sin(v), z(u)), -1)

    return lg.ParametricSurface(point, u_range, (0, 2 * np.pi), periodic=(False, True), poles=poles)


EGG = revolution(
    lambda u: np.sin(u) * (1 + 0.25 * np.cos(u)), lambda u: -1.4 * np.cos(u), (0, np.pi), True
)
SPINDLE = revolution(
    lambda u: np.sin(u) * (1.2 + 0.4 * np.sin(3 * u)),
    lambda u: 2.0 * np.cos(u) + 0.3 * np.sin(2 * u),
    (0, np.pi),
    True,
)
BOWL = revolution(lambda u: u, lambda u: u * u, (0, 1.0), ((True, False), False))
VIEWS = [
    lg.ParallelProjector.from_angles(30, 25),
    lg.CentralProjector(eye=(6, -5, 4), target=(0, 0, 0)),
]


def _check_revolution(surface, n1, n2, projector):
    """Every stroke on a meridian or a parallel (1e-9 of the figure); each
    parallel once and whole; each meridian from end to end; no duplicates."""
    scene = lg.Scene()
    scene.add(surface, lg.LinesOfCurvature(n1, n2))
    drawing = scene.render(projector, hidden_lines=True)
    strokes = [s for s in drawing.strokes if s.family == "curvature"]
    d = surface.domain
    lo, hi = surface.bounds()
    size = float(np.linalg.norm(hi - lo))
    height = float(np.ptp(surface.point(np.linspace(*d.u1, 2001), 0.0)[:, 2]))
    parallels, meridians = {}, {}
    for s in strokes:
        x = s.xyz
        rho = np.hypot(x[:, 0], x[:, 1])
        if np.ptp(x[:, 2]) <= 1e-9 * size and np.ptp(rho) <= 1e-9 * size:
            key = round(float(x[0, 2]) / size, 6)
            parallels.setdefault(key, []).append(s)
            continue
        far = int(np.argmax(rho))
        phi = np.arctan2(x[far, 1], x[far, 0])
        off_plane = np.abs(-np.sin(phi) * x[:, 0] + np.cos(phi) * x[:, 1])
        outside = np.cos(phi) * x[:, 0] + np.sin(phi) * x[:, 1] < -1e-9 * size
        assert off_plane.max() <= 1e-9 * size and not outside.any(), "neither parallel nor meridian"
        meridians.setdefault(round(float(phi) % (2 * np.pi), 6), []).append(s)
    assert len(parallels) == n1 and len(meridians) == n2
    for group in parallels.values():
        rho = float(np.hypot(*group[0].xyz[0, :2]))
        drawn = sum(np.linalg.norm(np.diff(s.xyz, axis=0), axis=1).sum() for s in group)
        assert drawn == pytest.approx(2 * np.pi * rho, rel=1e-3)  # once, and whole
    u = np.linspace(*d.u1, 4001)
    profile = surface.point(u, 0.0)
    meridian_length = np.linalg.norm(np.diff(profile, axis=0), axis=1).sum()
    for phi, group in meridians.items():
        x = np.concatenate([s.xyz for s in group])
        for end in surface.point(np.array(d.u1), np.full(2, phi)):  # its two ends
            assert np.linalg.norm(x - end, axis=1).min() <= 0.01 * height
        drawn = sum(np.linalg.norm(np.diff(s.xyz, axis=0), axis=1).sum() for s in group)
        assert drawn == pytest.approx(meridian_length, rel=1e-3)  # not drawn twice


@pytest.mark.parametrize("projector", VIEWS, ids=["parallel", "central"])
@pytest.mark.parametrize("surface", [EGG, SPINDLE, BOWL], ids=["egg", "spindle", "bowl"])
def test_surfaces_of_revolution_give_meridians_and_parallels(surface, projector):
    _check_revolution(surface, 6, 8, projector)


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    a=st.floats(-0.3, 0.3),
    b=st.floats(-0.15, 0.15),
    c=st.floats(0.6, 2.0),
    k=st.integers(1, 3),
)
def test_random_profiles_of_revolution(a, b, c, k):
    surface = revolution(
        lambda u: np.sin(u) * (1 + a * np.cos(u) + b * np.sin(k * u)),
        lambda u: -c * np.cos(u),
        (0, np.pi),
        True,
    )
    _check_revolution(surface, 5, 7, VIEWS[0])


def test_bowl_boundary_is_the_rim_only():
    (b,) = BOWL.boundary()
    assert len(b) == 1
    x, _ = b.evaluate(np.zeros(5, int), np.linspace(b.t0[0], b.t1[0], 5))
    assert np.allclose(np.hypot(x[:, 0], x[:, 1]), 1.0) and np.allclose(x[:, 2], 1.0)


# ---------------------------------------------------------------------------
# the triaxial ellipsoid in a parametrization whose parameter lines are not
# lines of curvature: every numeric line lies on one confocal quadric
# ---------------------------------------------------------------------------
A, B, C = 3.0, 2.0, 1.5
ELLIPSOID = lg.ParametricSurface(
    lambda u, v: np.stack(
        np.broadcast_arrays(A * np.cos(u) * np.cos(v), B * np.cos(u) * np.sin(v), C * np.sin(u)),
        -1,
    ),
    (-1.45, 1.45),
    (0, 2 * np.pi),
    periodic=(False, True),
)


def _confocal_parameters(x):
    """The two roots lam in (c^2, b^2) and (b^2, a^2) of
    x^2/(a^2-lam) + y^2/(b^2-lam) + z^2/(c^2-lam) = 1 (a cubic in lam, one
    root 0 for points of the ellipsoid), computed here from the polynomial."""
    a2, b2, c2 = A * A, B * B, C * C
    out = []
    for p in x:
        X, Y, Z = p**2
        # (a2-l)(b2-l)(c2-l) - X (b2-l)(c2-l) - Y (a2-l)(c2-l) - Z (a2-l)(b2-l) = 0
        poly = np.poly1d([-1.0, a2 + b2 + c2, -(a2 * b2 + a2 * c2 + b2 * c2), a2 * b2 * c2])
        poly -= X * np.poly1d([1.0, -(b2 + c2), b2 * c2])
        poly -= Y * np.poly1d([1.0, -(a2 + c2), a2 * c2])
        poly -= Z * np.poly1d([1.0, -(a2 + b2), a2 * b2])
        r = np.sort(poly.roots.real)
        out.append(r[1:])
    return np.array(out)


def test_ellipsoid_lines_lie_on_confocal_quadrics_and_are_distinct():
    batches = field_line_batches(ELLIPSOID, principal_field, 5, 5)
    assert sum(len(b) for b in batches) == 10
    lines = []
    for b in batches:
        for k in range(len(b)):
            t = np.linspace(b.t0[k], b.t1[k], 60)
            x, _ = b.evaluate(np.full(60, k), t)
            lam = _confocal_parameters(x)
            # one of the two confocal parameters is constant along the line
            assert min(np.ptp(lam[:, 0]), np.ptp(lam[:, 1])) < 1e-5 * A * A
            lines.append(x)
    for i in range(len(lines)):
        for j in range(i):
            gap = np.linalg.norm(lines[i][:, None] - lines[j][None], axis=2).min(axis=1)
            assert gap.max() > 1e-3, "two lines retrace each other"


# ---------------------------------------------------------------------------
# the monkey saddle: a flat umbilic at the origin
# ---------------------------------------------------------------------------
CM = 0.6
SADDLE = lg.MonkeySaddle(extent=1.0, c=CM)


def _saddle_forms(x, y):
    """First and second fundamental forms of z = c (x^3 - 3 x y^2), written out."""
    zx, zy = CM * (3 * x * x - 3 * y * y), CM * (-6 * x * y)
    zxx, zxy, zyy = 6 * CM * x, -6 * CM * y, -6 * CM * x
    w = np.sqrt(1 + zx * zx + zy * zy)
    return (1 + zx * zx, zx * zy, 1 + zy * zy), (zxx / w, zxy / w, zyy / w)


def test_saddle_closed_forms_and_the_lean_principal_field():
    """The saddle's closed-form fundamental forms are the ones written out
    here, and the tracer's lean principal field (with them, and from the
    derivatives of another surface) takes the branch ``principal_field``
    gives, with the same sign, to rounding."""
    from lgraph.families.numeric import principal_oriented

    rng = np.random.default_rng(3)
    uv = rng.uniform(-1, 1, (500, 2))
    g, L = _saddle_forms(uv[:, 0], uv[:, 1])
    assert np.allclose(SADDLE.fundamental_forms(uv[:, 0], uv[:, 1]), g + L, rtol=1e-14, atol=1e-15)
    for S in (SADDLE, lg.Enneper()):
        D, strength, G = principal_field(S, uv)
        ref = rng.normal(size=(500, 2))  # unit in the metric, as the tracer passes it
        ref /= np.sqrt(G[:, 0] * ref[:, 0] ** 2 + 2 * G[:, 1] * ref[:, 0] * ref[:, 1]
                       + G[:, 2] * ref[:, 1] ** 2)[:, None]  # fmt: skip
        Gr = np.stack([G[:, 0] * ref[:, 0] + G[:, 1] * ref[:, 1],
                       G[:, 1] * ref[:, 0] + G[:, 2] * ref[:, 1]], axis=1)  # fmt: skip
        c = np.einsum("ibj,ij->ib", D, Gr)
        b = (np.abs(c[:, 1]) > np.abs(c[:, 0])).astype(int)
        cb = c[np.arange(500), b]
        want = D[np.arange(500), b] * np.sign(cb)[:, None]
        out, ok = principal_oriented(S, 2e-3)(uv, ref)
        assert np.array_equal(ok, (strength > 2e-3) & (np.abs(cb) > 0.5))
        assert np.allclose(out[ok], want[ok], rtol=0, atol=1e-12)
        assert not out[~ok].any()


def _lines(batches, n=4001):
    for b in batches:
        for k in range(len(b)):
            t = np.linspace(b.t0[k], b.t1[k], n)
            yield b, k, t


def _max_turn(b, k, t):
    x, _ = b.evaluate(np.full(len(t), k), t)
    d = np.diff(x, axis=0)
    d = d[np.linalg.norm(d, axis=1) > 0]
    c = np.einsum("ij,ij->i", d[1:], d[:-1]) / (
        np.linalg.norm(d[1:], axis=1) * np.linalg.norm(d[:-1], axis=1)
    )
    return np.degrees(np.arccos(np.clip(c, -1, 1))).max()


@pytest.mark.parametrize("field", [principal_field, asymptotic_field], ids=["curvature", "asym"])
def test_monkey_saddle_lines_have_no_corners(field):
    """Turning between successive chords shrinks with the chord length (a
    smooth curve), also where lines pass the flat umbilic; a corner keeps it."""
    batches = field_line_batches(SADDLE, field, 8, 8)
    assert sum(len(b) for b in batches) == 16
    for b, k, t in _lines(batches, 2001):
        coarse = _max_turn(b, k, t)
        fine = _max_turn(b, k, np.linspace(t[0], t[-1], 8001))
        assert fine < 2.0 or fine < 0.4 * coarse, (k, coarse, fine)


def test_monkey_saddle_asymptotic_lines_have_zero_normal_curvature():
    batches = field_line_batches(SADDLE, asymptotic_field, 7, 7)
    assert sum(len(b) for b in batches) == 14
    for b, k, t in _lines(batches, 1500):
        idx = np.full(len(t), k)
        h = 1e-6
        tp, tm = np.minimum(t + h, b.t1[k]), np.maximum(t - h, b.t0[k])
        (_, uvp), (_, uvm), (_, uv) = (b.evaluate(idx, tt) for tt in (tp, tm, t))
        du = (uvp - uvm) / (tp - tm)[:, None]  # tangent by differences, in the test
        x, y = uv[:, 0], uv[:, 1]
        (g11, g12, g22), (L11, L12, L22) = _saddle_forms(x, y)
        first = g11 * du[:, 0] ** 2 + 2 * g12 * du[:, 0] * du[:, 1] + g22 * du[:, 1] ** 2
        second = L11 * du[:, 0] ** 2 + 2 * L12 * du[:, 0] * du[:, 1] + L22 * du[:, 1] ** 2
        g = g11 * g22 - g12 * g12
        H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
        K = (L11 * L22 - L12 * L12) / g
        scale = np.abs(H) + np.sqrt(np.maximum(H * H - K, 0))  # max |principal curvature|
        away = np.hypot(x, y) > 1e-3
        rel = np.abs(second / first)[away] / scale[away]
        worst = int(np.argmax(rel))
        assert rel.max() < 1e-6, (rel.max(), uv[away][worst], t[away][worst], b.t0[k], b.t1[k])


def test_results_do_not_hang_on_the_last_bits():
    """The same surface with coordinates changed by 1e-14 (another CPU, another
    SIMD path) gives the same lines."""

    class Twin(lg.Surface):
        domain = SADDLE.domain
        size = SADDLE.size
        defined_past_domain = SADDLE.defined_past_domain  # the same formulas past the edges

        def _wobble(self, x):
            return x * (1 + 1e-14 * np.sin(1e3 * x))

        def point(self, u1, u2):
            return self._wobble(SADDLE.point(u1, u2))

        def derivatives(self, u1, u2):
            return tuple(self._wobble(x) for x in SADDLE.derivatives(u1, u2))

        def second_derivatives(self, u1, u2):
            return tuple(self._wobble(x) for x in SADDLE.second_derivatives(u1, u2))

    twin = Twin()
    for field in (principal_field, asymptotic_field):
        ref = [x for b in field_line_batches(SADDLE, field, 6, 6) for x in _points(b)]
        got = [x for b in field_line_batches(twin, field, 6, 6) for x in _points(b)]
        assert len(ref) == len(got)
        for x, y in zip(ref, got):
            assert np.abs(x - y).max() < 1e-6


def _points(b, n=200):
    for k in range(len(b)):
        yield b.evaluate(np.full(n, k), np.linspace(b.t0[k], b.t1[k], n))[0]


def test_lines_complete_by_default_and_even_spacing_trims():
    complete = field_line_batches(SADDLE, principal_field, 6, 6)
    even = field_line_batches(SADDLE, principal_field, 6, 6, spacing="even")
    for b in complete:  # complete lines end on the boundary (or at the umbilic)
        for k in range(len(b)):
            _, uv = b.evaluate(np.array([k, k]), np.array([b.t0[k], b.t1[k]]))
            on_edge = np.isclose(np.abs(uv), 1.0, atol=1e-9).any(axis=1)
            at_umbilic = np.hypot(uv[:, 0], uv[:, 1]) < 1e-3
            assert np.all(on_edge | at_umbilic), uv
    assert sum(len(b) for b in even) >= 12
    with pytest.raises(ValueError, match="spacing must be one of"):
        lg.LinesOfCurvature(3, 3, spacing="sparse")
    scene = lg.Scene()
    scene.add(SADDLE, lg.LinesOfCurvature(4, 4, spacing="even"))
    assert any(s.family == "curvature" for s in scene.render(VIEWS[0]).strokes)


def test_trace_closes_loops_exactly():
    """A parallel of the ellipsoid above (no closed form there) is a loop that
    ends on its seed."""
    seed = np.array([[0.3, 1.0]])
    D, _, _ = principal_field(ELLIPSOID, seed)
    lines = trace(ELLIPSOID, principal_field, seed, D[0, :1])
    lines2 = trace(ELLIPSOID, principal_field, seed, D[0, 1:])
    assert lines.closed[0] and lines2.closed[0]
    for L in (lines, lines2):
        end = L.uv_line(0, np.array([L.ends[0, 0]]))[0]
        wrapped = ELLIPSOID.domain.wrap(end[None])[0]
        assert np.allclose(ELLIPSOID.point(*wrapped), ELLIPSOID.point(*seed[0]), atol=1e-9)
