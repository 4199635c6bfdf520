"""Locating visibility flips between samples to near machine precision.

Where an exact ellipse (a parameter line of an ellipsoid) crosses its own
ellipsoid's contour, the flip is in closed form
(:mod:`lgraph.render.ellipses`); other flips caused by an
ellipsoid, and flips on the curves of a surface that offers transition
functions for its own points (:meth:`~lgraph.Surface.visibility_margins`,
e.g. a surface of revolution: its contour, its rims), are found by a
safeguarded parabola search on a continuous margin (about three steps);
flips on the net's one crossing of their chord, where a curve passes its
own surface's contour (the zero of ``N . ray``) or through another sheet of
its own numeric surface (:mod:`lgraph.render.sheets`) are taken there when
ray tests beside it confirm them; the rest by K-section on the exact
visibility test.  Every result is verified by the full test, and both ends
of every located flip are inserted into the samples.
"""

from __future__ import annotations

from collections.abc import Callable

import attrs
import numpy as np

from .. import _tolerance as tol
from ..surfaces._base import ON
from .brackets import (
    Brackets,
    confirmed,
    net_guesses,
    own_contour_zeros,
    sections,
    sub_points,
)
from .crossings import net_meetings
from .ellipses import contour_crossings, ellipse_crossings, seed_crossings
from .occlusion import Occlusion
from .sampling import Samples, merge
from .sheets import through_sheets

__all__ = ["contour_crossings", "locate_flips", "seed_crossings"]

#: a flip on the net's one crossing of its chord: first bracketed this far
#: (of the curve's span) on either side of it (:func:`_guided`)
GUIDE_RTOL = 1e-7


@attrs.define
class _Flips:
    """All visibility flips of the scene in flat arrays (one entry per flip).

    Flip ``i`` lies on curve ``cid[i]``, between samples ``f[i]`` and
    ``f[i] + 1``; ``lo < hi`` bracket it and ``hlo`` is the hidden state at
    ``lo``.
    """

    f: np.ndarray
    cid: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    hlo: np.ndarray
    span: np.ndarray
    owner: np.ndarray
    kind: np.ndarray

    @classmethod
    def find(cls, s: Samples) -> _Flips:
        f = np.flatnonzero((s.cid[1:] == s.cid[:-1]) & (s.hidden[1:] != s.hidden[:-1]))
        c = s.cid[f]
        return cls(f, c, s.t[f], s.t[f + 1], s.hidden[f], (s.t1 - s.t0)[c], *s.owners(f))

    def __len__(self) -> int:
        return len(self.f)

    def whole(self, s: Samples, idx: np.ndarray | None = None) -> np.ndarray:
        """Mask of brackets (all, or those at ``idx``) still open and still
        their whole chord between samples ``s.t`` (no search has narrowed them)."""
        sel = slice(None) if idx is None else idx
        f = self.f[sel]
        return self.open(idx) & (self.lo[sel] == s.t[f]) & (self.hi[sel] == s.t[f + 1])

    def collapse(self, i: np.ndarray, t: np.ndarray) -> None:
        """Brackets ``i`` closed about their flips ``t`` (no further search)."""
        step = 0.25 * tol.BISECTION_RTOL * np.maximum(self.span[i], np.abs(t))
        self.lo[i], self.hi[i] = t - step, t + step

    def brackets(self, i: np.ndarray, alone: np.ndarray | None = None) -> Brackets:
        """Brackets ``i`` for :mod:`lgraph.render.brackets` (``alone``: those
        that hold no other candidate)."""
        x = (self.cid, self.owner, self.kind, self.lo, self.hi, self.hlo)
        return Brackets(*(y[i] for y in x), alone=alone)

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


