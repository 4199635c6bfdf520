"""Lines of curvature on the nine quadrics, checked against independent geometry.

* principal directions from the implicit equation: the Hessian of ``F``
  restricted to the tangent plane (the shape operator up to the factor
  ``1/|grad F|``), its eigenvectors -- compared with every chord;
* the paper's equation (3.3) from fundamental forms obtained by finite
  differences of ``point()``;
* implicit-equation residuals, umbilics, no NaN / warnings near umbilics.

The implicit equations are written here from the public contract, not taken
from the classes.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import lgraph as lg


def implicit(kind: str, *p: float) -> tuple[np.ndarray, np.ndarray, float]:
    """``(A, b, d)`` of ``x^T A x + b.x + d = 0`` straight from the contract."""
    if kind == "Ellipsoid":
        a, b, c = p
        return np.diag([a**-2, b**-2, c**-2]), np.zeros(3), -1.0
    if kind == "Sphere":
        (r,) = p
        return np.eye(3) / r**2, np.zeros(3), -1.0
    if kind == "HyperboloidOneSheet":
        a, b, c = p
        return np.diag([a**-2, b**-2, -(c**-2)]), np.zeros(3), -1.0
    if kind == "HyperboloidTwoSheets":
        a, b, c = p
        return np.diag([a**-2, b**-2, -(c**-2)]), np.zeros(3), 1.0
    if kind == "EllipticCone":
        a, b = p
        return np.diag([a**-2, b**-2, -1.0]), np.zeros(3), 0.0
    if kind == "EllipticParaboloid":
        a, b = p
        return np.diag([a**-2, b**-2, 0.0]), np.array([0, 0, -1.0]), 0.0
    if kind == "HyperbolicParaboloid":
        a, b = p
        return np.diag([a**-2, -(b**-2), 0.0]), np.array([0, 0, -1.0]), 0.0
    if kind == "EllipticCylinder":
        a, b = p
        return np.diag([a**-2, b**-2, 0.0]), np.zeros(3), -1.0
    if kind == "HyperbolicCylinder":
        a, b = p
        return np.diag([a**-2, -(b**-2), 0.0]), np.zeros(3), -1.0
    if kind == "ParabolicCylinder":
        (a,) = p
        return np.diag([a**-2, 0.0, 0.0]), np.array([0, 0, -1.0]), 0.0
    raise KeyError(kind)


CASES = [
    ("Ellipsoid", (3.0, 2.0, 1.2), {}),
    ("Ellipsoid", (1.0, 2.5, 1.7), {}),
    ("Ellipsoid", (2.0, 2.0, 1.0), {}),  # oblate
    ("Ellipsoid", (1.0, 1.0, 2.0), {}),  # prolate
    ("Ellipsoid", (1.0, 1.5, 1.5), {}),  # rotational about x
    ("Sphere", (1.3,), {}),
    ("HyperboloidOneSheet", (1.0, 1.6, 1.2), {}),
    ("HyperboloidOneSheet", (2.0, 1.0, 0.7), {"height": 2.0}),
    ("HyperboloidOneSheet", (1.0, 1.0, 1.0), {}),
    ("HyperboloidTwoSheets", (1.0, 1.6, 1.0), {"height": 3.0}),
    ("HyperboloidTwoSheets", (2.0, 0.8, 1.5), {}),
    ("HyperboloidTwoSheets", (1.0, 1.0, 1.0), {}),
    ("EllipticCone", (1.0, 0.6), {}),
    ("EllipticCone", (0.7, 0.7), {"height": 2.0}),
    ("EllipticParaboloid", (1.0, 1.6), {"height": 2.0}),
    ("EllipticParaboloid", (2.0, 1.0), {}),
    ("EllipticParaboloid", (1.0, 1.0), {}),
    ("HyperbolicParaboloid", (1.0, 1.5), {}),
    ("HyperbolicParaboloid", (2.0, 2.0), {"extent": 1.5}),
    ("EllipticCylinder", (1.0, 0.6), {}),
    ("EllipticCylinder", (1.0, 1.0), {}),
    ("HyperbolicCylinder", (1.0, 1.0), {}),
    ("HyperbolicCylinder", (0.5, 1.5), {"width": 2.0}),
    ("ParabolicCylinder", (1.0,), {}),
    ("ParabolicCylinder", (0.4,), {"extent": 2.0}),
]
IDS = [f"{k}{p}{''.join(sorted(kw))}" for k, p, kw in CASES]


def make(kind: str, p: tuple, kw: dict) -> lg.Surface:
    return getattr(lg, kind)(*p, **kw)


def dense_curvature_points(surface: lg.Surface, n1: int = 7, n2: int = 9, m: int = 601):
    """Every curvature curve evaluated at ``m`` parameters: (points, chord, midpoints)."""
    out = []
    for batch in lg.LinesOfCurvature(n1, n2).batches(surface, None):
        assert batch.family == "curvature"
        k = len(batch)
        frac = np.linspace(0, 1, m)
        t = batch.t0[:, None] + (batch.t1 - batch.t0)[:, None] * frac
        tm = 0.5 * (t[:, 1:] + t[:, :-1])
        idx = np.repeat(np.arange(k), m)
        x, uv = batch.evaluate(idx, t.ravel())
        xm, uvm = batch.evaluate(np.repeat(np.arange(k), m - 1), tm.ravel())
        x = np.asarray(x).reshape(k, m, 3)
        uv = None if uv is None else np.asarray(uv).reshape(k, m, 2)
        out.append((x, uv, np.asarray(xm).reshape(k, m - 1, 3)))
    return out


def principal_frame(A: np.ndarray, b: np.ndarray, x: np.ndarray):
    """Unit normal, principal directions and curvatures from the implicit equation."""
    g = 2 * x @ A + b
    gn = np.linalg.norm(g, axis=-1)
    n = g / np.maximum(gn, 1e-300)[:, None]
    helper = np.where((np.abs(n[:, :1]) < 0.8), [[1.0, 0, 0]], [[0, 1.0, 0]])
    e1 = np.cross(n, helper)
    e1 /= np.maximum(np.linalg.norm(e1, axis=1), 1e-300)[:, None]
    e2 = np.cross(n, e1)
    H = 2 * A
    s11 = np.einsum("ni,ij,nj->n", e1, H, e1) / np.maximum(gn, 1e-300)
    s12 = np.einsum("ni,ij,nj->n", e1, H, e2) / np.maximum(gn, 1e-300)
    s22 = np.einsum("ni,ij,nj->n", e2, H, e2) / np.maximum(gn, 1e-300)
    S = np.stack([np.stack([s11, s12], -1), np.stack([s12, s22], -1)], -2)
    k, V = np.linalg.eigh(S)
    d1 = V[:, 0, :1] * e1 + V[:, 1, :1] * e2
    d2 = V[:, 0, 1:] * e1 + V[:, 1, 1:] * e2
    return n, d1, d2, k, gn


def chord_angles(A, b, x, xm):
    """Angle (deg) of each chord to the nearer principal direction at its
    midpoint, and a mask of usable chords (away from umbilics / singular points)."""
    chord = (x[:, 1:] - x[:, :-1]).reshape(-1, 3)
    mid = xm.reshape(-1, 3)
    n, d1, d2, k, gn = principal_frame(A, b, mid)
    c = chord - (chord * n).sum(1)[:, None] * n
    ln = np.linalg.norm(c, axis=1)
    good = ln > 0
    c = c / np.where(good, ln, 1)[:, None]
    ang = np.degrees(
        np.arccos(np.clip(np.maximum(np.abs((c * d1).sum(1)), np.abs((c * d2).sum(1))), 0, 1))
    )
    aniso = np.abs(k[:, 1] - k[:, 0]) / (np.abs(k).max(axis=1) + 1e-300)
    good &= aniso > 0.05
    good &= gn > 1e-3 * np.max(gn)  # cone vertex
    return ang, good


@pytest.mark.parametrize("kind,p,kw", CASES, ids=IDS)
def test_chords_follow_principal_directions(kind, p, kw):
    s = make(kind, p, kw)
    A, b, d = implicit(kind, *p)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        curves = dense_curvature_points(s)
    all_ang = []
    for x, uv, xm in curves:
        assert np.isfinite(x).all() and np.isfinite(xm).all()
        if uv is not None:
            assert np.isfinite(uv).all()
        pts = x.reshape(-1, 3)
        F = np.einsum("ni,ij,nj->n", pts, A, pts) + pts @ b + d
        scale = np.abs(np.einsum("ni,ij,nj->n", pts, np.abs(A), pts)) + np.abs(pts @ b) + abs(d)
        assert np.max(np.abs(F) / np.maximum(scale, 1e-300)) <= 1e-9
        ang, good = chord_angles(A, b, x, xm)
        if kind == "Sphere":
            continue  # every direction is principal
        all_ang.append(ang[good])
    if kind != "Sphere":
        ang = np.concatenate(all_ang)
        assert len(ang) > 1000
        assert np.percentile(ang, 99) <= 0.5, np.percentile(ang, 99)
        assert ang.max() <= 2.0, ang.max()


@pytest.mark.parametrize("kind,p,kw", CASES, ids=IDS)
def test_curves_stay_on_the_drawn_patch(kind, p, kw):
    s = make(kind, p, kw)
    lo, hi = s.bounds()
    for x, _uv, _xm in dense_curvature_points(s, 5, 5, 101):
        pts = x.reshape(-1, 3)
        span = np.max(hi - lo)
        assert np.all(pts >= lo - 1e-9 * span) and np.all(pts <= hi + 1e-9 * span)
        if hasattr(s, "patch_margin"):
            assert np.all(s.patch_margin(pts) >= -1e-9 * span)


def fd_forms(surface, u1, u2, h=1e-4):
    """g_ik and L_ik by central differences of point() (independent of the class)."""
    f = surface.point
    x1 = (f(u1 + h, u2) - f(u1 - h, u2)) / (2 * h)
    x2 = (f(u1, u2 + h) - f(u1, u2 - h)) / (2 * h)
    x0 = f(u1, u2)
    x11 = (f(u1 + h, u2) - 2 * x0 + f(u1 - h, u2)) / h**2
    x22 = (f(u1, u2 + h) - 2 * x0 + f(u1, u2 - h)) / h**2
    x12 = (f(u1 + h, u2 + h) - f(u1 + h, u2 - h) - f(u1 - h, u2 + h) + f(u1 - h, u2 - h)) / (
        4 * h * h
    )
    N = np.cross(x1, x2)
    nn = np.linalg.norm(N, axis=-1)
    N = N / nn[:, None]
    dot = lambda a, c: np.einsum("ni,ni->n", a, c)  # noqa: E731
    return (
        (dot(x1, x1), dot(x1, x2), dot(x2, x2)),
        (dot(N, x11), dot(N, x12), dot(N, x22)),
        x1,
        x2,
        nn,
    )


@pytest.mark.parametrize(
    "kind,p,kw",
    [c for c in CASES if c[0] != "Sphere"],
    ids=[i for i, c in zip(IDS, CASES) if c[0] != "Sphere"],
)
def test_equation_3_3_from_finite_difference_forms(kind, p, kw):
    """Along a line of curvature ``det [[L du, g du]] = 0`` (paper (3.3)):
    ``(L11 g12 - L12 g11) du1^2 + (L11 g22 - L22 g11) du1 du2
    + (L12 g22 - L22 g12) du2^2 = 0``; compared as a normalized residual."""
    s = make(kind, p, kw)
    A, b, _ = implicit(kind, *p)
    res = []
    for x, uv, xm in dense_curvature_points(s, 6, 6, 401):
        duv = (uv[:, 1:] - uv[:, :-1]).reshape(-1, 2)
        um = 0.5 * (uv[:, 1:] + uv[:, :-1]).reshape(-1, 2)
        step = np.linalg.norm(duv, axis=1)
        ok = step < 0.05 * (np.median(step) + 1e-12) * 40  # no seam / piece jumps
        ang, good = chord_angles(A, b, x, xm)
        (g11, g12, g22), (L11, L12, L22), x1, x2, nn = fd_forms(s, um[:, 0], um[:, 1])
        ok &= good & (nn > 1e-2 * np.median(nn))  # away from poles / vertices
        du1, du2 = duv[:, 0], duv[:, 1]
        det = (
            (L11 * g12 - L12 * g11) * du1**2
            + (L11 * g22 - L22 * g11) * du1 * du2
            + (L12 * g22 - L22 * g12) * du2**2
        )
        # normalize: |L| |g| |dx|^2 with dx the 3-D step
        dx = du1[:, None] * x1 + du2[:, None] * x2
        Ln = np.sqrt(L11**2 + 2 * L12**2 + L22**2)
        gn = np.sqrt(g11**2 + 2 * g12**2 + g22**2)
        r = np.abs(det) / (Ln * gn * np.einsum("ni,ni->n", dx, dx) / gn + 1e-300)
        res.append(r[ok])
    r = np.concatenate(res)
    assert len(r) > 500
    assert np.percentile(r, 99) < 2e-2 and np.max(r) < 7e-2, (np.percentile(r, 99), r.max())


UMBILICS = [
    ("Ellipsoid", (3.0, 2.0, 1.2), {}, 4),
    ("Ellipsoid", (1.0, 2.5, 1.7), {}, 4),
    ("Ellipsoid", (2.0, 2.0, 1.0), {}, 2),
    ("Sphere", (1.0,), {}, 0),
    ("HyperboloidOneSheet", (1.0, 1.6, 1.2), {}, 0),
    ("HyperboloidTwoSheets", (1.0, 1.6, 1.0), {}, 4),
    ("HyperboloidTwoSheets", (2.0, 0.8, 1.5), {}, 4),
    ("HyperboloidTwoSheets", (1.0, 1.0, 1.0), {}, 2),
    ("EllipticCone", (1.0, 0.6), {}, 0),
    ("EllipticParaboloid", (1.0, 1.6), {}, 2),
    ("EllipticParaboloid", (2.0, 1.0), {}, 2),
    ("EllipticParaboloid", (1.0, 1.0), {}, 1),
    ("HyperbolicParaboloid", (1.0, 1.5), {}, 0),
    ("EllipticCylinder", (1.0, 0.6), {}, 0),
    ("HyperbolicCylinder", (1.0, 1.0), {}, 0),
    ("ParabolicCylinder", (1.0,), {}, 0),
]


@pytest.mark.parametrize("kind,p,kw,count", UMBILICS)
def test_umbilics(kind, p, kw, count):
    s = make(kind, p, kw)
    u = np.asarray(s.umbilics())
    assert u.shape == (count, 3)
    if count:
        A, b, d = implicit(kind, *p)
        F = np.einsum("ni,ij,nj->n", u, A, u) + u @ b + d
        assert np.max(np.abs(F)) < 1e-12
        _, _, _, k, _ = principal_frame(A, b, u)
        assert np.max(np.abs(k[:, 1] - k[:, 0]) / np.abs(k).max(axis=1)) < 1e-9
    # independent search: on a fine grid of the surface, near-umbilic points
    # lie only near the listed umbilics
    d = s.domain
    g1, g2 = np.meshgrid(np.linspace(*d.u1, 241), np.linspace(*d.u2, 241), indexing="ij")
    pts = s.point(g1.ravel(), g2.ravel())
    A, b, _ = implicit(kind, *p)
    _, _, _, k, gn = principal_frame(A, b, pts)
    ok = gn > 1e-6
    aniso = np.abs(k[:, 1] - k[:, 0]) / (np.abs(k).max(axis=1) + 1e-300)
    near = pts[ok & (aniso < 1e-3)]
    if kind == "Sphere":
        return
    for q in near:
        assert count and np.min(np.linalg.norm(u - q, axis=1)) < 0.05 * s.size


def test_lines_near_umbilics_are_continuous():
    """Curves passing very close to the umbilics have no gaps: consecutive dense
    samples stay close (relative to the curve length)."""
    for s in (lg.Ellipsoid(3, 2, 1.2), lg.HyperboloidTwoSheets(1, 1.6, 1, height=3),
              lg.EllipticParaboloid(1, 1.6, height=2), lg.Ellipsoid(2, 2 + 1e-9, 1)):  # fmt: skip
        for x, _uv, _xm in dense_curvature_points(s, 40, 40, 2001):
            step = np.linalg.norm(np.diff(x, axis=1), axis=-1)
            length = step.sum(axis=1)
            assert np.all(step.max(axis=1) < 0.02 * length + 1e-12)


def test_rendered_curvature_strokes_follow_principal_directions():
    """The same chord check on what the renderer outputs (strokes of family
    "curvature"), for a scene with two quadrics, in world coordinates."""
    e = lg.Ellipsoid(3, 2, 1.2)
    h = lg.HyperboloidTwoSheets(1, 1.6, 1, height=3)
    sc = lg.Scene()
    sc.add(e, lg.LinesOfCurvature(8, 8))
    sc.add(h, lg.LinesOfCurvature(6, 6), transform=lg.translate(7, 0, 0))
    d = sc.render(lg.ParallelProjector(direction=(1, -2, 1)), hidden_lines=True, tolerance=1e-5)
    strokes = [s for s in d.strokes if s.family == "curvature"]
    assert strokes
    for surf, off in ((e, np.zeros(3)), (h, np.array([7.0, 0, 0]))):
        A, b, dd = implicit(type(surf).__name__, *((3, 2, 1.2) if surf is e else (1, 1.6, 1)))
        angs = []
        for st in strokes:
            if st.surface is not surf or len(st.xyz) < 3:
                continue
            x = st.xyz - off
            ang, good = chord_angles(A, b, x[None], (0.5 * (x[1:] + x[:-1]))[None])
            # chords of the adaptive polyline: their midpoints are O(chord^2) off
            # the surface; only short chords compare with the tangent
            ln = np.linalg.norm(np.diff(x, axis=0), axis=1)
            angs.append(ang[good & (ln < 0.02 * surf.size)])
        ang = np.concatenate(angs)
        assert len(ang) > 200
        assert np.percentile(ang, 99) <= 0.5 and ang.max() <= 2.0
