"""Affine transforms of 3-space, composable with ``@``.

``(a @ b)(x) == a(b(x))``: the right-hand transform is applied first.

>>> import numpy as np
>>> t = translate(1, 0, 0) @ rotate("z", 90)
>>> np.round(t.apply([1.0, 0.0, 0.0]), 12)
array([1., 1., 0.])
>>> np.round(t.inverse().apply(t.apply([0.3, -2.0, 5.0])), 12)
array([ 0.3, -2. ,  5. ])
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import attrs
import numpy as np

from .._validate import vector3

__all__ = ["Transform", "translate", "rotate", "scale", "IDENTITY"]


def _matrix(value: Any) -> np.ndarray:
    m = np.array(value, dtype=float)
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        raise ValueError(f"Transform: matrix must be a finite 3x3 array, got {value!r}")
    if abs(np.linalg.det(m)) < 1e-300:
        raise ValueError("Transform: matrix must be invertible")
    m.setflags(write=False)
    return m


def _offset(value: Any) -> np.ndarray:
    return vector3("Transform", "offset", value)


@attrs.frozen(eq=False)
class Transform:
    """``x -> matrix @ x + offset``.

    Points transform with :meth:`apply`, directions with :meth:`apply_vector`
    and normals with :meth:`apply_normal` (inverse transpose).
    """

    matrix: np.ndarray = attrs.field(factory=lambda: np.eye(3), converter=_matrix)
    offset: np.ndarray = attrs.field(factory=lambda: np.zeros(3), converter=_offset)

    def __matmul__(self, other: Transform) -> Transform:
        if not isinstance(other, Transform):
            return NotImplemented
        return Transform(self.matrix @ other.matrix, self.matrix @ other.offset + self.offset)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Transform):
            return NotImplemented
        return bool(
            np.array_equal(self.matrix, other.matrix) and np.array_equal(self.offset, other.offset)
        )

    def __hash__(self) -> int:
        return hash((self.matrix.tobytes(), self.offset.tobytes()))

    is_identity: bool = attrs.field(init=False, repr=False)

    @is_identity.default
    def _is_identity(self) -> bool:
        return bool(np.array_equal(self.matrix, np.eye(3)) and not np.any(self.offset))

    def apply(self, points: Any) -> np.ndarray:
        """Transform points, shape (..., 3)."""
        p = np.asarray(points, dtype=float)
        return p @ self.matrix.T + self.offset

    def apply_vector(self, vectors: Any) -> np.ndarray:
        """Transform direction vectors (no translation), shape (..., 3)."""
        return np.asarray(vectors, dtype=float) @ self.matrix.T

    def apply_normal(self, normals: Any) -> np.ndarray:
        """Transform normal vectors (inverse transpose), renormalized."""
        n = np.asarray(normals, dtype=float) @ np.linalg.inv(self.matrix)
        return n / np.linalg.norm(n, axis=-1, keepdims=True)

    def inverse(self) -> Transform:
        if self.is_identity:
            return self
        inv = np.linalg.inv(self.matrix)
        return Transform(inv, -inv @ self.offset)

    def __repr__(self) -> str:
        return f"Transform(matrix={self.matrix.tolist()}, offset={self.offset.tolist()})"


IDENTITY = Transform()


def translate(x: float, y: float, z: float) -> Transform:
    """Translation by ``(x, y, z)``."""
    return Transform(np.eye(3), vector3("translate", "(x, y, z)", (x, y, z)))


_AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


def rotate(axis: Any, degrees: float) -> Transform:
    """Rotation by ``degrees`` (right-handed) about ``axis`` through the origin.

    ``axis`` is ``"x"``, ``"y"``, ``"z"`` or any non-zero 3-vector.
    """
    if isinstance(axis, str):
        if axis.lower() not in _AXES:
            raise ValueError(f"rotate: axis must be 'x', 'y', 'z' or a 3-vector, got {axis!r}")
        axis = _AXES[axis.lower()]
    a = vector3("rotate", "axis", axis, nonzero=True)
    if isinstance(degrees, bool) or not isinstance(degrees, numbers.Real):
        raise ValueError(f"rotate: degrees must be a finite number, got {degrees!r}")
    deg = float(degrees)
    if not math.isfinite(deg):
        raise ValueError(f"rotate: degrees must be a finite number, got {degrees!r}")
    k = a / np.abs(a).max()  # no overflow or underflow in the norm
    k /= np.linalg.norm(k)
    th = math.radians(deg)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    r = np.eye(3) + math.sin(th) * kx + (1 - math.cos(th)) * (kx @ kx)
    return Transform(r, np.zeros(3))


def scale(sx: float, sy: float | None = None, sz: float | None = None) -> Transform:
    """Scaling by ``(sx, sy, sz)`` (uniform when only ``sx`` is given)."""
    sy = sx if sy is None else sy
    sz = sx if sz is None else sz
    v = vector3("scale", "(sx, sy, sz)", (sx, sy, sz))
    if np.any(v == 0):
        raise ValueError(f"scale: factors must be non-zero, got {tuple(v)}")
    return Transform(np.diag(v), np.zeros(3))
