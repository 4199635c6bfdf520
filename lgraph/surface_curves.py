"""More curves on surfaces and small scene objects for figures.

* :class:`AsymptoticLines` (family ``"asymptotic"``, where ``K < 0``),
  :class:`Geodesic` (a family: one geodesic from a point and a direction) and
  :class:`IntersectionCurve` (the curve where the node's surface meets
  another), all computed numerically for any surface;
* :class:`Arrow` (a thin 3-D arrow: cylinder shaft and cone head, with exact
  contour and hits) and :class:`Parallelogram` (a planar patch whose contour
  is its boundary): real scene objects that hide and are hidden.

>>> import numpy as np
>>> import lgraph as lg
>>> g = geodesic(lg.Torus(3, 1), (0.0, 0.0), (1.0, 0.0), 2.0)
>>> bool(np.allclose(g(np.array([2.0]))[0, 2], 0.0, atol=1e-9))  # the outer equator
True
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from ._budget import check_geodesic, check_intersection
from ._own import CONTOUR, OFF
from ._validate import as_number, count, finite_positive, one_of, vector3
from .curvature import asymptotic_field
from .curves import CurveBatch, CurveOnSurface
from .families import SPACINGS, Family, register_family
from .surfaces._base import Domain, Surface

if TYPE_CHECKING:
    from .projectors import Projector

__all__ = [
    "AsymptoticLines",
    "Geodesic",
    "geodesic",
    "IntersectionCurve",
    "intersection_curves",
    "Arrow",
    "Parallelogram",
]


# ---------------------------------------------------------------------------
# asymptotic lines
# ---------------------------------------------------------------------------
@attrs.frozen
class AsymptoticLines(Family):
    """``n1`` and ``n2`` asymptotic lines (``II(du) = 0``) of the two families,
    on the part of the surface where the Gauss curvature is negative.

    Surfaces with closed forms supply ``asymptotic_lines(n1, n2)`` (the rulings
    of the hyperboloid of one sheet and the hyperbolic paraboloid); others are
    integrated numerically (:mod:`!lgraph.fieldlines`): complete lines by
    default, or trimmed to even spacing with ``spacing="even"``.

    >>> AsymptoticLines(-1, 3)
    Traceback (most recent call last):
    ...
    ValueError: AsymptoticLines: n1 must be an integer from 0 to 100000, got -1
    """

    view_dependent: ClassVar[bool] = False

    n1: int = attrs.field(default=8, validator=count("AsymptoticLines"))
    n2: int = attrs.field(default=8, validator=count("AsymptoticLines"))
    spacing: str = attrs.field(
        default="complete", kw_only=True, validator=one_of("AsymptoticLines", SPACINGS)
    )

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        closed_form = getattr(surface, "asymptotic_lines", None)
        if closed_form is not None:  # e.g. the rulings of doubly ruled quadrics
            return [
                attrs.evolve(b, family="asymptotic", curve_family=None)
                for b in closed_form(self.n1, self.n2)
            ]
        from .field_families import field_line_batches

        return field_line_batches(
            surface, asymptotic_field, self.n1, self.n2, family="asymptotic", spacing=self.spacing
        )


register_family("asymptotic_lines", AsymptoticLines)


# ---------------------------------------------------------------------------
# geodesics
# ---------------------------------------------------------------------------
def _geodesic_rhs(surface: Any) -> Any:
    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        u1, u2, a, b = y
        u1a, u2a = np.array([u1]), np.array([u2])
        x1, x2 = surface.derivatives(u1a, u2a)
        x11, x12, x22 = surface.second_derivatives(u1a, u2a)
        acc = (x11 * a * a + 2 * x12 * a * b + x22 * b * b)[0]
        x1, x2 = x1[0], x2[0]
        g11, g12, g22 = x1 @ x1, x1 @ x2, x2 @ x2
        r1, r2 = -(x1 @ acc), -(x2 @ acc)
        det = g11 * g22 - g12 * g12
        return np.array([a, b, (g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det])

    return rhs


def _geodesic_solution(surface: Any, uv0: Any, direction: Any, length: float) -> Any:
    from scipy.integrate import solve_ivp

    uv0 = np.asarray(uv0, float)
    du = np.asarray(direction, float)
    x1, x2 = surface.derivatives(uv0[0], uv0[1])
    speed = np.linalg.norm(du[0] * x1 + du[1] * x2)
    if not speed > 0:
        raise ValueError("Geodesic: direction must be a non-zero tangent direction (du1, du2)")
    du = du / speed
    d = surface.domain

    def leave(_t: float, y: np.ndarray) -> float:
        out = 1.0
        for i in (0, 1):
            if not d.periodic[i]:
                lo, hi = d.range(i)
                out = min(out, (y[i] - lo) / d.span(i), (hi - y[i]) / d.span(i))
        return out

    leave.terminal = True  # type: ignore[attr-defined]
    sol = solve_ivp(
        _geodesic_rhs(surface),
        (0.0, length),
        np.concatenate([uv0, du]),
        method="DOP853",
        dense_output=True,
        rtol=1e-10,
        atol=1e-12 * max(d.span(0), d.span(1)),
        events=leave,
    )
    return sol.sol, float(sol.t[-1])


def geodesic(surface: Any, uv0: Any, direction: Any, length: float) -> CurveOnSurface:
    """The geodesic from parameters ``uv0`` in the parameter direction
    ``direction = (du1, du2)``, ``length`` long in 3-D arc length (shorter if
    it leaves the domain), as a :class:`CurveOnSurface` with ``t`` = arc length.

    Integrates ``G u'' = -J^T (x11 u1'^2 + 2 x12 u1' u2' + x22 u2'^2)``: the
    acceleration of a geodesic is normal to the surface.
    """
    length = check_geodesic("geodesic", surface, uv0, direction, length)
    sol, t1 = _geodesic_solution(surface, uv0, direction, length)
    return CurveOnSurface(
        surface, lambda t: surface.domain.wrap(np.asarray(sol(t))[:2].T), 0.0, max(t1, 1e-12)
    )


def _pair(owner: str, name: str, value: Any) -> tuple[float, float]:
    """Converter: a pair of finite numbers (ValueError naming ``name`` otherwise)."""
    try:
        a, b = (float(as_number(x)) for x in value)
    except (TypeError, ValueError):
        raise ValueError(
            f"{owner}: {name} must be a pair of finite numbers, got {value!r}"
        ) from None
    if not (np.isfinite(a) and np.isfinite(b)):
        raise ValueError(f"{owner}: {name} must be a pair of finite numbers, got {value!r}")
    return a, b


@attrs.frozen(eq=False)
class Geodesic(Family):
    """One geodesic of the node's surface (family ``"geodesic"``): from the
    parameters ``uv0`` in the parameter direction ``direction = (du1, du2)``,
    ``length`` long (3-D arc length); ``both_ways`` also runs it backward.

    >>> Geodesic((0, 0), (1, 0), length=0)
    Traceback (most recent call last):
    ...
    ValueError: Geodesic: length must be a positive finite number, got 0
    """

    view_dependent: ClassVar[bool] = False

    uv0: tuple[float, float] = attrs.field(converter=lambda v: _pair("Geodesic", "uv0", v))
    direction: tuple[float, float] = attrs.field(
        converter=lambda v: _pair("Geodesic", "direction", v)
    )
    length: float = attrs.field(
        default=10.0, converter=as_number, validator=finite_positive("Geodesic")
    )
    both_ways: bool = attrs.field(default=False, kw_only=True)

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        check_geodesic("Geodesic", surface, self.uv0, self.direction, self.length)
        fwd, t1 = _geodesic_solution(surface, self.uv0, self.direction, self.length)
        t0 = 0.0
        bwd = None
        if self.both_ways:
            bwd, tb = _geodesic_solution(
                surface, self.uv0, tuple(-x for x in self.direction), self.length
            )
            t0 = -tb

        def uv(_idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            out = np.empty((len(t), 2))
            pos = t >= 0
            if pos.any():
                out[pos] = np.asarray(fwd(t[pos]))[:2].T
            if (~pos).any() and bwd is not None:
                out[~pos] = np.asarray(bwd(-t[~pos]))[:2].T
            return surface.domain.wrap(out)

        return [CurveBatch.from_uv(surface, "geodesic", [t0], [t1], uv)]


# ---------------------------------------------------------------------------
# intersection curves
# ---------------------------------------------------------------------------
def _jac(surface: Any, uv: np.ndarray) -> np.ndarray:
    x1, x2 = surface.derivatives(uv[..., 0], uv[..., 1])
    return np.stack([x1, x2], axis=-1)  # (..., 3, 2)


def _correct(a: Any, b: Any, z: np.ndarray, steps: int = 8, tol: float = 1e-13) -> Any:
    """Gauss-Newton (minimal-norm steps) onto ``xa(z[:2]) = xb(z[2:])``; z (n, 4)."""
    z = np.array(z, float, copy=True)
    res = np.full(len(z), np.inf)
    for _ in range(steps):
        F = a.point(z[:, 0], z[:, 1]) - b.point(z[:, 2], z[:, 3])
        res = np.linalg.norm(F, axis=1)
        act = res > tol
        if not act.any():
            break
        J = np.concatenate([_jac(a, z[:, :2]), -_jac(b, z[:, 2:])], axis=2)  # (n, 3, 4)
        JJt = J @ J.transpose(0, 2, 1)
        with np.errstate(all="ignore"):
            y = np.linalg.solve(JJt + 1e-300 * np.eye(3), F[..., None])
        dz = (J.transpose(0, 2, 1) @ y)[..., 0]
        ok = act & np.isfinite(dz).all(axis=1)
        z[ok] -= dz[ok]
    return z, res


def _tangent4(a: Any, b: Any, z: np.ndarray) -> np.ndarray:
    """Unit-speed (in space) tangent of the intersection curve in (ua, ub)."""
    J = np.concatenate([_jac(a, z[None, :2]), -_jac(b, z[None, 2:])], axis=2)[0]
    t = np.array([(-1) ** k * np.linalg.det(np.delete(J, k, axis=1)) for k in range(4)])
    speed = np.linalg.norm(J[:, :2] @ t[:2])
    with np.errstate(divide="ignore", invalid="ignore"):
        return t / speed  # NaN where the surfaces' tangent planes degenerate (a pole)


def _inside(surface: Any, uv: np.ndarray) -> bool:
    d = surface.domain
    for i in (0, 1):
        if not d.periodic[i]:
            lo, hi = d.range(i)
            if not lo <= uv[i] <= hi:
                return False
    return True


def _march(a: Any, b: Any, z0: np.ndarray, h: float, nmax: int) -> tuple[np.ndarray, bool]:
    """Trace the intersection from ``z0`` both ways; returns (points (m, 4), closed)."""
    start_x = a.point(z0[0], z0[1])
    halves = []
    for sign in (1.0, -1.0):
        z = z0.copy()
        tprev = sign * _tangent4(a, b, z)
        pts = []
        closed = False
        for k in range(nmax):
            t = _tangent4(a, b, z)
            if not np.isfinite(t).all():
                break  # a degenerate point (a pole of a parametrization): stop here
            if t @ tprev < 0:
                t = -t
            zn, res = _correct(a, b, (z + h * t)[None])
            zn = zn[0]
            if not (res[0] < 1e-8 * (1 + h) and np.isfinite(zn).all()):
                break
            if not (_inside(a, zn[:2]) and _inside(b, zn[2:])):
                break
            pts.append(zn)
            tprev, z = t, zn
            if k > 3 and np.linalg.norm(a.point(zn[0], zn[1]) - start_x) < 0.6 * h:
                closed = True
                break
        halves.append((np.array(pts).reshape(-1, 4), closed))
        if closed:
            return np.vstack([z0[None], halves[0][0][:-1]]), True
    back = halves[1][0][::-1]
    return np.vstack([back, z0[None], halves[0][0]]), False


def _unwrap4(a: Any, b: Any, z: np.ndarray) -> np.ndarray:
    z = z.copy()
    for k, (s, i) in enumerate(((a, 0), (a, 1), (b, 0), (b, 1))):
        d = s.domain
        if d.periodic[i]:
            span = d.span(i)
            dz = np.diff(z[:, k])
            z[1:, k] += np.cumsum(-span * np.round(dz / span))
    return z


def intersection_curves(a: Any, b: Any, grid: int = 80, step: float | None = None) -> list[Any]:
    """Curves where surfaces ``a`` and ``b`` (same frame) meet, as a list of
    ``(z(t) callable -> (n, 4) = (ua1, ua2, ub1, ub2), t1, closed)``.

    Seeds come from close pairs of grid points, corrected by Gauss-Newton;
    each curve is marched with predictor steps along the tangent (null vector
    of ``[J_a, -J_b]``) and Newton corrections.
    """
    check_intersection("intersection_curves", a, b, grid, step)
    from scipy.interpolate import make_interp_spline  # imported when first needed
    from scipy.spatial import cKDTree

    size = min(a.size, b.size)
    h = step if step is not None else size / 150
    da, db = a.domain, b.domain

    def grid_uv(d: Domain) -> np.ndarray:
        g = [np.linspace(*d.range(i), grid) for i in (0, 1)]
        return np.stack(np.meshgrid(*g, indexing="ij"), -1).reshape(-1, 2)

    ua, ub = grid_uv(da), grid_uv(db)
    pa, pb = a.points(ua), b.points(ub)
    spacing = max(
        np.median(np.linalg.norm(np.diff(pa.reshape(grid, grid, 3), axis=0), axis=-1)),
        np.median(np.linalg.norm(np.diff(pb.reshape(grid, grid, 3), axis=0), axis=-1)),
    )
    tree = cKDTree(pb)
    dist, j = tree.query(pa, distance_upper_bound=2 * spacing)
    cand = np.nonzero(np.isfinite(dist))[0]
    if not len(cand):
        return []
    z0 = np.concatenate([ua[cand], ub[j[cand]]], axis=1)
    z, res = _correct(a, b, z0, steps=20)
    good = (res < 1e-10 * size) & np.isfinite(z).all(axis=1)
    z = z[good]
    z = z[[_inside(a, q[:2]) and _inside(b, q[2:]) for q in z]]
    curves = []
    used = np.zeros(len(z), bool)
    seeds_x = a.points(z[:, :2]) if len(z) else np.empty((0, 3))
    nmax = int(20 * max(a.size, b.size) / h)
    for k in range(len(z)):  # loop over curves: each seed either starts one or is consumed
        if used[k]:
            continue
        pts, closed = _march(a, b, z[k], h, nmax)
        if len(pts) < 3:
            used[k] = True
            continue
        xs = a.points(pts[:, :2])
        near = cKDTree(xs).query(seeds_x, distance_upper_bound=1.5 * h)[0]
        used |= np.isfinite(near)
        used[k] = True
        zz = _unwrap4(a, b, pts)
        if closed:
            zz = np.vstack([zz, zz[:1]])
            zz[-1] = _unwrap4(a, b, zz[-2:])[-1]
        t = np.concatenate(
            [[0.0], np.cumsum(np.linalg.norm(np.diff(a.points(zz[:, :2]), axis=0), axis=1))]
        )
        keep = np.concatenate([[True], np.diff(t) > 1e-9 * h])
        zz, t = zz[keep], t[keep]
        if closed:
            drift = zz[-1] - zz[0]
            from scipy.interpolate import CubicSpline

            sp = CubicSpline(t, zz - np.outer(t / t[-1], drift), bc_type="periodic")
            T = t[-1]

            def zf(tt: np.ndarray, sp: Any = sp, drift: np.ndarray = drift, T: float = T) -> Any:
                return sp(tt) + np.outer(tt / T, drift)
        else:
            zf = make_interp_spline(t, zz, k=min(3, len(t) - 1))
        curves.append((zf, float(t[-1]), closed))
    return curves


@attrs.frozen(eq=False)
class IntersectionCurve(Family):
    """The curves where the node's surface meets ``other`` (family
    ``"intersection"``).  ``other`` is given in the node's local frame (apply
    the same transform to both nodes).  Points are corrected onto both
    surfaces by Newton's method at every evaluation.

    >>> IntersectionCurve("sphere")
    Traceback (most recent call last):
    ...
    TypeError: IntersectionCurve: other must be a Surface, got str
    """

    view_dependent: ClassVar[bool] = False

    other: Any = attrs.field()
    family: str = attrs.field(default="intersection", kw_only=True)

    @other.validator
    def _check(self, _a: Any, v: Any) -> None:
        if not isinstance(v, Surface):
            raise TypeError(f"IntersectionCurve: other must be a Surface, got {type(v).__name__}")

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        check_intersection("IntersectionCurve", surface, self.other, 80, None)
        curves = intersection_curves(surface, self.other)
        if not curves:
            return []
        other = self.other

        def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            z = np.empty((len(t), 4))
            for c in np.unique(idx):
                sel = idx == c
                z[sel] = curves[c][0](t[sel])
            z, _ = _correct(surface, other, z, steps=4)
            uv = surface.domain.wrap(z[:, :2])
            return surface.point(uv[:, 0], uv[:, 1]), uv

        return [
            CurveBatch(
                self.family,
                np.zeros(len(curves)),
                np.array([c[1] for c in curves]),
                evaluate,
                closed=np.array([c[2] for c in curves]),
                surface=surface,
            )
        ]


# ---------------------------------------------------------------------------
# planar patches
# ---------------------------------------------------------------------------
def _vec(owner: str, name: str) -> Any:
    return attrs.field(
        converter=lambda v: vector3(owner, name, v), eq=attrs.cmp_using(np.array_equal)
    )


@attrs.frozen
class Parallelogram(Surface):
    """Planar patch ``origin + u1 e1 + u2 e2``, ``0 <= u1, u2 <= 1``.

    Its contour is its boundary; hits are exact.  :meth:`!centered` builds one
    around a point (e.g. a tangent plane).

    >>> p = Parallelogram((0, 0, 0), (1, 0, 0), (2, 0, 0))
    Traceback (most recent call last):
    ...
    ValueError: Parallelogram: e1 and e2 must be linearly independent
    """

    origin: np.ndarray = _vec("Parallelogram", "origin")
    e1: np.ndarray = _vec("Parallelogram", "e1")
    e2: np.ndarray = _vec("Parallelogram", "e2")

    def __attrs_post_init__(self) -> None:
        n = np.cross(self.e1, self.e2)
        if not np.linalg.norm(n) > 1e-12 * np.linalg.norm(self.e1) * np.linalg.norm(self.e2):
            raise ValueError("Parallelogram: e1 and e2 must be linearly independent")

    @classmethod
    def centered(cls, center: Any, e1: Any, e2: Any) -> Parallelogram:
        """The parallelogram ``center + a e1 + b e2`` with ``|a|, |b| <= 1``."""
        c = np.asarray(center, float)
        e1, e2 = np.asarray(e1, float), np.asarray(e2, float)
        return cls(c - e1 - e2, 2 * e1, 2 * e2)

    @property
    def domain(self) -> Domain:
        return Domain((0.0, 1.0), (0.0, 1.0))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return self.origin + u1[..., None] * self.e1 + u2[..., None] * self.e2

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, _ = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return (
            np.broadcast_to(self.e1, u1.shape + (3,)).copy(),
            np.broadcast_to(self.e2, u1.shape + (3,)).copy(),
        )

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u1, _ = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        z = np.zeros(u1.shape + (3,))
        return z, z.copy(), z.copy()

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        c = self.point(np.array([0, 1, 0, 1.0]), np.array([0, 0, 1, 1.0]))
        pad = 1e-9 * (np.linalg.norm(self.e1) + np.linalg.norm(self.e2))
        return c.min(axis=0) - pad, c.max(axis=0) + pad

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        """A plane is all umbilics: no lines of curvature."""
        return []

    def contour(self, projector: Projector) -> list[CurveBatch]:
        """The boundary (one closed curve, ``t`` in ``[0, 4]``)."""

        def uv(_idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            k = np.clip(np.floor(t), 0, 3)
            f = t - k
            u1 = np.select([k == 0, k == 1, k == 2], [f, 1.0, 1.0 - f], 0.0)
            u2 = np.select([k == 0, k == 1, k == 2], [0.0, f, 1.0], 1.0 - f)
            return np.stack([u1, u2], axis=-1)

        return [CurveBatch.from_uv(self, "contour", [0.0], [4.0], uv, closed=True, own=CONTOUR)]

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        o = np.asarray(origins, float).reshape(-1, 3)
        v = np.asarray(directions, float).reshape(-1, 3)
        smax = np.broadcast_to(np.asarray(smax, float), (len(o),))
        own = np.zeros(len(o), np.int8) if own is None else np.asarray(own).reshape(-1)
        n = np.cross(self.e1, self.e2)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = ((self.origin - o) @ n) / (v @ n)
        p = o + s[:, None] * v - self.origin
        # coordinates in the (e1, e2) basis
        g11, g12, g22 = self.e1 @ self.e1, self.e1 @ self.e2, self.e2 @ self.e2
        b1, b2 = p @ self.e1, p @ self.e2
        det = g11 * g22 - g12 * g12
        a1 = (g22 * b1 - g12 * b2) / det
        a2 = (g11 * b2 - g12 * b1) / det
        vn = np.linalg.norm(v, axis=1)
        eps = 1e-9 * self.size / np.where(vn > 0, vn, 1.0)
        inside = (a1 >= 0) & (a1 <= 1) & (a2 >= 0) & (a2 <= 1)
        # a ray from a point of the plane meets it only there
        return (own == OFF) & np.isfinite(s) & (s > eps) & (s < smax) & inside


# ---------------------------------------------------------------------------
# arrows
# ---------------------------------------------------------------------------
def _pos(owner: str, default: float | None = None) -> Any:
    return attrs.field(
        default=default,
        converter=lambda v: v if v is None else as_number(v),
        validator=attrs.validators.optional(finite_positive(owner)),
        kw_only=True,
    )


@attrs.frozen
class Arrow(Surface):
    """A thin 3-D arrow from ``tail`` to ``tip``: a cylinder shaft and a cone head.

    Drawn by its outline only (shaft and head silhouettes and the rim of the
    head: its :meth:`!contour`); add it with ``scene.add(arrow, lg.Contour(),
    contour=False)`` so that no parameter lines are drawn.  It hides what is
    behind it and is hidden like any surface.

    ``label`` (optional) is text put just beyond the tip, on the side the
    arrow points to in the picture (``"$N$"``), or a :class:`~lgraph.Label`
    placed as given; it is added to the scene with the arrow.

    >>> a = Arrow((0, 0, 0), (0, 0, 2))
    >>> round(a.head_length, 3), round(a.head_radius, 3)
    (0.4, 0.12)
    >>> Arrow((1, 1, 1), (1, 1, 1))
    Traceback (most recent call last):
    ...
    ValueError: Arrow: tail and tip must differ
    """

    tail: np.ndarray = _vec("Arrow", "tail")
    tip: np.ndarray = _vec("Arrow", "tip")
    head_length: float = _pos("Arrow")
    head_radius: float = _pos("Arrow")
    shaft_radius: float = _pos("Arrow")
    label: Any = attrs.field(default=None, kw_only=True)
    default_families = ()

    def __attrs_post_init__(self) -> None:
        L = float(np.linalg.norm(self.tip - self.tail))
        if not L > 0:
            raise ValueError("Arrow: tail and tip must differ")
        hl = self.head_length if self.head_length is not None else min(0.2 * L, 0.6)
        if hl >= L:
            raise ValueError(f"Arrow: head_length must be shorter than the arrow ({L}), got {hl}")
        hr = self.head_radius if self.head_radius is not None else 0.3 * hl
        sr = self.shaft_radius if self.shaft_radius is not None else 0.25 * hr
        if sr >= hr:
            raise ValueError("Arrow: shaft_radius must be smaller than head_radius")
        object.__setattr__(self, "head_length", hl)
        object.__setattr__(self, "head_radius", hr)
        object.__setattr__(self, "shaft_radius", sr)
        if self.label is not None:
            from .objects import Label

            if isinstance(self.label, str):
                d = self.tip - self.tail
                lab = Label(self.label, at=self.tip, anchor="auto", direction=d)
                object.__setattr__(self, "label", lab)
            elif not isinstance(self.label, Label):
                raise TypeError(
                    f"Arrow: label must be text or an lg.Label, got {type(self.label).__name__}"
                )

    # local frame: axis a, with e1, e2 orthonormal
    @property
    def _frame(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        d = self.tip - self.tail
        L = float(np.linalg.norm(d))
        a = d / L
        helper = np.eye(3)[int(np.argmin(np.abs(a)))]
        e1 = np.cross(a, helper)
        e1 /= np.linalg.norm(e1)
        return e1, np.cross(a, e1), a, L

    @property
    def domain(self) -> Domain:
        return Domain((0.0, 1.0), (0.0, 2 * np.pi), periodic=(False, True))

    def _radius(self, z: np.ndarray) -> np.ndarray:
        L = self._frame[3]
        zb = L - self.head_length
        return np.where(z < zb, self.shaft_radius, self.head_radius * (L - z) / self.head_length)

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        """``u1`` in [0, 1] along the axis, ``u2`` the angle around it."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        e1, e2, a, L = self._frame
        z = u1 * L
        r = self._radius(z)
        return (
            self.tail
            + z[..., None] * a
            + (r * np.cos(u2))[..., None] * e1
            + (r * np.sin(u2))[..., None] * e2
        )

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo = np.minimum(self.tail, self.tip) - self.head_radius
        hi = np.maximum(self.tail, self.tip) + self.head_radius
        return lo, hi

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return []

    def _local(self, x: np.ndarray, vector: bool = False) -> np.ndarray:
        e1, e2, a, _ = self._frame
        y = x if vector else x - self.tail
        return np.stack([y @ e1, y @ e2, y @ a], axis=-1)

    def contour(self, projector: Projector) -> list[CurveBatch]:
        """Shaft silhouette lines, head silhouette generators and the head's rim."""
        from .projectors import CentralProjector

        e1, e2, a, L = self._frame
        zb = L - self.head_length
        sr, hr, hl = self.shaft_radius, self.head_radius, self.head_length
        central = isinstance(projector, CentralProjector)
        segs = []  # (start, end) pairs in world coordinates
        if central:
            w_sh = self._local(projector.eye)  # cylinder: r(phi) . (eye - x) = 0
            w_hd = self._local(projector.eye) - np.array([0, 0, L])
        else:
            w_sh = w_hd = self._local(projector.frame[2], vector=True)

        def angles(A: float, B: float, C: float) -> list[float]:
            # A cos phi + B sin phi = C
            R = np.hypot(A, B)
            if R <= abs(C) or R == 0:
                return []
            base = np.arctan2(B, A)
            dphi = np.arccos(np.clip(C / R, -1, 1))
            return [base + dphi, base - dphi]

        def at(z: float, r: float, phi: float) -> np.ndarray:
            return self.tail + z * a + r * (np.cos(phi) * e1 + np.sin(phi) * e2)

        for phi in angles(w_sh[0], w_sh[1], sr if central else 0.0):
            segs.append((at(0.0, sr, phi), at(zb, sr, phi)))
        for phi in angles(w_hd[0], w_hd[1], -(hr / hl) * w_hd[2]):
            segs.append((at(zb, hr, phi), at(L, 0.0, phi)))
        batches = []
        if segs:
            S = np.array(segs)

            def ev(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, None]:
                p0, p1 = S[idx, 0], S[idx, 1]
                return p0 + t[:, None] * (p1 - p0), None

            batches.append(
                CurveBatch(
                    "contour", np.zeros(len(S)), np.ones(len(S)), ev, surface=self, own=CONTOUR
                )
            )

        def rim(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, None]:
            return self.tail + zb * a + hr * (
                np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2
            ), None

        batches.append(
            CurveBatch("contour", [0.0], [2 * np.pi], rim, closed=True, surface=self, own=CONTOUR)
        )
        return batches

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        o = self._local(np.asarray(origins, float).reshape(-1, 3))
        v = self._local(np.asarray(directions, float).reshape(-1, 3), vector=True)
        smax = np.broadcast_to(np.asarray(smax, float), (len(o),))
        own = np.zeros(len(o), np.int8) if own is None else np.asarray(own).reshape(-1)
        L = self._frame[3]
        zb = L - self.head_length
        sr, hr, hl = self.shaft_radius, self.head_radius, self.head_length
        vn = np.linalg.norm(v, axis=1)
        vn = np.where(vn > 0, vn, 1.0)
        rel = np.where(own == OFF, 1e-9, 1e-6)
        eps = rel * L / vn
        hit = np.zeros(len(o), bool)

        def accept(s: np.ndarray, zlo: float, zhi: float) -> np.ndarray:
            z = o[:, 2] + s * v[:, 2]
            return np.isfinite(s) & (s > eps) & (s < smax) & (z >= zlo) & (z <= zhi)

        def quadratic(
            qa: np.ndarray, qb: np.ndarray, qc: np.ndarray, zlo: float, zhi: float
        ) -> Any:
            disc = qb * qb - 4 * qa * qc
            sq = np.sqrt(np.maximum(disc, 0.0))
            q = -0.5 * (qb + np.copysign(sq, qb))
            with np.errstate(divide="ignore", invalid="ignore"):
                r1, r2 = q / qa, qc / q
            ok = disc >= 0
            return ok & (accept(r1, zlo, zhi) | accept(r2, zlo, zhi))

        with np.errstate(divide="ignore", invalid="ignore"):
            # shaft: x^2 + y^2 = sr^2
            qa = v[:, 0] ** 2 + v[:, 1] ** 2
            qb = 2 * (o[:, 0] * v[:, 0] + o[:, 1] * v[:, 1])
            qc = o[:, 0] ** 2 + o[:, 1] ** 2 - sr * sr
            hit |= quadratic(qa, qb, qc, 0.0, zb)
            # head: x^2 + y^2 = k^2 (L - z)^2
            k2 = (hr / hl) ** 2
            dz = L - o[:, 2]
            qa = v[:, 0] ** 2 + v[:, 1] ** 2 - k2 * v[:, 2] ** 2
            qb = 2 * (o[:, 0] * v[:, 0] + o[:, 1] * v[:, 1] + k2 * dz * v[:, 2])
            qc = o[:, 0] ** 2 + o[:, 1] ** 2 - k2 * dz * dz
            hit |= quadratic(qa, qb, qc, zb, L)
            # discs: head base (radius hr) at zb, tail end (radius sr) at 0
            for zd, rd in ((zb, hr), (0.0, sr)):
                s = (zd - o[:, 2]) / v[:, 2]
                p = o[:, :2] + s[:, None] * v[:, :2]
                hit |= (
                    np.isfinite(s)
                    & (s > eps)
                    & (s < smax)
                    & (np.einsum("ij,ij->i", p, p) <= rd * rd)
                )
        return hit
