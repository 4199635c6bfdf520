"""AlgebraicSurface: a polynomial ``F(x, y, z) = 0`` with exact derivatives and
a certain ray test; the classical algebraic surfaces as built-ins.

The polynomial is a formula of the scene-file language or a mapping
``{(i, j, k): c}`` (:mod:`!lgraph.surfaces.implicit._polynomial`); its gradient and
Hessian are exact.  Along a ray ``o + s v`` it is a polynomial of degree
``d`` in ``s``, whose crossings in the ray's interval inside the clip region
are counted with certainty by Descartes' rule of signs on Bernstein
coefficients (:mod:`!lgraph.surfaces.implicit._bernstein`).  A ray from a point on the
surface has the root ``s = 0`` divided out (twice from a contour point,
where the ray is tangent); an origin where ``F`` vanishes to rounding error
(``|F(o)| <= 1e-12`` times ``F``'s terms in absolute value: a singular point
marked by :class:`~lgraph.Singularities`, say) is treated the same way.

>>> s = AlgebraicSurface("x^2 + y^2 - z^2 - 1", radius=2)
>>> s.hit_count(np.array([[-3.0, 0, 0]]), np.array([[1.0, 0, 0]]), np.array([np.inf])).tolist()
[2]
>>> AlgebraicSurface({(1, 0, 0): 1.0, (0, 0, 0): 2.0}, radius=1).polynomial_terms()
{(0, 0, 0): 2.0, (1, 0, 0): 1.0}
>>> AlgebraicSurface("x - x", radius=1)
Traceback (most recent call last):
...
ValueError: AlgebraicSurface: polynomial must not be constant, got 'x - x'
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import attrs
import numpy as np

from ..._own import CONTOUR, OFF, ON
from ..._tolerance import ON_SURFACE_RTOL
from . import ImplicitSurface
from ._bernstein import count_roots
from ._polynomial import Polynomial

__all__ = ["AlgebraicSurface", "CayleyCubic", "ClebschCubic", "KummerSurface"]
__all__ += ["RomanSteiner", "GoursatSurface"]

#: the search grid's work: its nodes times the terms of a dense polynomial
MAX_GRID_WORK = 1e9
#: curves are seeded from certain bounds up to this degree (beyond: corner signs only)
MAX_CERTAIN_SEED_DEGREE = 6


@attrs.frozen(eq=False, repr=False)
class AlgebraicSurface(ImplicitSurface):
    """The algebraic surface ``polynomial = 0`` inside a ball or a box.

    The ray test is certain (module docstring); singular points are found by
    :class:`~lgraph.Singularities`.

    Parameters
    ----------
    polynomial : str or mapping
        A formula in ``x, y, z`` (:mod:`lgraph.formula`: sums, products,
        integer powers, division by numbers; never evaluated as Python) or
        ``{(i, j, k): c}`` for ``c x^i y^j z^k``; degree at most 12.
    radius : float, optional
        The clip ball's radius, as for :class:`~lgraph.ImplicitSurface`
        (also ``center``, ``bounds`` and ``grid``).
    constants : mapping, optional
        Named numbers the formula may use.
    """

    hit_cost: ClassVar[float] = 60.0
    hit_call_cost: ClassVar[float] = 3000.0

    polynomial: Any = attrs.field(default=None)
    constants: Any = attrs.field(default=None, kw_only=True)
    F: Any = attrs.field(init=False, default=None)
    gradient: Any = attrs.field(init=False, default=None)
    hessian: Any = attrs.field(init=False, default=None)
    lipschitz: Any = attrs.field(init=False, default=None)
    poly: Polynomial = attrs.field(init=False, default=None)

    def __attrs_post_init__(self) -> None:
        name = type(self).__name__
        if self.polynomial is None:
            raise TypeError(f"{name}: polynomial is required (a formula or {{(i, j, k): c}})")
        poly = Polynomial.from_source(self.polynomial, name, "polynomial", constants=self.constants)
        if poly.degree < 1:
            raise ValueError(f"{name}: polynomial must not be constant, got {self.polynomial!r}")
        grid = self.grid if isinstance(self.grid, int) else 0
        if grid**3 * (poly.degree + 1) ** 3 > MAX_GRID_WORK:
            most = int((MAX_GRID_WORK / (poly.degree + 1) ** 3) ** (1 / 3))
            raise ValueError(
                f"{name}: grid must be at most {most} for degree {poly.degree} (grid^3 x "
                f"(degree + 1)^3 at most {MAX_GRID_WORK:.0e}), got {self.grid!r}"
            )
        object.__setattr__(self, "poly", poly)
        object.__setattr__(self, "F", _PolyF(poly))
        super().__attrs_post_init__()

    def polynomial_terms(self) -> dict[tuple[int, int, int], float]:
        """The coefficients ``{(i, j, k): c}`` of the expanded polynomial."""
        return self.poly.terms()

    @property
    def degree(self) -> int:
        return self.poly.degree

    def implicit(self, points: Any) -> np.ndarray:
        return self.poly.value(points)

    def grad(self, points: Any) -> np.ndarray:
        return self.poly.gradient(points)

    def hess(self, points: Any) -> np.ndarray:
        return self.poly.hessian(points)

    def _fg(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return self.poly.value_gradient(x)

    def hit_count(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """The crossings of each ray with the clipped surface, counted with
        certainty (module docstring)."""
        o, v, lo, hi = self._ray_span(origins, directions, smax)
        own = np.zeros(len(o), np.int8) if own is None else np.asarray(own).ravel()
        own = np.where((own == OFF) & self._on_surface(o), ON, own)
        meets = hi > lo  # rays missing the clip region meet nothing
        q = np.zeros((len(o), self.degree + 1))
        q[meets] = self.poly.along(o[meets], v[meets])
        out = np.zeros(len(o), np.int64)
        for drop, rows in ((0, own == OFF), (1, own == ON), (2, own == CONTOUR)):
            r = np.flatnonzero(rows & meets)
            if len(r):  # s = 0 divided out once (ON) or twice (CONTOUR)
                out[r] = count_roots(q[r, drop:], lo[r], hi[r])
        return out

    def _on_surface(self, o: np.ndarray) -> np.ndarray:
        """Origins where ``F`` vanishes to rounding error."""
        bound = Polynomial(np.abs(self.poly.c)).value(np.abs(o))
        return np.abs(self.poly.value(o)) <= ON_SURFACE_RTOL * bound

    def _seed_cells(self, g_poly: Any) -> Any:
        """Certain seed cells (docs/algebraic.rst, "Seeds"): the search grid's
        cells where the Bernstein bounds of ``F`` and of ``G`` (the contour's
        or the clip sphere's polynomial; a plane's range is its corners')
        contain 0.  Up to degree ``MAX_CERTAIN_SEED_DEGREE``."""
        if self.degree > MAX_CERTAIN_SEED_DEGREE:
            return None
        from .._memo import per_surface

        grid = self._search()
        n = int(grid["n"])
        X = grid["x"].reshape(n, n, n, 3)
        axes = (X[:-1, 0, 0, 0], X[0, :-1, 0, 1], X[0, 0, :-1, 2])
        w = X[1, 1, 1] - X[0, 0, 0]
        f_cells = per_surface(self, ("F cells", n), lambda: _may_vanish(self.poly.c, axes, w))
        g = _g_polynomial(self.poly, g_poly)
        g_cells = None if g is None else _may_vanish(g, axes, w)

        def cells(candidates: np.ndarray, k: int, straddles: np.ndarray) -> np.ndarray:
            keep = f_cells[candidates]
            keep &= (straddles if g_cells is None else g_cells)[candidates]
            return candidates[keep]

        return cells

    def singular_points(self) -> np.ndarray:
        """The ordinary singular points (nodes) inside the clip region, ``(n, 3)``
        (:mod:`!lgraph.surfaces.implicit._singular`), once per surface."""
        from .._memo import per_surface
        from ._singular import singular_points

        return per_surface(self, "singular points", lambda: singular_points(self)).copy()

    def describe(self) -> str:
        return f"{type(self).__name__} {self.polynomial!r} (degree {self.degree})"


def _may_vanish(c: np.ndarray, axes: tuple[np.ndarray, ...], w: np.ndarray) -> np.ndarray:
    """Per cell of a grid (cell ``(a, b, c)`` is ``[x_a, x_a + w_x] x ...``,
    ``axes`` the lower coordinates; flat, in C order): whether the Bernstein
    bounds of the polynomial ``c`` there contain 0.  The grid is a product,
    so the Bernstein coefficients are three contractions with per-axis
    matrices, one slab of cells at a time."""
    from ._singular import _axis_maps

    d = c.shape[0] - 1
    M = [_axis_maps(d, np.stack([a, a, a], axis=1), np.full((len(a), 3), wi))[:, 0]
         for a, wi in zip(axes, w)]  # fmt: skip
    nx, ny, nz = (len(a) for a in axes)
    out = np.empty((nx, ny, nz), bool)
    t = np.einsum("pqr,bqj->bprj", c, M[1])  # y first: (ny, p, r, j)
    t = np.einsum("bprj,crk->bcpjk", t, M[2])  # (ny, nz, p, j, k)
    for a in range(nx):  # one slab of cells x_a: its coefficients, then their range
        b = np.einsum("bcpjk,pi->bcijk", t, M[0][a]).reshape(ny, nz, -1)
        pad = 1e-12 * np.abs(b).max(axis=2)
        out[a] = (b.min(axis=2) - pad <= 0) & (b.max(axis=2) + pad >= 0)
    return out.ravel()


def _g_polynomial(poly: Polynomial, spec: Any) -> np.ndarray | None:
    """The coefficients of the second equation ``G`` of a traced curve:
    ``grad F . w`` (parallel contour), ``grad F . (x - eye)`` (central), the
    clip sphere ``(|x - c|^2 - r^2) / 2``; None for planes (their corners
    decide exactly)."""
    if spec is None:
        return None
    kind = spec[0]
    d1 = poly.d1
    if kind == "parallel":
        return sum(float(wi) * di for wi, di in zip(spec[1], d1))
    if kind == "central":
        eye = spec[1]
        out = np.zeros_like(poly.c)
        for i in range(3):
            out += np.roll(d1[i], 1, axis=i) - eye[i] * d1[i]  # x_i F_i - e_i F_i
        return out
    c, r = spec[1], spec[2]
    q = np.zeros((3, 3, 3))
    q[0, 0, 0] = (float(c @ c) - r * r) / 2
    for i in range(3):
        e = [0, 0, 0]
        e[i] = 2
        q[tuple(e)] = 0.5
        e[i] = 1
        q[tuple(e)] = -c[i]
    return q


class _PolyF:
    """``F(x, y, z)`` of a polynomial (picklable)."""

    def __init__(self, poly: Polynomial) -> None:
        self.poly = poly

    def __call__(self, x: Any, y: Any, z: Any) -> np.ndarray:
        return self.poly.value(np.stack(np.broadcast_arrays(x, y, z), axis=-1))


# ---------------------------------------------------------------------------
# the classical surfaces
# ---------------------------------------------------------------------------
#: the Clebsch diagonal cubic in the affine chart where all 27 lines are real
#: and finite (see docs/algebraic.rst)
CLEBSCH = (
    "81*(x^3 + y^3 + z^3) - 189*(x^2*y + x^2*z + x*y^2 + x*z^2 + y^2*z + y*z^2) "
    "+ 54*x*y*z + 126*(x*y + x*z + y*z) - 9*(x^2 + y^2 + z^2) - 9*(x + y + z) + 1"
)


@attrs.frozen(eq=False, repr=False)
class ClebschCubic(AlgebraicSurface):
    """Clebsch's diagonal cubic surface, the cubic with 27 real lines
    (:meth:`lines`), in a ball of ``radius`` (default 1).

    >>> c = ClebschCubic()
    >>> len(c.lines()), c.degree
    (27, 3)
    """

    _shown: ClassVar[tuple[str, ...]] = ()

    polynomial: Any = attrs.field(init=False, default=CLEBSCH)
    radius: Any = attrs.field(default=1.0, kw_only=True)

    def line_data(self) -> np.ndarray:
        """The 27 lines as rows ``(p, d)``: ``p`` the line's point nearest the
        origin, ``d`` a unit direction (docs/algebraic.rst derives them)."""
        from ._clebsch import clebsch_lines

        return clebsch_lines()

    def lines(self) -> list[Any]:
        """The 27 lines as free curves (:class:`~lgraph.Curve`), each the
        exact segment inside the clip ball (lines missing the ball left out)."""
        from ...curves import Curve

        out = []
        c, r = self.clip.centre, self.clip.radius
        for row in self.line_data():
            p, d = row[:3], row[3:]
            m = p - c
            b = float(m @ d)
            disc = b * b - (float(m @ m) - r * r)
            if disc <= 0:
                continue
            half = math.sqrt(disc)
            out.append(Curve(_Line(p, d), -b - half, -b + half, derivative_func=_Dir(d)))
        return out


class _Line:
    def __init__(self, p: np.ndarray, d: np.ndarray) -> None:
        self.p, self.d = p, d

    def __call__(self, t: np.ndarray) -> np.ndarray:
        return self.p + np.asarray(t, float)[..., None] * self.d


class _Dir:
    def __init__(self, d: np.ndarray) -> None:
        self.d = d

    def __call__(self, t: np.ndarray) -> np.ndarray:
        return np.broadcast_to(self.d, np.shape(t) + (3,)).copy()


@attrs.frozen(eq=False, repr=False)
class CayleyCubic(AlgebraicSurface):
    """Cayley's nodal cubic ``x^2 + y^2 + z^2 - 2 x y z - 1 = 0``: four nodes,
    at ``(1, 1, 1)``, ``(1, -1, -1)``, ``(-1, 1, -1)``, ``(-1, -1, 1)`` (the
    most a cubic surface can have), in a ball of ``radius`` (default 2)."""

    _shown: ClassVar[tuple[str, ...]] = ()

    polynomial: Any = attrs.field(init=False, default="x^2 + y^2 + z^2 - 2*x*y*z - 1")
    radius: Any = attrs.field(default=2.0, kw_only=True)


def _kummer(mu: float) -> str:
    lam = (3 * mu * mu - 1) / (3 - mu * mu)
    r2 = math.sqrt(2)
    return (
        f"(x^2 + y^2 + z^2 - {mu * mu!r})^2 - {lam!r}*(1 - z - {r2!r}*x)*(1 - z + {r2!r}*x)"
        f"*(1 + z + {r2!r}*y)*(1 + z - {r2!r}*y)"
    )


@attrs.frozen(eq=False, repr=False)
class KummerSurface(AlgebraicSurface):
    """Kummer's quartic ``(x^2 + y^2 + z^2 - mu^2)^2 - lambda p q r s = 0``
    with ``lambda = (3 mu^2 - 1) / (3 - mu^2)`` and the four planes ``p, q =
    1 - z -+ sqrt(2) x``, ``r, s = 1 + z +- sqrt(2) y`` (a tetrahedron): 16
    real nodes for ``1 < mu^2 < 3`` (docs/algebraic.rst), in a ball of
    ``radius`` (default 3)."""

    _shown: ClassVar[tuple[str, ...]] = ("mu",)

    mu: float = attrs.field(default=1.3)
    polynomial: Any = attrs.field(init=False, default=None)
    radius: Any = attrs.field(default=3.0, kw_only=True)

    def __attrs_post_init__(self) -> None:
        mu = self.mu
        if isinstance(mu, bool) or not isinstance(mu, (int, float)) or not math.isfinite(mu):
            raise ValueError(f"KummerSurface: mu must be a finite number, got {mu!r}")
        if not (0 < mu * mu < 3) or abs(mu * mu - 1 / 3) < 1e-12:
            raise ValueError(
                f"KummerSurface: mu must satisfy 0 < mu^2 < 3, mu^2 != 1/3, got {mu!r}"
            )
        object.__setattr__(self, "polynomial", _kummer(float(mu)))
        super().__attrs_post_init__()


@attrs.frozen(eq=False, repr=False)
class RomanSteiner(AlgebraicSurface):
    """Steiner's Roman surface in implicit form ``x^2 y^2 + y^2 z^2 + z^2 x^2
    - r x y z = 0`` (the image of the sphere under ``(yz, xz, xy)``;
    it is singular along three segments of the axes), in a ball of
    ``radius`` (default ``0.6 r``)."""

    _shown: ClassVar[tuple[str, ...]] = ("r",)

    r: float = attrs.field(default=1.0)
    polynomial: Any = attrs.field(init=False, default=None)
    radius: Any = attrs.field(default=None, kw_only=True)

    def __attrs_post_init__(self) -> None:
        r = self.r
        if (
            isinstance(r, bool)
            or not isinstance(r, (int, float))
            or not (math.isfinite(r) and r > 0)
        ):
            raise ValueError(f"RomanSteiner: r must be a positive finite number, got {r!r}")
        object.__setattr__(self, "polynomial", f"x^2*y^2 + y^2*z^2 + z^2*x^2 - {float(r)!r}*x*y*z")
        if self.radius is None and self.bounds_ is None:
            object.__setattr__(self, "radius", 0.6 * float(r))
        super().__attrs_post_init__()


@attrs.frozen(eq=False, repr=False)
class GoursatSurface(AlgebraicSurface):
    """Goursat's quartic ``x^4 + y^4 + z^4 + a (x^2 + y^2 + z^2)^2 + b (x^2 +
    y^2 + z^2) + c = 0`` (the symmetries of the cube), in a ball of
    ``radius`` (default 2)."""

    _shown: ClassVar[tuple[str, ...]] = ("a", "b", "c")

    a: float = attrs.field(default=0.0)
    b: float = attrs.field(default=-1.0)
    c: float = attrs.field(default=0.5)
    polynomial: Any = attrs.field(init=False, default=None)
    radius: Any = attrs.field(default=2.0, kw_only=True)

    def __attrs_post_init__(self) -> None:
        for name in ("a", "b", "c"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"GoursatSurface: {name} must be a finite number, got {v!r}")
        a, b, c = (float(v) for v in (self.a, self.b, self.c))
        poly = f"x^4 + y^4 + z^4 + {a!r}*(x^2 + y^2 + z^2)^2 + {b!r}*(x^2 + y^2 + z^2) + {c!r}"
        object.__setattr__(self, "polynomial", poly)
        super().__attrs_post_init__()
