"""Lines of a line field on a surface, traced all at once (:func:`trace`).

A *line field* (:func:`lgraph.curvature.principal_field`,
:func:`lgraph.curvature.asymptotic_field`) gives two unoriented directions at
every point of the parameter plane.  Which lines a family draws is decided in
:mod:`lgraph.families.numeric`; derivation and guarantees:
``docs/mathematics.rst``, "Numeric line families".

* The curve parameter is 3-D arc length.  Every line advances in lockstep with
  its own step size (Dormand and Prince's embedded 5(4) pair, error per step below
  ``FIELD_RTOL`` of the parameter spans,
  ``ASYMPTOTIC_RTOL`` for asymptotic lines), so one
  field evaluation serves every line; lines are evaluated with the method's
  own 4th-order continuous extension.
* At every stage a line takes the branch of the field nearest (in the
  surface's metric) to its current direction, with that direction's sign:
  it never switches branch.  Nothing depends on the last bits of floating point.
* A line stops at the patch boundary (a step that leaves it is redone to end
  on it), where it passes an umbilic given to :func:`trace`, where the field
  degenerates (the step would have to shrink below
  ``FIELD_MIN_STEP``), when it returns to its seed
  (closed), or after ``FIELD_MAX_LENGTH`` sizes.

>>> import numpy as np
>>> import lgraph as lg
>>> from lgraph.curvature import principal_field
>>> L = trace(lg.MonkeySaddle(), principal_field, [[0.5, 0.2]], [[1.0, 0.0]])
>>> bool(L.ends[0, 0] > 0 and L.ends[1, 0] > 0), bool(L.closed[0])
(True, False)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._tolerance import (
    FIELD_CLOSE_RTOL,
    FIELD_FIRST_STEP,
    FIELD_MAX_ITERATIONS,
    FIELD_MAX_LENGTH,
    FIELD_MAX_STEP,
    FIELD_MIN_STEP,
    FIELD_RTOL,
    FIELD_SINGULAR_RTOL,
    UMBILIC_STOP,
)
from ..curves import CurveBatch

__all__ = ["FieldLines", "trace"]


# Dormand-Prince 5(4): nodes, stage coefficients, 5th-order weights, and the
# difference of the 5th- and 4th-order weights (7 stages, the last one is the
# field at the new point and starts the next step).
_A = (
    (),
    (1 / 5,),
    (3 / 40, 9 / 40),
    (44 / 45, -56 / 15, 32 / 9),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
)
_B = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84)
_E = (71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40)
#: a step ends on an edge or the seed when that lies within this fraction of its end
_END_RTOL = 1e-7
# the quartic term of the continuous extension (Hairer, Norsett and Wanner's DOPRI5)
_D = (-12715105075 / 11282082432, 0.0, 87487479700 / 32700410799,
      -10690763975 / 1880347072, 701980252875 / 199316789632,
      -1453857185 / 822651844, 69997945 / 29380423)  # fmt: skip
# the same as arrays (stage combinations are matrix products in trace)
_A_ROWS = [np.array(a) for a in _A[1:]]
_B_ROW, _E_ROW, _D_ROW = np.array(_B), np.array(_E), np.array(_D)


def _cubic(y0: np.ndarray, k0: np.ndarray, y1: np.ndarray, k1: np.ndarray,
           h: np.ndarray) -> np.ndarray:  # fmt: skip
    """Coefficients ``(n, 4, 2)`` (constant first) of the cubic Hermite
    interpolants of steps ``y0 -> y1`` with arc-length tangents ``k0, k1``,
    in the step fraction ``0..1``."""
    hk0, hk1 = h[:, None] * k0, h[:, None] * k1
    return np.stack([y0, hk0, 3 * (y1 - y0) - 2 * hk0 - hk1, 2 * (y0 - y1) + hk0 + hk1], axis=1)


def _at(C: np.ndarray, th: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Point and arc-length derivative of cubics ``C`` at fractions ``th``."""
    t = th[:, None]
    p = ((C[:, 3] * t + C[:, 2]) * t + C[:, 1]) * t + C[:, 0]
    dp = ((3 * C[:, 3] * t + 2 * C[:, 2]) * t + C[:, 1]) / h[:, None]
    return p, dp


