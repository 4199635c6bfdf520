"""AlgebraicSurface: polynomial expansion, certain root counting, exact
derivatives, built-ins (Clebsch's 27 lines, nodes of Cayley and Kummer),
against independent checks."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import lgraph as lg
from lgraph.formula import formula
from lgraph.surfaces.implicit._bernstein import count_roots
from lgraph.surfaces.implicit._polynomial import Polynomial


# -- the polynomial ------------------------------------------------------------
@pytest.mark.parametrize(
    "text",
    [
        "(x^2 + y^2 + z^2 + 3)^2 - 16*(x^2 + y^2)",
        "x*y*z/3 - 2*z^3 + (x - 2*y)^3 * (z + 1) - 7",
        "-(x + y)^2*(y - z)/4 + x^5",
    ],
)
def test_expansion_evaluates_like_the_formula(text):
    p = Polynomial.from_source(text)
    f = formula(text, ("x", "y", "z"))
    pts = np.random.default_rng(0).normal(size=(50, 3))
    assert np.allclose(p.value(pts), f(*pts.T), rtol=1e-12, atol=1e-10)
    # exact derivatives against the formula's own symbolic ones
    for i, v in enumerate("xyz"):
        assert np.allclose(p.gradient(pts)[:, i], f.derivative(v)(*pts.T), rtol=1e-12, atol=1e-9)
        for j, w in enumerate("xyz"):
            d2 = f.derivative(v).derivative(w)(*pts.T)
            assert np.allclose(p.hessian(pts)[:, i, j], d2, rtol=1e-12, atol=1e-9)


def test_ray_polynomial_matches_values_along_the_ray():
    p = Polynomial.from_source("(x^2 + y^2 + z^2 + 3)^2 - 16*(x^2 + y^2) + x*y*z")
    rng = np.random.default_rng(2)
    o, v = rng.normal(size=(30, 3)), rng.normal(size=(30, 3))
    q = p.along(o, v)
    s = rng.uniform(-2, 2, 30)
    direct = p.value(o + s[:, None] * v)
    assert np.allclose(np.polynomial.polynomial.polyval(s, q.T, tensor=False), direct)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("sin(x)", "must be a polynomial"),
        ("x^0.5", "must be a polynomial"),
        ("x/y", "must be a polynomial"),
        ("(x + y + z + 1)^1000", "degree at most 12"),
        ("x^7 * y^7", "degree at most 12"),
    ],
)
def test_non_polynomials_refused(text, message):
    with pytest.raises(ValueError, match=message):
        lg.AlgebraicSurface(text, radius=1)


def test_mapping_checked():
    s = lg.AlgebraicSurface({(2, 0, 0): 1, (0, 2, 0): 1, (0, 0, 2): 1, (0, 0, 0): -1}, radius=2)
    assert s.degree == 2
    with pytest.raises(ValueError, match="keys must be exponents"):
        lg.AlgebraicSurface({(1, 0): 1.0}, radius=1)
    with pytest.raises(ValueError, match="coefficients must be finite"):
        lg.AlgebraicSurface({(1, 0, 0): float("nan")}, radius=1)
    with pytest.raises(TypeError, match="formula string or a mapping"):
        lg.AlgebraicSurface(3.0, radius=1)


# -- certain root counting ---------------------------------------------------------
def _from_roots(real, pairs, lead):
    """Ascending coefficients of lead * prod (s - r) * prod ((s - a)^2 + b^2)."""
    c = np.array([float(lead)])
    for r in real:
        c = np.convolve(c, [-r, 1.0])
    for a, b in pairs:
        c = np.convolve(c, [a * a + b * b, -2 * a, 1.0])
    return c


def test_root_counts_against_numpy_roots():
    rng = np.random.default_rng(7)
    rows, expected = [], []
    for _ in range(400):
        deg = int(rng.integers(1, 9))
        q = rng.normal(size=deg + 1)
        rows.append(np.pad(q, (0, 8 - deg)))
        r = np.roots(q[::-1])
        real = r[np.abs(r.imag) < 1e-9].real
        expected.append(real)
    q = np.array(rows)
    lo, hi = np.full(len(q), -0.7), np.full(len(q), 1.9)
    got = count_roots(q, lo, hi)
    for g, real in zip(got, expected):
        inside = real[(real > -0.7) & (real < 1.9)]
        # leave out roots within 1e-6 of an end: undecidable from numpy's roots
        if np.any(np.abs(real - (-0.7)) < 1e-6) or np.any(np.abs(real - 1.9) < 1e-6):
            continue
        assert g == len(inside)


@pytest.mark.parametrize("gap", [1e-3, 1e-5, 1e-7])
def test_close_roots_are_separated(gap):
    # (closer pairs: p between the roots is ~gap^2, below the coefficients' rounding,
    # and the floating-point polynomial may have no real roots there at all)
    q = _from_roots([0.3, 0.3 + gap, 1.2], [(0.5, 0.2)], 2.0)[None, :]
    assert count_roots(q, np.array([0.0]), np.array([2.0])).tolist() == [3]
    assert count_roots(q, np.array([0.3 + gap / 2]), np.array([2.0])).tolist() == [2]


def test_double_roots_do_not_cross():
    # (s - 0.5)^2 (s - 1.5): one crossing; a ray tangent to a surface crosses nothing there
    q = _from_roots([0.5, 0.5, 1.5], [], 1.0)[None, :]
    assert count_roots(q, np.array([0.0]), np.array([2.0])).tolist() == [1]
    # a double root rounded: no crossing or a pair of them ~1e-8 apart (both are
    # the floating-point polynomial's truth); the parity is certain
    q = _from_roots([0.5, 0.5], [(1.0, 1e-3)], -3.0)[None, :]
    assert count_roots(q, np.array([0.0]), np.array([2.0]))[0] in (0, 2)
    # and a double root at a number exact in binary is exact: no crossing
    q = np.array([[0.25, -1.0, 1.0]])  # (s - 1/2)^2
    assert count_roots(q, np.array([0.0]), np.array([2.0])).tolist() == [0]


def test_hit_count_against_dense_sign_scan():
    torus = "(x^2 + y^2 + z^2 + 4 - 0.49)^2 - 16*(x^2 + y^2)"
    s = lg.AlgebraicSurface(torus, radius=3)
    rng = np.random.default_rng(5)
    n = 600
    o = rng.uniform(-3, 3, (n, 3))
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    got = s.hit_count(o, v, np.full(n, np.inf))
    # independent: dense scan of F inside the ball
    b = np.einsum("ij,ij->i", o, v)
    c = np.einsum("ij,ij->i", o, o) - 9
    disc = np.maximum(b * b - c, 0)
    lo = np.maximum(-b - np.sqrt(disc), 1e-9)
    hi = -b + np.sqrt(disc)
    t = np.linspace(0, 1, 8001)
    sv = lo[:, None] + (np.maximum(hi, lo) - lo)[:, None] * t
    x, y, z = (o[:, None, i] + sv * v[:, None, i] for i in range(3))
    f = (x**2 + y**2 + z**2 + 4 - 0.49) ** 2 - 16 * (x**2 + y**2)
    scan = (np.sign(f[:, 1:]) * np.sign(f[:, :-1]) < 0).sum(1)
    # rays with a near-tangency are undecidable for the scan: leave out those
    # where |F| has a small local minimum without a sign change
    a, m, c = np.abs(f[:, :-2]), np.abs(f[:, 1:-1]), np.abs(f[:, 2:])
    same = (np.sign(f[:, :-2]) == np.sign(f[:, 1:-1])) & (np.sign(f[:, 2:]) == np.sign(f[:, 1:-1]))
    dip = same & (m <= a) & (m <= c) & (m < 1e-3 * np.abs(f).max(1, keepdims=True))
    grazing = dip.any(axis=1)
    assert (got[~grazing] == scan[~grazing]).all()
    assert (~grazing).sum() > 0.9 * n and got.sum() > 0.3 * n


# -- the same surface written two ways ---------------------------------------------------
def test_ellipsoid_contour_as_lg_ellipsoid():
    a, b, c = 2.0, 1.2, 0.9
    s = lg.AlgebraicSurface(f"x^2/{a * a} + y^2/{b * b} + z^2/{c * c} - 1", radius=3)
    p = lg.ParallelProjector(direction=(1.0, -0.8, 0.6))
    (batch,) = s.contour(p)
    x, _ = batch.evaluate(np.zeros(300, int), np.linspace(0, batch.t1[0], 300))
    # the exact contour of lg.Ellipsoid: sampled densely, distances to it
    (eb,) = lg.Ellipsoid(a, b, c).contour(p)
    tt = np.linspace(eb.t0[0], eb.t1[0], 200001)
    y, _ = eb.evaluate(np.zeros(len(tt), int), tt)
    from scipy.spatial import cKDTree

    dist = cKDTree(y).query(x)[0]
    assert dist.max() < 3e-5 * 2  # the dense sampling's spacing, not the contour's error
    # and exactly: on the ellipsoid and on the plane x . (A w) = 0
    w = p.frame[2]
    assert np.abs(x @ (w / [a * a, b * b, c * c])).max() < 1e-10
    assert np.abs(s.implicit(x)).max() < 1e-12


def test_torus_visibility_as_lg_torus():
    R, r = 2.0, 0.7
    alg = lg.AlgebraicSurface(f"(x^2 + y^2 + z^2 + {R * R - r * r})^2 - {4 * R * R}*(x^2 + y^2)",
                              radius=3)  # fmt: skip
    exact = lg.Torus(R, r)
    p = lg.ParallelProjector(direction=(0.3, -1.0, 0.8))
    scene = lg.Scene()
    scene.add(alg, lg.LevelLines(6, direction=(1, 0, 0.2)))
    drawing = scene.render(p, hidden_lines=True)
    # every visible / hidden stroke's middle points, tested by lg.Torus's own exact ray test
    d = p.frame[2]
    for st in drawing.strokes:
        n = len(st.xyz)
        if n < 8:
            continue
        mid = st.xyz[n // 4 : n - n // 4]
        own = np.full(len(mid), lg.surfaces.CONTOUR if st.family == "contour" else lg.surfaces.ON)
        hidden = exact.hits(mid, np.broadcast_to(d, mid.shape), np.full(len(mid), np.inf), own)
        assert (hidden == (not st.visible)).all(), st.family
    x = np.concatenate([st.xyz for st in drawing.strokes])
    assert np.abs(exact.implicit(x)).max() < 1e-10 * 16 * 9


# -- built-ins -------------------------------------------------------------------------
def test_clebsch_27_lines_on_the_surface():
    c = lg.ClebschCubic()
    lines = c.lines()
    assert len(lines) == 27
    scale = 189.0  # the largest coefficient
    dirs, pts = [], []
    for line in lines:
        t = np.linspace(line.t0, line.t1, 50)
        x = line(t)
        assert np.abs(c.implicit(x)).max() < 1e-12 * scale
        assert np.linalg.norm(x[[0, -1]], axis=1) == pytest.approx([1.0, 1.0], abs=1e-12)
        d = (x[-1] - x[0]) / np.linalg.norm(x[-1] - x[0])
        dirs.append(d)
        pts.append(x[0] - (x[0] @ d) * d)
    # 27 distinct lines
    for i, j in itertools.combinations(range(27), 2):
        same = np.linalg.norm(pts[i] - pts[j]) < 1e-9 and abs(abs(dirs[i] @ dirs[j]) - 1) < 1e-12
        assert not same


def test_clebsch_line_incidences():
    """Each of the 27 lines meets exactly 10 others (a classical identity)."""
    L = lg.ClebschCubic().line_data()
    p, d = L[:, :3], L[:, 3:]
    meets = np.zeros(27, int)
    for i, j in itertools.combinations(range(27), 2):
        n = np.cross(d[i], d[j])
        if np.linalg.norm(n) < 1e-12:  # parallel: they meet at infinity
            hit = True
        else:
            hit = abs((p[j] - p[i]) @ n) / np.linalg.norm(n) < 1e-10
        meets[i] += hit
        meets[j] += hit
    assert (meets == 10).all()


def _is_node(s, x):
    g = s.grad(x)
    return np.abs(s.implicit(x)).max() < 1e-10 and np.abs(g).max() < 1e-9


def test_cayley_four_nodes():
    s = lg.CayleyCubic()
    p = s.singular_points()
    assert len(p) == 4
    assert _is_node(s, p)
    expected = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    for q in expected:
        assert np.linalg.norm(p - q, axis=1).min() < 1e-12


@pytest.mark.parametrize("mu", [1.3, 1.5])
def test_kummer_sixteen_nodes(mu):
    s = lg.KummerSurface(mu)
    p = s.singular_points()
    assert len(p) == 16
    assert _is_node(s, p)
    # the nodes are the same for an independent Newton search from random starts
    rng = np.random.default_rng(1)
    x = rng.uniform(-2.5, 2.5, (4000, 3))
    for _ in range(60):
        with np.errstate(all="ignore"):
            step = np.linalg.solve(s.hess(x), s.grad(x)[..., None])[..., 0]
        x = x - np.where(np.isfinite(step), np.clip(step, -0.3, 0.3), 0)
    ok = (np.abs(s.grad(x)).max(1) < 1e-10) & (np.abs(s.implicit(x)) < 1e-10)
    ok &= np.linalg.norm(x, axis=1) < 3
    found = x[ok]
    assert len(found)
    assert all(np.linalg.norm(p - q, axis=1).min() < 1e-8 for q in found)


def test_singularities_family_marks_points():
    scene = lg.Scene()
    scene.add(lg.CayleyCubic(), lg.LevelLines(3), lg.Singularities(size=5))
    drawing = scene.render(lg.ParallelProjector(direction=(1, 0.7, 0.45)), hidden_lines=True)
    dots = [s for s in drawing.strokes if s.family == "point"]
    assert len(dots) == 4
    # independent: a dense march of F from each node toward the viewer, inside the ball
    d = np.array([1, 0.7, 0.45]) / np.linalg.norm([1, 0.7, 0.45])
    s = lg.CayleyCubic()
    for dot in dots:
        o = dot.xyz[0]
        b, c = o @ d, o @ o - 4.0
        t = np.linspace(1e-4, -b + np.sqrt(b * b - c), 200001)
        f = s.implicit(o + t[:, None] * d)
        crosses = bool((np.sign(f[1:]) * np.sign(f[:-1]) < 0).any())
        assert dot.visible == (not crosses)
    assert any(dot.visible for dot in dots)


def test_builtins_validated():
    with pytest.raises(ValueError, match="KummerSurface: mu"):
        lg.KummerSurface(2.0)
    with pytest.raises(ValueError, match="RomanSteiner: r"):
        lg.RomanSteiner(-1)
    with pytest.raises(ValueError, match="GoursatSurface: b"):
        lg.GoursatSurface(b=float("inf"))
    x = np.array([[0.3, 0.2, 0.1]])
    r = lg.RomanSteiner(1.0)
    # the Roman surface is the image of the sphere under (yz, xz, xy)
    u = np.random.default_rng(0).normal(size=(20, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    img = np.stack([u[:, 1] * u[:, 2], u[:, 0] * u[:, 2], u[:, 0] * u[:, 1]], axis=1)
    assert np.abs(r.implicit(img)).max() < 1e-15
    assert r.implicit(x).shape == (1,)


def test_surfaces_pickle():
    import pickle

    p = np.array([[0.3, -0.2, 0.5]])
    for s in (lg.KummerSurface(1.3), lg.ClebschCubic(), lg.AlgebraicSurface("x*y - z", radius=1)):
        t = pickle.loads(pickle.dumps(s))
        assert np.array_equal(t.implicit(p), s.implicit(p))
        assert t.clip.radius == s.clip.radius


def test_central_view_visibility_against_dense_march():
    s = lg.CayleyCubic(radius=2.0)
    eye = np.array([6.0, 3.5, 2.5])
    scene = lg.Scene()
    scene.add(s, lg.LevelLines(5))
    drawing = scene.render(lg.CentralProjector(eye=eye), hidden_lines=True)
    checked = {True: 0, False: 0}
    for st in drawing.strokes:
        n = len(st.xyz)
        if n < 8:
            continue
        p = st.xyz[n // 4 : n - n // 4]
        w = eye - p
        dist = np.linalg.norm(w, axis=1)
        d = w / dist[:, None]
        # the part of each ray inside the clip ball, up to the eye
        b = np.einsum("ij,ij->i", p, d)
        c = np.einsum("ij,ij->i", p, p) - 4.0
        hi = np.minimum(-b + np.sqrt(np.maximum(b * b - c, 0)), dist)
        t = np.linspace(0, 1, 6001)[None, :] * np.maximum(hi - 1e-6, 0)[:, None] + 1e-6
        x = p[:, None, :] + t[..., None] * d[:, None, :]
        f = (
            x[..., 0] ** 2
            + x[..., 1] ** 2
            + x[..., 2] ** 2
            - 2 * x[..., 0] * x[..., 1] * x[..., 2]
            - 1
        )
        crosses = (np.sign(f[:, 1:]) * np.sign(f[:, :-1]) < 0).any(axis=1)
        assert (crosses == (not st.visible)).all(), st.family
        checked[st.visible] += len(p)
    assert checked[True] > 100 and checked[False] > 100


def test_a_component_smaller_than_a_grid_cell_is_found():
    # a sphere of radius 0.02 beside the unit sphere: far smaller than a cell
    # of the search grid (6 / 48 = 0.125); the Bernstein bounds of the cells seed it
    p = np.array([1.2, 0.3, -0.4])
    F = "(x^2 + y^2 + z^2 - 1)*((x - 1.2)^2 + (y - 0.3)^2 + (z + 0.4)^2 - 0.0004)"
    s = lg.AlgebraicSurface(F, radius=3)
    proj = lg.ParallelProjector(direction=(1, 0.5, 0.3))
    (contour,) = s.contour(proj)
    (sections,) = s.level_lines((0, 0, 1), [-0.4])
    for batch, radius in ((contour, 0.02), (sections, 0.02)):
        assert len(batch) == 2
        small = []
        for k in range(2):
            x, _ = batch.evaluate(np.full(50, k), np.linspace(0, batch.t1[k], 50))
            small.append(np.abs(np.linalg.norm(x - p, axis=1) - radius).max() < 1e-12)
        assert sorted(small) == [False, True]  # one on each sphere
    # and the ray test counts the tiny sphere: roots of the two spheres' quadratics
    v = proj.frame[2]
    o = p - 3.0 * v
    expected = 0
    for c, r in ((np.zeros(3), 1.0), (p, 0.02)):
        b, cc = (o - c) @ v, (o - c) @ (o - c) - r * r
        roots = -b + np.array([-1, 1]) * np.sqrt(max(b * b - cc, 0))
        expected += int(((roots > 0) & (b * b > cc)).sum())
    assert expected == 4
    assert s.hit_count(o[None], v[None], np.array([np.inf]))[0] == expected


def test_box_clip_visibility_against_dense_march():
    s = lg.AlgebraicSurface("x^2 + y^2 - z^2 - 0.5", bounds=((-1.5, 1.5), (-1.2, 1.2), (-1, 1)))
    proj = lg.ParallelProjector(direction=(0.8, -1.0, 0.6))
    scene = lg.Scene()
    scene.add(s, lg.LevelLines(5))
    drawing = scene.render(proj, hidden_lines=True)
    assert {st.family for st in drawing.strokes} == {"level", "contour", "boundary"}
    v = proj.frame[2]
    lo_b, hi_b = np.array([-1.5, -1.2, -1.0]), np.array([1.5, 1.2, 1.0])
    checked = {True: 0, False: 0}
    for st in drawing.strokes:
        n = len(st.xyz)
        if n < 8:
            continue
        p = st.xyz[n // 4 : n - n // 4]
        with np.errstate(divide="ignore"):
            exit_ = np.min(np.where(v > 0, (hi_b - p) / v, (lo_b - p) / v), axis=1)
        t = np.linspace(0, 1, 6001)[None, :] * np.maximum(exit_ - 1e-6, 0)[:, None] + 1e-6
        x = p[:, None, :] + t[..., None] * v
        f = x[..., 0] ** 2 + x[..., 1] ** 2 - x[..., 2] ** 2 - 0.5
        crosses = (np.sign(f[:, 1:]) * np.sign(f[:, :-1]) < 0).any(axis=1)
        assert (crosses == (not st.visible)).all(), st.family
        checked[st.visible] += len(p)
    assert checked[True] > 100 and checked[False] > 100
