"""The nine quadrics: parametrizations, exact contours, patch-aware hits and
hidden-line removal against an independent brute-force ray cast."""

from __future__ import annotations

import numpy as np
import pytest
from test_lines_of_curvature_quadrics import CASES, IDS, implicit, make

import lgraph as lg

VIEWS = [
    lg.ParallelProjector(direction=(1.2, -2.0, 1.0)),
    lg.ParallelProjector(direction=(0.3, 0.2, 1.0)),
    lg.ParallelProjector(direction=(1.0, 0.0, 0.0)),
    lg.CentralProjector(eye=(7.0, -5.0, 4.0)),
    lg.CentralProjector(eye=(2.0, 9.0, -3.0)),
    lg.CentralProjector(eye=(0.5, 0.3, 8.0)),
]


@pytest.mark.parametrize("kind,p,kw", CASES, ids=IDS)
def test_point_satisfies_equation_and_uv_roundtrip(kind, p, kw):
    s = make(kind, p, kw)
    A, b, d = implicit(kind, *p)
    dom = s.domain
    u1, u2 = np.meshgrid(np.linspace(*dom.u1, 41), np.linspace(*dom.u2, 43), indexing="ij")
    x = s.point(u1.ravel(), u2.ravel())
    F = np.einsum("ni,ij,nj->n", x, A, x) + x @ b + d
    assert np.max(np.abs(F)) < 1e-11 * max(1.0, np.max(np.abs(x)) ** 2)
    lo, hi = s.bounds()
    assert np.all(x >= lo - 1e-12) and np.all(x <= hi + 1e-12)
    uv = s.uv_of(x)
    assert np.allclose(s.point(uv[:, 0], uv[:, 1]), x, atol=1e-9)
    # analytic derivatives agree with central differences of point()
    h = 1e-6
    x1, x2 = s.derivatives(u1.ravel(), u2.ravel())
    f1 = (s.point(u1.ravel() + h, u2.ravel()) - s.point(u1.ravel() - h, u2.ravel())) / (2 * h)
    f2 = (s.point(u1.ravel(), u2.ravel() + h) - s.point(u1.ravel(), u2.ravel() - h)) / (2 * h)
    inner = (np.abs(u1.ravel()) > 2 * h) & (np.abs(u2.ravel()) > 2 * h)  # piece seams
    assert np.allclose(x1[inner], f1[inner], atol=1e-5) and np.allclose(
        x2[inner], f2[inner], atol=1e-5
    )


@pytest.mark.parametrize("kind,p,kw", CASES, ids=IDS)
def test_contour_is_exact(kind, p, kw):
    s = make(kind, p, kw)
    A, b, d = implicit(kind, *p)
    lo, hi = s.bounds()
    size = float(np.linalg.norm(hi - lo))
    found = 0
    for proj in VIEWS:
        for bt in s.contour(proj):
            m = 200
            t = (bt.t0[:, None] + (bt.t1 - bt.t0)[:, None] * np.linspace(0, 1, m)).ravel()
            x, uv = bt.evaluate(np.repeat(np.arange(len(bt)), m), t)
            grad = 2 * x @ A + b
            w = proj.view_vectors(x)
            cosang = np.abs((grad * w).sum(1)) / (
                np.linalg.norm(grad, axis=1) * np.linalg.norm(w, axis=1)
            )
            ok = np.linalg.norm(grad, axis=1) > 1e-6  # the cone's vertex
            assert np.max(cosang[ok]) < 1e-9
            F = np.einsum("ni,ij,nj->n", x, A, x) + x @ b + d
            scale = np.einsum("ni,ij,nj->n", x, np.abs(A), x) + np.abs(x @ b) + abs(d)
            assert np.max(np.abs(F) / np.maximum(scale, 1e-300)) < 1e-9
            if hasattr(s, "patch_margin"):
                assert np.all(s.patch_margin(x) >= -1e-9 * size)
            found += len(x)
    assert found > 0


