"""Locating visibility flips between samples to near machine precision.

Flips caused by an ellipsoid are found by regula falsi on a continuous hiding
margin (a handful of steps); the rest by K-section on the exact visibility
test.  Both ends of every located flip are inserted into the samples.
"""

from __future__ import annotations

import attrs
import numpy as np

from . import _tolerance as tol
from ._occlusion import Occlusion
from ._sampling import Samples, evaluate, merge, owner_arrays
from .projectors import Projector

__all__ = ["locate_flips"]


@attrs.define
class _Flips:
    """All visibility flips of the scene in flat arrays (one entry per flip).

    Flip ``i`` lies on curve ``cid[i]`` of sample set ``k[i]``, between samples
    ``f[i]`` and ``f[i] + 1``; ``lo < hi`` bracket it and ``hlo`` is the hidden
    state at ``lo``.
    """

    k: np.ndarray
    f: np.ndarray
    cid: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    hlo: np.ndarray
    span: np.ndarray
    owner: np.ndarray
    kind: np.ndarray

    @classmethod
    def find(cls, all_s: list[Samples]) -> _Flips:
        parts = []
        for k, s in enumerate(all_s):
            f = np.nonzero((s.cid[1:] == s.cid[:-1]) & (s.hidden[1:] != s.hidden[:-1]))[0]
            if len(f):
                owner, kind = owner_arrays(s, len(f))
                span = (s.batch.t1 - s.batch.t0)[s.cid[f]]
                parts.append((np.full(len(f), k), f, s.cid[f], s.t[f], s.t[f + 1],
                              s.hidden[f], span, owner, kind))  # fmt: skip
        if not parts:
            z = np.empty(0)
            return cls(*(z.astype(int), z.astype(int), z.astype(int), z, z, z.astype(bool), z,
                         z.astype(int), z.astype(np.int8)))  # fmt: skip
        return cls(*(np.concatenate(col) for col in zip(*parts)))

    def __len__(self) -> int:
        return len(self.k)

    def open(
        self,
        idx: np.ndarray | None = None,
        lo: np.ndarray | None = None,
        hi: np.ndarray | None = None,
    ) -> np.ndarray:
        """Mask of brackets (all, or those at ``idx``) still wider than
        ``BISECTION_RTOL`` of the span; ``lo, hi`` replace the stored ends."""
        sel = slice(None) if idx is None else idx
        lo = self.lo[sel] if lo is None else lo
        hi = self.hi[sel] if hi is None else hi
        return (hi - lo) > tol.BISECTION_RTOL * np.maximum(self.span[sel], np.abs(lo))


def _points(
    all_s: list[Samples],
    projector: Projector,
    k: np.ndarray,
    cid: np.ndarray,
    t: np.ndarray,
    project: bool = True,
) -> tuple[np.ndarray, np.ndarray | None]:
    """World points and (unless ``project`` is False) projections of parameters
    ``t`` on curves ``(k, cid)``; one ``evaluate`` call per sample set involved."""
    if len(k) and np.all(k == k[0]):  # one sample set: no sorting and scattering
        s = all_s[k[0]]
        xyz, _, xy = evaluate(s.batch, s.transform, projector if project else None, cid, t)
        return xyz, xy
    xyz = np.empty((len(t), 3))
    xy = np.empty((len(t), 2)) if project else None
    order = np.argsort(k, kind="stable")
    ks = k[order]
    cuts = np.nonzero(np.diff(ks))[0] + 1
    for sel in np.split(order, cuts):
        if len(sel):
            s = all_s[k[sel[0]]]
            p = projector if project else None
            xyz[sel], _, pxy = evaluate(s.batch, s.transform, p, cid[sel], t[sel])
            if project:
                xy[sel] = pxy
    return xyz, xy


