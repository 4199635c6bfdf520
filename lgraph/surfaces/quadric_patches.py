"""The unbounded quadrics, drawn on bounded patches.

Hyperboloids of one and two sheets, the elliptic cone, the elliptic and
hyperbolic paraboloids and the three quadric cylinders, each in its normal
form (axis z, centred at the origin) with a default extent changeable by
keyword.  Only the drawn patch hides anything; contours and lines of
curvature are cut to it exactly.  The ray test and the contour conic come
from :class:`~lgraph.surfaces.quadrics.Quadric`.
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from .._validate import as_number, finite_positive
from ..curves import CurveBatch
from ._base import Domain
from .quadrics import Quadric, _positive

__all__ = [
    "HyperboloidOneSheet",
    "HyperboloidTwoSheets",
    "EllipticCone",
    "EllipticParaboloid",
    "HyperbolicParaboloid",
    "EllipticCylinder",
    "HyperbolicCylinder",
    "ParabolicCylinder",
]


def _optional_positive(owner: str) -> Any:
    """Keyword-only field: a positive number, or None for the class default."""

    def check(inst: Any, attribute: Any, value: Any) -> None:
        if value is not None:
            finite_positive(owner)(inst, attribute, value)

    return attrs.field(default=None, kw_only=True, converter=as_number, validator=check)


def _set_default(inst: Any, name: str, value: float) -> None:
    current = getattr(inst, name)
    object.__setattr__(inst, name, float(value if current is None else current))


def _angle(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    return np.mod(np.arctan2(y, x), 2 * np.pi)


class _PatchQuadric(Quadric):
    """A quadric drawn on the patch where :meth:`patch_margin` ``>= 0``.

    Only the patch hides anything (:meth:`in_patch` is checked by ray hits),
    contour and lines of curvature are cut to it.
    """

    def in_patch(self, points: np.ndarray) -> np.ndarray:
        return np.asarray(self.patch_margin(points)) >= 0

    def patch_margin(self, points: Any) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def boundary(self) -> list[CurveBatch]:
        """Edges of the drawn patch; per piece for surfaces made of pieces."""
        if hasattr(self, "_pieces"):
            return _piece_lines(self, 0, 0, ("boundary", "boundary"), even=False, ends=True)
        return super().boundary()


def _piece_lines(
    surface: Any, n1: int, n2: int, names: tuple[str, str], even: bool, ends: bool = False
) -> list[CurveBatch]:
    """Lines ``u1 = const`` and ``u2 = const`` on every piece of a surface.

    ``surface._pieces()`` lists ``(u1 range, u2 range, mode, fix)``: a
    sub-rectangle of the domain, how ``u2`` values are spread (``"periodic"``
    or ``"ends"``), and ``fix = (axis, sign)`` forcing the sign of the
    piece-selecting parameter (so that ``-0.0`` and rounding never jump to
    another piece), or None.  ``even``: spread the ``u2 = const`` lines evenly
    by arc length (lines of curvature of cylinders) instead of uniformly.
    ``ends``: the pieces' edges instead (``n1, n2`` unused).
    """
    from ._patch import spread

    out: list[CurveBatch] = []
    for r1, r2, mode, fix in surface._pieces():
        per = mode == "periodic"
        sub = Domain(r1, r2, periodic=(False, per))
        c1 = sub.ends(0) if ends else sub.lines(0, n1)
        if ends:
            c2 = sub.ends(1)
        elif even:
            sg = 1.0 if fix is None or fix[0] != 1 else fix[1]
            c2 = spread(
                lambda s, r=r1[0], sg=sg: surface.point(
                    r, np.copysign(np.abs(s), sg) if sg < 0 else s
                ),
                r2[0], r2[1], n2, mode,
            )  # fmt: skip
        else:
            c2 = sub.lines(1, n2)

        def make(cols: Any, fix: Any = fix) -> Any:
            def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
                p = cols(idx, t)
                if fix is not None:
                    p[:, fix[0]] = np.copysign(np.abs(p[:, fix[0]]), fix[1])
                return p

            return uv

        if len(c1):
            out.append(
                CurveBatch.from_uv(
                    surface, names[0], np.full(len(c1), r2[0]), np.full(len(c1), r2[1]),
                    make(lambda idx, t, c1=c1: np.column_stack([c1[idx], t])), closed=per,
                )
            )  # fmt: skip
        if len(c2):
            out.append(
                CurveBatch.from_uv(
                    surface, names[1], np.full(len(c2), r1[0]), np.full(len(c2), r1[1]),
                    make(lambda idx, t, c2=c2: np.column_stack([t, c2[idx]])),
                )
            )  # fmt: skip
    return out


@attrs.frozen
class HyperboloidOneSheet(_PatchQuadric):
    """Hyperboloid of one sheet ``x^2/a^2 + y^2/b^2 - z^2/c^2 = 1``, drawn for
    ``|z| <= height`` (default ``2 c``).

    ``x = (a cosh u1 cos u2, b cosh u1 sin u2, c sinh u1)``, ``u2`` periodic.
    Lines of curvature: confocal coordinates (:mod:`!lgraph.surfaces._loc`),
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
        from ._loc import one_sheet_lines

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
        from ._loc import two_sheets_lines

        return two_sheets_lines(self, n1, n2)

    def umbilics(self) -> np.ndarray:
        """4 umbilics (the 2 vertices if a = b), in the plane of the axis and the
        smaller transverse semi-axis (listed whether or not inside the patch)."""
        from ._loc import two_sheets_umbilics

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
        from ._loc import cone_lines

        return cone_lines(self, n1, n2)