def _dense_at(y0: np.ndarray, k0: np.ndarray, y1: np.ndarray, k1: np.ndarray,
              r5: np.ndarray, h: np.ndarray, th: np.ndarray) -> np.ndarray:  # fmt: skip
    """Dormand and Prince's continuous extension of steps (rows) at fractions
    ``th``: the cubic Hermite interpolant plus ``th^2 (1 - th)^2 r5``."""
    t = th[:, None]
    ydiff = y1 - y0
    bspl = h[:, None] * k0 - ydiff
    r4 = ydiff - h[:, None] * k1 - bspl
    return y0 + t * (ydiff + (1 - t) * (bspl + t * (r4 + (1 - t) * r5)))


_GRID17 = np.linspace(0.0, 1.0, 17)
_GRID33 = np.linspace(0.0, 1.0, 33)


def _quartic(y0: np.ndarray, k0: np.ndarray, y1: np.ndarray, k1: np.ndarray,
             h: np.ndarray, r5: np.ndarray) -> np.ndarray:  # fmt: skip
    """Coefficients ``(n, 5, 2)`` (constant first) of the continuous extension
    of steps (:func:`_dense_at`) as polynomials in the step fraction."""
    a = y1 - y0
    hk0 = h[:, None] * k0
    b = hk0 - a
    r4 = a - h[:, None] * k1 - b
    return np.stack([y0, hk0, r4 + r5 - b, -(r4 + 2 * r5), r5], axis=1)


def _exit(C: np.ndarray, lo: np.ndarray, hi: np.ndarray, per: np.ndarray) -> np.ndarray:
    """The fraction where each polynomial (coefficients ``(n, d + 1, 2)``,
    constant first; it starts inside the box ``lo..hi`` and ends outside it)
    first leaves the box: the first of 16 parts that ends outside, then
    safeguarded Newton steps on the excess over the box (the larger of the
    two coordinates'; callers silence floating-point warnings)."""
    grid = _GRID17
    deg = C.shape[1] - 1
    powers = np.arange(deg + 1)
    p = np.einsum("ti,nik->ntk", grid[:, None] ** powers, C)
    lo_, hi_ = np.where(per, -np.inf, lo), np.where(per, np.inf, hi)
    excess = np.maximum(p - hi_, lo_ - p).max(axis=2)  # > 0 outside
    first = np.argmax(excess > 0, axis=1)
    a, b = grid[first - 1], grid[first]
    D = C[:, 1:] * powers[1:, None]  # the derivative's coefficients
    # start where the excess interpolated linearly over the part vanishes
    rows = np.arange(len(C))
    fa, fb = excess[rows, first - 1], excess[rows, first]
    c = a + (b - a) * np.fmin(np.fmax(fa / (fa - fb), 0.0), 1.0)
    for _ in range(6):
        T = c[:, None] ** powers
        p = np.einsum("ni,nik->nk", T, C)
        dp = np.einsum("ni,nik->nk", T[:, :-1], D)
        up, down = p - hi_, lo_ - p
        excess = np.maximum(up, down)  # > 0 outside
        # its slope: the upper side's where that is the nearer (inside too)
        slope = np.where(up >= down, dp, -dp)
        j = excess[:, 1] > excess[:, 0]  # the larger coordinate (the first on ties)
        f = np.where(j, excess[:, 1], excess[:, 0])
        df = np.where(j, slope[:, 1], slope[:, 0])
        outside = f > 0
        a, b = np.where(outside, a, c), np.where(outside, c, b)
        new = c - f / df  # (stays on a root found: f = 0 moves a there)
        new = np.where((new >= a) & (new <= b), new, 0.5 * (a + b))
        if np.abs(new - c).max() <= 1e-14:  # converged (to far below _END_RTOL)
            c = new
            break
        c = new
    return c


def _chord_gap(y0: np.ndarray, y1: np.ndarray, target: np.ndarray, span: np.ndarray,
               per: Any) -> np.ndarray:  # fmt: skip
    """Distance (scaled parameters, max norm) of ``target`` to the chords ``y0 -> y1``."""
    r0 = _rel(y0, target, span, per)
    dr = (y1 - y0) / span
    with np.errstate(invalid="ignore", divide="ignore"):
        tc = -(r0[:, 0] * dr[:, 0] + r0[:, 1] * dr[:, 1]) / (dr[:, 0] ** 2 + dr[:, 1] ** 2)
    tc = np.fmin(np.fmax(tc, 0.0), 1.0)[:, None]  # NaN (a step of length 0) -> 0
    return np.abs(r0 + tc * dr).max(axis=1)


