"""Surfaces of revolution: a meridian profile ``t -> (rho, z)`` turned about an axis.

``x(t, phi) = rho(t) (cos phi e1 + sin phi e2) + z(t) a`` with ``u1 = t`` (along
the meridian) and ``u2 = phi`` (around the axis ``a``).  Everything the
renderer asks has a closed form or a 1-D reduction:

* **lines of curvature**: the meridians ``phi = const`` and the parallels
  ``t = const`` (``F = x1 . x2 = 0`` and ``M = N . x12 = 0`` identically), i.e. the
  parameter lines, exact;
* **contour**: on the parallel ``t`` the normal is
  ``N = (rho' a - z' r(phi)) / |P'|``; ``N . w = 0`` becomes
  ``z' R0 cos(phi - psi0) = C(t)`` with ``(R0, psi0)`` the polar form of the
  view vector (parallel view) or of the eye (central view) in the plane
  ``(e1, e2)`` and ``C = rho' w_a`` (parallel) or ``C = z' rho + rho' (e_a - z)``
  (central, eye ``e``): two points ``phi = psi0 +- arccos(C / (z' R0))`` per
  parallel.  The contour's folds (``(z' R0)^2 = C^2``) are found on a grid in
  ``t`` and refined; each curve is parametrized so that it stays smooth through
  its folds;
* **ray hits**: a line with unit direction ``v`` meets the parallel ``t``
  exactly when ``c^2 (rho^2 - d^2) = k^2 (z - h*)^2`` (``c = v . a``,
  ``k^2 = 1 - c^2``, ``d`` the line's distance from the axis, ``h*`` the height
  of its closest approach): the meridian section of the hyperboloid the line
  sweeps.  This 1-D function of ``t`` is scanned on a grid with its derivative;
  sign changes are bracketed and refined, and every grid cell where the
  function turns back toward zero has its extremum located, so pairs of
  nearby roots (grazing rays) are not missed (see
  :mod:`lgraph.surfaces.revolution._hits`).

>>> import numpy as np
>>> import lgraph as lg
>>> s = SurfaceOfRevolution(lg.named_profile("circle"), (0, 2 * np.pi))
>>> s.point(0.0, np.pi / 2).round(12).tolist()
[0.0, 3.0, 0.0]
>>> SurfaceOfRevolution(lambda t: (t - 1, t), (0, 2))
Traceback (most recent call last):
...
ValueError: SurfaceOfRevolution: profile must have rho >= 0, got rho=-1 at t=0
>>> SurfaceOfRevolution(lambda t: (1 + t * 0, t), (1, 1))
Traceback (most recent call last):
...
ValueError: SurfaceOfRevolution: t_range must be a pair (lo, hi) ... with lo < hi, got (1, 1)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from ..._own import OFF
from ..._tolerance import FD_STEP_2
from ..._validate import count, interval, vector3
from ...curves import _d1, _d2
from .._base import Domain, Surface
from .profiles import Profile, named_profile, profile_from_points

if TYPE_CHECKING:
    from ...curves import CurveBatch
    from ...scene.projectors import Projector

__all__ = ["SurfaceOfRevolution", "Pseudosphere", "revolution_from_profile"]

_TWO_PI = 2 * math.pi


def _frame(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Orthonormal ``(e1, e2, a)``; for the z axis exactly ``(x, y, z)``."""
    a = axis / np.linalg.norm(axis)
    helper = np.array([1.0, 0.0, 0.0]) if abs(a[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = helper - (helper @ a) * a
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    return e1, e2, a


def _pair(value: Any, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """A profile's ``(rho, z)`` as two float arrays of ``shape``."""
    r, z = value
    r, z = np.asarray(r, float), np.asarray(z, float)
    if r.shape != shape:
        r = np.broadcast_to(r, shape)
    if z.shape != shape:
        z = np.broadcast_to(z, shape)
    return r, z


def _as_profile(value: Any) -> Any:
    """A profile: a callable as given, a name of a built-in profile
    (:data:`~lgraph.surfaces.revolution.profiles.PROFILES`, default parameters) or knots
    ``[[rho, z], ...]`` interpolated by a spline."""
    if callable(value):
        return value
    if isinstance(value, str):
        try:
            return named_profile(value)
        except ValueError as exc:
            raise ValueError(f"SurfaceOfRevolution: profile: {exc}") from None
    if isinstance(value, (list, tuple, np.ndarray)):
        return profile_from_points(value)
    raise TypeError(
        "SurfaceOfRevolution: profile must be callable, a profile name or [[rho, z], ...] "
        f"knots, got {type(value).__name__}"
    )


def _axis(value: Any) -> np.ndarray:
    return vector3("SurfaceOfRevolution", "axis", value, nonzero=True)


@attrs.frozen(eq=False)
class SurfaceOfRevolution(Surface):
    """The surface swept by the profile ``t -> (rho, z)`` turning about ``axis``.

    Parameters
    ----------
    profile : callable, Profile, str or knots
        ``profile(t)`` takes an array ``t`` and returns ``(rho, z)`` (two arrays
        like ``t``, ``rho >= 0``).  A :class:`~lgraph.surfaces.revolution.profiles.Profile`
        may carry analytic derivatives; otherwise eighth-order central
        differences are used.  A string names a built-in profile
        (``"egg"``, ``"vase"``, ``"pseudosphere"``, ``"catenoid"``, ``"circle"``);
        a list of ``[rho, z]`` knots is interpolated by a cubic spline.
    t_range : (lo, hi), optional
        The drawn part of the profile (default: the profile's natural range);
        ends with ``rho = 0`` are poles.
    axis : 3 numbers
        Direction of the axis through the origin (default ``z``).
    angle_range : (lo, hi)
        The turning angle ``phi``; a full turn by default.
    resolution : int
        Grid cells along the profile for the contour and the ray test; each
        cell may hold at most one extremum of the ray function (profiles with
        more wiggles need more).

    ``u1 = t``, ``u2 = phi``.  Lines of curvature: the parallels (``n1``) and the
    meridians (``n2``).

    >>> import lgraph as lg
    >>> egg = lg.SurfaceOfRevolution(lg.named_profile("egg"), (0, np.pi))
    >>> egg.domain.poles, egg.domain.periodic
    (((True, True), (False, False)), (False, True))
    """

    profile: Callable[[np.ndarray], Any] | str | Sequence[Sequence[float]] = attrs.field(
        converter=_as_profile
    )
    t_range: tuple[float, float] | None = attrs.field(
        default=None,
        converter=lambda v: None if v is None else interval("SurfaceOfRevolution", "t_range", v),
    )
    axis: np.ndarray = attrs.field(default=(0.0, 0.0, 1.0), converter=_axis, kw_only=True)
    angle_range: tuple[float, float] = attrs.field(
        default=(0.0, _TWO_PI),
        converter=lambda v: interval("SurfaceOfRevolution", "angle_range", v),
        kw_only=True,
    )
    resolution: int = attrs.field(
        default=256, validator=count("SurfaceOfRevolution", 16, 1 << 16), kw_only=True
    )
    _grid: dict = attrs.field(init=False, repr=False, factory=dict)

    hit_cost = 12.0
    hit_call_cost = 800.0

    def __attrs_post_init__(self) -> None:
        if self.t_range is None:
            natural = getattr(self.profile, "t_range", None)
            if natural is None:
                raise ValueError(
                    "SurfaceOfRevolution: t_range is required for a profile without a "
                    "natural parameter range"
                )
            object.__setattr__(self, "t_range", interval("SurfaceOfRevolution", "t_range", natural))
        span = self.angle_range[1] - self.angle_range[0]
        if span > _TWO_PI * (1 + 1e-12):
            raise ValueError(
                f"SurfaceOfRevolution: angle_range must span at most 2 pi, got {self.angle_range}"
            )
        e1, e2, a = _frame(self.axis)
        t = np.linspace(*self.t_range, self.resolution + 1)
        try:
            rho, z = self.rz(t)
        except Exception as exc:  # noqa: BLE001 - report any failure of user code
            raise ValueError(f"SurfaceOfRevolution: profile(t) failed: {exc!r}") from exc
        bad = ~(np.isfinite(rho) & np.isfinite(z))
        if bad.any():
            k = int(np.argmax(bad))
            raise ValueError(
                "SurfaceOfRevolution: profile must return finite (rho, z), "
                f"got ({rho[k]}, {z[k]}) at t={t[k]:.6g}"
            )
        scale = max(float(np.abs(rho).max()), float(np.ptp(z)), 1e-300)
        if np.any(rho < -1e-12 * scale):
            k = int(np.argmax(rho < -1e-12 * scale))
            raise ValueError(
                f"SurfaceOfRevolution: profile must have rho >= 0, got rho={rho[k]:.6g} "
                f"at t={t[k]:.6g}"
            )
        if float(np.abs(rho).max()) == 0.0:
            raise ValueError("SurfaceOfRevolution: profile must leave the axis (rho > 0 somewhere)")
        drho, dz = self.drz(t)
        ends = np.array([[rho[0], z[0], drho[0], dz[0]], [rho[-1], z[-1], drho[-1], dz[-1]]])
        speed = max(float(np.hypot(drho, dz).max()), 1e-300)
        closed = bool(
            np.hypot(*(ends[0, :2] - ends[1, :2])) <= 1e-12 * scale
            and np.hypot(*(ends[0, 2:] - ends[1, 2:])) <= 1e-9 * speed
        )
        pole = (bool(abs(rho[0]) <= 1e-12 * scale), bool(abs(rho[-1]) <= 1e-12 * scale))
        lo, hi = float(z.min()), float(z.max())
        r = float(rho.max())
        pad = 0.01 * max(r, hi - lo)
        side = r * np.sqrt(np.clip(1 - a * a, 0, 1))
        blo = np.minimum(lo * a, hi * a) - side - pad
        bhi = np.maximum(lo * a, hi * a) + side + pad
        self._grid.update(
            t=t, rho=rho, z=z, drho=drho, dz=dz, frame=(e1, e2, a), pole=pole, closed=closed,
            bounds=(blo, bhi), size=float(np.linalg.norm(bhi - blo)),
        )  # fmt: skip

    # -- the profile ----------------------------------------------------------
    def rz(self, t: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(rho(t), z(t))`` as float arrays shaped like ``t``."""
        t = np.asarray(t, dtype=float)
        return _pair(self.profile(t), t.shape)

    def _fd(self, t: np.ndarray, order: int) -> tuple[np.ndarray, np.ndarray]:
        def f(x: np.ndarray) -> np.ndarray:
            return np.stack(self.rz(x), axis=-1)

        span = self.t_range[1] - self.t_range[0]
        d = _d1(f, t, 2e-3 * span) if order == 1 else _d2(f, t, 1.5 * FD_STEP_2 * span)
        return d[..., 0], d[..., 1]

    def drz(self, t: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(rho'(t), z'(t))`` (analytic when the profile has a ``derivative``)."""
        t = np.asarray(t, dtype=float)
        der = getattr(self.profile, "derivative", None)
        if der is None:
            return self._fd(t, 1)
        return _pair(der(t), t.shape)

    def ddrz(self, t: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(rho''(t), z''(t))``."""
        t = np.asarray(t, dtype=float)
        der = getattr(self.profile, "second_derivative", None)
        if der is None:
            return self._fd(t, 2)
        return _pair(der(t), t.shape)

    # -- what it is -------------------------------------------------------------
    @property
    def frame(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(e1, e2, a)``: ``phi = 0`` direction, ``phi = pi/2`` direction, axis."""
        return self._grid["frame"]

    @property
    def domain(self) -> Domain:
        span = self.angle_range[1] - self.angle_range[0]
        periodic = abs(span - _TWO_PI) <= 1e-12 * _TWO_PI
        return Domain(
            self.t_range,
            self.angle_range,
            periodic=(self.profile_closed, periodic),
            poles=(self.poles, False),
        )

    @property
    def profile_closed(self) -> bool:
        """Whether the profile is a closed curve over ``t_range`` (a torus): then
        ``t`` is periodic and the surface has no boundary parallels."""
        return self._grid["closed"]

    @property
    def poles(self) -> tuple[bool, bool]:
        """Whether the profile meets the axis at ``t_range[0]`` / ``t_range[1]``."""
        return self._grid["pole"]

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self._grid["bounds"]
        return lo.copy(), hi.copy()

    @property
    def size(self) -> float:
        return self._grid["size"]

    def _radial(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        e1, e2, _ = self.frame
        c, s = np.cos(phi)[..., None], np.sin(phi)[..., None]
        return c * e1 + s * e2, -s * e1 + c * e2

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        t, phi = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        rho, z = self.rz(t)
        r, _ = self._radial(phi)
        return rho[..., None] * r + z[..., None] * self.frame[2]

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        t, phi = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        rho, _ = self.rz(t)
        dr, dz = self.drz(t)
        r, p = self._radial(phi)
        return dr[..., None] * r + dz[..., None] * self.frame[2], rho[..., None] * p

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        t, phi = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        rho, _ = self.rz(t)
        dr, _ = self.drz(t)
        ddr, ddz = self.ddrz(t)
        r, p = self._radial(phi)
        return (
            ddr[..., None] * r + ddz[..., None] * self.frame[2],
            dr[..., None] * p,
            -rho[..., None] * r,
        )

    # -- what it draws ------------------------------------------------------------
    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        """``n1`` parallels and ``n2`` meridians: the lines of curvature, exactly."""
        from ...families._lines import parameter_line_batches

        d = self.domain
        return parameter_line_batches(self, d.lines(0, n1), d.lines(1, n2))

    def parabolic_lines(self) -> list[CurveBatch]:
        """The parallels where ``K = 0``: where the tangent plane is perpendicular
        to the axis (``z' = 0``) or the meridian has an inflection
        (``rho' z'' - z' rho'' = 0``); roots in ``t`` refined to machine precision."""
        from ...families._lines import parameter_line_batches

        def zprime(t: np.ndarray) -> np.ndarray:
            return self.drz(t)[1]

        def bend(t: np.ndarray) -> np.ndarray:
            dr, dz = self.drz(t)
            ddr, ddz = self.ddrz(t)
            return dr * ddz - dz * ddr

        roots = np.concatenate([self._roots_in_t(zprime), self._roots_in_t(bend)])
        roots = roots[~self._at_pole(roots)]
        return parameter_line_batches(self, np.unique(roots), [], "parabolic", "parabolic")

    def level_lines(self, direction: Any, values: Any) -> list[CurveBatch] | None:
        """Sections by planes ``x . direction = value``: parallels when the
        direction is the axis (roots of ``z(t) = +-value``), else None."""
        from ...families._lines import parameter_line_batches

        d = np.asarray(direction, float)
        d = d / np.linalg.norm(d)
        cos = float(d @ self.frame[2])
        if abs(abs(cos) - 1) > 1e-14:
            return None
        roots = [
            self._roots_in_t(lambda t, v=v: cos * self.rz(t)[1] - v)
            for v in np.atleast_1d(np.asarray(values, float)).tolist()
        ]
        r = np.concatenate(roots) if roots else np.empty(0)
        r = r[~self._at_pole(r)]
        return parameter_line_batches(self, r, [], "level", "level")

    def _at_pole(self, t: np.ndarray) -> np.ndarray:
        rho, _ = self.rz(t)
        return np.abs(rho) <= 1e-9 * self.size

    def _roots_in_t(self, func: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """Roots of ``func(t)`` inside ``t_range`` (sign changes on the grid, refined)."""
        from ..._roots import bracketed_roots

        t = self._grid["t"]
        f = func(t)
        exact = t[1:-1][f[1:-1] == 0]
        j = np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)[0]
        if not len(j):
            return exact
        span = self.t_range[1] - self.t_range[0]
        x = bracketed_roots(lambda x, sel: func(x), t[j], t[j + 1], f[j], f[j + 1], 4e-16 * span)
        return np.concatenate([exact, x])

    def contour(self, projector: Projector) -> list[CurveBatch]:
        """The contour in closed form per parallel (see the module docstring)."""
        from ._contour import contour

        return contour(self, projector)

    # -- what it hides -----------------------------------------------------------
    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Exact ray test by reduction to the profile plane (module docstring).

        On a certified convex closed surface (:attr:`convex`), the rays from its
        own points are decided by the sign of the hiding margin instead
        (:mod:`lgraph.surfaces.revolution._convex`)."""
        from ._hits import hits

        if own is None or not self.convex:
            return hits(self, origins, directions, smax, own)
        from ._convex import margin

        own = np.asarray(own)
        o = np.asarray(origins, dtype=float).reshape(-1, 3)
        v = np.asarray(directions, dtype=float).reshape(-1, 3)
        sm = np.broadcast_to(np.asarray(smax, dtype=float), (len(o),))
        mine = own != OFF
        if mine.all():
            return margin(self, o, v, sm, own, exact=False) > 0
        out = np.zeros(len(o), bool)
        out[mine] = margin(self, o[mine], v[mine], sm[mine], own[mine], exact=False) > 0
        rest = ~mine
        out[rest] = hits(self, o[rest], v[rest], sm[rest], own[rest])
        return out

    @property
    def convex(self) -> bool:
        """Whether the surface is the whole boundary of a convex solid, proved
        by its profile's ``Profile.convex``
        interval (poles at both ends of ``t_range``, a full turn)."""
        from ._convex import convex_sign

        return convex_sign(self) != 0

    def visibility_margins(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray,
        uv: np.ndarray | None = None,
        which: int | None = None,
    ) -> np.ndarray | None:
        """Its contour (``N . v``), rims and grazing rays as transition functions;
        a convex surface's exact hiding margin
        (:mod:`lgraph.surfaces.revolution._margins`)."""
        from ._margins import margins

        return margins(self, origins, directions, smax, own, uv, which)


def revolution_from_profile(
    profile: Profile, t_range: Any = None, **kw: Any
) -> SurfaceOfRevolution:
    """A surface of revolution of a :class:`Profile` over its natural ``t_range``
    (or the one given)."""
    return SurfaceOfRevolution(profile, profile.t_range if t_range is None else t_range, **kw)


def Pseudosphere(a: float = 1.0, extent: float = 3.0, **kw: Any) -> SurfaceOfRevolution:  # noqa: N802
    """Beltrami's pseudosphere: the tractrix ``rho = a sech t``, ``z = a (t - tanh t)``
    turned about ``z``, ``0 <= t <= extent``; Gaussian curvature ``-1/a^2``.

    >>> import numpy as np
    >>> s = Pseudosphere(2.0)
    >>> k1, k2 = s.principal_curvatures(np.array([1.0]), np.array([0.3]))
    >>> round(float(k1[0] * k2[0]), 9)
    -0.25
    """
    return revolution_from_profile(named_profile("pseudosphere", a=a, extent=extent), **kw)
