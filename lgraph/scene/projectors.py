"""Projectors own the eye: they map world points to the projection plane and
give, for any point, the ray toward the viewer.

>>> import numpy as np
>>> p = ParallelProjector(direction=(0, 0, 1))
>>> p.project(np.array([[1.0, 2.0, 3.0]]))
array([[1., 2.]])
>>> c = CentralProjector(eye=(0, 0, 10), target=(0, 0, 0))
>>> c.project(np.array([[1.0, 2.0, 0.0]]))
array([[1., 2.]])
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from .._budget import check_frames
from .._validate import as_number, positive_finite, vector3
from ..geometry.vectors import cross3

__all__ = ["Projector", "ParallelProjector", "CentralProjector", "orbit"]


def _frame(toward_viewer: np.ndarray, up: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Orthonormal (right, up, toward viewer) frame; ``up`` need not be orthogonal."""
    # scale by the largest component first: no underflow or overflow for
    # directions like (1e-320, 0, 0) or (1e300, 1e300, 0)
    e3 = toward_viewer / np.abs(toward_viewer).max()
    e3 /= np.linalg.norm(e3)
    u = up / np.abs(up).max()
    u /= np.linalg.norm(u)
    if abs(float(u @ e3)) > 1 - 1e-9:  # looking along the up vector: pick another
        u = np.array([0.0, 1.0, 0.0]) if abs(e3[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    e1 = cross3(u, e3)
    e1 /= np.linalg.norm(e1)
    e2 = cross3(e3, e1)
    return e1, e2, e3


def _direction_from_angles(azimuth: float, elevation: float) -> np.ndarray:
    azimuth, elevation = as_number(azimuth), as_number(elevation)
    for name, v in (("azimuth", azimuth), ("elevation", elevation)):
        if not (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)):
            raise ValueError(f"Projector: {name} must be a finite number of degrees, got {v!r}")
    if not -90 <= elevation <= 90:
        raise ValueError(f"Projector: elevation must lie in [-90, 90] degrees, got {elevation!r}")
    az, el = math.radians(azimuth), math.radians(elevation)
    return np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])


def linear_map(points: np.ndarray, m: np.ndarray) -> np.ndarray:
    """``points @ m`` for points ``(..., 3)`` and ``m`` ``(3, k)``, or one
    matrix per point ``(..., 3, k)``: written out term by term, so that every
    machine (whatever its BLAS) and a point projected alone or among others
    (:mod:`lgraph.render.views`) get the same bits.

    >>> linear_map(np.array([[1.0, 2.0, 3.0]]), np.eye(3)[:, :2]).tolist()
    [[1.0, 2.0]]
    """
    if points.ndim == 2 and m.ndim == 2:  # column by column: the same terms, faster
        return _map_columns(points, m.T.tolist())
    x, y, z = points[..., 0, None], points[..., 1, None], points[..., 2, None]
    return x * m[..., 0, :] + y * m[..., 1, :] + z * m[..., 2, :]


def _map_columns(points: np.ndarray, columns: list[list[float]]) -> np.ndarray:
    """:func:`linear_map` of points ``(n, 3)`` by a matrix given as its
    ``columns`` (each ``[m0j, m1j, m2j]``): every term as there, in the same
    order, on whole columns."""
    x, y, z = points[:, 0], points[:, 1], points[:, 2]
    out = np.empty((len(points), len(columns)))
    for j, (a, b, c) in enumerate(columns):
        np.add(x * a + y * b, z * c, out=out[:, j])
    return out