def _rel(p: np.ndarray, seed: np.ndarray, span: np.ndarray, per: Any) -> np.ndarray:
    """Parameters relative to ``seed`` in spans (glued ones to the nearest copy
    in the cover; ``per`` is the domain)."""
    if not any(per.glued):  # the rectangle is the cover: no copies to look for
        return (p - seed) / span
    return (p - per.nearest_image(p, seed)) / span


def _closest(C: np.ndarray, h: np.ndarray, seed: np.ndarray, span: np.ndarray,
             per: Any) -> tuple[np.ndarray, ...]:  # fmt: skip
    """The fraction (0..1) where each cubic passes closest to its
    seed (scaled parameters): the best of 33 samples, then Newton on
    ``(p - seed) . p' = 0``; with the point and tangent there."""
    grid = _GRID33
    t = grid[None, :, None]
    p = ((C[:, None, 3] * t + C[:, None, 2]) * t + C[:, None, 1]) * t + C[:, None, 0]
    q = _rel(p, seed[:, None], span, per)
    th = grid[np.argmin((q * q).sum(axis=2), axis=1)]
    for _ in range(6):
        p, dp = _at(C, th, h)
        r = _rel(p, seed, span, per) / span  # gradient of the scaled distance
        w = dp * h[:, None]
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.einsum("ij,ij->i", r, w) / np.einsum("ij,ij->i", w / span, w / span)
        th = np.clip(th - np.nan_to_num(step), 0.0, 1.0)
    p, dp = _at(C, th, h)
    return th, p, dp


class FieldLines:
    """Lines traced by :func:`trace`: line ``k`` runs over arc lengths
    ``-ends[1, k] .. ends[0, k]`` (0 at its seed); ``closed[k]`` lines are loops
    over ``0 .. ends[0, k]``.

    Stored as the integrator's nodes (parameters, unit tangents, and the
    quartic term of each step's continuous extension) and evaluated with the
    method's own 4th-order interpolant, all lines at once (:meth:`uv`).
    """

    def __init__(self, surface: Any, s: list, y: list, k: list, r5: list,
                 closed: np.ndarray) -> None:  # fmt: skip
        self.surface = surface
        self.domain = surface.domain
        self.m = len(s)
        self.closed = np.asarray(closed, bool)
        self.ends = np.array([[float(si[-1]) for si in s], [float(-si[0]) for si in s]])
        self.ends = self.ends.reshape(2, self.m)
        counts = np.array([len(si) for si in s], int)
        self._start = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(int)
        self._count = counts
        lengths = self.ends[0] + self.ends[1]
        # a global increasing key: line k's arc lengths shifted past all before it
        self._shift = np.concatenate([[0.0], np.cumsum(lengths + 1.0)[:-1]]) + self.ends[1]
        self._s = np.concatenate(s) if s else np.empty(0)
        self._key = self._s + np.repeat(self._shift, counts)
        self._y = np.concatenate(y) if y else np.empty((0, 2))
        self._k = np.concatenate(k) if k else np.empty((0, 2))
        self._r5 = np.concatenate(r5) if r5 else np.empty((0, 2))

    def uv(self, idx: Any, t: Any) -> np.ndarray:
        """Parameters ``(n, 2)`` of lines ``idx`` at signed arc lengths ``t``
        (unwrapped: periodic parameters may leave their range)."""
        idx = np.asarray(idx, int)
        t = np.clip(np.asarray(t, float), -self.ends[1, idx], self.ends[0, idx])
        lo = self._start[idx]
        hi = lo + np.maximum(self._count[idx] - 2, 0)
        j = np.clip(np.searchsorted(self._key, t + self._shift[idx], "right") - 1, lo, hi)
        if not len(j):
            return np.empty((0, 2))
        j1 = np.minimum(j + 1, len(self._s) - 1)
        h = self._s[j1] - self._s[j]
        single = h <= 0  # a line of one node
        hs = np.where(single, 1.0, h)
        th = np.where(single, 0.0, (t - self._s[j]) / hs)
        return _dense_at(self._y[j], self._k[j], self._y[j1], self._k[j1], self._r5[j], hs, th)

    def uv_line(self, k: int, t: np.ndarray) -> np.ndarray:
        """:meth:`uv` of one line."""
        return self.uv(np.full(len(t), k), t)

    def points(self, k: int, t: np.ndarray) -> np.ndarray:
        """3-D points of line ``k`` at arc lengths ``t``."""
        uv = self.domain.wrap(self.uv_line(k, np.asarray(t, float)), clip=False)
        return self.surface.point(uv[:, 0], uv[:, 1])

    def batch(self, family: str, keep: Any = None) -> CurveBatch | None:
        """The lines ``keep`` (default all, those of zero length left out) as one batch."""
        ks = np.arange(self.m) if keep is None else np.asarray(keep, int)
        ks = ks[(self.ends[0, ks] + self.ends[1, ks]) > 0]
        if not len(ks):
            return None
        domain = self.domain
        return CurveBatch.from_uv(
            self.surface,
            family,
            -self.ends[1, ks],
            self.ends[0, ks],
            lambda c, t: domain.wrap(self.uv(ks[np.asarray(c, int)], t)),
            closed=self.closed[ks],
        )


