"""ImplicitSurface: a surface ``F(x, y, z) = 0`` clipped by a box or a ball.

It has no parametrization: its curves (the contour, plane sections, the clip
curve) are space curves ``F = 0, G = 0`` traced by
:mod:`!lgraph.surfaces.implicit._trace` (their strokes have ``uv`` None), yet they lie
on the surface and count as its own points in the ray tests.  The ray test
samples ``F`` along the part of each ray inside the clip region; given a
Lipschitz bound ``L >= |grad F|`` on the region it subdivides until every
interval either shows a sign change or is proved free of roots
(``|F(a)| + |F(b)| > L |b - a|``), which makes it certain up to a tangency
shorter than the self-hit tolerance.  Without the bound, a pair of roots
closer together than ``1 / RAY_SAMPLES`` of the ray's chord through the
region can be missed.

>>> import numpy as np
>>> s = ImplicitSurface(lambda x, y, z: x**2 + y**2 + z**2 - 1, radius=2)
>>> s.hits(np.array([[0.0, 0, -3]]), np.array([[0.0, 0, 1]]), np.array([10.0])).tolist()
[True]
>>> ImplicitSurface(lambda x, y, z: x, radius=0)
Traceback (most recent call last):
...
ValueError: ImplicitSurface: radius must be a positive finite number, got 0
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from ..._own import CONTOUR, ON
from ..._tolerance import IMPLICIT_FD_STEP as FD_STEP
from ..._tolerance import SELF_HIT_RTOL
from ..._validate import finite_positive, vector3
from ...families import level as _level  # noqa: F401  (registers "level_lines", the default)
from .._base import Surface
from ._trace import Clip, curve_batch, surface_grid, trace_curves

if TYPE_CHECKING:
    from ...curves import CurveBatch
    from ...scene.projectors import Projector

__all__ = ["ImplicitSurface"]


def _bounds(owner: str, value: Any) -> tuple[tuple[float, float], ...] | None:
    if value is None:
        return None
    try:
        b = np.array(value, dtype=float)
    except (TypeError, ValueError):
        b = None
    if b is None or b.shape != (3, 2) or not np.isfinite(b).all() or not (b[:, 0] < b[:, 1]).all():
        raise ValueError(
            f"{owner}: bounds must be ((x0, x1), (y0, y1), (z0, z1)) with finite x0 < x1, "
            f"y0 < y1, z0 < z1, got {value!r}"
        )
    return tuple((float(lo), float(hi)) for lo, hi in b)


def _callable(owner: str, optional: bool = False) -> Callable[[Any, Any, Any], None]:
    def check(_i: Any, a: Any, v: Any) -> None:
        if (v is None and optional) or callable(v):
            return
        raise TypeError(f"{owner}: {a.name} must be callable, got {type(v).__name__}")

    return check


def _optional_positive(owner: str) -> Callable[[Any, Any, Any], None]:
    def check(inst: Any, a: Any, v: Any) -> None:
        if v is not None:
            finite_positive(owner)(inst, a, v)

    return check


@attrs.frozen(eq=False, repr=False)
class ImplicitSurface(Surface):
    """The surface ``F(x, y, z) = 0`` inside a box or a ball.

    Parameters
    ----------
    F : callable
        ``F(x, y, z)`` of three arrays (broadcast together), vectorized.
    bounds : ((x0, x1), (y0, y1), (z0, z1)), optional
        The clip box.  Give ``bounds`` or ``radius``.
    radius : float, optional
        The clip ball's radius (about ``center``).
    center : 3 numbers
        The clip ball's centre (default the origin).
    gradient, hessian : callable, optional
        ``gradient(x, y, z) -> (..., 3)``, ``hessian(x, y, z) -> (..., 3, 3)``;
        numeric (fourth-order central differences) when not given.
    lipschitz : float, optional
        A bound on ``|grad F|`` in the clip region: makes the ray test
        certain (module docstring).
    grid : int
        Nodes per axis of the search grid that seeds every curve (9 to 129):
        a closed curve smaller than a grid cell can be missed.

    Curves drawn on it are space curves: strokes have ``uv`` None, and the
    parametric methods (``point``, ``domain``, ``parameter_lines``, ...)
    raise TypeError.  It draws plane sections by default
    (``LevelLines``, family ``"level"``), its contour and its clip curve
    (family ``"boundary"``).
    """

    parametric: ClassVar[bool] = False
    default_families: ClassVar[tuple[str, ...]] = ("level_lines",)
    hit_cost: ClassVar[float] = 2000.0
    hit_call_cost: ClassVar[float] = 2000.0

    F: Callable[..., Any] = attrs.field(validator=_callable("ImplicitSurface"))
    bounds_: tuple[tuple[float, float], ...] | None = attrs.field(
        default=None,
        kw_only=True,
        alias="bounds",
        converter=lambda v: _bounds("ImplicitSurface", v),
    )
    radius: float | None = attrs.field(
        default=None, kw_only=True, validator=_optional_positive("ImplicitSurface")
    )
    center: np.ndarray = attrs.field(
        default=(0.0, 0.0, 0.0),
        kw_only=True,
        converter=lambda v: vector3("ImplicitSurface", "center", v),
    )
    gradient: Callable[..., Any] | None = attrs.field(
        default=None, kw_only=True, validator=_callable("ImplicitSurface", True)
    )
    hessian: Callable[..., Any] | None = attrs.field(
        default=None, kw_only=True, validator=_callable("ImplicitSurface", True)
    )
    lipschitz: float | None = attrs.field(
        default=None, kw_only=True, validator=_optional_positive("ImplicitSurface")
    )
    grid: int = attrs.field(default=49, kw_only=True)

    def __attrs_post_init__(self) -> None:
        name = type(self).__name__
        if (self.bounds_ is None) == (self.radius is None):
            raise ValueError(f"{name}: give exactly one of bounds or radius")
        if (
            isinstance(self.grid, bool)
            or not isinstance(self.grid, int)
            or not 9 <= self.grid <= 129
        ):
            raise ValueError(f"{name}: grid must be an integer from 9 to 129, got {self.grid!r}")
        clip = self.clip
        c = clip.lo + 0.5 * (clip.hi - clip.lo)
        with np.errstate(all="ignore"):
            probe = np.asarray(self.F(*(np.full(2, v) for v in c)), dtype=float)
        if probe.shape != (2,):
            raise ValueError(
                f"{name}: F must map arrays x, y, z of shape (n,) to shape (n,), "
                f"got shape {probe.shape} for n=2"
            )

    # -- what it is ------------------------------------------------------------
    @property
    def clip(self) -> Any:
        """The clip region (box or ball)."""
        if self.radius is not None:
            r = float(self.radius)
            return Clip(self.center - r, self.center + r, r, self.center)
        b = np.array(self.bounds_)
        return Clip(b[:, 0], b[:, 1])

    @property
    def domain(self) -> Any:
        raise TypeError(
            f"{type(self).__name__} has no parametrization (no domain); its curves are "
            "space curves: use LevelLines, the contour and the boundary"
        )

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        raise TypeError(
            f"{type(self).__name__}.point: an implicit surface has no parametrization; "
            "evaluate implicit(points) instead"
        )

    def parameter_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        raise TypeError(
            f"{type(self).__name__}: an implicit surface has no parameter lines; draw "
            "LevelLines (plane sections) instead"
        )

    def lines_of_curvature(self, n1: int, n2: int, spacing: str = "complete") -> list[CurveBatch]:
        """``n1`` and ``n2`` lines of the two principal families (family
        ``"curvature"``), integrated in space from seeds spread over the
        surface (:mod:`!lgraph.surfaces.implicit._curvature`); ``spacing``
        is ignored (the lines are complete)."""
        from ._curvature import implicit_lines_of_curvature

        return implicit_lines_of_curvature(self, n1, n2)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        pad = 1e-9 * self.clip.size
        return self.clip.lo - pad, self.clip.hi + pad

    def sample_points(self) -> np.ndarray:
        """Points ``(n, 3)`` spread over the drawn surface (the centres of the
        search grid's cells that ``F = 0`` crosses, in the clip region): what a
        parameter grid is for a parametrized surface (frame windows, checks
        of the eye's position)."""
        from ._trace import _cell_centres, _cell_min, _straddles

        grid = self._search()
        n = int(grid["n"])
        cells = _straddles(grid["f"], n) & (_cell_min(grid["clip"], n) <= 0)
        return _cell_centres(grid["x"], n)[cells]

    def implicit(self, points: Any) -> np.ndarray:
        """``F`` at points ``(..., 3)``."""
        p = np.asarray(points, dtype=float)
        return np.asarray(self.F(p[..., 0], p[..., 1], p[..., 2]), dtype=float)

    def grad(self, points: Any) -> np.ndarray:
        """``grad F`` at points ``(..., 3)`` (given, or fourth-order differences)."""
        p = np.asarray(points, dtype=float)
        if self.gradient is not None:
            return np.asarray(self.gradient(p[..., 0], p[..., 1], p[..., 2]), float)
        h = FD_STEP * self.clip.size
        f = self.implicit(p[..., None, :] + h * _STENCIL1)  # all 12 points in one call
        return f @ _W1 / h

    def hess(self, points: Any) -> np.ndarray:
        """The Hessian of ``F`` at points ``(..., 3, 3)`` (given, or second-order
        central differences: it only steers Newton's method)."""
        p = np.asarray(points, dtype=float)
        if self.hessian is not None:
            return np.asarray(self.hessian(p[..., 0], p[..., 1], p[..., 2]), float)
        h = 10 * FD_STEP * self.clip.size
        f = self.implicit(p[..., None, :] + h * _STENCIL2) / (h * h)
        c = f[..., :1]
        diag = f[..., 1:4] + f[..., 4:7] - 2 * c  # f(x + h e_i) + f(x - h e_i) - 2 f(x)
        H = np.zeros(p.shape + (3,))
        for k, (i, j) in enumerate(((0, 1), (0, 2), (1, 2))):
            q = f[..., 7 + 4 * k : 11 + 4 * k]  # (+,+), (+,-), (-,+), (-,-)
            H[..., i, j] = H[..., j, i] = (q[..., 0] - q[..., 1] - q[..., 2] + q[..., 3]) / 4
        H[..., [0, 1, 2], [0, 1, 2]] = diag
        return H

    def normal_at(self, points: Any) -> np.ndarray:
        """The unit normal ``grad F / |grad F|`` at points ``(..., 3)``."""
        g = self.grad(points)
        with np.errstate(all="ignore"):
            return g / np.linalg.norm(g, axis=-1, keepdims=True)

    def _fg(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        with np.errstate(all="ignore"):
            return self.implicit(x), self.grad(x)

    def _search(self) -> dict[str, np.ndarray]:
        """The search grid (F and grad F at its nodes), once per surface."""
        from .._memo import per_surface

        def compute() -> dict[str, np.ndarray]:
            g = surface_grid(self.F, self.grad, self.clip, self.grid)
            g["clip"] = self.clip.excess(g["x"])[0]
            return g

        return per_surface(self, ("implicit grid", self.grid), compute)

    def _seed_cells(self, g_poly: Any) -> Any:
        """``cells(candidates, k)`` for :func:`~lgraph.surfaces.implicit._trace.trace_curves`
        (certain bounds of ``F`` and ``G_k`` per cell), or None: general
        surfaces have none."""
        return None

    def _curves(
        self, family: str, gg: Any, g_on_grid: np.ndarray, g_poly: Any = None
    ) -> list[CurveBatch]:
        grid = self._search()
        cells = self._seed_cells(g_poly)
        curves = trace_curves(self._fg, gg, self.clip, grid, g_on_grid, grid["clip"], cells)
        return curve_batch(self, family, curves, self._fg, gg)

    # -- what it draws -----------------------------------------------------------
    def boundary(self) -> list[CurveBatch]:
        """The clip curve (family ``"boundary"``): ``F = 0`` on the sphere or
        on the faces of the box."""
        from .._memo import per_surface

        return per_surface(self, "boundary", self._boundary)

    def _boundary(self) -> list[CurveBatch]:
        clip, X = self.clip, self._search()["x"]
        if clip.radius is not None:
            c, r = clip.centre, clip.radius

            def sphere(x: np.ndarray, _idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
                d = x - c
                return (np.einsum("ij,ij->i", d, d) - r * r) / (2 * r), d / r

            on_grid = (np.sum((X - c) ** 2, axis=1) - r * r) / 2
            return self._curves("boundary", sphere, on_grid, ("sphere", c, r))
        normals = np.repeat(np.eye(3), 2, axis=0)
        offsets = np.stack([clip.lo, clip.hi], axis=1).ravel()
        return self._curves("boundary", _planes(normals, offsets), (X @ normals.T - offsets).T)

    def contour(self, projector: Projector) -> list[CurveBatch]:
        """The contour ``F = 0, grad F . v = 0`` (``v`` the view direction; for a
        central projection ``grad F . (x - eye) = 0``)."""
        from ...scene.projectors import CentralProjector

        grid = self._search()
        if isinstance(projector, CentralProjector):
            eye = np.asarray(projector.eye, float)

            def gg(x: np.ndarray, _idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
                with np.errstate(all="ignore"):
                    g, H = self.grad(x), self.hess(x)
                return np.einsum("ij,ij->i", g, x - eye), np.einsum("nij,nj->ni", H, x - eye) + g

            on_grid = np.einsum("ij,ij->i", grid["g"], grid["x"] - eye)
            g_poly: Any = ("central", eye)
        else:
            w = np.asarray(projector.frame[2], float)

            def gg(x: np.ndarray, _idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
                with np.errstate(all="ignore"):
                    return self.grad(x) @ w, self.hess(x) @ w

            on_grid = grid["g"] @ w
            g_poly = ("parallel", w)
        return self._curves("contour", gg, on_grid, g_poly)

    def height_range(self, direction: Any) -> tuple[float, float]:
        """The range of ``x . direction`` (unit) over the drawn surface,
        estimated on the search grid (the cells that ``F = 0`` crosses)."""
        h = self.sample_points() @ np.asarray(direction, float)
        if not len(h):
            return 0.0, 0.0
        return float(h.min()), float(h.max())

    def level_lines(self, direction: Any, values: Any) -> list[CurveBatch]:
        """The plane sections ``x . direction = value`` (family ``"level"``)."""
        d = np.asarray(direction, float)
        d = d / np.linalg.norm(d)
        values = np.atleast_1d(np.asarray(values, float))
        normals = np.broadcast_to(d, (len(values), 3))
        X = self._search()["x"]
        on_grid = (X @ d)[None, :] - values[:, None]
        return self._curves("level", _planes(normals, values), on_grid)

    def meeting_curves(self, other: Any, placement: Any) -> list[CurveBatch]:
        """The curves where this surface meets ``other`` (whose local
        coordinates ``placement`` maps into this surface's), family
        ``"intersection"``: ``F = 0, G = 0`` with ``G`` the other's implicit
        equation (numeric gradient), traced like the contour.  Only surfaces
        with an equation that bound a solid (sphere, ellipsoid, torus, ...)
        or are implicit themselves (then cut to their clip region too, the
        ends there to the tracing step); for others nothing is drawn, with a
        warning."""
        import warnings

        G = getattr(other, "implicit", None)
        closed = G is not None and (
            not getattr(other, "parametric", True) or other._solid() is not None
        )
        if not closed:
            warnings.warn(
                f"{type(self).__name__}: the intersection with {type(other).__name__} is not "
                "drawn (implicit surfaces meet closed or implicit surfaces only)",
                stacklevel=2,
            )
            return []
        back = placement.inverse()
        h = FD_STEP * self.clip.size

        def gval(x: np.ndarray) -> np.ndarray:
            with np.errstate(all="ignore"):
                return np.asarray(G(back.apply(x)), float)

        def gg(x: np.ndarray, _idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            f = gval(x[..., None, :] + h * _STENCIL1)
            return gval(x), f @ _W1 / h

        grid = self._search()
        curves = trace_curves(self._fg, gg, self.clip, grid, gval(grid["x"]), grid["clip"])
        other_clip = getattr(other, "clip", None)
        if other_clip is not None:
            curves = _inside_runs(curves, lambda x: other_clip.excess(back.apply(x))[0] <= 0)
        return curve_batch(self, "intersection", curves, self._fg, gg)

    # -- what it hides -------------------------------------------------------------
    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Whether each ray meets the clipped surface (module docstring)."""
        return self.hit_count(origins, directions, smax, own) > 0

    def hit_count(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """The sign changes of ``F`` along each ray inside the clip region."""
        from ._hits import sampled_crossings

        o, v, lo, hi = self._ray_span(origins, directions, smax)
        start = None if own is None else self._start_sign(o, v, np.asarray(own).ravel())
        return sampled_crossings(self.implicit, o, v, lo, hi, self.lipschitz, start)

    def _start_sign(self, o: np.ndarray, v: np.ndarray, own: np.ndarray) -> np.ndarray:
        """For rays from points on the surface, the sign of ``F(o + s v)`` for
        small ``s > 0`` from its Taylor series (``F(o) = 0``): that of
        ``grad F . v``, or of ``v^T H v`` where the ray is tangent (a contour
        point, or ``grad F . v`` zero); 0 for the other rays."""
        out = np.zeros(len(o))
        rows = np.flatnonzero((own == ON) | (own == CONTOUR))
        if not len(rows):
            return out
        oo, vv = o[rows], v[rows]
        with np.errstate(all="ignore"):
            g = self.grad(oo)
            q = np.einsum("ni,nij,nj->n", vv, self.hess(oo), vv)
        first = np.where(own[rows] == CONTOUR, 0.0, np.einsum("ij,ij->i", g, vv))
        out[rows] = np.where(first != 0, np.sign(first), np.sign(q))
        return np.nan_to_num(out)

    def _ray_span(self, origins: Any, directions: Any, smax: Any) -> tuple[np.ndarray, ...]:
        """Rays as arrays and the interval ``(lo, hi)`` of ``s`` that counts:
        past the self-hit tolerance, before ``smax``, inside the clip region."""
        o = np.asarray(origins, dtype=float).reshape(-1, 3)
        v = np.asarray(directions, dtype=float).reshape(-1, 3)
        smax = np.broadcast_to(np.asarray(smax, dtype=float), (len(o),))
        s_in, s_out = self.clip.ray_interval(o, v)
        eps = SELF_HIT_RTOL * self.clip.size / np.linalg.norm(v, axis=1)
        return o, v, np.maximum(s_in, eps), np.minimum(s_out, smax)

    def describe(self) -> str:
        where = f"radius {self.radius:g}" if self.radius is not None else f"bounds {self.bounds_}"
        return f"{type(self).__name__} ({where})"

    def __repr__(self) -> str:
        what = getattr(self, "polynomial", None)
        head = repr(what) if isinstance(what, str) else getattr(self.F, "__name__", "F")
        shown = getattr(type(self), "_shown", None)  # a built-in: its parameters
        if shown is not None:
            head = ", ".join(f"{k}={getattr(self, k)!r}" for k in shown)
        if self.radius is not None:
            where = f"radius={self.radius!r}"
            if np.any(self.center):
                where += f", center={tuple(self.center.tolist())}"
        else:
            where = f"bounds={self.bounds_}"
        return f"{type(self).__name__}({', '.join(x for x in (head, where) if x)})"


def _inside_runs(curves: list, inside: Any) -> list:
    """The runs of each traced curve's points where ``inside`` holds."""
    out = []
    for pts, closed, k in curves:
        m = inside(pts)
        if m.all():
            out.append((pts, closed, k))
            continue
        edges = np.flatnonzero(np.diff(np.concatenate([[0], m.astype(int), [0]])))
        for a, b in zip(edges[::2], edges[1::2]):
            if b - a >= 2:
                out.append((pts[a:b], False, k))
    return out


def _stencils() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Offsets (in steps) and weights of the numeric gradient (fourth order)
    and the points of the numeric Hessian."""
    e = np.eye(3)
    s1 = np.concatenate([k * e for k in (-2, -1, 1, 2)])  # rows: offset k along axis i
    w1 = np.concatenate([c * e for c in (1 / 12, -8 / 12, 8 / 12, -1 / 12)])  # (12, 3)
    rows = [np.zeros(3), *e, *(-e)]
    for i, j in ((0, 1), (0, 2), (1, 2)):
        rows += [e[i] + e[j], e[i] - e[j], -e[i] + e[j], -e[i] - e[j]]
    return s1, w1, np.array(rows)


_STENCIL1, _W1, _STENCIL2 = _stencils()


def _planes(normals: np.ndarray, offsets: np.ndarray) -> Any:
    """``G_k(x) = n_k . x - c_k`` and its gradient, per curve ``k``."""
    normals = np.asarray(normals, float)
    offsets = np.asarray(offsets, float)

    def gg(x: np.ndarray, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        n = normals[idx]
        return np.einsum("ij,ij->i", x, n) - offsets[idx], n

    return gg
