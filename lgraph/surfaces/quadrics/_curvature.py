r"""Closed-form lines of curvature on the nine quadrics.

Every formula here comes from a triply orthogonal system and Dupin's theorem
(paper Theorem 6.1): the surfaces of such a system meet in lines of
curvature.  The substitutions below turn the square roots of the confocal
coordinates into trigonometric or hyperbolic functions, so that each line of
curvature is **one** smooth closed or complete curve that runs through the
sign changes of the coordinates (no octant pieces, no NaN, no gaps near
umbilics).

Ellipsoid (paper §7, Lemma 7.1)
-------------------------------
Sort the squared semi-axes ``p < q < r`` (coordinates ``X1, X2, X3``).  The
confocal family ``X1^2/(p-l) + X2^2/(q-l) + X3^2/(r-l) = 1`` has the ellipsoid
as member ``l = 0``; through each of its points pass one hyperboloid of one
sheet ``l = mu`` in ``(p, q)`` and one of two sheets ``l = nu`` in ``(q, r)``,
and (7.6)-(7.8) give ``X_i^2 = prod_k (A_i - l_k) / prod_{j != i} (A_i - A_j)``.
With ``mu = p + (q-p) sin^2 phi`` and ``nu = q + (r-q) cos^2 theta`` all
divisions by ``q - p`` and ``r - q`` cancel::

    X1 = sqrt(p) sin(phi) sqrt(((q-p) + (r-q) cos^2 theta) / (r-p))
    X2 = sqrt(q) cos(phi) cos(theta)
    X3 = sqrt(r) sin(theta) sqrt(((r-p) - (q-p) sin^2 phi) / (r-p))

``theta = const`` (``phi`` over a full turn) are closed loops around the
longest axis, ``phi = const`` loops around the shortest axis; ``theta, phi`` in
``(-pi/2, pi/2)`` give every line once, the limits ``+-pi/2`` are the arcs
through the four umbilics ``(+-sqrt(p(q-p)/(r-p)), 0, +-sqrt(r(r-q)/(r-p)))``.

Hyperboloid of one sheet ``(X2^2/s + X3^2/l - X1^2/c^2 = 1, s <= l)``
--------------------------------------------------------------------
Member ``l = 0`` of the family with ``A = (-c^2, s, l)``; the other coordinates
``l1 = -c^2 - (c^2+s) sinh^2 t`` and ``l3 = s + (l-s) cos^2 theta`` give::

    X1 = c sinh(t) sqrt((c^2 + s + (l-s) cos^2 theta) / (c^2 + l))
    X2 = sqrt(s) cos(theta) cosh(t)
    X3 = sqrt(l) sin(theta) sqrt((l + c^2 + (c^2+s) sinh^2 t) / (l + c^2))

``theta = const``: complete curves through the waist; ``t = const``: loops.

Hyperboloid of two sheets ``(X3^2/c^2 - X1^2/l - X2^2/s = 1, s <= l)``
----------------------------------------------------------------------
Member ``l = 0`` of the family with ``A = (-l, -s, c^2)``;
``l1 = -l - (c^2+l) sinh^2 t`` and ``l2 = -l + (l-s) sin^2 phi`` give::

    X1 = sqrt(l) sinh(t) sin(phi)
    X2 = sqrt(s) cos(phi) sqrt((l - s + (c^2+l) sinh^2 t) / (c^2 + s))
    X3 = +-c cosh(t) sqrt((c^2 + s + (l-s) cos^2 phi) / (c^2 + s))

``phi = const`` (``t`` in R): complete curves; ``t = const > 0``: loops.  Umbilics
at ``t = 0, phi = 0, pi``: ``(0, +-sqrt(s(l-s)/(c^2+s)), +-c sqrt((c^2+l)/(c^2+s)))``.

Paraboloids: confocal paraboloids
---------------------------------
``G_l = X^2/(P-l) + Y^2/(Q-l) - 2Z + l = 0`` is triply orthogonal:
``G_l - G_m = (l-m)[X^2/((P-l)(P-m)) + Y^2/((Q-l)(Q-m)) + 1]`` and the bracket
is ``grad G_l . grad G_m / 4``.  Multiplying by ``(P-l)(Q-l)`` gives a monic
cubic in ``l`` with roots ``l1, l2, l3``; evaluating at ``l = P, Q`` and
comparing the ``l^2`` terms::

    X^2 = (P-l1)(P-l2)(P-l3)/(Q-P),  Y^2 = (Q-l1)(Q-l2)(Q-l3)/(P-Q),
    2Z = l1 + l2 + l3 - P - Q.

*Elliptic paraboloid* ``z = x^2/a^2 + y^2/b^2`` (``P = min/2 < Q = max/2``,
``D = Q - P``), member ``l1 = 0``, ``l2 = P + D sin^2 phi``,
``l3 = Q + D sinh^2 t``::

    X = sqrt(P D) sin(phi) cosh(t),  Y = sqrt(Q D) cos(phi) sinh(t),
    Z = D (sin^2 phi + sinh^2 t) / 2.

Umbilics ``(+-sqrt(P D), 0, D/2)``.

*Hyperbolic paraboloid* ``z = x^2/a^2 - y^2/b^2`` (``alpha = a^2/2``,
``beta = b^2/2``, ``E = alpha + beta``): member ``l2 = 0`` with ``P = -beta``,
``Q = alpha``, ``l1 = -beta - E sinh^2 s``, ``l3 = alpha + E sinh^2 t``::

    x = sqrt(alpha E) cosh(s) sinh(t),  y = sqrt(beta E) sinh(s) cosh(t),
    z = E (sinh^2 t - sinh^2 s) / 2,

a regular global parametrization whose parameter lines are the lines of
curvature (it re-derives paper §5 without the garbled formulas).

Cone and cylinders (paper Examples 4.1, 4.2)
--------------------------------------------
Cylinders: rulings and cross-sections.  Elliptic cone: rulings and the
sections by spheres ``|x| = rho`` about the vertex,
``x = rho (a cos u, b sin u, 1) / sqrt(1 + a^2 cos^2 u + b^2 sin^2 u)`` on each
nappe (the spheres about the vertex are orthogonal to the rulings, and the
cones with the same vertex are the third family of the system).
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from ...curves import CurveBatch
from .._patch import curve_batch, spread

__all__ = [
    "ellipsoid_lines",
    "one_sheet_lines",
    "two_sheets_lines",
    "elliptic_paraboloid_lines",
    "hyperbolic_paraboloid_lines",
    "cone_lines",
]

_TWO_PI = 2 * np.pi
_HALF_PI = np.pi / 2


def _scatter(X: np.ndarray, order: np.ndarray) -> np.ndarray:
    """Points given in sorted coordinates ``X[..., k] = x[..., order[k]]`` -> x."""
    x = np.empty_like(X)
    x[..., order] = X
    return x


# -- ellipsoid ----------------------------------------------------------------
def ellipsoid_frame(axes: np.ndarray) -> tuple[np.ndarray, float, float, float]:
    sq = np.asarray(axes, float) ** 2
    order = np.argsort(sq, kind="stable")
    p, q, r = (float(v) for v in sq[order])
    return order, p, q, r


def ellipsoid_point(p: float, q: float, r: float, phi: Any, theta: Any) -> np.ndarray:
    """Sorted-frame point with ellipsoidal angles ``phi, theta`` (module docstring)."""
    phi, theta = np.broadcast_arrays(np.asarray(phi, float), np.asarray(theta, float))
    return _ellipsoid_xyz(p, q, r, *_phi_terms(p, q, r, phi), *_theta_terms(p, q, r, theta))


def _phi_terms(p: float, q: float, r: float, phi: Any) -> tuple[Any, Any, Any]:
    """``sin phi, cos phi`` and the factor ``k3(phi)`` of ``X3``."""
    s_phi, c_phi = np.sin(phi), np.cos(phi)
    return s_phi, c_phi, np.sqrt(np.maximum((r - p) - (q - p) * s_phi**2, 0.0) / (r - p))


def _theta_terms(p: float, q: float, r: float, theta: Any) -> tuple[Any, Any, Any]:
    """``sin theta, cos theta`` and the factor ``k1(theta)`` of ``X1``."""
    s_th, c_th = np.sin(theta), np.cos(theta)
    return s_th, c_th, np.sqrt(np.maximum((q - p) + (r - q) * c_th**2, 0.0) / (r - p))


def _ellipsoid_xyz(
    p: float, q: float, r: float, s_phi: Any, c_phi: Any, k3: Any, s_th: Any, c_th: Any, k1: Any
) -> np.ndarray:
    """The sorted-frame point from the terms of ``phi`` and ``theta`` (either
    may be per-curve constants, broadcast against the other's samples)."""
    out = np.empty((*np.broadcast_shapes(np.shape(s_phi), np.shape(s_th)), 3))
    out[..., 0] = math.sqrt(p) * s_phi * k1
    out[..., 1] = math.sqrt(q) * c_phi * c_th
    out[..., 2] = math.sqrt(r) * s_th * k3
    return out


def ellipsoid_umbilics(axes: np.ndarray) -> np.ndarray:
    order, p, q, r = ellipsoid_frame(axes)
    if r == p:
        return np.empty((0, 3))
    X1 = np.sqrt(p * (q - p) / (r - p))
    X3 = np.sqrt(r * (r - q) / (r - p))
    pts = np.array([[s1 * X1, 0.0, s3 * X3] for s1 in (1, -1) for s3 in (1, -1)])
    return np.unique(_scatter(pts, order), axis=0)


def ellipsoid_lines(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """``n1`` loops ``theta = const`` (around the longest axis), ``n2`` loops
    ``phi = const`` (around the shortest axis); rotational ellipsoids give
    parallels and meridians, the sphere its parameter lines."""
    order, p, q, r = ellipsoid_frame(surface.axes)
    if r == p:
        from ...families._lines import parameter_line_batches

        d = surface.domain
        return parameter_line_batches(surface, d.lines(0, n1), d.lines(1, n2), "c1", "c2")
    # theta values spread along phi = 0 (the X2 X3 principal ellipse)
    thetas = spread(lambda s: ellipsoid_point(p, q, r, 0.0, s), -_HALF_PI, _HALF_PI, n1)
    phis = spread(lambda s: ellipsoid_point(p, q, r, s, 0.0), -_HALF_PI, _HALF_PI, n2)

    # per-curve constants: the angle, its sine and cosine and its factor (k1 or
    # k3), so that a sample costs the terms of its own angle only
    def loop_theta(par: np.ndarray, t: np.ndarray) -> np.ndarray:  # theta fixed, phi = t
        if q == r:  # oblate about X1: full meridians
            th = par[:, 0]
            X = np.stack(
                [np.sqrt(p) * np.sin(t), np.sqrt(q) * np.cos(t) * np.cos(th),
                 np.sqrt(r) * np.cos(t) * np.sin(th)], axis=-1)  # fmt: skip
        else:
            X = _ellipsoid_xyz(p, q, r, *_phi_terms(p, q, r, t), *par[:, 1:].T)
        return _scatter(X, order)

    def loop_phi(par: np.ndarray, t: np.ndarray) -> np.ndarray:  # phi fixed, theta = t
        if p == q:  # prolate about X3: full meridians
            ph = par[:, 0]
            X = np.stack(
                [np.sqrt(p) * np.cos(t) * np.sin(ph), np.sqrt(q) * np.cos(t) * np.cos(ph),
                 np.sqrt(r) * np.sin(t)], axis=-1)  # fmt: skip
        else:
            X = _ellipsoid_xyz(p, q, r, *par[:, 1:].T, *_theta_terms(p, q, r, t))
        return _scatter(X, order)

    theta_par = np.column_stack([thetas, *_theta_terms(p, q, r, thetas)])
    phi_par = np.column_stack([phis, *_phi_terms(p, q, r, phis)])
    return curve_batch(surface, "c1", loop_theta, theta_par, 0.0, _TWO_PI, True, clip=False) + (
        curve_batch(surface, "c2", loop_phi, phi_par, 0.0, _TWO_PI, True, clip=False)
    )


# -- hyperboloid of one sheet -------------------------------------------------
def _transverse(a: float, b: float) -> tuple[np.ndarray, float, float]:
    """Order so that the smaller of ``a^2, b^2`` comes first."""
    return (np.array([0, 1]) if a <= b else np.array([1, 0])), min(a, b) ** 2, max(a, b) ** 2


def one_sheet_point(s: float, big: float, c: float, t: Any, theta: Any) -> np.ndarray:
    """``(X1 = z, X2 [small axis], X3 [large axis])`` (module docstring)."""
    t, theta = np.broadcast_arrays(np.asarray(t, float), np.asarray(theta, float))
    c2 = c * c
    sh = np.sinh(t)
    return np.stack(
        [
            c * sh * np.sqrt((c2 + s + (big - s) * np.cos(theta) ** 2) / (c2 + big)),
            np.sqrt(s) * np.cos(theta) * np.cosh(t),
            np.sqrt(big) * np.sin(theta) * np.sqrt((big + c2 + (c2 + s) * sh * sh) / (big + c2)),
        ],
        axis=-1,
    )


def one_sheet_lines(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """``n1`` loops ``t = const`` (parallels when a = b), ``n2`` complete curves
    ``theta = const`` through the waist (meridians when a = b)."""
    a, b, c, h = surface.a, surface.b, surface.c, surface.height
    tr, s, big = _transverse(a, b)
    T = float(np.arcsinh(h / c))  # loops with |t| <= T lie in |z| <= h

    to_xyz = functools.partial(_scatter, order=np.array([2, tr[0], tr[1]]))

    ts = spread(
        lambda u: np.stack(
            [one_sheet_point(s, big, c, u, 0.0), one_sheet_point(s, big, c, u, _HALF_PI)]
        ),
        -T, T, n1, "ends",
    )  # fmt: skip
    thetas = spread(lambda u: one_sheet_point(s, big, c, 0.0, u), 0.0, _TWO_PI, n2, "periodic")
    # the curve theta = const leaves |z| <= h at |t| = asinh(h / (c K(theta)))
    K = np.sqrt((c * c + s + (big - s) * np.cos(thetas) ** 2) / (c * c + big))
    tmax = np.arcsinh(h / (c * K))
    return curve_batch(
        surface, "c1", lambda par, t: to_xyz(one_sheet_point(s, big, c, par[:, 0], t)),
        ts, 0.0, _TWO_PI, True, clip=False,
    ) + curve_batch(
        surface, "c2", lambda par, t: to_xyz(one_sheet_point(s, big, c, t, par[:, 0])),
        thetas, -tmax, tmax, False, clip=False,
    )  # fmt: skip


# -- hyperboloid of two sheets ------------------------------------------------
def two_sheets_point(s: float, big: float, c: float, sheet: Any, t: Any, phi: Any) -> np.ndarray:
    """``(X1 [large transverse axis], X2 [small], X3 = z)`` on sheet ``+-1``."""
    sheet, t, phi = np.broadcast_arrays(*(np.asarray(v, float) for v in (sheet, t, phi)))
    c2 = c * c
    sh = np.sinh(t)
    return np.stack(
        [
            np.sqrt(big) * sh * np.sin(phi),
            np.sqrt(s) * np.cos(phi) * np.sqrt((big - s + (c2 + big) * sh * sh) / (c2 + s)),
            sheet * c * np.cosh(t) * np.sqrt((c2 + s + (big - s) * np.cos(phi) ** 2) / (c2 + s)),
        ],
        axis=-1,
    )


def _two_sheets_order(a: float, b: float) -> tuple[np.ndarray, float, float]:
    """Index of (X1 = larger transverse axis, X2 = smaller) among (x, y)."""
    return (np.array([0, 1]) if a >= b else np.array([1, 0])), min(a, b) ** 2, max(a, b) ** 2


def two_sheets_umbilics(a: float, b: float, c: float) -> np.ndarray:
    tr, s, big = _two_sheets_order(a, b)
    c2 = c * c
    X2 = np.sqrt(s * (big - s) / (c2 + s))
    X3 = c * np.sqrt((c2 + big) / (c2 + s))
    out = []
    for s2 in (1.0, -1.0):
        for s3 in (1.0, -1.0):
            x = np.zeros(3)
            x[tr[1]] = s2 * X2
            x[2] = s3 * X3
            out.append(x)
    return np.unique(np.array(out), axis=0)


def two_sheets_lines(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """On each sheet: ``n1`` loops ``t = const > 0`` (parallels when a = b),
    ``n2`` complete curves ``phi = const`` (meridians through the vertex when a = b)."""
    a, b, c, h = surface.a, surface.b, surface.c, surface.height
    tr, s, big = _two_sheets_order(a, b)
    c2 = c * c
    rot = s == big

    to_xyz = functools.partial(_scatter, order=np.array([tr[0], tr[1], 2]))

    def meridian(sheet: Any, t: Any, phi: Any) -> np.ndarray:
        sheet, t, phi = np.broadcast_arrays(*(np.asarray(v, float) for v in (sheet, t, phi)))
        sh = np.sinh(t)
        return np.stack(
            [np.sqrt(big) * sh * np.sin(phi), np.sqrt(s) * sh * np.cos(phi),
             sheet * c * np.cosh(t)], axis=-1)  # fmt: skip

    T = float(np.arccosh(h / c))  # loops reach |z| <= h only for t <= T
    ts = spread(
        lambda u: np.stack([two_sheets_point(s, big, c, 1, u, 0.0),
                            two_sheets_point(s, big, c, 1, u, _HALF_PI)]),
        0.0, T, n1,
    )  # fmt: skip
    tref = 0.6 * T
    phis = spread(lambda u: two_sheets_point(s, big, c, 1, tref, u), 0.0, np.pi, n2)
    K = np.sqrt((c2 + s + (big - s) * np.cos(phis) ** 2) / (c2 + s))
    keep = c * K < h
    phis, K = phis[keep], K[keep]
    tmax = np.arccosh(h / (c * K))
    out = []
    for sheet in (1.0, -1.0):
        out += curve_batch(
            surface, "c1",
            lambda par, t, sh=sheet: to_xyz(two_sheets_point(s, big, c, sh, par[:, 0], t)),
            ts, 0.0, _TWO_PI, True,
        )  # fmt: skip
        f = meridian if rot else (lambda sh_, t, ph: two_sheets_point(s, big, c, sh_, t, ph))
        out += curve_batch(
            surface, "c2", lambda par, t, sh=sheet, f=f: to_xyz(f(sh, t, par[:, 0])),
            phis, -tmax, tmax, False, clip=False,
        )  # fmt: skip
    return out


# -- elliptic paraboloid --------------------------------------------------------
def paraboloid_point(P: float, Q: float, phi: Any, t: Any) -> np.ndarray:
    """``(X [smaller axis], Y, Z)`` on ``X^2/P + Y^2/Q = 2Z``, ``D = Q - P > 0``."""
    phi, t = np.broadcast_arrays(np.asarray(phi, float), np.asarray(t, float))
    D = Q - P
    sh = np.sinh(t)
    return np.stack(
        [
            np.sqrt(P * D) * np.sin(phi) * np.cosh(t),
            np.sqrt(Q * D) * np.cos(phi) * sh,
            0.5 * D * (np.sin(phi) ** 2 + sh * sh),
        ],
        axis=-1,
    )


def elliptic_paraboloid_umbilics(a: float, b: float) -> np.ndarray:
    tr, P, Q = _transverse(a, b)
    P, Q = P / 2, Q / 2
    D = Q - P
    out = []
    for sg in (1.0, -1.0) if D > 0 else (1.0,):
        x = np.zeros(3)
        x[tr[0]] = sg * np.sqrt(P * D)
        x[2] = D / 2
        out.append(x)
    return np.array(out)


def elliptic_paraboloid_lines(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """``n1`` loops ``t = const > 0`` (parallels when a = b) and ``n2`` complete
    curves ``phi = const`` (meridians when a = b)."""
    a, b, h = surface.a, surface.b, surface.height
    tr, P, Q = _transverse(a, b)
    P, Q = P / 2, Q / 2
    D = Q - P

    to_xyz = functools.partial(_scatter, order=np.array([tr[0], tr[1], 2]))

    if D == 0:  # rotational: parallels z = const and meridians
        r = np.sqrt(h)
        meridian = lambda u: np.stack([a * u, 0 * u, u * u], axis=-1)  # noqa: E731
        rs = spread(meridian, 0.0, r, n1 + 1, "ends")[1:]
        angles = np.arange(n2) / max(n2, 1) * np.pi

        def par(pr: np.ndarray, t: np.ndarray) -> np.ndarray:
            rr = pr[:, 0]
            return np.stack([a * rr * np.cos(t), b * rr * np.sin(t), rr * rr], axis=-1)

        def mer(pr: np.ndarray, t: np.ndarray) -> np.ndarray:
            u = pr[:, 0]
            return np.stack([a * t * np.cos(u), b * t * np.sin(u), t * t], axis=-1)

        return curve_batch(surface, "c1", par, rs, 0.0, _TWO_PI, True, clip=False) + curve_batch(
            surface, "c2", mer, angles, -r, r, False, clip=False
        )
    T = float(np.arcsinh(np.sqrt(2 * h / D)))  # loops reach z <= h only for t <= T
    ts = spread(
        lambda u: np.stack([paraboloid_point(P, Q, 0.0, u), paraboloid_point(P, Q, _HALF_PI, u)]),
        0.0, T, n1,
    )  # fmt: skip
    # the last loop touches the rim; keep the spread but move it inside
    phis = spread(lambda u: paraboloid_point(P, Q, u, 0.7 * T), -_HALF_PI, _HALF_PI, n2)
    # phi = const leaves z <= h where sinh^2 t = 2h/D - sin^2 phi
    tmax = np.arcsinh(np.sqrt(np.maximum(2 * h / D - np.sin(phis) ** 2, 0.0)))
    keep = tmax > 0
    return curve_batch(
        surface, "c1", lambda pr, t: to_xyz(paraboloid_point(P, Q, t, pr[:, 0])),
        ts, 0.0, _TWO_PI, True,
    ) + curve_batch(
        surface, "c2", lambda pr, t: to_xyz(paraboloid_point(P, Q, pr[:, 0], t)),
        phis[keep], -tmax[keep], tmax[keep], False, clip=False,
    )  # fmt: skip


# -- hyperbolic paraboloid ------------------------------------------------------
def hyperbolic_paraboloid_point(a: float, b: float, s: Any, t: Any) -> np.ndarray:
    s, t = np.broadcast_arrays(np.asarray(s, float), np.asarray(t, float))
    al, be = a * a / 2, b * b / 2
    E = al + be
    return np.stack(
        [
            np.sqrt(al * E) * np.cosh(s) * np.sinh(t),
            np.sqrt(be * E) * np.sinh(s) * np.cosh(t),
            0.5 * E * (np.sinh(t) ** 2 - np.sinh(s) ** 2),
        ],
        axis=-1,
    )


def hyperbolic_paraboloid_lines(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """``n1`` lines ``s = const`` and ``n2`` lines ``t = const`` (module docstring),
    each cut exactly to the patch ``|x| <= a r, |y| <= b r``."""
    a, b, r = surface.a, surface.b, surface.extent
    al, be = a * a / 2, b * b / 2
    E = al + be
    S = float(np.arcsinh(2 * r / np.sqrt(a * a + b * b)))  # s = 0 line: |x| <= a r
    ss = spread(lambda u: hyperbolic_paraboloid_point(a, b, u, 0.0), -S, S, n1, "ends")
    ts = spread(lambda u: hyperbolic_paraboloid_point(a, b, 0.0, u), -S, S, n2, "ends")

    # on s = c the x-bound uses alpha and a, the y-bound beta and b
    tm_s = _hp_limit(a, b, al, be, E, r, ss)
    tm_t = _hp_limit(b, a, be, al, E, r, ts)
    ks, kt = tm_s > 0, tm_t > 0
    return curve_batch(
        surface, "c1", lambda pr, t: hyperbolic_paraboloid_point(a, b, pr[:, 0], t),
        ss[ks], -tm_s[ks], tm_s[ks], False, clip=False,
    ) + curve_batch(
        surface, "c2", lambda pr, t: hyperbolic_paraboloid_point(a, b, t, pr[:, 0]),
        ts[kt], -tm_t[kt], tm_t[kt], False, clip=False,
    )  # fmt: skip


def _hp_limit(
    a: float, b: float, al: float, be: float, E: float, r: float, c: np.ndarray
) -> np.ndarray:
    """Largest ``|t|`` on the line ``s = c`` inside ``|x| <= a r, |y| <= b r``
    (roles of the axes swapped for the other family)."""
    t1 = np.arcsinh(r * a / (np.sqrt(al * E) * np.cosh(c)))
    sc = np.sinh(np.abs(c))
    with np.errstate(divide="ignore"):
        ch = np.where(sc > 0, r * b / (np.sqrt(be * E) * np.where(sc > 0, sc, 1.0)), np.inf)
    return np.where(ch >= 1.0, np.minimum(t1, np.arccosh(np.maximum(ch, 1.0))), 0.0)


# -- elliptic cone ----------------------------------------------------------------
def cone_lines(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """``n1`` sections by spheres about the vertex (on both nappes) and ``n2``
    rulings on each nappe (half-lines from the vertex at evenly spread angles,
    so both nappes are covered all round)."""
    a, b, h = surface.a, surface.b, surface.height
    rho_max = h * np.sqrt(1 + max(a, b) ** 2)
    rhos = rho_max * np.arange(1, n1 + 1) / max(n1, 1)

    def section(pr: np.ndarray, t: np.ndarray) -> np.ndarray:
        rho, sg = pr[:, 0], pr[:, 1]
        w = sg * rho / np.sqrt(1 + (a * np.cos(t)) ** 2 + (b * np.sin(t)) ** 2)
        return np.stack([a * w * np.cos(t), b * w * np.sin(t), w], axis=-1)

    us = spread(
        lambda u: np.stack([a * np.cos(u), b * np.sin(u), np.ones_like(u)], axis=-1),
        0.0, _TWO_PI, n2, "periodic",
    )  # fmt: skip

    def ruling(pr: np.ndarray, t: np.ndarray) -> np.ndarray:
        u = pr[:, 0]
        return np.stack([a * t * np.cos(u), b * t * np.sin(u), t], axis=-1)

    pars = np.array([[r_, sg] for sg in (1.0, -1.0) for r_ in rhos]).reshape(-1, 2)
    return (
        curve_batch(surface, "c1", section, pars, 0.0, _TWO_PI, True)
        + curve_batch(surface, "c2", ruling, us, 0.0, h, False, clip=False)
        + curve_batch(surface, "c2", ruling, us, -h, 0.0, False, clip=False)
    )