def _margin_search(s: Samples, fl: _Flips, vis: Occlusion) -> None:
    """Flips caused by an ellipsoid: root finding on its continuous hiding
    margin (:meth:`Occlusion.margin`, see :func:`_root_search`); exact
    ellipses on their own ellipsoid start from the closed-form crossing."""
    if not vis.nq or not len(fl):
        return
    hid_end = np.where(fl.hlo, fl.f, fl.f + 1)
    vis_end = np.where(fl.hlo, fl.f + 1, fl.f)
    q = s.cause[hid_end]
    ok = q >= 0
    ok[ok] = vis.q_pd[q[ok]]
    idx = np.flatnonzero(ok)
    if not len(idx):
        return
    rows = np.concatenate([vis_end[idx], hid_end[idx]])
    xyz = np.take(s.xyz, rows, axis=0)
    fa, fb = np.split(vis.margin(xyz, np.tile(q[idx], 2), np.tile(fl.owner[idx], 2),
                                 np.tile(fl.kind[idx], 2), s.view[s.cid[rows]]), 2)  # fmt: skip
    good = (fa <= 0) & (fb > 0)
    idx, fa, fb, q = idx[good], fa[good], fb[good], q[idx][good]
    a = np.where(fl.hlo[idx], fl.hi[idx], fl.lo[idx])  # visible end
    b = np.where(fl.hlo[idx], fl.lo[idx], fl.hi[idx])  # hidden end
    if s.ellipses is not None:
        _closed_form(s, fl, vis, idx, q, a, b)

    def margin(xyz: np.ndarray, k: np.ndarray, _uv: np.ndarray) -> np.ndarray:
        i = idx[k]
        return vis.margin(xyz, q[k], fl.owner[i], fl.kind[i], s.view[fl.cid[i]])

    _root_search(s, fl, vis, idx, a, b, fa, fb, margin)


def _own_margin_search(s: Samples, fl: _Flips, vis: Occlusion) -> None:
    """Flips on curves of a surface that offers transition functions for its
    own points (:meth:`~lgraph.Surface.visibility_margins`: for a
    surface of revolution, the normal component of the ray and how far the
    ray passes from its rims): each function in turn, for the flips still
    open across which it changes sign, is turned into a margin (positive at
    the hidden end) and its root found (:func:`_root_search`)."""
    if not vis.items or not len(fl):
        return
    idx0 = np.flatnonzero(fl.open())
    if not len(idx0):
        return
    hid_end = np.where(fl.hlo[idx0], fl.f[idx0], fl.f[idx0] + 1)
    vis_end = np.where(fl.hlo[idx0], fl.f[idx0] + 1, fl.f[idx0])
    rows = np.concatenate([vis_end, hid_end])
    ends = vis.own_margins(
        np.take(s.xyz, rows, axis=0),
        np.tile(fl.owner[idx0], 2),
        np.tile(fl.kind[idx0], 2),
        np.take(s.uv, rows, axis=0),
        view=s.view[s.cid[rows]],
    )  # every function at both ends (brackets that stay open keep their ends)
    for i in range(len(ends)):
        still = fl.open(idx0)
        ga, gb = np.split(ends[i], 2)
        # a sign change (NaN: no such function), or a visible end on the transition
        good = still & ((ga * gb < 0) | ((np.abs(ga) <= tol.TRANSITION_ZERO) & (gb != 0)))
        idx, ga, gb = idx0[good], ga[good], gb[good]
        if not len(idx):
            continue
        orient = np.sign(gb)  # the margin is positive at the hidden end
        ga = np.where(orient * ga > 0, 0.0, ga)
        a = np.where(fl.hlo[idx], fl.hi[idx], fl.lo[idx])  # visible end
        b = np.where(fl.hlo[idx], fl.lo[idx], fl.hi[idx])  # hidden end

        def margin(
            xyz: np.ndarray, k: np.ndarray, uv: np.ndarray, i: int = i, idx: np.ndarray = idx,
            orient: np.ndarray = orient,
        ) -> np.ndarray:  # fmt: skip
            j = idx[k]
            m = vis.own_margins(xyz, fl.owner[j], fl.kind[j], uv, i, s.view[fl.cid[j]])
            return orient[k] * m[0]

        _root_search(s, fl, vis, idx, a, b, orient * ga, orient * gb, margin)


