"""Brackets of a change between two samples of a curve: K-section's
sub-points and its cost per bracket, and the net's crossings, refined on the
exact curves, that narrow a bracket at once (a flip of visibility or a
change of depth most likely lies where the curve passes behind the net:
:mod:`lgraph.render.flips`, :mod:`lgraph.render.depth`), and the zeros of
``N . ray`` where a curve passes its own surface's contour."""

from __future__ import annotations

from typing import TYPE_CHECKING

import attrs
import numpy as np

from .. import _tolerance as tol
from .._own import ON
from .._roots import bracketed_roots
from .crossings import net_meetings
from .sampling import Samples

if TYPE_CHECKING:
    from .occlusion import Occlusion

#: a flip where a curve passes its own contour is confirmed by ray tests this
#: far (of the span) on either side of the contour, the first that agree: the
#: numeric ray test takes a fold's root closer than about 1e-5 of the scene
#: for the point's own, so right beside the contour it sees the point visible
OWN_GUIDE_RTOLS = (1e-7, 1e-5, 1e-4, 1e-3)
#: wider than this, only in a chord that holds no other candidate (a wide
#: agreement could straddle another flip)
ALONE_RTOL = 1e-4

__all__ = [
    "Brackets",
    "confirmed",
    "exact_crossings",
    "net_guesses",
    "own_contour_zeros",
    "sections",
    "sub_points",
]


def exact_crossings(
    s: Samples,
    c: np.ndarray,
    t: np.ndarray,
    n: np.ndarray,
    tau: np.ndarray,
    steps: int = 4,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Crossings of two curves' images refined on the exact curves: from
    ``t`` on curves ``c`` and ``tau`` on curves ``n`` (a polyline crossing),
    Newton's method on ``P(x_c(t)) = P(x_n(tau))`` (the curves' tangents by
    one-sided differences, one evaluation call a step); returns ``t, tau``
    and the image distance left between the two points.

    A tangential meeting (a singular Jacobian) keeps its start; the caller
    checks what it gets."""
    t, tau = np.array(t, dtype=float), np.array(tau, dtype=float)
    m = len(t)
    if not m:
        return t, tau, np.empty(0)
    lo_c, hi_c = np.minimum(s.t0[c], s.t1[c]), np.maximum(s.t0[c], s.t1[c])
    lo_n, hi_n = np.minimum(s.t0[n], s.t1[n]), np.maximum(s.t0[n], s.t1[n])
    t, tau = np.clip(t, lo_c, hi_c), np.clip(tau, lo_n, hi_n)
    cid = np.concatenate([c, c, n, n])
    gap = np.full(m, np.inf)
    for step in range(steps + 1):
        # differences toward the inside of each curve's range, from where
        # the points are now (a step may have carried them to an end)
        hc, hn = _inward(t, lo_c, hi_c), _inward(tau, lo_n, hi_n)
        _, _, xy = s.evaluate(cid, np.concatenate([t, t + hc, tau, tau + hn]), True)
        pc, pc2, pn, pn2 = np.split(xy, 4)
        r = pc - pn
        gap = np.hypot(r[:, 0], r[:, 1])
        if step == steps:
            break
        dc, dn = (pc2 - pc) / hc[:, None], (pn2 - pn) / hn[:, None]
        # solve dc dt - dn dtau = -r
        det = dc[:, 0] * (-dn[:, 1]) - dc[:, 1] * (-dn[:, 0])
        with np.errstate(divide="ignore", invalid="ignore"):
            dt = (-r[:, 0] * (-dn[:, 1]) + r[:, 1] * (-dn[:, 0])) / det
            dtau = (dc[:, 0] * (-r[:, 1]) - dc[:, 1] * (-r[:, 0])) / det
        ok = np.isfinite(dt) & np.isfinite(dtau)
        t = np.clip(np.where(ok, t + dt, t), lo_c, hi_c)
        tau = np.clip(np.where(ok, tau + dtau, tau), lo_n, hi_n)
    return t, tau, gap


def _inward(t: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """A difference step of 1e-7 of the range ``lo .. hi`` from ``t`` that
    stays inside it."""
    h = 1e-7 * (hi - lo)
    return np.where(t + h <= hi, h, -h)


def net_guesses(
    s: Samples,
    vis: Occlusion,
    a: np.ndarray,
    margin: float,
    meetings: tuple[np.ndarray, ...] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For the chords ``a, a + 1`` (sorted) that cross the sampled net once:
    that crossing on the exact curves (:func:`exact_crossings`), where a
    visibility or depth change of the chord most likely lies.  Returns the
    chords' rows in ``a``, the crossings' parameters and ``w = margin`` of
    each curve's span, for those whose ``t -+ w`` lie inside their chord.
    ``meetings``: :func:`~lgraph.render.crossings.net_meetings` of ``a``, if
    the caller has them."""
    q, f, b, g = net_meetings(s, vis, a) if meetings is None else meetings
    row = np.searchsorted(a, q)
    sel = (np.bincount(row, minlength=len(a))[row] == 1) & (b >= 0)  # one, on a sampled curve
    row, q, f, b, g = row[sel], q[sel], f[sel], b[sel], g[sel]
    c = s.cid[q]
    t = s.t[q] + f * (s.t[q + 1] - s.t[q])
    tau = s.t[b] + g * (s.t[b + 1] - s.t[b])
    t, _, gap = exact_crossings(s, c, t, s.cid[b], tau)
    w = margin * np.abs(s.t1[c] - s.t0[c])
    met = gap <= 1e-9 * np.hypot(*(s.xy[q + 1] - s.xy[q]).T)
    met &= (t - w > s.t[q]) & (t + w < s.t[q + 1])
    return row[met], t[met], w[met]