def brute_hits(kind, p, surf, o, v, smax):
    """Independent: both roots of the quadratic, patch test from the contract's
    extents (written here), no self-hit handling (origins off the surface)."""
    A, b, d = implicit(kind, *p)
    qa = np.einsum("ni,ij,nj->n", v, A, v)
    qb = 2 * np.einsum("ni,ij,nj->n", o, A, v) + v @ b
    qc = np.einsum("ni,ij,nj->n", o, A, o) + o @ b + d
    disc = qb * qb - 4 * qa * qc
    hit = np.zeros(len(o), bool)
    with np.errstate(invalid="ignore", divide="ignore"):
        roots = [(-qb - np.sqrt(disc)) / (2 * qa), (-qb + np.sqrt(disc)) / (2 * qa), -qc / qb]
        lin = np.abs(qa) < 1e-14
        for j, s in enumerate(roots):
            use = lin if j == 2 else ~lin
            x = o + np.where(np.isfinite(s), s, 0)[:, None] * v
            hit |= (
                use & (disc >= 0) & np.isfinite(s) & (s > 1e-9) & (s < smax) & patch(kind, surf, x)
            )
    return hit


def patch(kind, s, x):
    X, Y, Z = x[:, 0], x[:, 1], x[:, 2]
    e = 1e-12
    if kind in ("Ellipsoid", "Sphere"):
        return np.ones(len(x), bool)
    if kind in ("HyperboloidOneSheet", "HyperboloidTwoSheets", "EllipticCone", "EllipticCylinder"):
        return np.abs(Z) <= s.height + e
    if kind == "EllipticParaboloid":
        return Z <= s.height + e
    if kind == "HyperbolicParaboloid":
        return (np.abs(X) <= s.a * s.extent + e) & (np.abs(Y) <= s.b * s.extent + e)
    if kind == "HyperbolicCylinder":
        return (np.abs(Y) <= s.width + e) & (np.abs(Z) <= s.height + e)
    if kind == "ParabolicCylinder":
        return (np.abs(X) <= s.a * s.extent + e) & (np.abs(Y) <= s.length + e)
    raise KeyError(kind)


@pytest.mark.parametrize("kind,p,kw", CASES, ids=IDS)
def test_hits_check_the_patch(kind, p, kw):
    s = make(kind, p, kw)
    rng = np.random.default_rng(7)
    lo, hi = s.bounds()
    c, r = (lo + hi) / 2, np.max(hi - lo)
    o = c + rng.uniform(-1.5 * r, 1.5 * r, (3000, 3))
    v = rng.normal(size=(3000, 3))
    smax = np.where(rng.uniform(size=3000) < 0.5, np.inf, rng.uniform(0, 3 * r, 3000))
    got = s.hits(o, v, smax, np.zeros(3000, np.int8))
    want = brute_hits(kind, p, s, o, v, smax)
    assert np.mean(got == want) > 0.998


def test_default_extents_and_keywords():
    assert lg.HyperboloidOneSheet(1, 1, 2).height == 4.0
    assert lg.HyperboloidOneSheet(1, 1, 2, height=1).height == 1.0
    assert lg.EllipticCone(1, 2).height == 1.0
    assert lg.HyperbolicParaboloid(1, 2, extent=3).extent == 3.0
    assert lg.HyperbolicCylinder(1, 2).width == 4.0
    with pytest.raises(ValueError, match="EllipticCone: height must be a positive finite number"):
        lg.EllipticCone(1, 1, height=-1)
    with pytest.raises(ValueError, match="HyperbolicParaboloid: a must be a positive"):
        lg.HyperbolicParaboloid(0, 1)


@pytest.mark.parametrize(
    "surf", [lg.HyperboloidTwoSheets(1, 1.5, 1), lg.HyperbolicCylinder(1, 1)], ids=["two", "hcyl"]
)
def test_multi_piece_parameter_lines_never_jump(surf):
    for bt in surf.parameter_lines(6, 7):
        m = 400
        t = (bt.t0[:, None] + (bt.t1 - bt.t0)[:, None] * np.linspace(0, 1, m)).ravel()
        x, _ = bt.evaluate(np.repeat(np.arange(len(bt)), m), t)
        step = np.linalg.norm(np.diff(x.reshape(len(bt), m, 3), axis=1), axis=-1)
        assert step.max() < 0.05 * surf.size
    axis = 2 if isinstance(surf, lg.HyperboloidTwoSheets) else 0
    pieces = set()
    for bt in surf.parameter_lines(3, 3):
        x, _ = bt.evaluate(np.arange(len(bt)), bt.t0)
        pieces |= set(np.sign(x[:, axis]).tolist())
    assert pieces == {-1.0, 1.0}


# -- hidden-line removal against a brute-force ray cast --------------------------
SCENE = [
    ("EllipticCone", (0.8, 0.5), {"height": 1.5}, lg.translate(0, 0, 0)),
    ("HyperboloidOneSheet", (0.6, 0.9, 0.8), {"height": 1.4}, lg.translate(1.6, 0.6, 0)),
    ("Ellipsoid", (1.0, 0.7, 0.9), {}, lg.translate(0.6, -1.2, 0.3)),
]