def _root_search(
    s: Samples,
    fl: _Flips,
    vis: Occlusion,
    idx: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    fa: np.ndarray,
    fb: np.ndarray,
    margin: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
) -> None:
    """Brackets ``idx`` from their visible ends ``a`` (margin ``fa <= 0``) to
    their hidden ends ``b`` (``fb > 0``) shrunk onto the root of a continuous
    hiding margin (``margin(xyz, k, uv)`` at points ``xyz`` with parameters
    ``uv`` of brackets ``idx[k]``):
    safeguarded, a handful of steps instead of dozens.

    Each step evaluates the margin at an estimate ``u`` and at ``u -+ h``; the
    bracket shrinks to the sub-interval where it changes sign, and the next
    estimate is the root of the parabola through the three values (Newton's
    step when ``h`` is too small for a clean second difference), or the
    secant of the bracket's ends when that root leaves the bracket (its
    middle when the last step did not halve the bracket).  ``h``
    follows the size of the last correction, so that once the estimates
    converge the three points straddle the root and the bracket collapses
    on both sides; at the end ``h`` is half the target width.  Results are
    verified with the full visibility test; brackets that fail stay for
    :func:`_k_section`."""
    if not len(idx):
        return
    # ``h`` is at least half the target width, and a clean second difference
    # needs it well above rounding (relative to the bracket's scale)
    scale = np.maximum(fl.span[idx], np.maximum(np.abs(a), np.abs(b)))
    h_min = 0.5 * tol.BISECTION_RTOL * scale
    h_quad = 1e-6 * scale
    u = a + _secant(fa, fb) * (b - a)
    h = 1e-2 * np.abs(b - a)
    rows3 = np.array([-1.0, 0.0, 1.0])
    for _ in range(tol.BISECTION_MAX_STEPS):
        g = np.flatnonzero(fl.open(idx, np.minimum(a, b), np.maximum(a, b)))
        if not len(g):
            break
        ag, bg = a[g], b[g]
        width = np.abs(bg - ag)
        # an estimate within half the target width of an end (a root there,
        # met by a margin at rounding level) moves that far inside, so that
        # the three points straddle it at the target width
        ug = np.clip(u[g], np.minimum(ag, bg) + h_min[g], np.maximum(ag, bg) - h_min[g])
        sgn = np.sign(bg - ag)  # from the visible end toward the hidden end
        room = np.minimum(np.abs(ug - ag), np.abs(bg - ug))  # keep the three points inside
        hg = np.minimum(np.maximum(h[g], h_min[g]), room)
        tt = ug[:, None] + (sgn * hg)[:, None] * rows3
        ig = idx[g]
        xyz, uv, _ = s.evaluate(np.repeat(fl.cid[ig], 3), tt.ravel(), None)
        m = margin(xyz, np.repeat(g, 3), uv).reshape(-1, 3)
        hid = m > 0
        first = np.where(hid.any(axis=1), hid.argmax(axis=1), 3)  # first hidden point
        r = np.arange(len(g))
        new_b, new_a = first < 3, first > 0
        b[g[new_b]], fb[g[new_b]] = tt[r[new_b], first[new_b]], m[r[new_b], first[new_b]]
        ia = first[new_a] - 1
        a[g[new_a]], fa[g[new_a]] = tt[r[new_a], ia], m[r[new_a], ia]
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
            # the secant after a step that did not halve the bracket (the margin
            # flat at rounding level near an end, where the secant stagnates):
            # bisect instead
            slow = ~inside & (np.abs(bg - ag) > 0.5 * width)
        u[g] = np.where(slow, 0.5 * (ag + bg), np.where(inside, nxt, fallback))
        h[g] = np.where(inside & ~slow, 1e-4 * np.abs(step), 1e-2 * np.abs(bg - ag))
    # verify with the full test; accepted brackets replace the originals.  A
    # bracket much narrower than the target may end on a point whose margin is
    # at rounding level (the full test may see its sign differently): closed
    # brackets are first widened to nearly the target width about their middle
    done = np.flatnonzero(~fl.open(idx, np.minimum(a, b), np.maximum(a, b)))
    mid, sgn = 0.5 * (a[done] + b[done]), np.sign(b[done] - a[done])
    half = np.maximum(0.99 * h_min[done], 0.5 * np.abs(b[done] - a[done]))
    wa, wb = mid - sgn * half, mid + sgn * half
    wide = ~fl.open(idx[done], np.minimum(wa, wb), np.maximum(wa, wb))
    a[done[wide]], b[done[wide]] = wa[wide], wb[wide]
    ok = _verify(s, fl, vis, idx, a, b)
    sel, hl = idx[ok], fl.hlo[idx[ok]]
    fl.lo[sel] = np.where(hl, b[ok], a[ok])
    fl.hi[sel] = np.where(hl, a[ok], b[ok])