@attrs.frozen
class EllipticParaboloid(_PatchQuadric):
    """Elliptic paraboloid ``z = x^2/a^2 + y^2/b^2``, drawn for ``z <= height``
    (default 1).

    ``x = (a u1 cos u2, b u1 sin u2, u1^2)``, ``0 <= u1 <= sqrt(height)``.
    Lines of curvature: confocal paraboloids (:mod:`!lgraph.surfaces._loc`),
    ``n1`` loops and ``n2`` complete curves; 2 umbilics (1 if a = b).
    """

    a: float = _positive("EllipticParaboloid")
    b: float = _positive("EllipticParaboloid")
    height: float = _optional_positive("EllipticParaboloid")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", 1.0)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, self.b**-2, 0.0]), np.array([0.0, 0.0, -1.0]), 0.0

    @property
    def domain(self) -> Domain:
        return Domain((0.0, np.sqrt(self.height)), (0.0, 2 * np.pi), periodic=(False, True))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * u1 * np.cos(u2), self.b * u1 * np.sin(u2), u1 * u1], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        c2, s2 = np.cos(u2), np.sin(u2)
        x1 = np.stack([self.a * c2, self.b * s2, 2 * u1], axis=-1)
        x2 = np.stack([-self.a * u1 * s2, self.b * u1 * c2, np.zeros_like(u1)], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        X, Y = x[..., 0] / self.a, x[..., 1] / self.b
        return np.stack([np.hypot(X, Y), _angle(Y, X)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = np.sqrt(self.height)
        return np.array([-self.a * r, -self.b * r, 0.0]), np.array(
            [self.a * r, self.b * r, self.height]
        )

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.height - np.asarray(points, float)[..., 2]

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        from ._loc import elliptic_paraboloid_lines

        return elliptic_paraboloid_lines(self, n1, n2)

    def umbilics(self) -> np.ndarray:
        """``(+-sqrt(P(Q-P)), 0, (Q-P)/2)`` with ``P, Q = a^2/2, b^2/2`` (a < b;
        on the axis of the smaller semi-axis); the vertex alone if a = b."""
        from ._loc import elliptic_paraboloid_umbilics

        return elliptic_paraboloid_umbilics(self.a, self.b)


@attrs.frozen
class HyperbolicParaboloid(_PatchQuadric):
    """Hyperbolic paraboloid ``z = x^2/a^2 - y^2/b^2`` on the patch
    ``|x| <= a extent, |y| <= b extent`` (default ``extent = 1``).

    ``x = (a u1, b u2, u1^2 - u2^2)`` (paper §5).  Lines of curvature: the
    confocal-paraboloid parametrization ``(cosh s sinh t, sinh s cosh t)``
    (:mod:`!lgraph.surfaces._loc`), cut exactly to the patch.
    """

    a: float = _positive("HyperbolicParaboloid")
    b: float = _positive("HyperbolicParaboloid")
    extent: float = _optional_positive("HyperbolicParaboloid")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "extent", 1.0)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, -(self.b**-2), 0.0]), np.array([0.0, 0.0, -1.0]), 0.0

    @property
    def domain(self) -> Domain:
        r = self.extent
        return Domain((-r, r), (-r, r))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * u1, self.b * u2, u1 * u1 - u2 * u2], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        one, zero = np.ones_like(u1), np.zeros_like(u1)
        return (
            np.stack([self.a * one, zero, 2 * u1], axis=-1),
            np.stack([zero, self.b * one, -2 * u2], axis=-1),
        )

    def asymptotic_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """The two families of rulings: with ``p = x/a + y/b`` and
        ``q = x/a - y/b`` the surface is ``z = p q``, so ``p = const`` and
        ``q = const`` are straight lines on it.  ``n1`` values of ``p`` and
        ``n2`` of ``q`` are spread over ``(-2 e, 2 e)``; each line is cut exactly
        to the square patch (``|p + q|, |p - q| <= 2 e``, so the free parameter
        runs over ``|c| - 2 e .. 2 e - |c|``).
        """
        e = self.extent
        out = []
        for n, swap in ((n1, False), (n2, True)):
            if n <= 0:
                continue
            c = Domain((-2 * e, 2 * e), (0.0, 1.0)).lines(0, n)
            half = 2 * e - np.abs(c)

            def uv(idx: np.ndarray, t: np.ndarray, c=c, swap=swap) -> np.ndarray:
                p, q = (t, c[idx]) if swap else (c[idx], t)
                return np.column_stack([(p + q) / 2, (p - q) / 2])

            out.append(CurveBatch.from_uv(self, "asymptotic", -half, half, uv))
        return out

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack([x[..., 0] / self.a, x[..., 1] / self.b], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = self.extent
        return np.array([-self.a * r, -self.b * r, -r * r]), np.array(
            [self.a * r, self.b * r, r * r]
        )

    def patch_margin(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        r = self.extent
        return np.minimum(r - np.abs(x[..., 0]) / self.a, r - np.abs(x[..., 1]) / self.b)

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        from ._loc import hyperbolic_paraboloid_lines

        return hyperbolic_paraboloid_lines(self, n1, n2)


def _ruled_loc(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """Cylinders (paper Example 4.1): the parameter lines are the lines of
    curvature -- ``n1`` cross-sections ``u1 = const``, ``n2`` rulings spread
    evenly by arc length along the cross-section, on every piece."""
    return _piece_lines(surface, n1, n2, ("c1", "c2"), even=True)


@attrs.frozen
class EllipticCylinder(_PatchQuadric):
    """Elliptic cylinder ``x^2/a^2 + y^2/b^2 = 1``, ``|z| <= height`` (default
    ``max(a, b)``); ``x = (a cos u2, b sin u2, u1)``.  Lines of curvature: the
    cross-sections and the rulings."""

    a: float = _positive("EllipticCylinder")
    b: float = _positive("EllipticCylinder")
    height: float = _optional_positive("EllipticCylinder")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", max(self.a, self.b))

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, self.b**-2, 0.0]), np.zeros(3), -1.0

    @property
    def domain(self) -> Domain:
        return Domain((-self.height, self.height), (0.0, 2 * np.pi), periodic=(False, True))

    def _pieces(self) -> list[tuple]:
        return [(self.domain.u1, self.domain.u2, "periodic", None)]

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * np.cos(u2), self.b * np.sin(u2), u1], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        z = np.zeros_like(u1)
        x1 = np.stack([z, z, np.ones_like(u1)], axis=-1)
        x2 = np.stack([-self.a * np.sin(u2), self.b * np.cos(u2), z], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack([x[..., 2], _angle(x[..., 1] / self.b, x[..., 0] / self.a)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        hi = np.array([self.a, self.b, self.height])
        return -hi, hi

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.height - np.abs(np.asarray(points, float)[..., 2])

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return _ruled_loc(self, n1, n2)


@attrs.frozen
class HyperbolicCylinder(_PatchQuadric):
    """Hyperbolic cylinder ``x^2/a^2 - y^2/b^2 = 1``, both branches, on
    ``|y| <= width`` (default ``2 b``) and ``|z| <= height`` (default ``max(a, b)``).

    ``u1 = z``; ``u2`` in ``[-2V, 2V]`` (``V = asinh(width/b)``) encodes the
    branch: ``u2 >= 0`` is the branch ``x > 0`` with ``v = u2 - V``, ``u2 < 0``
    the branch ``x < 0`` with ``v = u2 + V``; ``x = (+-a cosh v, b sinh v, u1)``.
    Parameter lines are drawn per branch (:meth:`!parameter_lines`).
    """

    a: float = _positive("HyperbolicCylinder")
    b: float = _positive("HyperbolicCylinder")
    height: float = _optional_positive("HyperbolicCylinder")
    width: float = _optional_positive("HyperbolicCylinder")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", max(self.a, self.b))
        _set_default(self, "width", 2 * self.b)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, -(self.b**-2), 0.0]), np.zeros(3), -1.0

    @property
    def _V(self) -> float:
        return float(np.arcsinh(self.width / self.b))

    @property
    def domain(self) -> Domain:
        return Domain((-self.height, self.height), (-2 * self._V, 2 * self._V))

    def _pieces(self) -> list[tuple]:
        V, r1 = self._V, self.domain.u1
        return [(r1, (0.0, 2 * V), "ends", (1, 1.0)), (r1, (-2 * V, 0.0), "ends", (1, -1.0))]

    def _branch(self, u2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        sg = np.where(np.signbit(u2), -1.0, 1.0)  # -0.0 belongs to the branch x < 0
        return sg, u2 - sg * self._V

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        sg, v = self._branch(u2)
        return np.stack([sg * self.a * np.cosh(v), self.b * np.sinh(v), u1], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        sg, v = self._branch(u2)
        z = np.zeros_like(u1)
        x1 = np.stack([z, z, np.ones_like(u1)], axis=-1)
        x2 = np.stack([sg * self.a * np.sinh(v), self.b * np.cosh(v), z], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        sg = np.where(x[..., 0] < 0, -1.0, 1.0)
        u2 = np.arcsinh(x[..., 1] / self.b) + sg * self._V
        return np.stack([x[..., 2], np.copysign(u2, sg)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        hi = np.array([self.a * np.cosh(self._V), self.width, self.height])
        return -hi, hi

    def patch_margin(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.minimum(self.width - np.abs(x[..., 1]), self.height - np.abs(x[..., 2]))

    def parameter_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """``n1`` cross-sections and ``n2`` rulings on each branch."""
        return _piece_lines(self, n1, n2, ("u1", "u2"), even=False)

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return _ruled_loc(self, n1, n2)


@attrs.frozen
class ParabolicCylinder(_PatchQuadric):
    """Parabolic cylinder ``z = x^2/a^2`` on ``|x| <= a extent`` (default
    ``extent = 1``), ``|y| <= length`` (default ``a``).

    ``x = (a u2, u1, u2^2)``: ``u1 = y`` runs along the rulings.
    """

    a: float = _positive("ParabolicCylinder")
    extent: float = _optional_positive("ParabolicCylinder")
    length: float = _optional_positive("ParabolicCylinder")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "extent", 1.0)
        _set_default(self, "length", self.a)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, 0.0, 0.0]), np.array([0.0, 0.0, -1.0]), 0.0

    @property
    def domain(self) -> Domain:
        return Domain((-self.length, self.length), (-self.extent, self.extent))

    def _pieces(self) -> list[tuple]:
        return [(self.domain.u1, self.domain.u2, "ends", None)]

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * u2, u1, u2 * u2], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        z = np.zeros_like(u1)
        x1 = np.stack([z, np.ones_like(u1), z], axis=-1)
        x2 = np.stack([self.a * np.ones_like(u1), z, 2 * u2], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack([x[..., 1], x[..., 0] / self.a], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = self.extent
        return np.array([-self.a * r, -self.length, 0.0]), np.array(
            [self.a * r, self.length, r * r]
        )

    def patch_margin(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.minimum(self.extent - np.abs(x[..., 0]) / self.a, self.length - np.abs(x[..., 1]))

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return _ruled_loc(self, n1, n2)
