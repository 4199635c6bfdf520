"""The Surface base class: what a surface is, what it draws, what it hides.

A subclass must supply :meth:`Surface.point` and a :attr:`Surface.domain`.
Derivatives, normals and fundamental forms have numeric defaults here; classes
override them with analytic formulas.  :meth:`Surface.contour` and
:meth:`Surface.hits` are the two questions the renderer asks; a surface with
analytic answers overrides them.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Any

import numpy as np

from .._own import CONTOUR, OFF, ON
from .._tolerance import FD_STEP_1, FD_STEP_2
from ._domain import Domain, domain_flags  # noqa: F401 - domain_flags: re-exported

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..scene.projectors import Projector

__all__ = ["Domain", "Surface", "OFF", "ON", "CONTOUR", "numeric_ray_test"]


# fourth-order central stencils at offsets -2, -1, 1, 2 (first and second derivative;
# the second derivative's centre weight is -5/2)
_OFF = (-2.0, -1.0, 1.0, 2.0)
_W1 = (1 / 12, -2 / 3, 2 / 3, -1 / 12)
_W2 = (-1 / 12, 4 / 3, 4 / 3, -1 / 12)
#: the five nodes -2..2 of a stencil shifted by 0, +-1 or +-2 steps (rows:
#: shift -2..2), so that near an edge of the patch every node lies inside it
_NODES = np.arange(-2.0, 3.0)[None, :] + np.arange(-2.0, 3.0)[:, None]


def _shifted_weights(order: int) -> np.ndarray:
    """Weights ``(5, 5)`` of the derivative of ``order`` at 0 from values at
    the nodes ``_NODES[shift + 2]`` (exact for quartics); the centred row is
    the classical one (its centre weight 0 for the first derivative)."""
    w = np.empty((5, 5))
    rhs = np.zeros(5)
    rhs[order] = float(order)  # k! for k = 1, 2
    for row, t in enumerate(_NODES):
        w[row] = np.linalg.solve(np.vander(t, 5, increasing=True).T, rhs)
    w[2] = (_W1[0], _W1[1], 0.0, _W1[2], _W1[3]) if order == 1 else (
        _W2[0], _W2[1], -2.5, _W2[2], _W2[3])  # fmt: skip
    return w


_SW1, _SW2 = _shifted_weights(1), _shifted_weights(2)


def _shifts(domain: Domain, i: int, u: np.ndarray, h: float) -> np.ndarray:
    """Integer shifts (-2..2) of the stencils at ``u`` along ``u_i`` (step
    ``h``) that keep their nodes inside the rectangle: 0 away from the edges
    and for glued parameters (their values past a seam are mapped back)."""
    if domain.glued[i]:
        return np.zeros(u.shape, int)
    lo, hi = domain.range(i)
    with np.errstate(invalid="ignore"):
        up = np.clip(np.ceil(2.0 - (u - lo) / h - 1e-9), 0, 2)
        down = np.clip(np.ceil(2.0 - (hi - u) / h - 1e-9), 0, 2)
    return np.nan_to_num(up - down).astype(int)


class Surface:
    """Base class of all surfaces.

    Subclasses are frozen attrs classes that define :attr:`!domain` and
    :meth:`!point`; everything else has a default.  Vectorized methods take
    broadcastable arrays ``u1, u2`` and return arrays of shape ``(..., 3)``.

    Parameters that are not numbers are reported by name, whatever the class:

    >>> import lgraph as lg
    >>> lg.Sphere(1).point("north", 0.0)
    Traceback (most recent call last):
    ...
    TypeError: Sphere.point: u1 must be a number or an array of numbers, got str
    """

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        impl = cls.__dict__.get("point")
        if impl is None or getattr(impl, "_checked", False):
            return

        @functools.wraps(impl)
        def point(self: Surface, u1: Any, u2: Any) -> np.ndarray:
            try:
                return impl(self, u1, u2)
            except (TypeError, ValueError):
                # only on failure: name a parameter that is not numeric
                for name, value in (("u1", u1), ("u2", u2)):
                    try:
                        np.asarray(value, dtype=float)
                    except (TypeError, ValueError):
                        raise TypeError(
                            f"{type(self).__name__}.point: {name} must be a number or an array "
                            f"of numbers, got {type(value).__name__}"
                        ) from None
                raise

        point._checked = True  # type: ignore[attr-defined]
        cls.point = point  # type: ignore[method-assign]

    #: Cost of ``hits``: per ray, and fixed per call, in units of one grouped
    #: quadric test (about 0.3 us here).  The renderer uses them to choose how
    #: many points to test at once when locating visibility flips.
    hit_cost: float = 400.0
    hit_call_cost: float = 1e5

    #: Families drawn when a node is added with none (besides the contour).
    default_families: tuple[str, ...] = ("parameter_lines",)

    #: The family name its contour's strokes get (and its style key): figure
    #: objects such as :class:`~lgraph.Arrow` say ``"arrow"``.  Visibility
    #: treats the curves as a contour whatever the name.
    outline_family: str = "contour"

    # -- what it is ---------------------------------------------------------
    @property
    def domain(self) -> Domain:  # pragma: no cover - abstract
        raise NotImplementedError(f"{type(self).__name__} must define a domain")

    def point(self, u1: Any, u2: Any) -> np.ndarray:  # pragma: no cover - abstract
        """Point ``x(u1, u2)``, shape ``broadcast(u1, u2).shape + (3,)``."""
        raise NotImplementedError(f"{type(self).__name__} must define point(u1, u2)")

    def points(self, uv: np.ndarray) -> np.ndarray:
        """``point`` of an ``(..., 2)`` array of parameters."""
        uv = np.asarray(uv, dtype=float)
        return self.point(uv[..., 0], uv[..., 1])

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned box ``(lo, hi)`` containing the drawn patch (local coords).

        The default samples the domain on a 65 x 65 grid and pads by a few
        percent, once per surface object (surfaces are immutable; see
        :mod:`!lgraph.surfaces._memo`).
        """
        from ._memo import per_surface

        def sampled() -> tuple[np.ndarray, np.ndarray]:
            d = self.domain
            u1, u2 = np.meshgrid(np.linspace(*d.u1, 65), np.linspace(*d.u2, 65), indexing="ij")
            p = self.point(u1, u2).reshape(-1, 3)
            lo, hi = p.min(axis=0), p.max(axis=0)
            pad = 0.05 * (hi - lo).max() + 1e-12
            return lo - pad, hi + pad

        lo, hi = per_surface(self, "bounds", sampled)
        return lo.copy(), hi.copy()

    @property
    def size(self) -> float:
        """Characteristic length (diagonal of :meth:`bounds`)."""
        lo, hi = self.bounds()
        return float(np.linalg.norm(hi - lo))

    # -- derivatives and fundamental forms ----------------------------------
    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        """First partial derivatives ``x1 = dx/du1`` and ``x2 = dx/du2``.

        Default: fourth-order finite differences (all stencil points in one
        call of :meth:`!point`), central away from the edges of the patch and
        shifted inward near an edge that is not glued, so that ``point`` is
        only evaluated inside the rectangle.

        >>> import lgraph as lg
        >>> s = lg.ParametricSurface(lambda u, v: np.stack(np.broadcast_arrays(u, v, u**3), -1),
        ...                          (0, 1), (0, 1))
        >>> bool(abs(s.derivatives(1.0, 0.0)[0][2] - 3.0) < 1e-9)
        True
        """
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        d = self.domain
        h1 = FD_STEP_1 * d.span(0)
        h2 = FD_STEP_1 * d.span(1)
        k1, k2 = _shifts(d, 0, u1, h1), _shifts(d, 1, u2, h2)
        t1 = np.moveaxis(_NODES[k1 + 2], -1, 0)  # (5, ...)
        t2 = np.moveaxis(_NODES[k2 + 2], -1, 0)
        zero = np.zeros_like(t1)
        p = self._stencil(u1, u2, np.concatenate([t1 * h1, zero]), np.concatenate([zero, t2 * h2]))
        w1 = np.moveaxis(_SW1[k1 + 2], -1, 0)[..., None]
        w2 = np.moveaxis(_SW1[k2 + 2], -1, 0)[..., None]
        return (w1 * p[:5]).sum(axis=0) / h1, (w2 * p[5:]).sum(axis=0) / h2

    derivatives.finite_differences = True  # type: ignore[attr-defined]

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Second partial derivatives ``x11, x12, x22``.

        Default: finite differences of ``point`` on a 5 x 5 grid of steps
        ``FD_STEP_2`` of the spans (central away from the edges, rounding and
        truncation errors both near ``1e-10``: smooth enough for ODE solvers;
        shifted inward near an edge that is not glued, like
        :meth:`derivatives`), all 25 points in one call of :meth:`!point`.
        """
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        d = self.domain
        h1 = FD_STEP_2 * d.span(0)
        h2 = FD_STEP_2 * d.span(1)
        k1, k2 = _shifts(d, 0, u1, h1), _shifts(d, 1, u2, h2)
        t1 = np.moveaxis(_NODES[k1 + 2], -1, 0)  # (5, ...)
        t2 = np.moveaxis(_NODES[k2 + 2], -1, 0)
        # the grid (i, j) -> row 5 i + j
        d1 = np.repeat(t1, 5, axis=0) * h1
        d2 = np.tile(t2, (5,) + (1,) * u1.ndim) * h2
        p = self._stencil(u1, u2, d1, d2).reshape((5, 5) + u1.shape + (3,))
        # the grid's rows through the point itself (node 0 is at index 2 - shift)
        c2 = (2 - k2)[None, None, ..., None]
        c1 = (2 - k1)[None, None, ..., None]
        along1 = np.take_along_axis(p, c2, axis=1)[:, 0]
        along2 = np.take_along_axis(p, c1, axis=0)[0]
        a1 = np.moveaxis(_SW2[k1 + 2], -1, 0)[..., None]
        a2 = np.moveaxis(_SW2[k2 + 2], -1, 0)[..., None]
        x11 = (a1 * along1).sum(axis=0) / (h1 * h1)
        x22 = (a2 * along2).sum(axis=0) / (h2 * h2)
        b1 = np.moveaxis(_SW1[k1 + 2], -1, 0)[:, None, ..., None]
        b2 = np.moveaxis(_SW1[k2 + 2], -1, 0)[None, :, ..., None]
        x12 = (b1 * b2 * p).sum(axis=(0, 1)) / (h1 * h2)
        return x11, x12, x22

    def _stencil(
        self, u1: np.ndarray, u2: np.ndarray, d1: np.ndarray, d2: np.ndarray
    ) -> np.ndarray:
        """``point(u1 + d1[k], u2 + d2[k])`` for every row ``k``, in one call."""
        return np.asarray(self.point(u1 + d1, u2 + d2), dtype=float)

    def normal(self, u1: Any, u2: Any) -> np.ndarray:
        """Unit normal ``N = x1 x x2 / |x1 x x2|`` (the paper's, §3).

        Its orientation follows the parametrization: for :class:`Sphere` and
        :class:`Ellipsoid` (latitude ``u1``, longitude ``u2``) it points
        *inward*.  For closed surfaces :meth:`outward_normal` gives the
        outward one.
        """
        x1, x2 = self.derivatives(u1, u2)
        n = np.cross(x1, x2)
        norm = np.linalg.norm(n, axis=-1, keepdims=True)
        with np.errstate(invalid="ignore", divide="ignore"):
            return n / norm

    def _solid(self) -> Any:
        """For a closed surface bounding a solid: its implicit function
        (negative inside); otherwise None."""
        return None

    def outward_normal(self, u1: Any, u2: Any) -> np.ndarray:
        """Unit normal pointing out of the solid a closed surface bounds.

        :meth:`normal` with its sign chosen so that the surface's implicit
        function (negative inside) grows along it.  Raises ValueError for a
        surface that bounds no solid (a patch, an open or unbounded surface).

        >>> import lgraph as lg
        >>> n = lg.Sphere(2).outward_normal(0.3, 1.0)
        >>> p = lg.Sphere(2).point(0.3, 1.0)
        >>> bool(np.allclose(n, p / 2))
        True
        """
        f = self._solid()
        if f is None:
            raise ValueError(
                f"{type(self).__name__}: outward_normal needs a closed surface that bounds a "
                "solid (sphere, ellipsoid, torus, ...); use normal() and choose its sign"
            )
        n = self.normal(u1, u2)
        x = self.point(u1, u2)
        lo, hi = self.bounds()
        h = 1e-6 * float(np.linalg.norm(np.asarray(hi) - np.asarray(lo)))
        sign = np.where(f(x + h * n) >= f(x - h * n), 1.0, -1.0)
        return n * sign[..., None]

    def first_fundamental_form(self, u1: Any, u2: Any) -> tuple[np.ndarray, ...]:
        """``g11, g12, g22`` (``g_ik = x_i . x_k``)."""
        x1, x2 = self.derivatives(u1, u2)
        return (
            np.einsum("...i,...i", x1, x1),
            np.einsum("...i,...i", x1, x2),
            np.einsum("...i,...i", x2, x2),
        )

    def second_fundamental_form(self, u1: Any, u2: Any) -> tuple[np.ndarray, ...]:
        """``L11, L12, L22`` (``L_ik = N . x_ik``)."""
        n = self.normal(u1, u2)
        x11, x12, x22 = self.second_derivatives(u1, u2)
        return (
            np.einsum("...i,...i", n, x11),
            np.einsum("...i,...i", n, x12),
            np.einsum("...i,...i", n, x22),
        )

    def principal_curvatures(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        """Principal curvatures ``k1 <= k2`` (sign follows the normal :meth:`normal`)."""
        from ..curvature import principal_curvatures

        return principal_curvatures(self, u1, u2)

    def principal_directions(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        """Unit 3-D principal directions ``(e1, e2)`` belonging to ``k1 <= k2``."""
        from ..curvature import principal_directions

        return principal_directions(self, u1, u2)

    # -- what it draws -------------------------------------------------------
    def boundary(self) -> list[CurveBatch]:
        """The edges of the drawn patch (family ``"boundary"``), drawn by default
        like the contour: the parameter lines at the non-periodic, non-pole ends
        of the domain, and, on a surface with the numeric contour, the singular
        curves of its parametrization inside the domain (cuspidal edges; see
        :mod:`!lgraph.surfaces.parametric._singular_edges`).  Surfaces made of several
        pieces override this."""
        from ..families._lines import parameter_line_batches

        d = self.domain
        edges = parameter_line_batches(self, d.ends(0), d.ends(1), "boundary", "boundary")
        if type(self).contour is Surface.contour:
            from .parametric._singular_edges import singular_edge_batches

            edges = edges + singular_edge_batches(self)
        return edges

    def parameter_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """``n1`` lines ``u1 = const`` (family ``"u1"``) and ``n2`` lines
        ``u2 = const`` (``"u2"``), spread by :meth:`Domain.lines`.  Surfaces made
        of several pieces override this."""
        from ..families._lines import parameter_line_batches

        d = self.domain
        return parameter_line_batches(self, d.lines(0, n1), d.lines(1, n2))

    def contour(self, projector: Projector) -> list[CurveBatch]:
        """Contour curves for ``projector`` (given in this surface's local frame).

        Default: numeric (marching squares on ``N . w = 0``, refined by Newton;
        see :mod:`!lgraph.surfaces.parametric._contour`).
        """
        from .parametric._contour import contour

        return contour(self, projector)

    def lines_of_curvature(self, n1: int, n2: int, spacing: str = "complete") -> list[CurveBatch]:
        """``n1`` and ``n2`` lines of the two principal families.

        Default: numeric integration of the principal direction field (see
        :func:`lgraph.families.numeric.numeric_lines_of_curvature`; ``spacing`` is
        ``"complete"`` or ``"even"``); classes with closed forms override it.
        """
        from ..families.numeric import numeric_lines_of_curvature

        return numeric_lines_of_curvature(self, n1, n2, spacing=spacing)

    lines_of_curvature.numeric = True  # type: ignore[attr-defined]

    # -- what it hides -------------------------------------------------------
    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Which rays ``origins + s * directions``, ``0 < s < smax``, meet the drawn patch.

        ``own`` (same length, optional) tells for each origin whether it lies on
        this surface (:data:`!ON`), on its contour (:data:`!CONTOUR`) or not
        (:data:`!OFF`); a ray never counts its own origin as a hit.
        Directions need not be unit vectors; ``s`` is measured in their units.

        Default: numeric (bounding-box hierarchy + Newton; see
        :mod:`!lgraph.surfaces.parametric._hits`).
        """
        from .parametric._hits import hits

        return hits(self, origins, directions, smax, own)

    def hit_count(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """How many times each ray ``origins + s * directions``, ``0 < s <
        smax``, crosses the drawn patch (int array; arguments as :meth:`hits`).
        The renderer asks it for the occlusion depth of hidden strokes
        (``Stroke.occlusion``).

        Default: for a surface that uses the numeric ray test, the distinct
        roots of every patch box the ray meets (see
        :mod:`!lgraph.surfaces.parametric._hits`); a class with a ray test of its
        own counts 1 where :meth:`hits` is True (a lower bound: override this
        method to count exactly, as quadrics, tori and planes do).
        """
        if type(self).hits is not Surface.hits:
            return np.asarray(self.hits(origins, directions, smax, own), dtype=np.int64)
        from .parametric._hits import hits

        return hits(self, origins, directions, smax, own, count=True)

    def visibility_margins(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray,
        uv: np.ndarray | None = None,
        which: int | None = None,
    ) -> np.ndarray | None:
        """Continuous functions of a point on this surface whose sign changes
        mark where the surface may start or stop hiding it, or None (default).

        Optional: ``(k, n)`` values of order 1 (dimensionless), NaN where a
        function does not apply; for
        example minus the normal component of the ray (zero where the point
        crosses the surface's own contour), or how far the ray passes from a
        boundary curve.  The renderer locates a visibility flip of this
        surface's curves by root finding on the first function that changes
        sign across it (instead of repeated ray tests), and verifies every
        result with :meth:`hits`; flips of other kinds are found by bisection.
        ``own`` as for :meth:`hits`; ``uv`` (optional, ``(n, 2)``): the
        origins' parameters, when the caller knows them (NaN rows: unknown);
        ``which``: only that function (a ``(1, n)`` result).
        """
        return None

    def describe(self) -> str:
        return repr(self)


def numeric_ray_test(surface: Any) -> bool:
    """Whether ``surface`` is tested by the numeric ray test (the default
    :meth:`Surface.hits`, :mod:`!lgraph.surfaces.parametric._hits`)."""
    return surface is not None and type(surface).hits is Surface.hits
