"""The hyperboloids of one and two sheets and the elliptic cone, on bounded patches.

``x^2/a^2 + y^2/b^2 - z^2/c^2 = 1`` (one sheet), ``= -1`` (two sheets) and
the cone ``x^2/a^2 + y^2/b^2 = z^2``, axis z, each cut at a height that is
changeable by keyword.  Lines of curvature in closed form
(:mod:`lgraph.surfaces.quadrics._curvature`): the hyperboloids' by confocal coordinates
(docs/mathematics.rst, "Ellipsoids and hyperboloids: confocal coordinates
(paper §7)"); the cone's are its rulings and its sections by spheres about
the vertex ("Ruled surfaces, general cylinders and cones (paper §4)").  The
one-sheet hyperboloid's asymptotic lines are its two families of rulings.
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from ...curves import CurveBatch
from .._base import Domain
from ._unbounded import _angle, _optional_positive, _PatchQuadric, _piece_lines, _set_default
from .quadric import _positive

__all__ = ["HyperboloidOneSheet", "HyperboloidTwoSheets", "EllipticCone"]


@attrs.frozen
class HyperboloidOneSheet(_PatchQuadric):
    """Hyperboloid of one sheet ``x^2/a^2 + y^2/b^2 - z^2/c^2 = 1``, drawn for
    ``|z| <= height`` (default ``2 c``).

    ``x = (a cosh u1 cos u2, b cosh u1 sin u2, c sinh u1)``, ``u2`` periodic.
    Lines of curvature: confocal coordinates (:mod:`!lgraph.surfaces.quadrics._curvature`),
    ``n1`` closed loops (parallels if a = b) and ``n2`` complete curves
    through the waist (meridians if a = b).

    >>> import numpy as np
    >>> h = HyperboloidOneSheet(1, 2, 1.5, height=2)
    >>> float(np.abs(h.implicit(h.point(0.4, 1.0))))  < 1e-14, h.height
    (True, 2.0)
    """

    a: float = _positive("HyperboloidOneSheet")
    b: float = _positive("HyperboloidOneSheet")
    c: float = _positive("HyperboloidOneSheet")
    height: float = _optional_positive("HyperboloidOneSheet")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", 2 * self.c)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, self.b**-2, -(self.c**-2)]), np.zeros(3), -1.0

    @property
    def _U(self) -> float:
        return float(np.arcsinh(self.height / self.c))

    @property
    def domain(self) -> Domain:
        return Domain((-self._U, self._U), (0.0, 2 * np.pi), periodic=(False, True))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        ch = np.cosh(u1)
        return np.stack(
            [self.a * ch * np.cos(u2), self.b * ch * np.sin(u2), self.c * np.sinh(u1)], axis=-1
        )

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        ch, sh, c2, s2 = np.cosh(u1), np.sinh(u1), np.cos(u2), np.sin(u2)
        x1 = np.stack([self.a * sh * c2, self.b * sh * s2, self.c * ch], axis=-1)
        x2 = np.stack([-self.a * ch * s2, self.b * ch * c2, np.zeros_like(ch)], axis=-1)
        return x1, x2

    def asymptotic_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """The two families of rulings (the asymptotic lines of a doubly ruled
        surface): ``n1`` and ``n2`` lines through points of the waist ellipse
        at evenly spaced angles ``th``,
        ``x = (a (cos th - s sin th), b (sin th + s cos th), +-c s)``,
        ``|s| <= height / c`` (then ``x^2/a^2 + y^2/b^2 = 1 + s^2 = 1 + z^2/c^2``).
        """
        smax = self.height / self.c
        out = []
        for n, sign in ((n1, 1.0), (n2, -1.0)):
            if n <= 0:
                continue
            th = 2 * np.pi * (np.arange(n) + 0.25 * (1 - sign)) / n

            def evaluate(idx: np.ndarray, s: np.ndarray, th=th, sign=sign) -> tuple:
                t = th[idx]
                x = np.stack(
                    [
                        self.a * (np.cos(t) - s * np.sin(t)),
                        self.b * (np.sin(t) + s * np.cos(t)),
                        sign * self.c * s,
                    ],
                    axis=-1,
                )
                return x, self.uv_of(x)

            out.append(
                CurveBatch(
                    "asymptotic", np.full(n, -smax), np.full(n, smax), evaluate, surface=self
                )  # fmt: skip
            )
        return out

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack(
            [np.arcsinh(x[..., 2] / self.c), _angle(x[..., 1] / self.b, x[..., 0] / self.a)], -1
        )

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = np.cosh(self._U)
        hi = np.array([self.a * r, self.b * r, self.height])
        return -hi, hi

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.height - np.abs(np.asarray(points, float)[..., 2])

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        from ._curvature import one_sheet_lines

        return one_sheet_lines(self, n1, n2)


@attrs.frozen
class HyperboloidTwoSheets(_PatchQuadric):
    """Hyperboloid of two sheets ``x^2/a^2 + y^2/b^2 - z^2/c^2 = -1``, both sheets
    drawn for ``c <= |z| <= height`` (default ``2.5 c``).

    ``u1`` in ``[-U, U]`` is signed: its sign picks the sheet, ``|u1|`` the
    hyperbolic distance from the vertex, ``x = (a sinh|u1| cos u2,
    b sinh|u1| sin u2, sign(u1) c cosh u1)``.  Parameter lines are drawn per
    sheet (:meth:`!parameter_lines`).  Lines of curvature: confocal coordinates,
    ``n1`` loops and ``n2`` complete curves on each sheet; 4 real umbilics.

    >>> HyperboloidTwoSheets(1, 1, 1, height=0.5)
    Traceback (most recent call last):
    ...
    ValueError: HyperboloidTwoSheets: height must be greater than c=1, got 0.5
    """

    a: float = _positive("HyperboloidTwoSheets")
    b: float = _positive("HyperboloidTwoSheets")
    c: float = _positive("HyperboloidTwoSheets")
    height: float = _optional_positive("HyperboloidTwoSheets")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", 2.5 * self.c)
        if not self.height > self.c:
            raise ValueError(
                f"HyperboloidTwoSheets: height must be greater than c={self.c!r}, "
                f"got {self.height!r}"
            )

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, self.b**-2, -(self.c**-2)]), np.zeros(3), 1.0

    @property
    def _U(self) -> float:
        return float(np.arccosh(self.height / self.c))

    @property
    def domain(self) -> Domain:
        return Domain((-self._U, self._U), (0.0, 2 * np.pi), periodic=(False, True))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        sg = np.where(np.signbit(u1), -1.0, 1.0)  # -0.0: lower sheet
        sh = np.sinh(np.abs(u1))
        return np.stack(
            [self.a * sh * np.cos(u2), self.b * sh * np.sin(u2), sg * self.c * np.cosh(u1)], -1
        )

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        sg = np.where(np.signbit(u1), -1.0, 1.0)  # -0.0: lower sheet
        ch, sh, c2, s2 = np.cosh(u1), np.sinh(np.abs(u1)), np.cos(u2), np.sin(u2)
        x1 = np.stack([sg * self.a * ch * c2, sg * self.b * ch * s2, self.c * sh], -1)
        x2 = np.stack([-self.a * sh * s2, self.b * sh * c2, np.zeros_like(sh)], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        rho = np.arccosh(np.maximum(np.abs(x[..., 2]) / self.c, 1.0))
        u1 = np.where(x[..., 2] < 0, -rho, rho)
        return np.stack([u1, _angle(x[..., 1] / self.b, x[..., 0] / self.a)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = np.sinh(self._U)
        hi = np.array([self.a * r, self.b * r, self.height])
        return -hi, hi

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.height - np.abs(np.asarray(points, float)[..., 2])

    def parameter_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """``n1`` circles ``u1 = const`` and ``n2`` half-meridians per sheet."""
        return _piece_lines(self, n1, n2, ("u1", "u2"), even=False)

    def _pieces(self) -> list[tuple]:
        U, tp = self._U, (0.0, 2 * np.pi)
        return [((0.0, U), tp, "periodic", (0, 1.0)), ((-U, 0.0), tp, "periodic", (0, -1.0))]

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        from ._curvature import two_sheets_lines

        return two_sheets_lines(self, n1, n2)

    def umbilics(self) -> np.ndarray:
        """4 umbilics (the 2 vertices if a = b), in the plane of the axis and the
        smaller transverse semi-axis (listed whether or not inside the patch)."""
        from ._curvature import two_sheets_umbilics

        return two_sheets_umbilics(self.a, self.b, self.c)


@attrs.frozen
class EllipticCone(_PatchQuadric):
    """Elliptic cone ``x^2/a^2 + y^2/b^2 = z^2``, both nappes, ``|z| <= height``
    (default 1).

    ``x = (a u1 cos u2, b u1 sin u2, u1)``: the rulings ``u2 = const`` run
    through the vertex from one nappe to the other.  Lines of curvature
    (paper Example 4.2): ``n1`` sections by spheres about the vertex (on both
    nappes), ``n2`` rulings.
    """

    a: float = _positive("EllipticCone")
    b: float = _positive("EllipticCone")
    height: float = _optional_positive("EllipticCone")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", 1.0)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, self.b**-2, -1.0]), np.zeros(3), 0.0

    @property
    def domain(self) -> Domain:
        return Domain((-self.height, self.height), (0.0, 2 * np.pi), periodic=(False, True))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * u1 * np.cos(u2), self.b * u1 * np.sin(u2), u1], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        c2, s2 = np.cos(u2), np.sin(u2)
        x1 = np.stack([self.a * c2, self.b * s2, np.ones_like(u1)], axis=-1)
        x2 = np.stack([-self.a * u1 * s2, self.b * u1 * c2, np.zeros_like(u1)], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        z = x[..., 2]
        sg = np.where(z < 0, -1.0, 1.0)
        return np.stack([z, _angle(sg * x[..., 1] / self.b, sg * x[..., 0] / self.a)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        hi = np.array([self.a, self.b, 1.0]) * self.height
        return -hi, hi

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.height - np.abs(np.asarray(points, float)[..., 2])

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        from ._curvature import cone_lines

        return cone_lines(self, n1, n2)
