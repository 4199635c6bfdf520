"""Figure surfaces: planar parallelograms and 3-D arrows (cylinder shaft, cone head).

Both are :class:`~lgraph.Surface` subclasses that hide and are hidden like
any surface, with exact ray tests: a plane for :class:`Parallelogram`; for
:class:`Arrow`, the quadratics of a circular cylinder and a circular cone
(the quadric ray test of docs/mathematics.rst, "Quadrics: ray test and
contour", in the arrow's own frame) and its two end discs.  Their contours
are exact too: the parallelogram's boundary; the arrow's silhouette
generators, where the view vector is tangent to the cylinder or cone.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from ..._own import CONTOUR, OFF
from ..._validate import as_number, finite_positive, vector3
from ...curves import CurveBatch
from ...surfaces._base import Domain, Surface

if TYPE_CHECKING:
    from ..projectors import Projector

__all__ = ["Parallelogram", "Arrow"]


def _vec(owner: str, name: str) -> Any:
    return attrs.field(
        converter=lambda v: vector3(owner, name, v), eq=attrs.cmp_using(np.array_equal)
    )


@attrs.frozen
class Parallelogram(Surface):
    """Planar patch ``origin + u1 e1 + u2 e2``, ``0 <= u1, u2 <= 1``.

    Its contour is its boundary; hits are exact.  :meth:`!centered` builds one
    around a point (e.g. a tangent plane).

    >>> p = Parallelogram((0, 0, 0), (1, 0, 0), (2, 0, 0))
    Traceback (most recent call last):
    ...
    ValueError: Parallelogram: e1 and e2 must be linearly independent
    """

    origin: np.ndarray = _vec("Parallelogram", "origin")
    e1: np.ndarray = _vec("Parallelogram", "e1")
    e2: np.ndarray = _vec("Parallelogram", "e2")

    def __attrs_post_init__(self) -> None:
        n = np.cross(self.e1, self.e2)
        if not np.linalg.norm(n) > 1e-12 * np.linalg.norm(self.e1) * np.linalg.norm(self.e2):
            raise ValueError("Parallelogram: e1 and e2 must be linearly independent")

    @classmethod
    def centered(cls, center: Any, e1: Any, e2: Any) -> Parallelogram:
        """The parallelogram ``center + a e1 + b e2`` with ``|a|, |b| <= 1``."""
        c = np.asarray(center, float)
        e1, e2 = np.asarray(e1, float), np.asarray(e2, float)
        return cls(c - e1 - e2, 2 * e1, 2 * e2)

    @property
    def domain(self) -> Domain:
        return Domain((0.0, 1.0), (0.0, 1.0))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return self.origin + u1[..., None] * self.e1 + u2[..., None] * self.e2

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, _ = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return (
            np.broadcast_to(self.e1, u1.shape + (3,)).copy(),
            np.broadcast_to(self.e2, u1.shape + (3,)).copy(),
        )

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u1, _ = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        z = np.zeros(u1.shape + (3,))
        return z, z.copy(), z.copy()

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        c = self.point(np.array([0, 1, 0, 1.0]), np.array([0, 0, 1, 1.0]))
        pad = 1e-9 * (np.linalg.norm(self.e1) + np.linalg.norm(self.e2))
        return c.min(axis=0) - pad, c.max(axis=0) + pad

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        """A plane is all umbilics: no lines of curvature."""
        return []

    def contour(self, projector: Projector) -> list[CurveBatch]:
        """The boundary (one closed curve, ``t`` in ``[0, 4]``)."""

        def uv(_idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            k = np.clip(np.floor(t), 0, 3)
            f = t - k
            u1 = np.select([k == 0, k == 1, k == 2], [f, 1.0, 1.0 - f], 0.0)
            u2 = np.select([k == 0, k == 1, k == 2], [0.0, f, 1.0], 1.0 - f)
            return np.stack([u1, u2], axis=-1)

        return [CurveBatch.from_uv(self, "contour", [0.0], [4.0], uv, closed=True, own=CONTOUR)]

    def hit_count(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """A plane is crossed at most once: ``hits`` as a count."""
        return self.hits(origins, directions, smax, own).astype(np.int64)

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        o = np.asarray(origins, float).reshape(-1, 3)
        v = np.asarray(directions, float).reshape(-1, 3)
        smax = np.broadcast_to(np.asarray(smax, float), (len(o),))
        own = np.zeros(len(o), np.int8) if own is None else np.asarray(own).reshape(-1)
        n = np.cross(self.e1, self.e2)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = ((self.origin - o) @ n) / (v @ n)
        p = o + s[:, None] * v - self.origin
        # coordinates in the (e1, e2) basis
        g11, g12, g22 = self.e1 @ self.e1, self.e1 @ self.e2, self.e2 @ self.e2
        b1, b2 = p @ self.e1, p @ self.e2
        det = g11 * g22 - g12 * g12
        a1 = (g22 * b1 - g12 * b2) / det
        a2 = (g11 * b2 - g12 * b1) / det
        vn = np.linalg.norm(v, axis=1)
        eps = 1e-9 * self.size / np.where(vn > 0, vn, 1.0)
        inside = (a1 >= 0) & (a1 <= 1) & (a2 >= 0) & (a2 <= 1)
        # a ray from a point of the plane meets it only there
        return (own == OFF) & np.isfinite(s) & (s > eps) & (s < smax) & inside


def _pos(owner: str, default: float | None = None) -> Any:
    return attrs.field(
        default=default,
        converter=lambda v: v if v is None else as_number(v),
        validator=attrs.validators.optional(finite_positive(owner)),
        kw_only=True,
    )


@attrs.frozen
class Arrow(Surface):
    """A thin 3-D arrow from ``tail`` to ``tip``: a cylinder shaft and a cone head.

    Drawn by its outline only (shaft and head silhouettes and the rim of the
    head: its :meth:`!contour`), as strokes of the family ``"arrow"`` (the
    style key ``{"arrow": lg.Style(...)}``, the TikZ style ``lgraph/arrow``):
    ``scene.add(arrow)`` draws just that, no parameter lines and no patch
    boundary.  It hides what is behind it and is hidden like any surface.

    ``label`` (optional) is text put just beyond the tip, on the side the
    arrow points to in the picture (``"$N$"``), or a :class:`~lgraph.Label`
    placed as given; it is added to the scene with the arrow.

    >>> a = Arrow((0, 0, 0), (0, 0, 2))
    >>> round(a.head_length, 3), round(a.head_radius, 3)
    (0.4, 0.12)
    >>> Arrow((1, 1, 1), (1, 1, 1))
    Traceback (most recent call last):
    ...
    ValueError: Arrow: tail and tip must differ
    """

    tail: np.ndarray = _vec("Arrow", "tail")
    tip: np.ndarray = _vec("Arrow", "tip")
    head_length: float = _pos("Arrow")
    head_radius: float = _pos("Arrow")
    shaft_radius: float = _pos("Arrow")
    label: Any = attrs.field(default=None, kw_only=True)
    default_families = ()
    outline_family = "arrow"

    def __attrs_post_init__(self) -> None:
        L = float(np.linalg.norm(self.tip - self.tail))
        if not L > 0:
            raise ValueError("Arrow: tail and tip must differ")
        hl = self.head_length if self.head_length is not None else min(0.2 * L, 0.6)
        if hl >= L:
            raise ValueError(f"Arrow: head_length must be shorter than the arrow ({L}), got {hl}")
        hr = self.head_radius if self.head_radius is not None else 0.3 * hl
        sr = self.shaft_radius if self.shaft_radius is not None else 0.25 * hr
        if sr >= hr:
            raise ValueError("Arrow: shaft_radius must be smaller than head_radius")
        object.__setattr__(self, "head_length", hl)
        object.__setattr__(self, "head_radius", hr)
        object.__setattr__(self, "shaft_radius", sr)
        if self.label is not None:
            from .marks import Label

            if isinstance(self.label, str):
                d = self.tip - self.tail
                lab = Label(self.label, at=self.tip, anchor="auto", direction=d)
                object.__setattr__(self, "label", lab)
            elif not isinstance(self.label, Label):
                raise TypeError(
                    f"Arrow: label must be text or an lg.Label, got {type(self.label).__name__}"
                )

    # local frame: axis a, with e1, e2 orthonormal
    @property
    def _frame(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        d = self.tip - self.tail
        L = float(np.linalg.norm(d))
        a = d / L
        helper = np.eye(3)[int(np.argmin(np.abs(a)))]
        e1 = np.cross(a, helper)
        e1 /= np.linalg.norm(e1)
        return e1, np.cross(a, e1), a, L

    @property
    def domain(self) -> Domain:
        return Domain((0.0, 1.0), (0.0, 2 * np.pi), periodic=(False, True))

    def _radius(self, z: np.ndarray) -> np.ndarray:
        L = self._frame[3]
        zb = L - self.head_length
        return np.where(z < zb, self.shaft_radius, self.head_radius * (L - z) / self.head_length)

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        """``u1`` in [0, 1] along the axis, ``u2`` the angle around it."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        e1, e2, a, L = self._frame
        z = u1 * L
        r = self._radius(z)
        return (
            self.tail
            + z[..., None] * a
            + (r * np.cos(u2))[..., None] * e1
            + (r * np.sin(u2))[..., None] * e2
        )

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo = np.minimum(self.tail, self.tip) - self.head_radius
        hi = np.maximum(self.tail, self.tip) + self.head_radius
        return lo, hi

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return []

    def boundary(self) -> list[CurveBatch]:
        """None: the tail's disc and the tip are not lines of the figure."""
        return []

    def _local(self, x: np.ndarray, vector: bool = False) -> np.ndarray:
        e1, e2, a, _ = self._frame
        y = x if vector else x - self.tail
        return np.stack([y @ e1, y @ e2, y @ a], axis=-1)

    def contour(self, projector: Projector) -> list[CurveBatch]:
        """Shaft silhouette lines, head silhouette generators and the head's rim."""
        from ..projectors import CentralProjector

        e1, e2, a, L = self._frame
        zb = L - self.head_length
        sr, hr, hl = self.shaft_radius, self.head_radius, self.head_length
        central = isinstance(projector, CentralProjector)
        segs = []  # (start, end) pairs in world coordinates
        if central:
            w_sh = self._local(projector.eye)  # cylinder: r(phi) . (eye - x) = 0
            w_hd = self._local(projector.eye) - np.array([0, 0, L])
        else:
            w_sh = w_hd = self._local(projector.frame[2], vector=True)

        def angles(A: float, B: float, C: float) -> list[float]:
            # A cos phi + B sin phi = C
            R = np.hypot(A, B)
            if R <= abs(C) or R == 0:
                return []
            base = np.arctan2(B, A)
            dphi = np.arccos(np.clip(C / R, -1, 1))
            return [base + dphi, base - dphi]

        def at(z: float, r: float, phi: float) -> np.ndarray:
            return self.tail + z * a + r * (np.cos(phi) * e1 + np.sin(phi) * e2)

        for phi in angles(w_sh[0], w_sh[1], sr if central else 0.0):
            segs.append((at(0.0, sr, phi), at(zb, sr, phi)))
        for phi in angles(w_hd[0], w_hd[1], -(hr / hl) * w_hd[2]):
            segs.append((at(zb, hr, phi), at(L, 0.0, phi)))
        batches = []
        if segs:
            S = np.array(segs)

            def ev(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, None]:
                p0, p1 = S[idx, 0], S[idx, 1]
                return p0 + t[:, None] * (p1 - p0), None

            batches.append(
                CurveBatch(
                    "contour", np.zeros(len(S)), np.ones(len(S)), ev, surface=self, own=CONTOUR
                )
            )

        def rim(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, None]:
            return self.tail + zb * a + hr * (
                np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2
            ), None

        batches.append(
            CurveBatch("contour", [0.0], [2 * np.pi], rim, closed=True, surface=self, own=CONTOUR)
        )
        return batches

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        o = self._local(np.asarray(origins, float).reshape(-1, 3))
        v = self._local(np.asarray(directions, float).reshape(-1, 3), vector=True)
        smax = np.broadcast_to(np.asarray(smax, float), (len(o),))
        own = np.zeros(len(o), np.int8) if own is None else np.asarray(own).reshape(-1)
        L = self._frame[3]
        zb = L - self.head_length
        sr, hr, hl = self.shaft_radius, self.head_radius, self.head_length
        vn = np.linalg.norm(v, axis=1)
        vn = np.where(vn > 0, vn, 1.0)
        rel = np.where(own == OFF, 1e-9, 1e-6)
        eps = rel * L / vn
        hit = np.zeros(len(o), bool)

        def accept(s: np.ndarray, zlo: float, zhi: float) -> np.ndarray:
            z = o[:, 2] + s * v[:, 2]
            return np.isfinite(s) & (s > eps) & (s < smax) & (z >= zlo) & (z <= zhi)

        def quadratic(
            qa: np.ndarray, qb: np.ndarray, qc: np.ndarray, zlo: float, zhi: float
        ) -> Any:
            disc = qb * qb - 4 * qa * qc
            sq = np.sqrt(np.maximum(disc, 0.0))
            q = -0.5 * (qb + np.copysign(sq, qb))
            with np.errstate(divide="ignore", invalid="ignore"):
                r1, r2 = q / qa, qc / q
            ok = disc >= 0
            return ok & (accept(r1, zlo, zhi) | accept(r2, zlo, zhi))

        with np.errstate(divide="ignore", invalid="ignore"):
            # shaft: x^2 + y^2 = sr^2
            qa = v[:, 0] ** 2 + v[:, 1] ** 2
            qb = 2 * (o[:, 0] * v[:, 0] + o[:, 1] * v[:, 1])
            qc = o[:, 0] ** 2 + o[:, 1] ** 2 - sr * sr
            hit |= quadratic(qa, qb, qc, 0.0, zb)
            # head: x^2 + y^2 = k^2 (L - z)^2
            k2 = (hr / hl) ** 2
            dz = L - o[:, 2]
            qa = v[:, 0] ** 2 + v[:, 1] ** 2 - k2 * v[:, 2] ** 2
            qb = 2 * (o[:, 0] * v[:, 0] + o[:, 1] * v[:, 1] + k2 * dz * v[:, 2])
            qc = o[:, 0] ** 2 + o[:, 1] ** 2 - k2 * dz * dz
            hit |= quadratic(qa, qb, qc, zb, L)
            # discs: head base (radius hr) at zb, tail end (radius sr) at 0
            for zd, rd in ((zb, hr), (0.0, sr)):
                s = (zd - o[:, 2]) / v[:, 2]
                p = o[:, :2] + s[:, None] * v[:, :2]
                hit |= (
                    np.isfinite(s)
                    & (s > eps)
                    & (s < smax)
                    & (np.einsum("ij,ij->i", p, p) <= rd * rd)
                )
        return hit
