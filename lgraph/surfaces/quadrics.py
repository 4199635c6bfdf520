"""Quadrics ``x^T A x + b . x + d = 0``: analytic hits and contours.

The shared :class:`Quadric` base turns a ray into a quadratic in ``s``.  For a
point on the quadric itself the constant term vanishes, so its own root is
``s = 0`` and the second intersection is exactly ``s = -qb/qa``: no
discriminant, which would be ill-conditioned for grazing rays near the contour.

>>> import numpy as np
>>> e = Ellipsoid(3, 2, 1)
>>> p = e.point(np.array([0.3]), np.array([1.0]))
>>> float(abs(e.implicit(p)[0])) < 1e-15
True
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from .._tolerance import SELF_HIT_RTOL
from .._validate import as_number, finite_positive
from ..curves import CurveBatch
from ._base import CONTOUR, ON, Domain, Surface

__all__ = ["Quadric", "Ellipsoid", "Sphere"]

_HALF_PI = np.pi / 2


class Quadric(Surface):
    """Base class: a quadric ``F(x) = x^T A x + b . x + d = 0`` (local coordinates).

    Subclasses define :attr:`A`, :attr:`b`, :attr:`d`, a parametrization and,
    for unbounded quadrics, :meth:`in_patch` (which part is drawn and hides).
    """

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:  # pragma: no cover
        """``(A, b, d)`` of ``x^T A x + b . x + d = 0`` (A symmetric 3x3)."""
        raise NotImplementedError

    def implicit(self, points: Any) -> np.ndarray:
        """``F(x)``; zero on the surface."""
        A, b, d = self.coefficients
        x = np.asarray(points, dtype=float)
        return np.einsum("...i,ij,...j", x, A, x) + x @ b + d

    def gradient(self, points: Any) -> np.ndarray:
        """``grad F(x) = 2 A x + b``."""
        A, b, _ = self.coefficients
        x = np.asarray(points, dtype=float)
        return 2 * x @ A + b

    def in_patch(self, points: np.ndarray) -> np.ndarray:
        """Whether points of the quadric belong to the drawn patch (default: all)."""
        return np.ones(np.shape(points)[:-1], dtype=bool)

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        o = np.asarray(origins, dtype=float)
        v = np.asarray(directions, dtype=float)
        smax = np.broadcast_to(np.asarray(smax, dtype=float), o.shape[:-1])
        A, b, d = self.coefficients
        Av = v @ A
        qa = np.einsum("...i,...i", v, Av)
        qb = 2 * np.einsum("...i,...i", o, Av) + v @ b
        qc = np.einsum("...i,ij,...j", o, A, o) + o @ b + d
        own = np.zeros(o.shape[:-1], np.int8) if own is None else np.asarray(own)
        vnorm = np.linalg.norm(v, axis=-1)
        eps = SELF_HIT_RTOL * self.size / np.where(vnorm > 0, vnorm, 1.0)
        hit = np.zeros(o.shape[:-1], dtype=bool)

        def accept(s: np.ndarray, mask: np.ndarray, lower: np.ndarray | float) -> np.ndarray:
            ok = mask & np.isfinite(s) & (s > lower) & (s < smax)
            if ok.any():
                idx = np.nonzero(ok)
                ok[idx] = self.in_patch(o[idx] + s[idx][..., None] * v[idx])
            return ok

        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            # points on this surface: the second root is exactly -qb/qa
            on = own == ON
            if on.any():
                hit |= accept(-qb / qa, on, 0.0)
            # contour points: the view ray is tangent, a double root at s = 0;
            # it meets the quadric elsewhere only if it lies on it (a ruling)
            # -- then it is not hidden by its own surface either.
            off = (own != ON) & (own != CONTOUR)
            if off.any():
                disc = qb * qb - 4 * qa * qc
                real = off & (disc >= 0)
                sq = np.sqrt(np.where(real, disc, 0.0))
                q = -0.5 * (qb + np.copysign(sq, qb))
                lin = real & (np.abs(qa) <= 1e-14 * (np.abs(qb) + np.abs(qc)) + 1e-300)
                r1 = np.where(lin, -qc / qb, q / qa)
                r2 = np.where(lin, np.nan, qc / q)
                hit |= accept(r1, real, eps) | accept(r2, real, eps)
        return hit

    def describe(self) -> str:
        return repr(self)


def _affine_circle_batch(
    surface: Quadric,
    center: np.ndarray,
    e1: np.ndarray,
    e2: np.ndarray,
    radius: float,
    to_x: np.ndarray,
) -> CurveBatch:
    """Closed curve ``x(t) = to_x @ (center + radius (cos t e1 + sin t e2))``."""

    def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        y = center + radius * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)
        x = y @ to_x.T
        return x, surface.uv_of(x)

    return CurveBatch(
        "contour", [0.0], [2 * np.pi], evaluate, closed=True, surface=surface, own=CONTOUR
    )


def _plane_basis(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = n / np.linalg.norm(n)
    helper = np.eye(3)[int(np.argmin(np.abs(n)))]
    e1 = np.cross(n, helper)
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(n, e1)


class _Ellipsoidal(Quadric):
    """Shared code of Ellipsoid and Sphere (semi-axes ``axes``)."""

    @property
    def axes(self) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag(1.0 / self.axes**2), np.zeros(3), -1.0

    @property
    def domain(self) -> Domain:
        return Domain(
            (-_HALF_PI, _HALF_PI), (0.0, 2 * np.pi), periodic=(False, True), poles=(True, False)
        )

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return -self.axes.copy(), self.axes.copy()

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        """``(a cos u1 cos u2, b cos u1 sin u2, c sin u1)``: ``u1`` latitude, ``u2`` longitude."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        c1 = np.cos(u1)
        return np.stack([c1 * np.cos(u2), c1 * np.sin(u2), np.sin(u1)], axis=-1) * self.axes

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        c1, s1, c2, s2 = np.cos(u1), np.sin(u1), np.cos(u2), np.sin(u2)
        x1 = np.stack([-s1 * c2, -s1 * s2, c1], axis=-1) * self.axes
        x2 = np.stack([-c1 * s2, c1 * c2, np.zeros_like(c1)], axis=-1) * self.axes
        return x1, x2

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        c1, s1, c2, s2 = np.cos(u1), np.sin(u1), np.cos(u2), np.sin(u2)
        z = np.zeros_like(c1)
        x11 = np.stack([-c1 * c2, -c1 * s2, -s1], axis=-1) * self.axes
        x12 = np.stack([s1 * s2, -s1 * c2, z], axis=-1) * self.axes
        x22 = np.stack([-c1 * c2, -c1 * s2, z], axis=-1) * self.axes
        return x11, x12, x22

    def uv_of(self, points: Any) -> np.ndarray:
        """Parameters ``(u1, u2)`` of points on the surface (inverse of :meth:`point`)."""
        y = np.asarray(points, dtype=float) / self.axes
        u1 = np.arcsin(np.clip(y[..., 2], -1.0, 1.0))
        u2 = np.mod(np.arctan2(y[..., 1], y[..., 0]), 2 * np.pi)
        return np.stack([u1, u2], axis=-1)

    def contour(self, projector: Any) -> list[CurveBatch]:
        """Exact contour: in ``y = x / axes`` the ellipsoid is the unit sphere and
        the contour a circle (a great circle for parallel projection, the
        circle cut by the eye's polar plane for central projection)."""
        from ..projectors import CentralProjector

        ax = self.axes
        to_x = np.diag(ax)
        if isinstance(projector, CentralProjector):
            n = projector.eye / ax  # eye in sphere coordinates
            nn = float(n @ n)
            if nn <= 1.0:
                return []  # eye inside: no contour
            center = n / nn
            radius = float(np.sqrt(1.0 - 1.0 / nn))
        else:
            n = projector.frame[2] / ax  # (A x).d = 0  <=>  y.(d / axes) = 0
            center = np.zeros(3)
            radius = 1.0
        e1, e2 = _plane_basis(n)
        return [_affine_circle_batch(self, center, e1, e2, radius, to_x)]