@pytest.mark.parametrize(
    "proj",
    [lg.ParallelProjector(direction=(1.0, -2.5, 0.8)), lg.CentralProjector(eye=(6.0, -9.0, 4.0))],
    ids=["parallel", "central"],
)
def test_hidden_line_removal_matches_brute_force(proj):
    sc = lg.Scene()
    surfs = []
    for kind, p, kw, T in SCENE:
        s = make(kind, p, kw)
        surfs.append((kind, p, s, T))
        sc.add(s, lg.LinesOfCurvature(5, 6), transform=T)
    d = sc.render(proj, hidden_lines=True)
    assert any(not s.visible for s in d.strokes) and any(s.visible for s in d.strokes)
    checked = 0
    for st in d.strokes:
        if len(st.xyz) < 5:
            continue
        x = st.xyz[2:-2]  # interior points: away from the exact transitions
        if hasattr(proj, "eye"):
            w = proj.eye - x
            smax = np.linalg.norm(w, axis=1)
            dirs = w / smax[:, None]
        else:
            dirs = np.broadcast_to(proj.frame[2], x.shape)
            smax = np.full(len(x), np.inf)
        hidden = np.zeros(len(x), bool)
        fragile = np.zeros(len(x), bool)
        for kind, p, s, T in surfs:
            inv = T.inverse()
            o, v = inv.apply(x), inv.apply_vector(dirs)
            A, b, dd = implicit(kind, *p)
            qa = np.einsum("ni,ij,nj->n", v, A, v)
            qb = 2 * np.einsum("ni,ij,nj->n", o, A, v) + v @ b
            qc = np.einsum("ni,ij,nj->n", o, A, o) + o @ b + dd
            disc = qb * qb - 4 * qa * qc
            mine = st.surface is s
            with np.errstate(invalid="ignore", divide="ignore"):
                sq = np.sqrt(np.maximum(disc, 0))
                r1, r2 = (-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)
                if mine:  # drop the point's own root (the one nearer to s = 0)
                    own1 = np.abs(r1) < np.abs(r2)
                    r1, r2 = np.where(own1, np.nan, r1), np.where(own1, r2, np.nan)
                for r in (r1, r2):
                    ok = (disc >= 0) & np.isfinite(r) & (r < smax) & (r > 1e-9 * s.size)
                    q = o + np.where(np.isfinite(r), r, 0)[:, None] * v
                    hidden |= ok & patch(kind, s, q)
                    # fragile: hits near the patch rim or near the origin
                    rim = np.abs(s.patch_margin(q)) < 1e-6
                    fragile |= (disc >= 0) & np.isfinite(r) & (rim | (np.abs(r) < 1e-6 * s.size))
                # grazing rays of other surfaces
                graze = np.abs(disc) < 1e-8 * (qb * qb + np.abs(qa * qc) + 1e-300)
                fragile |= graze & (not mine)
        use = ~fragile
        assert np.all(hidden[use] == (not st.visible)), (st.family, st.visible, hidden[use].mean())
        checked += int(use.sum())
    assert checked > 2000


@pytest.mark.parametrize("surf", [lg.Ellipsoid(3, 2, 1.5), lg.Sphere(0.7)])
def test_ellipsoid_parameter_lines_carry_their_exact_ellipses(surf) -> None:
    """``CurveBatch.ellipses`` (centre, two axes) reproduce every evaluated
    point of every parameter line, at any t (also outside the drawn range)."""
    (batch,) = surf.parameter_lines(5, 7)
    assert batch.ellipses.shape == (12, 3, 3)
    rng = np.random.default_rng(3)
    cid = rng.integers(0, 12, 300)
    t = rng.uniform(-7, 7, 300)
    x, _ = batch.evaluate(cid, t)
    e = batch.ellipses[cid]
    y = e[:, 0] + e[:, 1] * np.cos(t)[:, None] + e[:, 2] * np.sin(t)[:, None]
    assert np.abs(x - y).max() < 1e-14
    assert surf.parameter_lines(0, 0) == []


def test_curve_batch_rejects_misshapen_ellipses() -> None:
    with pytest.raises(ValueError, match=r"ellipses must have shape \(2, 3, 3\)"):
        lg.CurveBatch("c", [0, 0], [1, 1], lambda i, t: (None, None), ellipses=np.zeros((3, 3)))