def unit_rays(w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vectors ``w`` ``(..., 3)`` (changed in place) divided by their lengths;
    and the lengths."""
    n = np.sqrt(w[..., 0] * w[..., 0] + w[..., 1] * w[..., 1] + w[..., 2] * w[..., 2])
    with np.errstate(divide="ignore", invalid="ignore"):
        w /= n[..., None]
    return w, n


class Projector:
    """Base class: subclasses define the eye.

    Methods are vectorized over points of shape ``(..., 3)``.
    """

    #: (right, up, toward-viewer) unit vectors of the image plane
    frame: tuple[np.ndarray, np.ndarray, np.ndarray]

    def project(self, points: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        """Projection-plane coordinates ``(..., 2)``."""
        raise NotImplementedError

    def rays(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
        """Unit directions toward the viewer ``(..., 3)`` and the ray lengths ``(...)``
        up to the eye (``inf`` for parallel projection)."""
        raise NotImplementedError

    def view_vectors(self, points: np.ndarray) -> np.ndarray:  # pragma: no cover
        """Vectors ``w`` toward the viewer; contour points satisfy ``N . w = 0``."""
        raise NotImplementedError

    def describe(self) -> str:  # pragma: no cover
        raise NotImplementedError


@attrs.frozen(eq=False)
class ParallelProjector(Projector):
    """Parallel (orthographic) projection along ``direction``.

    Parameters
    ----------
    direction : 3 numbers
        Vector from the scene toward the viewer (need not be unit).
    up : 3 numbers
        World vector that appears upward in the picture (default ``z``).
    """

    direction: np.ndarray = attrs.field(
        converter=lambda v: vector3("ParallelProjector", "direction", v, nonzero=True)
    )
    up: np.ndarray = attrs.field(
        default=(0.0, 0.0, 1.0),
        converter=lambda v: vector3("ParallelProjector", "up", v, nonzero=True),
    )
    frame: tuple[np.ndarray, np.ndarray, np.ndarray] = attrs.field(init=False)
    #: the columns of :attr:`!_plane`, as floats (every projection uses them)
    _columns: list = attrs.field(init=False, repr=False)

    @frame.default
    def _frame_default(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return _frame(self.direction, self.up)

    @_columns.default
    def _columns_default(self) -> list:
        return self._plane.T.tolist()

    @classmethod
    def from_angles(cls, azimuth: float, elevation: float) -> ParallelProjector:
        """Viewer at ``azimuth`` (degrees from +x toward +y) and ``elevation``
        (degrees above the xy-plane), as in the paper's software."""
        return cls(direction=_direction_from_angles(azimuth, elevation))

    def project(self, points: np.ndarray) -> np.ndarray:
        p = np.asarray(points, dtype=float)
        if p.ndim == 2:
            return _map_columns(p, self._columns)
        return linear_map(p, self._plane)

    @property
    def _plane(self) -> np.ndarray:
        return np.column_stack(self.frame[:2])

    def rays(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        p = np.asarray(points, dtype=float)
        d = np.broadcast_to(self.frame[2], p.shape)
        return d, np.full(p.shape[:-1], np.inf)

    def view_vectors(self, points: np.ndarray) -> np.ndarray:
        return np.broadcast_to(self.frame[2], np.shape(points))

    def describe(self) -> str:
        d = np.round(self.frame[2], 4).tolist()
        return f"parallel projection, view direction {d}"


@attrs.frozen(eq=False)
class CentralProjector(Projector):
    """Central (perspective) projection from ``eye`` looking at ``target``.

    The image plane passes through ``target``, so objects near the target keep
    their size.
    """

    eye: np.ndarray = attrs.field(converter=lambda v: vector3("CentralProjector", "eye", v))
    target: np.ndarray = attrs.field(
        default=(0.0, 0.0, 0.0), converter=lambda v: vector3("CentralProjector", "target", v)
    )
    up: np.ndarray = attrs.field(
        default=(0.0, 0.0, 1.0),
        converter=lambda v: vector3("CentralProjector", "up", v, nonzero=True),
    )
    frame: tuple[np.ndarray, np.ndarray, np.ndarray] = attrs.field(init=False)
    distance: float = attrs.field(init=False)
    #: the eye and the columns of :attr:`!_basis`, as floats (every projection uses them)
    _eye3: list = attrs.field(init=False, repr=False)
    _columns: list = attrs.field(init=False, repr=False)

    @frame.default
    def _frame_default(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        dist = float(np.linalg.norm(self.eye - self.target))
        if not dist > 0:
            raise ValueError(
                f"CentralProjector: eye must differ from target, both are {self.eye.tolist()}"
            )
        return _frame(self.eye - self.target, self.up)

    @distance.default
    def _distance_default(self) -> float:
        return float(np.linalg.norm(self.eye - self.target))

    @_eye3.default
    def _eye3_default(self) -> list:
        return self.eye.tolist()

    @_columns.default
    def _columns_default(self) -> list:
        return self._basis.T.tolist()

    @classmethod
    def from_angles(
        cls,
        azimuth: float,
        elevation: float,
        distance: float,
        target: Any = (0.0, 0.0, 0.0),
    ) -> CentralProjector:
        """Eye at ``distance`` from ``target`` in the direction given by
        ``azimuth`` and ``elevation`` (degrees)."""
        distance = positive_finite("CentralProjector", "distance", distance)
        t = vector3("CentralProjector", "target", target)
        return cls(eye=t + distance * _direction_from_angles(azimuth, elevation), target=t)

    def depth(self, points: np.ndarray) -> np.ndarray:
        """Distance in front of the eye along the viewing axis (> 0 when visible)."""
        return (self.eye - np.asarray(points, dtype=float)) @ self.frame[2]

    def project(self, points: np.ndarray) -> np.ndarray:
        p = np.asarray(points, dtype=float)
        if p.ndim == 2:  # column by column: the terms of ``linear_map``, faster
            (ex, ey, ez), (c0, c1, c2) = self._eye3, self._columns
            x, y, z = p[:, 0] - ex, p[:, 1] - ey, p[:, 2] - ez
            out = np.empty((len(p), 2))
            with np.errstate(divide="ignore", invalid="ignore"):
                f = -self.distance / (x * c2[0] + y * c2[1] + z * c2[2])
                np.multiply(x * c0[0] + y * c0[1] + z * c0[2], f, out=out[:, 0])
                np.multiply(x * c1[0] + y * c1[1] + z * c1[2], f, out=out[:, 1])
            return out
        q = linear_map(p - self.eye, self._basis)
        with np.errstate(divide="ignore", invalid="ignore"):
            return q[..., :2] * (-self.distance / q[..., 2:])

    @property
    def _basis(self) -> np.ndarray:
        return np.column_stack(self.frame)

    def rays(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return unit_rays(self.eye - np.asarray(points, dtype=float))

    def view_vectors(self, points: np.ndarray) -> np.ndarray:
        return self.eye - np.asarray(points, dtype=float)

    def describe(self) -> str:
        return f"central projection, eye {self.eye.tolist()}, target {self.target.tolist()}"


def orbit(
    elevation: float = 25.0,
    frames: int = 24,
    distance: float | None = None,
    *,
    azimuth: float = 0.0,
    turn: float = 360.0,
    target: Any = (0.0, 0.0, 0.0),
) -> list[Projector]:
    """``frames`` views around the z axis: a turntable.

    The eye moves at constant ``elevation`` (degrees) from ``azimuth`` in steps
    of ``turn / frames`` degrees (the last view stops one step short of a full
    turn, so a looping animation does not repeat a frame).  With ``distance``
    None the views are parallel projections; with a distance, central
    projections from that distance to ``target``.

    >>> views = orbit(elevation=30, frames=4)
    >>> [v.direction.round(3).tolist() for v in views[:2]]
    [[0.866, 0.0, 0.5], [0.0, 0.866, 0.5]]
    >>> type(orbit(frames=2, distance=10)[0]).__name__
    'CentralProjector'
    >>> orbit(frames=0)
    Traceback (most recent call last):
    ...
    ValueError: orbit: frames must be an integer from 1 to 100000, got 0
    """
    frames = check_frames("orbit", frames)
    for name, v in (("azimuth", azimuth), ("turn", turn)):
        if isinstance(v, bool) or not (isinstance(v, (int, float)) and math.isfinite(v)):
            raise ValueError(f"orbit: {name} must be a finite number of degrees, got {v!r}")
    azimuths = azimuth + turn * np.arange(frames) / frames
    if distance is None:
        return [ParallelProjector.from_angles(float(a), elevation) for a in azimuths]
    return [CentralProjector.from_angles(float(a), elevation, distance, target) for a in azimuths]