def _positive(owner: str) -> Any:
    return attrs.field(converter=as_number, validator=finite_positive(owner))


@attrs.frozen
class Ellipsoid(_Ellipsoidal):
    """Ellipsoid ``x^2/a^2 + y^2/b^2 + z^2/c^2 = 1``.

    Parametrized (paper §3) by latitude ``u1`` in ``[-pi/2, pi/2]`` and
    longitude ``u2`` in ``[0, 2 pi)``.

    >>> Ellipsoid(0, 1, 1)
    Traceback (most recent call last):
    ...
    ValueError: Ellipsoid: a must be a positive finite number, got 0
    """

    a: float = _positive("Ellipsoid")
    b: float = _positive("Ellipsoid")
    c: float = _positive("Ellipsoid")

    @property
    def axes(self) -> np.ndarray:
        return np.array([self.a, self.b, self.c])


@attrs.frozen
class Sphere(_Ellipsoidal):
    """Sphere ``x^2 + y^2 + z^2 = r^2`` (latitude/longitude parameters).

    >>> Sphere(float("nan"))
    Traceback (most recent call last):
    ...
    ValueError: Sphere: r must be a positive finite number, got nan
    """

    r: float = _positive("Sphere")

    @property
    def axes(self) -> np.ndarray:
        return np.array([self.r, self.r, self.r])