def _regula_falsi(all_s: list[Samples], fl: _Flips, vis: Occlusion,
                  projector: Projector) -> None:  # fmt: skip
    """Flips caused by an ellipsoid: root finding on its continuous hiding
    margin ``f`` (safeguarded, a handful of steps instead of dozens).

    Each step evaluates ``f`` at an estimate ``u`` and at ``u -+ h``; the
    bracket shrinks to the sub-interval where ``f`` changes sign, and the next
    estimate is the root of the parabola through the three values (Newton's
    step when ``h`` is too small for a clean second difference), or the
    secant of the bracket's ends when that root leaves the bracket.  ``h``
    follows the size of the last correction, so that once the estimates
    converge the three points straddle the root and the bracket collapses
    on both sides; at the end ``h`` is half the target width.  Results are
    verified with the full visibility test; brackets that fail stay for
    :func:`_k_section`."""
    if not vis.nq or not len(fl):
        return
    hid_end = np.where(fl.hlo, fl.f, fl.f + 1)
    vis_end = np.where(fl.hlo, fl.f + 1, fl.f)
    # flat views over all sample sets: sample i of set k is row offset[k] + i
    offset = np.concatenate([[0], np.cumsum([len(s.t) for s in all_s])[:-1]])
    cause = np.concatenate([s.cause for s in all_s])
    q = cause[offset[fl.k] + hid_end]
    ok = q >= 0
    ok[ok] = vis.q_pd[q[ok]]
    idx = np.nonzero(ok)[0]
    if not len(idx):
        return
    xyz_all = np.concatenate([s.xyz for s in all_s])
    rows = offset[np.tile(fl.k[idx], 2)] + np.concatenate([vis_end[idx], hid_end[idx]])
    fa, fb = np.split(vis.margin(xyz_all[rows], np.tile(q[idx], 2), np.tile(fl.owner[idx], 2),
                                 np.tile(fl.kind[idx], 2)), 2)  # fmt: skip
    good = (fa <= 0) & (fb > 0)
    idx, fa, fb, q = idx[good], fa[good], fb[good], q[idx][good]
    a = np.where(fl.hlo[idx], fl.hi[idx], fl.lo[idx])  # visible end
    b = np.where(fl.hlo[idx], fl.lo[idx], fl.hi[idx])  # hidden end
    # ``h`` is at least half the target width, and a clean second difference
    # needs it well above rounding (relative to the bracket's scale)
    scale = np.maximum(fl.span[idx], np.maximum(np.abs(a), np.abs(b)))
    h_min = 0.5 * tol.BISECTION_RTOL * scale
    h_quad = 1e-6 * scale
    u = a + _secant(fa, fb) * (b - a)
    h = 1e-2 * np.abs(b - a)
    rows3 = np.array([-1.0, 0.0, 1.0])
    for _ in range(tol.BISECTION_MAX_STEPS):
        g = np.nonzero(fl.open(idx, np.minimum(a, b), np.maximum(a, b)))[0]
        if not len(g):
            break
        ag, bg, ug = a[g], b[g], u[g]
        sgn = np.sign(bg - ag)  # from the visible end toward the hidden end
        room = np.minimum(np.abs(ug - ag), np.abs(bg - ug))  # keep the three points inside
        hg = np.minimum(np.maximum(h[g], h_min[g]), room)
        tt = ug[:, None] + (sgn * hg)[:, None] * rows3
        ig = idx[g]
        xyz, _ = _points(all_s, projector, np.repeat(fl.k[ig], 3), np.repeat(fl.cid[ig], 3),
                         tt.ravel(), project=False)  # fmt: skip
        m = vis.margin(xyz, np.repeat(q[g], 3), np.repeat(fl.owner[ig], 3),
                       np.repeat(fl.kind[ig], 3)).reshape(-1, 3)  # fmt: skip
        hid = m > 0
        first = np.where(hid.any(axis=1), hid.argmax(axis=1), 3)  # first hidden point
        rows = np.arange(len(g))
        new_b, new_a = first < 3, first > 0
        b[g[new_b]], fb[g[new_b]] = tt[rows[new_b], first[new_b]], m[rows[new_b], first[new_b]]
        ia = first[new_a] - 1
        a[g[new_a]], fa[g[new_a]] = tt[rows[new_a], ia], m[rows[new_a], ia]
        # next estimate: root of the parabola (or line) through the three values
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            c1 = (m[:, 2] - m[:, 0]) / (2 * hg)
            c2 = np.where(hg >= h_quad[g], (m[:, 2] - 2 * m[:, 1] + m[:, 0]) / (2 * hg * hg), 0.0)
            disc = np.sqrt(np.maximum(c1 * c1 - 4 * c2 * m[:, 1], 0.0))
            step = -2 * m[:, 1] / (c1 + np.copysign(disc, c1))
            nxt = ug + sgn * step
            ag, bg = a[g], b[g]
            inside = (nxt - ag) * (nxt - bg) < 0
            fallback = ag + _secant(fa[g], fb[g]) * (bg - ag)
        u[g] = np.where(inside, nxt, fallback)
        h[g] = np.where(inside, 1e-4 * np.abs(step), 1e-2 * np.abs(bg - ag))
    # verify with the full test; accepted brackets replace the originals
    kk, cc = np.tile(fl.k[idx], 2), np.tile(fl.cid[idx], 2)
    xyz, xy = _points(all_s, projector, kk, cc, np.concatenate([a, b]))
    h = vis.hidden(xyz, xy, np.tile(fl.owner[idx], 2), np.tile(fl.kind[idx], 2))
    n = len(idx)
    ok = ~h[:n] & h[n:] & ~fl.open(idx, np.minimum(a, b), np.maximum(a, b))
    sel, hl = idx[ok], fl.hlo[idx[ok]]
    fl.lo[sel] = np.where(hl, b[ok], a[ok])
    fl.hi[sel] = np.where(hl, a[ok], b[ok])


