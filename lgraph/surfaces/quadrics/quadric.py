"""Quadrics ``x^T A x + b . x + d = 0``: analytic hits and contours.

The shared :class:`Quadric` base turns a ray into a quadratic in ``s``.  For a
point on the quadric itself the constant term vanishes, so its own root is
``s = 0`` and the second intersection is exactly ``s = -qb/qa``: no
discriminant, which would be ill-conditioned for grazing rays near the contour.
The bounded patches of the unbounded quadrics are in
:mod:`lgraph.surfaces.quadrics.hyperboloids`, :mod:`lgraph.surfaces.quadrics.paraboloids` and
:mod:`lgraph.surfaces.quadrics.cylinders`.

>>> import numpy as np
>>> e = Ellipsoid(3, 2, 1)
>>> p = e.point(np.array([0.3]), np.array([1.0]))
>>> float(abs(e.implicit(p)[0])) < 1e-15
True
"""

from __future__ import annotations

import weakref
from typing import Any

import attrs
import numpy as np

from ..._tolerance import SELF_HIT_RTOL
from ..._validate import as_number, finite_positive
from ...curves import CurveBatch
from ...geometry.vectors import cross3
from .._base import CONTOUR, Domain, Surface
from .._memo import by_value, per_value
from ._ray import quadric_ray_hits

__all__ = ["Quadric", "Ellipsoid", "Sphere"]

_HALF_PI = np.pi / 2
#: the ellipsoid's (latitude, longitude) domain (immutable, built once)
_LATITUDE_LONGITUDE = Domain(
    (-_HALF_PI, _HALF_PI), (0.0, 2 * np.pi), periodic=(False, True), poles=(True, False)
)