def _verify(
    s: Samples,
    fl: _Flips,
    vis: Occlusion,
    idx: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
) -> np.ndarray:
    """Which brackets ``idx`` are closed with ``a`` visible and ``b`` hidden
    by the full visibility test."""
    cid = np.tile(fl.cid[idx], 2)
    xyz, _, xy = s.evaluate(cid, np.concatenate([a, b]), True)
    hv = vis.hidden(xyz, xy, np.tile(fl.owner[idx], 2), np.tile(fl.kind[idx], 2), view=s.view[cid])
    n = len(idx)
    return ~hv[:n] & hv[n:] & ~fl.open(idx, np.minimum(a, b), np.maximum(a, b))


def _closed_form(
    s: Samples,
    fl: _Flips,
    vis: Occlusion,
    idx: np.ndarray,
    q: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
) -> None:
    """Flips of exact ellipses (``Samples.ellipses``) across the contour of the
    ellipsoid they lie on, in closed form (:func:`contour_crossings`); ``a,
    b`` (visible and hidden ends of the brackets ``idx``, hidden by quadrics
    ``q``) collapse onto them.  Brackets with no or two crossings keep their
    ends; every result is verified by the caller."""
    on = (fl.owner[idx] == vis.q_node[q]) & (fl.kind[idx] == ON)
    sel = np.flatnonzero(on & np.isfinite(s.ellipses[fl.cid[idx], 0, 0]))
    if not len(sel):
        return
    root = ellipse_crossings(s, fl.cid[idx[sel]], q[sel], vis)
    lo, hi = np.minimum(a[sel], b[sel]), np.maximum(a[sel], b[sel])
    root += 2 * np.pi * np.round(((0.5 * (lo + hi))[:, None] - root) / (2 * np.pi))
    inside = (root > lo[:, None]) & (root < hi[:, None])
    one = inside.sum(axis=1) == 1
    sel, root = sel[one], root[one][inside[one]]
    step = 0.25 * tol.BISECTION_RTOL * np.maximum(fl.span[idx[sel]], np.abs(root))
    toward_b = np.sign(b[sel] - a[sel])
    a[sel] = root - toward_b * step
    b[sel] = root + toward_b * step


def _secant(fa: np.ndarray, fb: np.ndarray) -> np.ndarray:
    """Where the secant through ``(0, fa)`` and ``(1, fb)`` crosses zero (0.5
    when that is not strictly inside)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        r = -fa / (fb - fa)
    return np.where((r > 0) & (r < 1), r, 0.5)


def _guided(s: Samples, fl: _Flips, vis: Occlusion, whole: np.ndarray, meetings: tuple) -> None:
    """Brackets ``whole`` (still a whole chord; ``meetings``, their
    :func:`~lgraph.render.crossings.net_meetings`) that the sampled net
    crosses once collapse onto the crossing on the exact curves
    (:func:`~lgraph.render.brackets.net_guesses`: where the curve passes
    behind that net curve) when ray tests ``GUIDE_RTOL`` of the span either
    side of it agree: two ray tests instead of a K-section's dozens."""
    row, t, _ = net_guesses(s, vis, fl.f[whole], GUIDE_RTOL, meetings)
    rows, t = confirmed(s, vis, fl.brackets(whole[row]), np.arange(len(row)), t, (GUIDE_RTOL,))
    fl.collapse(whole[row[rows]], t)