def _secant(fa: np.ndarray, fb: np.ndarray) -> np.ndarray:
    """Where the secant through ``(0, fa)`` and ``(1, fb)`` crosses zero (0.5
    when that is not strictly inside)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        r = -fa / (fb - fa)
    return np.where((r > 0) & (r < 1), r, 0.5)


def _k_section(all_s: list[Samples], fl: _Flips, vis: Occlusion,
               projector: Projector) -> None:  # fmt: skip
    """Remaining flips: each step splits every bracket into ``K`` parts at once
    (the exactness of bisection in ``1/log2(K)`` of the steps), keeping the
    first sub-bracket whose ends differ.  ``K`` trades the fixed cost of a
    step against the number and cost of the tests: large for a few flips on
    cheap surfaces, 2 (bisection) for many flips on costly ones."""
    n_open = int(fl.open().sum())
    # cost of a step: a fixed part plus the sub-points times the cost of a test;
    # pick the K with the least cost per bit gained (deterministic: no timing)
    ks = 2 ** np.arange(1, int(np.log2(tol.SECTIONS)) + 1)
    per_bit = (vis.cost_per_call + n_open * (ks - 1) * vis.cost_per_point) / np.log2(ks)
    K = int(ks[np.argmin(per_bit)])
    frac = np.arange(1, K) / K
    for _ in range(tol.BISECTION_MAX_STEPS):
        idx = np.nonzero(fl.open())[0]
        if not len(idx):
            break
        tm = fl.lo[idx, None] + (fl.hi[idx] - fl.lo[idx])[:, None] * frac
        rep = np.repeat(idx, K - 1)
        xyz, xy = _points(all_s, projector, fl.k[rep], fl.cid[rep], tm.ravel())
        h = vis.hidden(xyz, xy, fl.owner[rep], fl.kind[rep]).reshape(tm.shape)
        differs = h != fl.hlo[idx, None]
        # first sub-point whose state differs from lo's; none: flip in the last part
        first = np.where(differs.any(axis=1), differs.argmax(axis=1), K - 1)
        rows = np.arange(len(idx))
        has_lo, has_hi = first > 0, first < K - 1
        fl.lo[idx[has_lo]] = tm[rows[has_lo], first[has_lo] - 1]
        fl.hi[idx[has_hi]] = tm[rows[has_hi], first[has_hi]]


def locate_flips(all_s: list[Samples], vis: Occlusion, projector: Projector) -> None:
    """Locate every visibility flip between two samples to near machine
    precision (``BISECTION_RTOL`` of the parameter span) and insert both sides."""
    fl = _Flips.find(all_s)
    _regula_falsi(all_s, fl, vis, projector)
    _k_section(all_s, fl, vis, projector)
    order = np.argsort(fl.k, kind="stable")
    for sel in np.split(order, np.nonzero(np.diff(fl.k[order]))[0] + 1):
        if not len(sel):
            continue
        s = all_s[fl.k[sel[0]]]
        # both ends of each bracket, in order, right after the flip's first sample
        t = np.column_stack([fl.lo[sel], fl.hi[sel]]).ravel()
        c = np.repeat(fl.cid[sel], 2)
        xyz, uv, xy = evaluate(s.batch, s.transform, projector, c, t)
        hidden = np.column_stack([fl.hlo[sel], ~fl.hlo[sel]]).ravel()
        merge(s, np.repeat(fl.f[sel], 2), c, t, xyz, uv, xy, hidden)