class Quadric(Surface):
    """Base class: a quadric ``F(x) = x^T A x + b . x + d = 0`` (local coordinates).

    Subclasses define :attr:`!A`, :attr:`!b`, :attr:`!d`, a parametrization and,
    for unbounded quadrics, :meth:`in_patch` (which part is drawn and hides).
    """

    hit_cost = 2.0
    hit_call_cost = 300.0

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
        return self._ray_test(origins, directions, smax, own, False)

    def _ray_test(
        self, origins: Any, directions: Any, smax: Any, own: Any, count: bool
    ) -> np.ndarray:
        o = np.asarray(origins, dtype=float)
        v = np.asarray(directions, dtype=float)
        own = np.zeros(o.shape[:-1], np.int8) if own is None else np.asarray(own)
        A, b, d = self.coefficients
        vnorm = np.linalg.norm(v, axis=-1)
        eps = SELF_HIT_RTOL * self.size / np.where(vnorm > 0, vnorm, 1.0)
        return quadric_ray_hits(
            o, v, smax, own, A, b, d, eps, None if self.closed else self._patch_test, count
        )

    def hit_count(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """The ray's roots in the drawn patch, counted in closed form (0, 1 or 2)."""
        return self._ray_test(origins, directions, smax, own, True).astype(np.int64)

    @property
    def closed(self) -> bool:
        """True when the whole quadric is drawn (no patch test needed)."""
        return type(self).in_patch is Quadric.in_patch

    def _patch_test(self, points: np.ndarray, _index: np.ndarray) -> np.ndarray:
        return self.in_patch(points)

    def _solid(self) -> Any:
        # an ellipsoid: the whole quadric, A positive definite (F < 0 inside when d < 0)
        A, _, _ = self.coefficients
        if self.closed and np.all(np.linalg.eigvalsh(A) > 0):
            return self.implicit
        return None

    def patch_margin(self, points: Any) -> np.ndarray:
        """Continuous function of space points, ``>= 0`` exactly on the drawn patch
        (``+inf`` for closed quadrics)."""
        return np.full(np.shape(points)[:-1], np.inf)

    def uv_of(self, points: Any) -> np.ndarray:  # pragma: no cover - abstract
        """Parameters ``(u1, u2)`` of points on the surface (inverse of :meth:`!point`)."""
        raise NotImplementedError

    def contour(self, projector: Any) -> list[CurveBatch]:
        """Exact contour: the section of the quadric by the plane
        ``2 w^T A x + b.w = 0`` (parallel view ``w``) or by the polar plane
        ``(2 A e + b).x + b.e + 2 d = 0`` of the eye ``e`` (central view),
        parametrized in closed form and cut to the drawn patch
        (:mod:`!lgraph.surfaces.quadrics._conic`)."""
        from ._conic import contour_plane, plane_section

        n, h = contour_plane(self, projector)
        return plane_section(self, n, h)

    def umbilics(self) -> np.ndarray:
        """Real umbilic points ``(k, 3)`` (default: none)."""
        return np.empty((0, 3))

    def umbilic_marks(self, radius: float | None = None) -> list[Any]:
        """Small closed curves on the surface around :meth:`umbilics`, as
        :class:`~lgraph.curves.Curve` objects to add to a scene (marking them).

        Each is the circle of ``radius`` about the umbilic in its tangent plane,
        moved along the umbilic's normal onto the quadric (the root of the
        quadratic nearest the plane), so it lies on the surface and is seen
        from either side.  ``radius`` defaults to 1.5 % of the patch size.
        """
        from ...curves import Curve

        r = 0.015 * self.size if radius is None else float(radius)
        A, b, d = self.coefficients
        out = []
        for u in self.umbilics():
            nrm = self.gradient(u)
            nrm = nrm / np.linalg.norm(nrm)
            e1, e2 = _plane_basis(nrm)

            def mark(t: np.ndarray, u=u, n=nrm, e1=e1, e2=e2) -> np.ndarray:
                t = np.asarray(t, float)[..., None]
                p = u + r * (np.cos(t) * e1 + np.sin(t) * e2)
                # F(p + s n) = qa s^2 + qb s + qc; the small root (stable form)
                qa = n @ A @ n
                qb = 2 * (p @ A) @ n + b @ n
                qc = np.einsum("...i,ij,...j", p, A, p) + p @ b + d
                disc = np.sqrt(np.maximum(qb * qb - 4 * qa * qc, 0.0))
                s = -2 * qc / (qb + np.copysign(disc, qb))
                return p + s[..., None] * n

            out.append(Curve(mark, 0.0, 2 * np.pi, closed=True))
        return out

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
    """Closed curve ``x(t) = to_x @ (center + radius (cos t e1 + sin t e2))``,
    i.e. the ellipse ``c + p cos t + q sin t`` (said in ``ellipses``: such a
    curve is never aliased); its evaluation is the surface's ellipse kernel
    (one call for the contours of all views)."""
    # shared by equal surfaces: the contours of many equal spheres in one call
    kernel = per_value(surface, "ellipse kernel", lambda: _EllipseKernel(surface))
    params = np.concatenate([to_x @ center, radius * (to_x @ e1), radius * (to_x @ e2)])[None]

    def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return kernel(params[idx], t)

    return CurveBatch(
        "contour",
        [0.0],
        [2 * np.pi],
        evaluate,
        closed=True,
        surface=surface,
        own=CONTOUR,
        ellipses=params.reshape(1, 3, 3),
        kernel=(kernel, params),
    )


class _EllipseKernel:
    """Points ``c + p cos t + q sin t`` (rows ``c, p, q`` of ``params``) on
    ``surface``, with their surface parameters."""

    def __init__(self, surface: Quadric) -> None:
        # weak where the kernel is kept per surface object (``per_surface``:
        # its batches hold the surface while they are evaluated); held where
        # equal surfaces share it (``per_value``, a bounded table)
        self.surface = (lambda: surface) if by_value(surface) else weakref.ref(surface)

    def __call__(self, params: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x = params[:, 0:3] + np.cos(t)[:, None] * params[:, 3:6]
        x += np.sin(t)[:, None] * params[:, 6:9]
        return x, self.surface().uv_of(x)


def _plane_basis(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = n / np.linalg.norm(n)
    helper = np.eye(3)[int(np.argmin(np.abs(n)))]
    e1 = cross3(n, helper)
    e1 /= np.linalg.norm(e1)
    return e1, cross3(n, e1)


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
        return _LATITUDE_LONGITUDE

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return -self.axes.copy(), self.axes.copy()

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        """``(a cos u1 cos u2, b cos u1 sin u2, c sin u1)``: ``u1`` latitude, ``u2`` longitude."""
        u1, u2 = np.asarray(u1, float), np.asarray(u2, float)
        if u1.shape != u2.shape:  # (the renderer's parameters come in equal shapes)
            u1, u2 = np.broadcast_arrays(u1, u2)
        a, b, c = self.axes.tolist()
        out = np.empty(u1.shape + (3,))
        c1 = np.cos(u1)
        np.multiply(c1 * a, np.cos(u2), out=out[..., 0])
        np.multiply(c1 * b, np.sin(u2), out=out[..., 1])
        np.multiply(np.sin(u1), c, out=out[..., 2])
        return out

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

    def parameter_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """The parameter lines, each marked with its exact ellipse (see
        :class:`~lgraph.curves.CurveBatch`): ``u1 = c`` is
        ``(0, 0, c_3 sin c) + (a cos c, 0, 0) cos t + (0, b cos c, 0) sin t``
        (``t = u2``), ``u2 = c`` is
        ``(a cos c, b sin c, 0) cos t + (0, 0, c_3) sin t`` (``t = u1``)."""
        batches = super().parameter_lines(n1, n2)
        if not batches:
            return batches
        (batch,) = batches
        d = self.domain
        v1, v2 = d.lines(0, n1), d.lines(1, n2)
        a, b, c = self.axes.tolist()
        e1 = np.zeros((len(v1), 3, 3))
        e1[:, 0, 2] = c * np.sin(v1)
        e1[:, 1, 0] = a * np.cos(v1)
        e1[:, 2, 1] = b * np.cos(v1)
        e2 = np.zeros((len(v2), 3, 3))
        e2[:, 1, 0] = a * np.cos(v2)
        e2[:, 1, 1] = b * np.sin(v2)
        e2[:, 2, 2] = c
        return [attrs.evolve(batch, ellipses=np.concatenate([e1, e2]))]

    def uv_of(self, points: Any) -> np.ndarray:
        """Parameters ``(u1, u2)`` of points on the surface (inverse of :meth:`!point`)."""
        y = np.asarray(points, dtype=float) / self.axes
        u1 = np.arcsin(np.clip(y[..., 2], -1.0, 1.0))
        u2 = np.mod(np.arctan2(y[..., 1], y[..., 0]), 2 * np.pi)
        return np.stack([u1, u2], axis=-1)

    def contour(self, projector: Any) -> list[CurveBatch]:
        """Exact contour: in ``y = x / axes`` the ellipsoid is the unit sphere and
        the contour a circle (a great circle for parallel projection, the
        circle cut by the eye's polar plane for central projection)."""
        from ...scene.projectors import CentralProjector

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

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        """Closed-form lines of curvature from confocal coordinates (paper §7,
        Dupin's theorem; derivation in :mod:`!lgraph.surfaces.quadrics._curvature`): ``n1``
        closed loops around the longest axis, ``n2`` around the shortest, each
        one smooth closed curve.  Rotational ellipsoids give parallels and
        whole meridians; the sphere (every direction principal) its parameter
        lines.
        """
        from ._curvature import ellipsoid_lines

        return ellipsoid_lines(self, n1, n2)

    def umbilics(self) -> np.ndarray:
        """The 4 umbilics (2 poles of a spheroid; none listed for a sphere, where
        every point is umbilic), in the plane of the longest and shortest axes."""
        from ._curvature import ellipsoid_umbilics

        return ellipsoid_umbilics(self.axes)


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


# -- unbounded quadrics: drawn on a patch ------------------------------------
