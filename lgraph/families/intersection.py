"""Intersection curves: where a node's surface meets another, by marching on
the pair of parameter planes from seeds found on a grid."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from .._budget import check_intersection
from ..curves import CurveBatch
from ..surfaces._base import Domain, Surface
from . import Family

if TYPE_CHECKING:
    from ..scene.projectors import Projector

__all__ = ["IntersectionCurve", "intersection_curves"]


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
        # regularized relative to the scale of J (a cone's apex makes J J^T singular)
        reg = 1e-14 * np.trace(JJt, axis1=1, axis2=2)[:, None, None] + 1e-300
        with np.errstate(all="ignore"):
            y = np.linalg.solve(JJt + reg * np.eye(3), F[..., None])
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
    for j, s in enumerate((a, b)):  # across a twisted seam: the cover's deck maps
        if any(s.domain.twisted):
            z[:, 2 * j : 2 * j + 2] = s.domain.continuous(z[:, 2 * j : 2 * j + 2])
    for k, (s, i) in enumerate(((a, 0), (a, 1), (b, 0), (b, 1))):
        d = s.domain
        if d.periodic[i] is True and not any(d.twisted):
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
        if closed and len(t) < 4:  # a loop of a few steps: a point contact (at a pole)
            continue
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
        implicit = [not getattr(s, "parametric", True) for s in (surface, self.other)]
        if any(implicit):  # an implicit surface: traced in space on it
            from ..geometry.transforms import IDENTITY

            a, b = (surface, self.other) if implicit[0] else (self.other, surface)
            return [
                attrs.evolve(bt, family=self.family, surface=surface)
                for bt in a.meeting_curves(b, IDENTITY)  # type: ignore[attr-defined]
            ]
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