def _finish(ends: tuple, rows: np.ndarray, th: np.ndarray, target: np.ndarray) -> None:
    """End the steps ``rows`` on ``target`` (a patch edge or the seed) where
    the step ends there (``th`` ~ 1); where it would end a tiny step
    (about ``FIELD_MIN_STEP``) after its start, the line ends at the start
    instead.  ``ends`` holds the step's arrays, changed in place."""
    y1, stop_here, drop = ends
    full = th >= 1 - _END_RTOL
    y1[rows[full]] = target[full]
    drop[rows[~full]] = True
    stop_here[rows] = True


def trace(
    surface: Any,
    field: Any,
    seeds: Any,
    directions: Any,
    *,
    length: float | None = None,
    stop: float | None = None,
    rtol: float | None = None,
    max_step: float = FIELD_MAX_STEP,
    singular: Any = (),
    lean: Any = None,
) -> FieldLines:
    """Trace the lines of ``field`` through ``seeds`` ``(m, 2)``, each starting
    along the branch nearest to ``directions[k]`` (parameter directions),
    forward and backward, all at once (steps at most ``max_step`` sizes).
    Lines end where they pass within
    ``FIELD_SINGULAR_RTOL`` of a point of ``singular``
    (parameters of umbilics).  See the module docstring.

    ``lean(surface, stop)``, where given, makes the ``oriented(uv, ref)`` the
    steps use on domains without a twist: the field's branch nearest ``ref``
    in few array operations (``lgraph.families.numeric.principal_oriented``).
    """
    seeds = np.asarray(seeds, float).reshape(-1, 2)
    m = len(seeds)
    if m == 0:
        return FieldLines(surface, [], [], [], [], np.zeros(0, bool))
    d = surface.domain
    size = float(surface.size)
    length = FIELD_MAX_LENGTH * size if length is None else float(length)
    stop = float(getattr(field, "stop", UMBILIC_STOP) if stop is None else stop)
    rtol = float(getattr(field, "rtol", FIELD_RTOL) if rtol is None else rtol)
    singular = np.asarray(singular, float).reshape(-1, 2)
    span = np.array([d.span(0), d.span(1)])
    lo = np.array([d.u1[0], d.u2[0]])
    hi = np.array([d.u1[1], d.u2[1]])
    per = np.array(d.glued)
    twisted = any(d.twisted)

    def at(uv: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The field at cover points: directions and metric mapped from the
        rectangle (a twist reflects a coordinate)."""
        # trial stages past an edge that is not glued see the field of the
        # nearest edge point (the surface is never evaluated outside; the step
        # is then cut to end on the edge)
        if not twisted:
            return field(surface, d.wrap(uv, clip=True))
        base, _, sign = d.cells(uv)
        D, strength, G = field(surface, d.clip(base))
        G = G * np.stack([np.ones(len(G)), sign[:, 0] * sign[:, 1], np.ones(len(G))], axis=1)
        return D * sign[:, None, :], strength, G

    def oriented(uv: np.ndarray, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The field's direction at ``uv`` nearest to ``ref`` (same sign), and
        whether it is valid (finite, strong, at most 60 degrees from ``ref``)."""
        D, strength, G = at(uv)
        Gr = np.stack([G[:, 0] * ref[:, 0] + G[:, 1] * ref[:, 1],
                       G[:, 1] * ref[:, 0] + G[:, 2] * ref[:, 1]], axis=1)  # fmt: skip
        c = np.einsum("ibj,ij->ib", D, Gr)  # cosines with ref, per branch
        b = (np.abs(c[:, 1]) > np.abs(c[:, 0])).astype(int)
        rows = np.arange(len(uv))
        cb = c[rows, b]
        out = D[rows, b] * np.where(cb < 0, -1.0, 1.0)[:, None]
        with np.errstate(invalid="ignore"):
            ok = np.isfinite(out).all(axis=1) & (strength > stop) & (np.abs(cb) > 0.5)
        return np.where(ok[:, None], out, 0.0), ok

    if lean is not None and not twisted:
        fast = lean(surface, stop)
        if any(d.glued):
            oriented = lambda uv, ref: fast(d.wrap(uv, clip=True), ref)  # noqa: E731
        elif getattr(surface, "defined_past_domain", False):
            # closed forms that hold past the edges (the monkey saddle's):
            # trial stages there see the field itself, so steps that end
            # just past an edge keep their accuracy (lines grazing an edge
            # would crawl along it)
            oriented = fast
        else:  # trial stages past an edge see the field of the nearest edge point
            oriented = lambda uv, ref: fast(np.minimum(np.maximum(uv, lo), hi), ref)  # noqa: E731

    # rays 0..m-1 run forward, m..2m-1 backward from the same seeds
    Y = np.concatenate([seeds, seeds])
    ref = np.asarray(directions, float).reshape(-1, 2)
    ref = np.concatenate([ref, -ref])
    _, _, G0 = at(seeds)
    G0 = np.concatenate([G0, G0])
    nref = np.sqrt(G0[:, 0] * ref[:, 0] ** 2 + 2 * G0[:, 1] * ref[:, 0] * ref[:, 1]
                   + G0[:, 2] * ref[:, 1] ** 2)  # fmt: skip
    with np.errstate(invalid="ignore", divide="ignore"):
        ref = ref / nref[:, None]
    K, alive = oriented(Y, np.where(np.isfinite(ref), ref, 0.0))
    R = 2 * m
    S = np.zeros(R)
    H = np.full(R, FIELD_FIRST_STEP * size)
    hmin, hmax = FIELD_MIN_STEP * size, max_step * size
    closed = np.zeros(R, bool)
    left = np.zeros(R, bool)  # has been far from its seed (closing test)
    zero = np.zeros((R, 2))
    rec_i, rec_s, rec_y, rec_k, rec_r = [np.arange(R)], [S.copy()], [Y.copy()], [K.copy()], [zero]

    # (steps through singular points divide by zero; those steps are rejected)
    with np.errstate(invalid="ignore", divide="ignore"):
        for _iteration in range(FIELD_MAX_ITERATIONS):
            act = np.flatnonzero(alive)
            if not len(act):
                break
            y, k1 = Y[act], K[act]
            h = np.minimum(H[act], length - S[act])
            hc = h[:, None]
            # the stages' slopes as rows of one array: their combinations are products
            # (einsum, not BLAS: its threads spin and wake slowly on a loaded machine)
            ks = np.empty((7, 2 * len(act)))
            ks[0] = k1.ravel()
            ki, ok = k1, np.ones(len(act), bool)
            for j, a in enumerate(_A_ROWS, 1):
                ki, oki = oriented(y + hc * np.einsum("s,sn->n", a, ks[:j]).reshape(-1, 2), ki)
                ok &= oki
                ks[j] = ki.ravel()
            y5 = y + hc * np.einsum("s,sn->n", _B_ROW, ks[:6]).reshape(-1, 2)
            k7, ok7 = oriented(y5, ki)
            ok &= ok7
            ks[6] = k7.ravel()
            err = np.einsum("s,sn->n", _E_ROW, ks).reshape(-1, 2)
            err = (np.abs(hc * err) / span).max(axis=1)
            good = ok & (err <= rtol)
            fac = np.minimum(np.maximum(0.9 * (rtol / np.maximum(err, 1e-300)) ** 0.2, 0.2), 5.0)
            newh = np.where(ok, h * np.where(good, fac, np.minimum(fac, 0.5)), 0.1 * h)
            # a step that cannot shrink further: a singular point (or the field's edge)
            dead = ~good & (newh < hmin)
            H[act] = np.minimum(newh, hmax)
            alive[act[dead]] = False
            g = np.flatnonzero(good)
            if not len(g):
                continue
            hg = h[g]
            step = (y[g], k1[g], y5[g], k7[g], hg)  # the steps' cubics are built where needed
            y1, k1n = y5[g].copy(), k7[g].copy()
            r5 = hg[:, None] * np.einsum("s,sn->n", _D_ROW, ks).reshape(-1, 2)[g]
            stop_here = np.zeros(len(g), bool)
            redo = np.full(len(g), np.nan)  # retry with this step (ends on an edge or the seed)

            drop = np.zeros(len(g), bool)  # ends where it starts: no new node
            ends = (y1, stop_here, drop)
            # leaving the patch across a non-periodic side: end exactly on it
            out = np.flatnonzero((((y1 < lo) | (y1 > hi)) & ~per).any(axis=1))
            if len(out):
                # where the method's own continuous extension leaves the patch
                th = _exit(_quartic(*(a[out] for a in step), r5[out]), lo, hi, per)
                last = (th >= 1 - _END_RTOL) | (th * hg[out] <= 10 * hmin)
                box = (np.where(per, -np.inf, lo), np.where(per, np.inf, hi))
                _finish(ends, out[last], th[last], np.clip(y1[out[last]], *box))
                # retry with a step that ends just past the edge
                redo[out[~last]] = np.minimum(th[~last] * (1 + 0.1 * _END_RTOL), 1) * hg[out[~last]]
            # closing: a forward line passing its seed again after leaving it
            f = np.flatnonzero((act[g] < m) & np.isnan(redo) & ~stop_here)
            if len(f):
                gap = _chord_gap(y[g[f]], y1[f], seeds[act[g[f]]], span, d)
                near = f[(gap <= 0.05) & left[act[g[f]]]]
                left[act[g[f[gap > 0.05]]]] = True
                if len(near):
                    seed = seeds[act[g[near]]]
                    th, p, _ = _closest(_cubic(*(a[near] for a in step)), hg[near], seed, span, d)
                    hit = np.abs(_rel(p, seed, span, d)).max(axis=1) < FIELD_CLOSE_RTOL
                    last = hit & ((th >= 1 - _END_RTOL) | (th * hg[near] <= 10 * hmin))
                    # the loop ends exactly on its seed (shifted by whole periods)
                    shift = _rel(p[last], seed[last], span, d) * span
                    _finish(ends, near[last], th[last], p[last] - shift)
                    closed[act[g[near[last]]]] = True
                    alive[act[g[near[last]]] + m] = False  # the backward half is not needed
                    redo[near[hit & ~last]] = th[hit & ~last] * hg[near[hit & ~last]]
            # reaching a singular point (an umbilic): the line ends where it passes it
            for point in singular:
                f = np.flatnonzero(np.isnan(redo) & ~stop_here)
                gap = _chord_gap(y[g[f]], y1[f], np.broadcast_to(point, (len(f), 2)), span, d)
                near = f[gap <= FIELD_SINGULAR_RTOL]
                if len(near):
                    target = np.broadcast_to(point, (len(near), 2))
                    th, p, _ = _closest(_cubic(*(a[near] for a in step)), hg[near], target, span, d)
                    last = (th >= 1 - _END_RTOL) | (th * hg[near] <= 10 * hmin)
                    _finish(ends, near[last], th[last], y1[near[last]])
                    redo[near[~last]] = th[~last] * hg[near[~last]]
            again = ~np.isnan(redo)
            H[act[g[again]]] = redo[again]
            sel = ~again & ~drop
            acc = act[g[sel]]
            Y[acc], K[acc] = y1[sel], k1n[sel]
            S[acc] += hg[sel]
            alive[act[g[stop_here]]] = False  # after their last node
            alive[acc[S[acc] >= length * (1 - 1e-12)]] = False
            rec_i.append(acc)
            rec_s.append(S[acc].copy())
            rec_y.append(y1[sel])
            rec_k.append(k1n[sel])
            rec_r.append(r5[sel])

    ri = np.concatenate(rec_i)
    order = np.lexsort((np.concatenate(rec_s), ri))
    ri = ri[order]
    rs, ry, rk, rr = (np.concatenate(x)[order] for x in (rec_s, rec_y, rec_k, rec_r))
    bounds = np.searchsorted(ri, np.arange(R + 1))
    s_out, y_out, k_out, r_out = [], [], [], []
    for j in range(m):
        fa, fb = bounds[j], bounds[j + 1]
        ba, bb = bounds[j + m] + 1, bounds[j + m + 1]  # the seed is the forward half's
        if closed[j]:
            ba = bb  # a loop is its forward half
        s_out.append(np.concatenate([-rs[ba:bb][::-1], rs[fa:fb]]))
        y_out.append(np.concatenate([ry[ba:bb][::-1], ry[fa:fb]]))
        k_out.append(np.concatenate([-rk[ba:bb][::-1], rk[fa:fb]]))
        # each node carries the quartic term of the step that leaves it
        r_out.append(np.concatenate([rr[ba:bb][::-1], rr[fa + 1 : fb], np.zeros((1, 2))]))
    return FieldLines(surface, s_out, y_out, k_out, r_out, closed[:m])
