r"""Confocal quadrics and triply orthogonal systems (paper §6-§7).

The confocal family (paper (7.1)), for ``0 < a < b < c``::

    x^2/(a^2 - l) + y^2/(b^2 - l) + z^2/(c^2 - l) = 1

consists of ellipsoids (``l < a^2``), hyperboloids of one sheet
(``a^2 < l < b^2``, axis x) and of two sheets (``b^2 < l < c^2``, axis z).
Through every point off the coordinate planes pass exactly one member of each
kind, and they are mutually orthogonal (Lemma 7.1), so by Dupin's theorem they
meet in lines of curvature.

:class:`ConfocalQuadric` is a member; it delegates to the standard-form class
(:class:`~lgraph.surfaces.quadrics.quadric.Ellipsoid`, ``HyperboloidOneSheet``,
``HyperboloidTwoSheets``) with semi-axes ``sqrt(|A_i - l|)``.  The one-sheeted
members have their axis along x while the standard class has it along z: the
member then uses the cyclic permutation ``M`` (a rotation, ``world = M local``)
that maps local ``(x', y', z')`` to ``(y, z, x)``; points, derivatives,
contours and lines of curvature are mapped by ``M``, rays by ``M^T``.

Intersection curves (paper (7.6)-(7.8)): with ``A = (a^2, b^2, c^2)`` and the
ellipsoidal coordinates ``l1 < a^2 < l2 < b^2 < l3 < c^2`` of a point,
``x_i^2 = prod_k (A_i - l_k) / prod_{j != i} (A_i - A_j)``.  Two coordinates are
fixed on the intersection of two members; the third is substituted so that
the square roots become signed trigonometric or hyperbolic functions:

* ellipsoid ``l1`` & one sheet ``l2``: ``l3 = b^2 + (c^2-b^2) sin^2 t``,
  ``y ~ sin t``, ``z ~ cos t`` (two closed curves, ``x > 0`` and ``x < 0``);
* ellipsoid ``l1`` & two sheets ``l3``: ``l2 = a^2 + (b^2-a^2) sin^2 t``,
  ``x ~ sin t``, ``y ~ cos t`` (two closed curves, ``z > 0`` and ``z < 0``);
* one sheet ``l2`` & two sheets ``l3``: ``l1 = a^2 - (b^2-a^2) sinh^2 t``,
  ``x ~ sinh t`` (four complete curves, one per sign of ``y, z``).

>>> import numpy as np
>>> m = ConfocalQuadric(1, 2, 3, 2.0)
>>> m.kind
'hyperboloid of one sheet'
>>> p = m.point(np.array([0.3]), np.array([1.0]))[0]
>>> round(float(p @ (1 / (np.array([1, 4, 9]) - 2.0) * p)), 12)
1.0
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from ..._validate import as_number, finite_positive, finite_real
from ...curves import Curve, CurveBatch
from ...families import Family
from ...families._lines import parameter_line_batches
from .._base import Domain, Surface
from .._patch import clip_intervals
from ._unbounded import _PatchQuadric
from .hyperboloids import HyperboloidOneSheet, HyperboloidTwoSheets
from .quadric import Ellipsoid, Quadric

__all__ = ["ConfocalQuadric", "TripleOrthogonalSystem"]

#: world = _CYCLE @ local: local z' (the hyperboloid's axis) becomes world x
_CYCLE = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
_KINDS = ("ellipsoid", "hyperboloid of one sheet", "hyperboloid of two sheets")


def _optional_positive(owner: str) -> Any:
    def check(inst: Any, attribute: Any, value: Any) -> None:
        if value is not None:
            finite_positive(owner)(inst, attribute, value)

    return attrs.field(default=None, kw_only=True, converter=as_number, validator=check)


@attrs.frozen
class ConfocalQuadric(Quadric):
    """The member ``x^2/(a^2-lam) + y^2/(b^2-lam) + z^2/(c^2-lam) = 1`` of the
    confocal family, ``0 < a < b < c``.

    Its kind follows from ``lam``: ellipsoid (``lam < a^2``), hyperboloid of
    one sheet (``a^2 < lam < b^2``, axis x), of two sheets (``b^2 < lam < c^2``,
    axis z).  ``height`` (hyperboloids only) bounds the drawn patch along the
    axis, as in the standard classes.  It behaves as the matching standard
    quadric :attr:`!quadric`, turned by :attr:`!rotation` (module docstring).

    >>> ConfocalQuadric(1, 2, 3, 4.0)
    Traceback (most recent call last):
    ...
    ValueError: ConfocalQuadric: lam must differ from a^2, b^2, c^2 and be less than c^2=9, got 4.0
    >>> ConfocalQuadric(2, 1, 3, 0)
    Traceback (most recent call last):
    ...
    ValueError: ConfocalQuadric: need 0 < a < b < c, got a=2, b=1, c=3
    """

    a: float = attrs.field(converter=as_number, validator=finite_positive("ConfocalQuadric"))
    b: float = attrs.field(converter=as_number, validator=finite_positive("ConfocalQuadric"))
    c: float = attrs.field(converter=as_number, validator=finite_positive("ConfocalQuadric"))
    lam: float = attrs.field(converter=as_number, validator=finite_real("ConfocalQuadric"))
    height: float | None = _optional_positive("ConfocalQuadric")
    quadric: Quadric = attrs.field(init=False, repr=False)
    rotation: np.ndarray = attrs.field(init=False, repr=False, eq=False)

    def __attrs_post_init__(self) -> None:
        a2, b2, c2, lam = self.a**2, self.b**2, self.c**2, self.lam
        if not (self.a < self.b < self.c):
            raise ValueError(
                f"ConfocalQuadric: need 0 < a < b < c, got a={self.a!r}, b={self.b!r}, c={self.c!r}"
            )
        if lam < a2:
            q: Quadric = Ellipsoid(math.sqrt(a2 - lam), math.sqrt(b2 - lam), math.sqrt(c2 - lam))
            rot = np.eye(3)
        elif a2 < lam < b2:
            q = HyperboloidOneSheet(
                math.sqrt(b2 - lam), math.sqrt(c2 - lam), math.sqrt(lam - a2), height=self.height
            )
            rot = _CYCLE
        elif b2 < lam < c2:
            q = HyperboloidTwoSheets(
                math.sqrt(lam - a2), math.sqrt(lam - b2), math.sqrt(c2 - lam), height=self.height
            )
            rot = np.eye(3)
        else:
            raise ValueError(
                "ConfocalQuadric: lam must differ from a^2, b^2, c^2 and be less than "
                f"c^2={c2:g}, got {lam!r}"
            )
        object.__setattr__(self, "quadric", q)
        rot = rot.copy()
        rot.setflags(write=False)
        object.__setattr__(self, "rotation", rot)

    @property
    def kind(self) -> str:
        """``"ellipsoid"``, ``"hyperboloid of one sheet"`` or ``"hyperboloid of two sheets"``."""
        a2, b2 = self.a**2, self.b**2
        return _KINDS[0 if self.lam < a2 else 1 if self.lam < b2 else 2]

    def family_value(self, points: Any) -> np.ndarray:
        """``x^2/(a^2-lam) + y^2/(b^2-lam) + z^2/(c^2-lam) - 1`` (paper's ``g(lam)``)."""
        x = np.asarray(points, float)
        den = np.array([self.a**2, self.b**2, self.c**2]) - self.lam
        return (x * x / den).sum(-1) - 1.0

    # -- geometry, mapped by the rotation -------------------------------------
    def _out(self, v: np.ndarray) -> np.ndarray:
        return np.asarray(v) @ self.rotation.T

    def _in(self, v: Any) -> np.ndarray:
        return np.asarray(v, float) @ self.rotation

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        A, b, d = self.quadric.coefficients
        M = self.rotation
        return M @ A @ M.T, M @ b, d

    @property
    def domain(self) -> Domain:
        return self.quadric.domain

    @property
    def closed(self) -> bool:
        return self.quadric.closed

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        return self._out(self.quadric.point(u1, u2))

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        x1, x2 = self.quadric.derivatives(u1, u2)
        return self._out(x1), self._out(x2)

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return tuple(self._out(v) for v in self.quadric.second_derivatives(u1, u2))  # type: ignore[return-value]

    def uv_of(self, points: Any) -> np.ndarray:
        return self.quadric.uv_of(self._in(points))

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.quadric.bounds()
        corners = np.array(
            [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
        )
        w = self._out(corners)  # fmt: skip
        return w.min(axis=0), w.max(axis=0)

    def in_patch(self, points: np.ndarray) -> np.ndarray:
        return self.quadric.in_patch(self._in(points))

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.quadric.patch_margin(self._in(points))

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        return self.quadric.hits(self._in(origins), self._in(directions), smax, own)

    def _wrap(self, batches: list[CurveBatch]) -> list[CurveBatch]:
        out = []
        for bt in batches:

            def evaluate(idx: np.ndarray, t: np.ndarray, ev: Any = bt.evaluate) -> tuple:
                x, uv = ev(idx, t)
                return self._out(x), uv

            out.append(attrs.evolve(bt, evaluate=evaluate, surface=self))
        return out

    def contour(self, projector: Any) -> list[CurveBatch]:
        from ...geometry.transforms import Transform
        from ...render import local_projector

        if not np.array_equal(self.rotation, np.eye(3)):
            projector = local_projector(projector, Transform(self.rotation))
        return self._wrap(self.quadric.contour(projector))

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        """The standard class's closed forms, turned.

        (:mod:`!lgraph.surfaces.quadrics._curvature`)"""
        return self._wrap(self.quadric.lines_of_curvature(n1, n2))

    def parameter_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """Parameter lines of the standard class (per sheet where it has two)."""
        inner = getattr(self.quadric, "parameter_lines", None)
        if inner is None:
            from ...families import ParameterLines

            return self._wrap(ParameterLines(n1, n2).batches(self.quadric, None))
        return self._wrap(inner(n1, n2))

    def umbilics(self) -> np.ndarray:
        return self._out(self.quadric.umbilics()).reshape(-1, 3)


# -- intersection curves -------------------------------------------------------
def _intersection_pieces(
    A: np.ndarray, lam_i: float, lam_j: float
) -> tuple[Any, list[tuple[float, ...]], float, float, bool]:
    """Closed form of the intersection of confocal members ``lam_i < lam_j``
    (module docstring): ``(func(signs, t), sign tuples, t0, t1, closed)``."""
    a2, b2, c2 = A
    if lam_j < b2:  # ellipsoid l1 & one sheet l2, l3 free
        l1, l2 = lam_i, lam_j
        kx = math.sqrt((a2 - l1) * (l2 - a2) / (b2 - a2))  # times sqrt((l3-a2)/(c2-a2))
        ky = math.sqrt((b2 - l1) * (b2 - l2) / (b2 - a2))
        kz = math.sqrt((c2 - l1) * (c2 - l2) / (c2 - a2))

        def func(sg: tuple, t: np.ndarray) -> np.ndarray:
            s2 = np.sin(t) ** 2
            l3 = b2 + (c2 - b2) * s2
            x = sg[0] * kx * np.sqrt((l3 - a2) / (c2 - a2))
            return np.stack([x, ky * np.sin(t), kz * np.cos(t)], axis=-1)

        return func, [(1.0,), (-1.0,)], 0.0, 2 * math.pi, True
    if lam_i < a2:  # ellipsoid l1 & two sheets l3, l2 free
        l1, l3 = lam_i, lam_j
        kx = math.sqrt((a2 - l1) * (l3 - a2) / (c2 - a2))
        ky = math.sqrt((b2 - l1) * (l3 - b2) / (c2 - b2))

        def func(sg: tuple, t: np.ndarray) -> np.ndarray:
            l2 = a2 + (b2 - a2) * np.sin(t) ** 2
            z = sg[0] * np.sqrt((c2 - l1) * (c2 - l2) * (c2 - l3) / ((c2 - a2) * (c2 - b2)))
            return np.stack([kx * np.sin(t), ky * np.cos(t), z], axis=-1)

        return func, [(1.0,), (-1.0,)], 0.0, 2 * math.pi, True
    # one sheet l2 & two sheets l3, l1 = a2 - (b2 - a2) sinh^2 t free
    l2, l3 = lam_i, lam_j
    kx = math.sqrt((l2 - a2) * (l3 - a2) / (c2 - a2))
    ky = math.sqrt((b2 - l2) * (l3 - b2) / (c2 - b2))
    kz2 = (c2 - l2) * (c2 - l3) / ((c2 - a2) * (c2 - b2))

    def func(sg: tuple, t: np.ndarray) -> np.ndarray:
        sh = np.sinh(t)
        l1 = a2 - (b2 - a2) * sh * sh
        z = sg[1] * np.sqrt(kz2 * (c2 - l1))
        return np.stack([kx * sh, sg[0] * ky * np.cosh(t), z], axis=-1)

    signs = [(sy, sz) for sy in (1.0, -1.0) for sz in (1.0, -1.0)]
    return func, signs, -1.0, 1.0, False


def _patch_curves(
    func: Any, signs: list, t0: float, t1: float, closed: bool, members: list
) -> list:
    """Curves ``func(sign, t)`` cut to the drawn patches of ``members``."""
    out = []
    for sg in signs:
        if not closed:  # widen until the curve leaves every patch
            T = 1.0
            while T < 60 and all(
                np.all(m.patch_margin(func(sg, np.array([-T, T]))) >= 0) for m in members
            ):
                T *= 2
            t0, t1 = -T, T

        def margin(_idx: np.ndarray, t: np.ndarray, sg: tuple = sg) -> np.ndarray:
            x = func(sg, t)
            return np.min([m.patch_margin(x) for m in members], axis=0)

        _c, a, b, cl = clip_intervals(margin, np.array([t0]), np.array([t1]), np.array([closed]))
        for lo, hi, c in zip(a.tolist(), b.tolist(), cl.tolist()):
            out.append(Curve(lambda t, sg=sg: func(sg, t), lo, hi, closed=c))
    return out


@attrs.frozen
class _HalfPlane(_PatchQuadric):
    """The half-plane ``{rho (cos phi, sin phi, 0) + z e_z : 0 <= rho <= extent,
    |z| <= extent}`` (a degenerate quadric ``n . x = 0``); every direction is
    principal, its lines of curvature are its parameter lines."""

    phi: float
    extent: float

    @property
    def _dirs(self) -> tuple[np.ndarray, np.ndarray]:
        e = np.array([math.cos(self.phi), math.sin(self.phi), 0.0])
        return e, np.array([-e[1], e[0], 0.0])

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.zeros((3, 3)), self._dirs[1], 0.0

    @property
    def domain(self) -> Domain:
        return Domain((0.0, self.extent), (-self.extent, self.extent))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        e = self._dirs[0]
        return u1[..., None] * e + u2[..., None] * np.array([0.0, 0.0, 1.0])

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack([x @ self._dirs[0], x[..., 2]], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        c = self.point(
            np.array([0, self.extent, 0, self.extent]), np.array([-1, -1, 1, 1.0]) * self.extent
        )
        return c.min(axis=0), c.max(axis=0)  # fmt: skip

    def patch_margin(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        rho = x @ self._dirs[0]
        return np.minimum(np.minimum(rho, self.extent - rho), self.extent - np.abs(x[..., 2]))

    def contour(self, projector: Any) -> list[CurveBatch]:
        return []  # a plane has no contour; its outline is its boundary

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        d = self.domain
        return parameter_line_batches(self, d.lines(0, n1), d.lines(1, n2), "c1", "c2")


@attrs.frozen(eq=False)
class TripleOrthogonalSystem:
    """Chosen members of a triply orthogonal system and their mutual
    intersection curves (lines of curvature on each, by Dupin's theorem).

    Build one with :meth:`confocal` (paper Figure 7.1: ellipsoids and
    hyperboloids of one and two sheets) or :meth:`spherical` (Figure 6.1:
    sphere, cone, plane of spherical coordinates), then :meth:`add_to` a scene.

    >>> import lgraph as lg
    >>> system = TripleOrthogonalSystem.confocal(1, 2, 3, [-1.0, 2.0, 6.0])
    >>> [m.kind for m in system.members]
    ['ellipsoid', 'hyperboloid of one sheet', 'hyperboloid of two sheets']
    >>> len(system.curves) >= 4
    True
    """

    members: tuple[Surface, ...]
    curves: tuple[Curve, ...]

    @classmethod
    def confocal(
        cls, a: float, b: float, c: float, lams: Any, *, height: float | None = None
    ) -> TripleOrthogonalSystem:
        """Members ``ConfocalQuadric(a, b, c, lam)`` for ``lam`` in ``lams`` and the
        intersection curves of every pair of different kinds, cut to both patches."""
        members = [ConfocalQuadric(a, b, c, float(lam), height=height) for lam in lams]
        A = np.array([a * a, b * b, c * c], float)
        curves: list[Curve] = []
        for i, mi in enumerate(members):
            for mj in members[i + 1 :]:
                lo, hi = sorted((mi, mj), key=lambda m: m.lam)
                if lo.kind == hi.kind:
                    continue  # members of one family are disjoint
                func, signs, t0, t1, closed = _intersection_pieces(A, lo.lam, hi.lam)
                curves += _patch_curves(func, signs, t0, t1, closed, [lo, hi])
        return cls(tuple(members), tuple(curves))

    @classmethod
    def spherical(
        cls, radius: float = 1.0, polar_angle: float = 55.0, azimuth: float = -40.0
    ) -> TripleOrthogonalSystem:
        """Sphere ``r = radius``, cone ``theta = polar_angle`` (degrees, both
        nappes) and half-plane ``phi = azimuth`` (degrees) of spherical
        coordinates, with their intersection circles and arcs (Figure 6.1)."""
        from .hyperboloids import EllipticCone
        from .quadric import Sphere

        for name, v in (("radius", radius), ("polar_angle", polar_angle), ("azimuth", azimuth)):
            if not (isinstance(v, (int, float)) and math.isfinite(v)):
                raise ValueError(
                    f"TripleOrthogonalSystem: {name} must be a finite number, got {v!r}"
                )
        if not radius > 0 or not 0 < polar_angle < 90:
            raise ValueError(
                "TripleOrthogonalSystem: need radius > 0 and 0 < polar_angle < 90, "
                f"got radius={radius!r}, polar_angle={polar_angle!r}"
            )
        th, ph, R = math.radians(polar_angle), math.radians(azimuth), float(radius)
        k = math.tan(th)
        ext = 1.35 * R
        cone = EllipticCone(k, k, height=min(ext / max(k, 1e-9), ext))
        plane = _HalfPlane(ph, ext)
        e = np.array([math.cos(ph), math.sin(ph), 0.0])
        zc, rc = R * math.cos(th), R * math.sin(th)
        curves = [
            Curve(lambda t, s=s: np.stack([rc * np.cos(t), rc * np.sin(t), s * zc + 0 * t], -1),
                  0.0, 2 * math.pi, closed=True)
            for s in (1.0, -1.0)
        ]  # fmt: skip
        curves.append(
            Curve(lambda t: R * (np.cos(t)[:, None] * e + np.sin(t)[:, None] * [0, 0, 1.0]),
                  -math.pi / 2, math.pi / 2)
        )  # fmt: skip
        hmax = min(cone.height, ext / max(k, 1e-9))
        for s in (1.0, -1.0):
            curves.append(
                Curve(lambda t, s=s: t[:, None] * (k * e + [0, 0, s]), 0.0, hmax)
            )  # fmt: skip
        return cls((Sphere(R), cone, plane), tuple(curves))

    def add_to(
        self,
        scene: Any,
        *families: Any,
        transform: Any = None,
        style: Any = None,
        curve_style: Any = None,
        hides: bool = True,
    ) -> list[Any]:
        """Add every member (with ``families``; none given: contour only) and the
        intersection curves (drawn with ``curve_style``, default 1.8 times wider).
        ``hides=False`` makes the members transparent (nothing hidden)."""
        from ...families import Contour
        from ...scene.style import Style

        nodes = []
        for m in self.members:
            if families:
                nodes.append(scene.add(m, *families, transform=transform, style=style, hides=hides))
            elif isinstance(m, _HalfPlane):
                nodes.append(
                    scene.add(m, _Outline(), transform=transform, style=style, hides=hides)
                )
            else:
                nodes.append(
                    scene.add(
                        m, Contour(), transform=transform, style=style, contour=False, hides=hides
                    )
                )
        cs = curve_style if curve_style is not None else Style(width=Style().width * 1.8)
        for c in self.curves:
            nodes.append(scene.add(c, transform=transform, style=cs))
        return nodes

    def scene(self, *families: Any, **kw: Any) -> Any:
        """A new :class:`~lgraph.scene.graph.Scene` holding this system (see :meth:`add_to`)."""
        from ...scene.graph import Scene

        sc = Scene()
        self.add_to(sc, *families, **kw)
        return sc


class _Outline(Family):
    """Family drawing just the boundary of a rectangular patch (for the plane)."""

    def batches(self, surface: Any, projector: Any) -> list[CurveBatch]:
        d = surface.domain
        return parameter_line_batches(surface, np.array(d.u1), np.array(d.u2), "outline", "outline")