def sections(view: np.ndarray, open_: np.ndarray, k_views: int, vis: Occlusion) -> np.ndarray:
    """``K`` for K-section, per bracket (brackets in views ``view``; those
    ``open_`` counted): the fixed cost of a step against its sub-points'
    tests, the least cost per bit gained (deterministic: no timing); per
    view, so that views rendered together split a bracket as a view alone
    would."""
    n_open = np.bincount(view[open_], minlength=k_views)
    ks = 2 ** np.arange(1, int(np.log2(tol.SECTIONS)) + 1)
    per_bit = (vis.cost_per_call + n_open[:, None] * (ks - 1) * vis.cost_per_point) / np.log2(ks)
    return ks[np.argmin(per_bit, axis=1)][view]


def sub_points(lo: np.ndarray, hi: np.ndarray, idx: np.ndarray, k: np.ndarray) -> tuple:
    """The ``k - 1`` sub-points splitting brackets ``lo[idx] .. hi[idx]`` into
    ``k`` parts: ``(rep, t, first_differing)`` with ``rep`` the bracket of
    every sub-point and ``first_differing(differs)`` -- given which
    sub-points differ from their bracket's ``lo`` -- the rows (into ``t``) of
    the new ``lo`` and ``hi`` of every bracket (-1: unchanged), keeping the
    first sub-bracket whose ends differ (none: the last part)."""
    m = k - 1
    rep = np.repeat(idx, m)
    start = np.cumsum(m) - m
    j = np.arange(len(rep)) - np.repeat(start, m) + 1  # 1 .. m in each bracket
    t = lo[rep] + (hi[rep] - lo[rep]) * (j / np.repeat(k, m))

    def first_differing(differs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        first = np.minimum.reduceat(np.where(differs, j - 1, np.repeat(m, m)), start)
        new_lo = np.where(first > 0, start + first - 1, -1)
        new_hi = np.where(first < m, start + first, -1)
        return new_lo, new_hi

    return rep, t, first_differing


@attrs.frozen
class Brackets:
    """Brackets ``lo < hi`` of a change on curves ``cid`` (owners
    ``owner``, ownership codes ``kind``): ``before`` the state at ``lo``
    (the hidden flag, or the depth), ``after`` the depth at ``hi`` (None: a
    flip of visibility, the other state), ``alone`` which brackets hold no
    other candidate (None: none is alone)."""

    cid: np.ndarray
    owner: np.ndarray
    kind: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    before: np.ndarray
    after: np.ndarray | None = None
    alone: np.ndarray | None = None

    def take(self, i: np.ndarray) -> Brackets:
        """Brackets ``i`` of these."""
        return Brackets(*(None if x is None else x[i] for x in attrs.astuple(self, recurse=False)))

    @property
    def front_hi(self) -> np.ndarray:
        """Whether the end with more in front (the hidden end, or the
        deeper one) is ``hi``."""
        return ~self.before if self.after is None else self.after > self.before


def own_contour_zeros(s: Samples, vis: Occlusion, b: Brackets) -> tuple[np.ndarray, np.ndarray]:
    """Where curves lying on their surfaces (``ON``; a contour's own ``N .
    ray`` is zero all along it, its signs rounding) cross their own
    surfaces' contours in brackets ``b``: the zero of ``N . ray``
    (:meth:`Occlusion.own_cosines`, continuous along a curve on its own
    surface; known at both ends, of opposite signs: a crossing, or an odd
    number of them), refined on that function
    (:func:`~lgraph._roots.bracketed_roots`) to ``BISECTION_RTOL`` of the
    shortest curve's span, with no ray test.  Returns the brackets' rows and
    their zeros."""
    rows = np.flatnonzero(b.kind == ON)
    view = s.view[b.cid]

    def cosine(t: np.ndarray, sel: np.ndarray) -> np.ndarray:
        xyz, uv, _ = s.evaluate(b.cid[sel], t, True)
        return vis.own_cosines(xyz, b.owner[sel], view[sel], uv)[:, 0]

    flo, fhi = np.split(cosine(np.concatenate([b.lo[rows], b.hi[rows]]), np.tile(rows, 2)), 2)
    ok = np.isfinite(flo) & np.isfinite(fhi) & (flo * fhi < 0)
    rows, flo, fhi = rows[ok], flo[ok], fhi[ok]
    if not len(rows):
        return rows, np.zeros(0)
    span = np.abs(s.t1[b.cid[rows]] - s.t0[b.cid[rows]])
    t = bracketed_roots(
        lambda x, sel: cosine(x, rows[sel]),
        b.lo[rows],
        b.hi[rows],
        flo,
        fhi,
        xtol=tol.BISECTION_RTOL * float(span.min()),
    )
    return rows, t


def confirmed(
    s: Samples,
    vis: Occlusion,
    b: Brackets,
    todo: np.ndarray,
    t: np.ndarray,
    rtols: tuple[float, ...] = OWN_GUIDE_RTOLS,
) -> tuple[np.ndarray, np.ndarray]:
    """Changes ``t`` proposed in brackets ``todo`` of ``b`` that ray tests
    ``rtols`` of the span either side confirm (the state ``b.before``
    before, the other state or the depth ``b.after`` after), the first
    width that does; the widths over ``ALONE_RTOL`` only where the bracket
    holds no other candidate (``b.alone``: a wide agreement elsewhere could
    straddle another change).  The numeric ray test takes a root closer than
    about 1e-5 of the scene to the ray's origin for the origin's own, so
    beside its own contour or another sheet through the curve it errs: hence
    the widths.  Returns the confirmed brackets' rows and their changes."""
    count = b.after is not None
    span = np.abs(s.t1[b.cid] - s.t0[b.cid])
    alone = np.zeros(len(span), dtype=bool) if b.alone is None else b.alone
    rows, out = [], []
    for rtol in rtols:
        w = rtol * span[todo]
        inside = (t - w > b.lo[todo]) & (t + w < b.hi[todo])
        inside &= alone[todo] | (rtol <= ALONE_RTOL)
        i, ti, w = todo[inside], t[inside], w[inside]
        if not len(i):
            break
        # the state at ti - w and at ti + w
        c = np.tile(b.cid[i], 2)
        xyz, _, xy = s.evaluate(c, np.concatenate([ti - w, ti + w]), True)
        owner, kind, view = np.tile(b.owner[i], 2), np.tile(b.kind[i], 2), s.view[c]
        if count:
            h = np.maximum(vis.sheets(xyz, xy, owner, kind, view=view), 1)
        else:
            h = vis.hidden(xyz, xy, owner, kind, view=view)
        before, after = np.split(h, 2)
        good = before == b.before[i]
        good &= (after == b.after[i]) if count else (after != b.before[i])
        rows.append(i[good])
        out.append(ti[good])
        keep = ~np.isin(todo, i[good])
        todo, t = todo[keep], t[keep]
    if not rows:
        return np.zeros(0, dtype=int), np.zeros(0)
    return np.concatenate(rows), np.concatenate(out)