def _own_guided(s: Samples, fl: _Flips, vis: Occlusion, whole: np.ndarray, meetings: tuple) -> None:
    """Brackets of ``whole`` still a whole chord across which the curve passes
    its own surface's contour (:func:`~lgraph.render.brackets.own_contour_zeros`:
    at the zero of ``N . ray``), or through another sheet of its own numeric
    surface, the sheet in front at the hidden end
    (:func:`~lgraph.render.sheets.through_sheets`: where that sheet's ray root
    reaches the curve), collapse there when ray tests beside it confirm the
    flip (:func:`~lgraph.render.brackets.confirmed`; at the wider widths only
    in chords the net does not cross: ``meetings`` has none)."""
    alone = np.bincount(np.searchsorted(fl.f[whole], meetings[0]), minlength=len(whole)) == 0
    for find in (own_contour_zeros, through_sheets):
        still = fl.whole(s, whole)
        idx = whole[still]
        if not len(idx):
            return
        b = fl.brackets(idx, alone[still])
        rows, t = confirmed(s, vis, b, *find(s, vis, b))
        fl.collapse(idx[rows], t)


def _k_section(s: Samples, fl: _Flips, vis: Occlusion) -> None:
    """Remaining flips: each step splits every bracket into ``K`` parts at once
    (the exactness of bisection in ``1/log2(K)`` of the steps), keeping the
    first sub-bracket whose ends differ.  ``K`` trades the fixed cost of a
    step against the number and cost of the tests: large for a few flips on
    cheap surfaces, 2 (bisection) for many flips on costly ones."""
    still = fl.open()
    if not still.any():
        return
    K = sections(s.view[fl.cid], still, s.views.k, vis)  # per bracket, per view
    for _ in range(tol.BISECTION_MAX_STEPS):
        idx = np.nonzero(fl.open())[0]
        if not len(idx):
            break
        rep, tm, first_differing = sub_points(fl.lo, fl.hi, idx, K[idx])
        c = fl.cid[rep]
        xyz, _, xy = s.evaluate(c, tm, True)
        h = vis.hidden(xyz, xy, fl.owner[rep], fl.kind[rep], view=s.view[c])
        lo, hi = first_differing(h != fl.hlo[rep])
        fl.lo[idx[lo >= 0]] = tm[lo[lo >= 0]]
        fl.hi[idx[hi >= 0]] = tm[hi[hi >= 0]]


def locate_flips(s: Samples, vis: Occlusion) -> None:
    """Locate every visibility flip between two samples to near machine
    precision (``BISECTION_RTOL`` of the parameter span) and insert both sides."""
    fl = _Flips.find(s)
    if not len(fl):
        return
    _margin_search(s, fl, vis)
    _own_margin_search(s, fl, vis)
    whole = np.flatnonzero(fl.whole(s))
    if len(whole):  # the net's crossings of the chords no search has narrowed
        meetings = net_meetings(s, vis, fl.f[whole])
        _guided(s, fl, vis, whole, meetings)
        _own_guided(s, fl, vis, whole, meetings)
    _k_section(s, fl, vis)
    # both ends of each bracket, in order, right after the flip's first sample
    t = np.column_stack([fl.lo, fl.hi]).ravel()
    c = np.repeat(fl.cid, 2)
    xyz, uv, xy = s.evaluate(c, t, True)
    hidden = np.column_stack([fl.hlo, ~fl.hlo]).ravel()
    merge(s, np.repeat(fl.f, 2), c, t, xyz, uv, xy, hidden)
