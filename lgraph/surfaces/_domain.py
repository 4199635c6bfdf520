"""The parameter rectangle of a surface and how its edges are glued (Domain).

A parameter ``u_i`` may be *periodic* (``True``: ``x(lo_i, t) = x(hi_i, t)``)
or *twisted* (``"twisted"``: ``x(lo_i, t) = x(hi_i, a + b - t)`` with
``[a, b]`` the other parameter's range: Moebius strips, Klein bottles, the
projective plane).  Curves, contours and field lines are traced in the
*cover*, the plane tiled by copies of the rectangle, and mapped back by
:meth:`Domain.wrap`; a cover point in copy ``(k1, k2)`` is the rectangle's
point reflected in ``u_j`` for every odd ``k_i`` of a twisted ``u_i``
(docs/gluings.rst).
"""

from __future__ import annotations

from typing import Any, Protocol

import attrs
import numpy as np
import numpy.typing as npt

from .._validate import interval

__all__ = ["Domain", "Parametrized", "domain_flags", "GLUINGS"]

#: the values one entry of ``periodic`` may take
GLUINGS = (False, True, "twisted")


def _flag(value: Any, what: str) -> bool:
    """A strict bool (``True``/``False``, numpy's or 0/1): ``"no"`` or
    ``"twisted"`` is not silently true."""
    if isinstance(value, (bool, np.bool_)) or (
        isinstance(value, (int, np.integer)) and value in (0, 1)
    ):
        return bool(value)
    raise ValueError(f"{what} must be True or False, got {value!r}")


def _gluing(value: Any, what: str) -> bool | str:
    """One parameter's gluing: ``False``, ``True`` or ``"twisted"``."""
    if isinstance(value, str):
        if value == "twisted":
            return "twisted"
        raise ValueError(f"{what} must be False, True or 'twisted', got {value!r}")
    try:
        return _flag(value, what)
    except ValueError:
        raise ValueError(f"{what} must be False, True or 'twisted', got {value!r}") from None


def _pair(value: Any, single: bool, one: Any, what: str, allowed: str) -> tuple[Any, Any]:
    """``one(value)`` for both parameters (or ends) when ``single``, else the
    pair ``(one(a), one(b))`` of ``value = (a, b)``; ``allowed`` for the error."""
    if single:
        g = one(value, what)
        return (g, g)
    try:
        if isinstance(value, str):  # "no" is not a pair ("n", "o")
            raise TypeError
        a, b = value
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be {allowed}, got {value!r}") from None
    return (one(a, f"{what}[0]"), one(b, f"{what}[1]"))


def _gluing_pair(value: Any, what: str = "periodic") -> tuple[Any, Any]:
    """One gluing for both parameters or a pair ``(u1, u2)`` of them."""
    single = isinstance(value, (bool, np.bool_)) or (isinstance(value, str) and value == "twisted")
    allowed = "False, True, 'twisted' or a pair (u1, u2) of them"
    return _pair(value, single, _gluing, what, allowed)


def _bool_pair(value: Any, what: str = "periodic", pair: str = "(u1, u2)") -> tuple[bool, bool]:
    """One flag for both parameters (or ends) or a pair of flags."""
    single = isinstance(value, (bool, np.bool_))
    return _pair(value, single, _flag, what, f"a bool or a pair {pair} of bools")


def _pole_pairs(value: Any, what: str = "poles") -> tuple[tuple[bool, bool], tuple[bool, bool]]:
    """Poles per parameter end: ``True`` (all four ends), ``(p1, p2)`` (both
    ends of ``u1`` / ``u2``) or ``((lo1, hi1), (lo2, hi2))``, mixed freely."""
    if isinstance(value, (bool, np.bool_)):
        value = (value, value)
    try:
        a, b = value
    except (TypeError, ValueError):
        raise ValueError(
            f"{what} must be a bool, a pair (u1, u2) of bools, or a pair of pairs "
            f"((u1 low, u1 high), (u2 low, u2 high)), got {value!r}"
        ) from None
    ends = "(low, high)"
    return (_bool_pair(a, f"{what}[0]", ends), _bool_pair(b, f"{what}[1]", ends))


