"""Brackets of a change between two samples of a curve: K-section's
sub-points and its cost per bracket, and the net's crossings, refined on the
exact curves, that narrow a bracket at once (a flip of visibility or a
change of depth most likely lies where the curve passes behind the net:
:mod:`lgraph.render.flips`, :mod:`lgraph.render.depth`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import _tolerance as tol
from .crossings import net_meetings
from .sampling import Samples

if TYPE_CHECKING:
    from .occlusion import Occlusion

__all__ = ["exact_crossings", "net_guesses", "sections", "sub_points"]


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
    s: Samples, vis: Occlusion, a: np.ndarray, margin: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For the chords ``a, a + 1`` (sorted) that cross the sampled net once:
    that crossing on the exact curves (:func:`exact_crossings`), where a
    visibility or depth change of the chord most likely lies.  Returns the
    chords' rows in ``a``, the crossings' parameters and ``w = margin`` of
    each curve's span, for those whose ``t -+ w`` lie inside their chord."""
    q, f, b, g = net_meetings(s, vis, a)
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