def domain_flags(owner: str) -> tuple[Any, Any]:
    """attrs fields ``periodic`` and ``poles`` whose errors name ``owner``."""
    periodic = attrs.field(
        default=(False, False), converter=lambda v: _gluing_pair(v, f"{owner}: periodic")
    )
    poles = attrs.field(default=False, converter=lambda v: _pole_pairs(v, f"{owner}: poles"))
    return periodic, poles


_DOMAIN_FLAGS = domain_flags("Domain")


@attrs.frozen
class Domain:
    """The drawn parameter rectangle ``u1_range x u2_range`` and its gluing.

    ``periodic[i]`` says how the two ends of ``u_i`` are glued: ``False``
    (not: they are boundary curves), ``True`` (``u_i`` wraps around: the two
    ends are the same curve) or ``"twisted"`` (the two ends are the same
    curve traversed the other way round in the other parameter:
    ``x(lo_i, t) = x(hi_i, a + b - t)`` with ``[a, b]`` the other range).
    ``poles[i] = (low, high)`` says which ends of ``u_i`` collapse to
    single points (no boundary line is drawn there).  ``poles`` may be given
    as one bool, one bool per parameter, or a pair per parameter: a bowl
    with its vertex at ``u1 = 0`` and its rim at ``u1 = 1`` has
    ``poles=((True, False), False)``.

    >>> Domain((0, 1), (0, 1), poles=((True, False), False)).ends(0).tolist()
    [1.0]
    >>> d = Domain((0, 1), (0, 6.283185307179586), periodic=(False, True))
    >>> d.lines(0, 3).tolist()
    [0.25, 0.5, 0.75]
    >>> len(d.lines(1, 4))
    4
    >>> d.ends(0).tolist(), d.ends(1).tolist()
    ([0.0, 1.0], [])

    A Moebius strip's ``u1`` is twisted: past its end, ``u2`` comes back mirrored.

    >>> m = Domain((0, 1), (-1, 1), periodic=("twisted", False))
    >>> m.periodic, m.glued, m.wrap([[1.25, 0.5]]).tolist()
    (('twisted', False), (True, False), [[0.25, -0.5]])
    >>> Domain((0, 1), (0, 1), periodic=("no", False))
    Traceback (most recent call last):
    ...
    ValueError: Domain: periodic[0] must be False, True or 'twisted', got 'no'
    """

    u1: tuple[float, float] = attrs.field(converter=lambda v: interval("Domain", "u1", v))
    u2: tuple[float, float] = attrs.field(converter=lambda v: interval("Domain", "u2", v))
    periodic: tuple[Any, Any] = _DOMAIN_FLAGS[0]
    poles: tuple[tuple[bool, bool], tuple[bool, bool]] = _DOMAIN_FLAGS[1]

    def range(self, i: int) -> tuple[float, float]:
        return self.u1 if i == 0 else self.u2

    def span(self, i: int) -> float:
        lo, hi = self.range(i)
        return hi - lo

    @property
    def glued(self) -> tuple[bool, bool]:
        """Per parameter: are its two ends glued (periodic or twisted)?"""
        return (self.periodic[0] is not False, self.periodic[1] is not False)

    @property
    def twisted(self) -> tuple[bool, bool]:
        """Per parameter: are its two ends glued with a twist?"""
        return (self.periodic[0] == "twisted", self.periodic[1] == "twisted")

    def mirror(self, i: int, t: Any) -> np.ndarray:
        """``a + b - t``: parameter ``u_i``'s values reflected in the middle of its range."""
        lo, hi = self.range(i)
        return lo + hi - np.asarray(t, float)

    def lines(self, i: int, n: int) -> np.ndarray:
        """``n`` evenly spread values of ``u_i`` for drawing ``u_i = const`` lines.

        Glued parameters get ``n`` values without repeating the seam;
        otherwise the ``n`` values split the range into ``n + 1`` equal parts
        (the ends are the patch boundary, drawn by :meth:`Surface.boundary`, or
        poles).
        """
        lo, hi = self.range(i)
        if n <= 0:
            return np.empty(0)
        if self.glued[i]:
            return lo + (hi - lo) * np.arange(n) / n
        return lo + (hi - lo) * np.arange(1, n + 1) / (n + 1)

    def cells(self, uv: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Cover points ``(..., 2)`` as ``(base, copy, sign)``: the point of the
        rectangle, the copy ``(k1, k2)`` of the rectangle holding the cover
        point (0 for parameters that are not glued), and the sign of each
        coordinate of the map from the rectangle to that copy (``-1`` where
        a twist reflects it).  Parameters that are not glued are left as they
        are."""
        b = np.array(uv, dtype=float, copy=True)
        k = np.zeros(b.shape, int)
        sign = np.ones(b.shape)
        glued, twisted = self.glued, self.twisted
        for i in (0, 1):
            if not glued[i]:
                continue
            lo, hi = self.range(i)
            span = hi - lo
            with np.errstate(invalid="ignore"):
                q = np.floor((b[..., i] - lo) / span)
            k[..., i] = np.where(np.abs(q) < 2**62, q, 0).astype(int)  # NaN, inf: copy 0
            with np.errstate(invalid="ignore"):
                b[..., i] = lo + np.mod(b[..., i] - lo, span)
            if twisted[i]:
                j = 1 - i
                odd = (k[..., i] % 2) == 1
                b[..., j] = np.where(odd, self.mirror(j, b[..., j]), b[..., j])
                sign[..., j] = np.where(odd, -sign[..., j], sign[..., j])
        return b, k, sign

    def unwrap(self, base: Any, copy: Any) -> np.ndarray:
        """The cover points in copies ``copy`` ``(..., 2)`` of the rectangle's
        points ``base`` (the inverse of :meth:`cells`)."""
        c = np.array(base, dtype=float, copy=True)
        k = np.asarray(copy, int)
        for i in (1, 0):
            if not self.glued[i]:
                continue
            if self.twisted[i]:
                j = 1 - i
                odd = (k[..., i] % 2) == 1
                c[..., j] = np.where(odd, self.mirror(j, c[..., j]), c[..., j])
            c[..., i] = c[..., i] + k[..., i] * self.span(i)
        return c

    def _affine(self, copy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The maps ``x -> S x + t`` (``S`` signs) from the rectangle to copies ``copy``."""
        zero = np.zeros(np.shape(copy))
        t = self.unwrap(zero, copy)
        return self.unwrap(zero + 1.0, copy) - t, t

    def deck(self, p: Any, q: Any) -> tuple[np.ndarray, np.ndarray]:
        """The maps ``x -> S x + t`` of the cover (``(S, t)``, both ``(..., 2)``)
        that take points ``q`` to their copies nearest to cover points ``p``
        (distance in spans, max norm; arrays broadcast): how a curve through
        ``q`` continues into the copy of the rectangle around ``p``."""
        p, q = np.broadcast_arrays(np.asarray(p, float), np.asarray(q, float))
        qb, kq, _ = self.cells(q)
        span = np.array([self.span(0), self.span(1)])
        offsets = [(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1)
                   if (a == 0 or self.glued[0]) and (b == 0 or self.glued[1])]  # fmt: skip
        # the copy holding p and its neighbours in the plane (their numbers
        # are not neighbours across a twist), found from the copy's centre
        # (far from the edges where rounding decides)
        mid = np.array([sum(self.u1), sum(self.u2)]) / 2
        centre = self.unwrap(np.broadcast_to(mid, p.shape), self.cells(p)[1])
        copies = np.stack([self.cells(centre + np.array(o) * span)[1] for o in offsets])
        cand = self.unwrap(np.broadcast_to(qb, copies.shape), copies)
        best = np.argmin(np.abs((cand - p) / span).max(axis=-1), axis=0)
        k = np.take_along_axis(copies, best[None, ..., None], axis=0)[0]
        sk, tk = self._affine(k)
        sq, tq = self._affine(kq)
        return sk * sq, tk - sk * sq * tq

    def continuous(self, p: Any) -> np.ndarray:
        """A polyline ``(n, 2)`` of points given anywhere in the cover (say
        wrapped into the rectangle) moved, point by point, into the copies
        that make it continuous: each point the copy nearest to the one
        before it (the deck maps composed, all points at once)."""
        p = np.asarray(p, float)
        if len(p) < 2 or not any(self.glued):
            return p.copy()
        s, t = self.deck(p[:-1], p[1:])  # p[i] -> near p[i - 1]
        S = np.cumprod(np.vstack([np.ones((1, 2)), s]), axis=0)
        T = np.vstack([np.zeros((1, 2)), np.cumsum(S[:-1] * t, axis=0)])
        return S * p + T

    def nearest_image(self, p: Any, q: Any) -> np.ndarray:
        """The copies of points ``q`` nearest to cover points ``p`` (both
        ``(..., 2)``, broadcast; distance in spans, max norm): where a curve
        through ``p`` meets ``q`` again in the cover."""
        S, t = self.deck(p, q)
        return S * np.asarray(q, float) + t

    def wrap(self, uv: Any, clip: bool = True) -> np.ndarray:
        """A copy of parameters ``(..., 2)`` with glued ones mapped into the
        rectangle (a twisted one past its end reflects the other parameter)
        and (with ``clip``) the others clipped to it.

        >>> d = Domain((0, 1), (0, 2), periodic=(False, True))
        >>> d.wrap([[1.5, 2.5], [-1.0, -0.5]]).tolist()
        [[1.0, 0.5], [0.0, 1.5]]
        """
        if self.periodic[0] == "twisted" or self.periodic[1] == "twisted":
            uv = self.cells(uv)[0]
        else:  # plain periodic (the common case, in inner loops): no copies needed
            uv = np.array(uv, dtype=float, copy=True)
            for i in (0, 1):
                if self.periodic[i] is True:
                    lo, hi = self.range(i)
                    uv[..., i] = lo + np.mod(uv[..., i] - lo, hi - lo)
        if clip:
            for i in (0, 1):
                if not self.glued[i]:
                    uv[..., i] = np.clip(uv[..., i], *self.range(i))
        return uv

    def clip(self, uv: Any) -> np.ndarray:
        """A copy of parameters ``(..., 2)`` with those that are not glued
        clipped into the rectangle (glued ones are left in the cover): where
        a search that strays past an edge evaluates the surface instead.

        >>> Domain((0, 1), (0, 2), periodic=(False, True)).clip([[1.5, 2.5]]).tolist()
        [[1.0, 2.5]]
        """
        uv = np.array(uv, dtype=float, copy=True)
        for i in (0, 1):
            if not self.glued[i]:
                uv[..., i] = np.clip(uv[..., i], *self.range(i))
        return uv

    def ends(self, i: int) -> np.ndarray:
        """The values of ``u_i`` at which the patch has a boundary curve (both
        ends, unless ``u_i`` is glued; pole ends excluded)."""
        if self.glued[i]:
            return np.empty(0)
        return np.array([e for e, pole in zip(self.range(i), self.poles[i]) if not pole], float)


class Parametrized(Protocol):
    """What the numeric defaults of a surface (``lgraph.surfaces.parametric``'s
    contour, ray test, boxes and zero sets) need of it: a patch ``x(u1, u2)``
    over a :class:`Domain`, its derivatives, a box around it and its size.  Every
    :class:`~lgraph.Surface` is one; the helpers type their argument with this
    protocol so that they need not import the base class that calls them."""

    @property
    def domain(self) -> Domain: ...

    def point(self, u1: npt.ArrayLike, u2: npt.ArrayLike) -> np.ndarray: ...

    def derivatives(
        self, u1: npt.ArrayLike, u2: npt.ArrayLike
    ) -> tuple[np.ndarray, np.ndarray]: ...

    def second_derivatives(
        self, u1: npt.ArrayLike, u2: npt.ArrayLike
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...

    def bounds(self) -> tuple[np.ndarray, np.ndarray]: ...

    @property
    def size(self) -> float: ...
