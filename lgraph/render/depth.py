"""Occlusion depth: how many surface sheets lie between a hidden point and the eye.

After the visibility flips are located, every hidden sample is asked how
many times its ray to the eye crosses a surface of the scene
(``Occlusion.sheets``: the grouped ellipsoids'
roots counted in closed form, every other surface through its
``hit_count``).  Where two neighbouring hidden samples of a curve differ,
the change is located by bisection on the curve parameter (to
``BISECTION_RTOL`` of its span, as the flips) and both of its sides are
inserted, so that strokes split exactly where the depth changes
(``Stroke.occlusion``).

A depth change needs no sample of its own in between: the depth is
constant between two visibility candidates that the crossings step
(:mod:`lgraph.render.crossings`) has separated, except where a hidden curve
passes behind a further contour; there the two samples around it differ
and the bisection finds it.  A hidden sample always counts at least one
sheet (the ray test and the count agree except at grazing rays, where the
count may miss a tangential double root).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import _tolerance as tol
from .brackets import Brackets, confirmed, net_guesses, own_contour_zeros, sections, sub_points
from .crossings import net_crossings, net_meetings
from .sampling import merge
from .sheets import through_sheets

if TYPE_CHECKING:
    from .occlusion import Occlusion
    from .sampling import Samples

__all__ = ["occlusion_depth"]

#: passes of locating changes of depth: one locates the first change in each
#: bracket; a second change within the same bracket (rare) then splits the
#: strokes at a sample, not at the exact point (each pass costs as much as
#: the first on numeric surfaces)
_MAX_PASSES = 1
#: changes of depth are located to this fraction of the curve's parameter
#: span: finer than the guided ones (``GUIDE_RTOL``) and than anything a print
#: shows; closer to a fold than about ``SELF_HIT_RTOL`` of the scene the count
#: is ambiguous anyway (its own root and the fold's merge).  Each factor of 8
#: costs one K-section step of ray tests: 1e-12, as the flips, took three more
#: steps than this (a quarter of the cross-cap's render)
DEPTH_RTOL = 1e-9
#: a change of depth on the one crossing of its chord with the net is taken
#: there (both strokes end on it) when the counts this far (a fraction of the
#: curve's span) on either side agree with the bracket's ends
GUIDE_RTOL = 1e-7
#: a bracket this narrow (a fraction of the curve's span) holds a located change
LOCATED_RTOL = 4 * GUIDE_RTOL
#: a run of one depth whose image is smaller than this fraction of the figure
#: takes its hidden neighbour's depth: within a few ``SELF_HIT_RTOL`` of a
#: contour the count is ambiguous (the fold's own root is that close to the
#: point), and no print shows a change that short
SLIVER_RTOL = 10 * tol.SELF_HIT_RTOL


def _count(s: Samples, vis: Occlusion, rows: np.ndarray) -> np.ndarray:
    owner, kind = s.owners(rows)
    n = vis.sheets(
        np.take(s.xyz, rows, axis=0),
        np.take(s.xy, rows, axis=0),
        owner,
        kind,
        view=s.view[s.cid[rows]],
    )
    return np.maximum(n, 1)


def _cosines(s: Samples, vis: Occlusion, rows: np.ndarray) -> np.ndarray:
    """``N . ray`` of samples ``rows`` on their own surfaces (NaN: unknown)."""
    owner, _ = s.owners(rows)
    return vis.own_cosines(
        np.take(s.xyz, rows, axis=0), owner, s.view[s.cid[rows]], np.take(s.uv, rows, axis=0)
    )


def _candidates(s: Samples, vis: Occlusion, chord: np.ndarray, every: bool) -> np.ndarray:
    """Which chords ``chord`` (between two hidden samples) may hold a change
    of depth: those crossed by the net (:func:`~lgraph.render.crossings.net_crossings`)
    and those across which a curve passes its own surface's contour (the
    sign of ``N . ray`` changes); all of them with ``every`` (a net known
    to be incomplete)."""
    if every or not len(chord):
        return np.ones(len(chord), dtype=bool)
    q, _ = net_crossings(s, vis, chord)
    out = np.isin(chord, q)
    ends = np.concatenate([chord, chord + 1])
    side = np.nan_to_num(np.sign(_cosines(s, vis, ends)))
    a, b = side[: len(chord)], side[len(chord) :]
    out |= np.any(a != b, axis=1)
    return out


def occlusion_depth(
    s: Samples, vis: Occlusion, every: bool = False, figure: list[float] | None = None
) -> np.ndarray:
    """The number of sheets in front of every sample (0 where visible);
    inserts both sides of every change of depth along a hidden run.

    The depth can change only where the curve crosses the net or its own
    ellipsoid's contour (:func:`_candidates`): every run of hidden samples
    between two such chords is counted at its two ends (and at every sample
    where the ends disagree); ``every`` counts every hidden sample (a scene
    whose net is incomplete: a hiding surface that draws no contour).
    With ``figure`` (the size of every view's figure), runs of one depth
    smaller than ``SLIVER_RTOL`` of it join a hidden neighbour
    (:func:`_absorb_slivers`)."""
    n = len(s.t)
    depth = np.zeros(n, dtype=np.int64)
    hid = np.flatnonzero(s.hidden)
    if not len(hid):
        return depth
    # chords between two hidden samples of one curve
    hh = s.hidden[:-1] & s.hidden[1:] & (s.cid[:-1] == s.cid[1:]) & (s.t[1:] > s.t[:-1])
    chord = np.flatnonzero(hh)
    cut = ~hh  # between samples i and i + 1: a new segment begins
    cut[chord] = _candidates(s, vis, chord, every)
    first = np.concatenate([[True], cut])[hid]  # a hidden sample starting its segment
    last = np.concatenate([cut, [True]])[hid]
    seg = np.cumsum(first) - 1  # segment of every hidden sample
    ask = first | last
    count = np.zeros(len(hid), dtype=np.int64)
    count[ask] = _count(s, vis, hid[ask])
    lo = count[first]
    hi = count[last]
    odd = np.flatnonzero(lo != hi)  # ends disagree: count every sample there
    if len(odd):
        rest = np.isin(seg, odd) & ~ask
        count[rest] = _count(s, vis, hid[rest])
    fill = ~ask & ~np.isin(seg, odd)
    count[fill] = lo[seg[fill]]
    depth[hid] = count
    for _ in range(_MAX_PASSES):
        # neighbouring hidden samples of one curve with different depths, not
        # yet located (a located change is a bracket narrower than the tolerance)
        a = np.flatnonzero(
            s.hidden[:-1] & s.hidden[1:] & (s.cid[:-1] == s.cid[1:]) & (depth[:-1] != depth[1:])
        )
        cid = s.cid[a]
        span = np.abs(s.t1[cid] - s.t0[cid])
        a = a[s.t[a + 1] - s.t[a] > LOCATED_RTOL * span]
        if not len(a):
            break
        depth = _locate(s, vis, a, depth)
    # changes left (a second one in a bracket): split at the later sample, so
    # that the two strokes still meet (a copy of it ends the first)
    a = np.flatnonzero(
        s.hidden[:-1] & s.hidden[1:] & (s.cid[:-1] == s.cid[1:]) & (depth[:-1] != depth[1:])
    )
    cid = s.cid[a]
    a = a[s.t[a + 1] - s.t[a] > LOCATED_RTOL * np.abs(s.t1[cid] - s.t0[cid])]
    if len(a):
        b = a + 1
        xyz, uv, xy = (np.take(x, b, axis=0) for x in (s.xyz, s.uv, s.xy))
        new = merge(s, a, s.cid[b], s.t[b], xyz, uv, xy, np.ones(len(a), bool))
        out = np.empty(len(s.t), dtype=np.int64)
        out[~new] = depth
        out[new] = depth[a]
        depth = out
    if figure is not None:
        depth = _absorb_slivers(s, depth, SLIVER_RTOL * np.asarray(figure, dtype=float))
    return depth


def _absorb_slivers(s: Samples, depth: np.ndarray, small: np.ndarray) -> np.ndarray:
    """Give every hidden run of one depth whose image (to the next run's first
    sample) is smaller than ``small`` (per view) the depth of its hidden neighbour on the same curve
    (the one before it, else the one after): a sliver is the count's
    ambiguity beside a contour, not a change anyone could see."""
    depth = depth.copy()
    for _ in range(4):  # a sliver beside slivers: its neighbour's new depth
        brk = np.flatnonzero((s.cid[1:] != s.cid[:-1]) | (depth[1:] != depth[:-1])) + 1
        starts = np.concatenate([[0], brk])
        ends = np.concatenate([brk, [len(depth)]])
        cid, d = s.cid[starts], depth[starts]
        same_prev = np.concatenate([[False], cid[1:] == cid[:-1]])
        same_next = np.concatenate([cid[:-1] == cid[1:], [False]])
        # a run reaches to the next run's first sample (the change lies between)
        box = np.maximum.reduceat(s.xy, starts) - np.minimum.reduceat(s.xy, starts)
        step = np.zeros(len(starts))
        j = np.flatnonzero(same_next)
        step[j] = np.abs(s.xy[ends[j]] - s.xy[starts[j]]).max(axis=1)
        extent = np.maximum(box.max(axis=1), step)
        prev = np.where(same_prev, np.roll(d, 1), 0)
        nxt = np.where(same_next, np.roll(d, -1), 0)
        short = (d > 0) & (extent < small[s.view[cid]])
        sliver = short & ((prev > 0) | (nxt > 0))
        if not sliver.any():
            break
        # a neighbour that is no sliver itself first: two slivers side by
        # side do not swap their depths
        solid_prev = (prev > 0) & ~np.concatenate([[False], short[:-1]])
        solid_next = (nxt > 0) & ~np.concatenate([short[1:], [False]])
        firm = sliver & (solid_prev | solid_next)
        to = np.where(solid_prev, prev, np.where(solid_next, nxt, np.where(prev > 0, prev, nxt)))
        change = firm if firm.any() else sliver
        d[change] = to[change]
        depth = np.repeat(d, ends - starts)
    return depth


def _locate(s: Samples, vis: Occlusion, a: np.ndarray, depth: np.ndarray) -> np.ndarray:
    """Bisect every bracket ``a, a + 1`` to its change of depth, insert both
    ends (their depths counted) and return the depths of the merged samples."""
    cid = s.cid[a]
    lo, hi = s.t[a].copy(), s.t[a + 1].copy()
    dlo, dhi = depth[a], depth[a + 1].copy()
    span = np.abs(s.t1[cid] - s.t0[cid])
    owner, kind = s.owners(a)
    view = s.view[cid]
    # on the net's crossing where it is one, where the curve passes its own
    # contour (the count changes there, or, the ray test erring within 1e-5
    # of the scene of a fold, that close beside it) or through another sheet
    # of its own surface: where counts beside it agree
    meetings = net_meetings(s, vis, a)
    alone = np.bincount(np.searchsorted(a, meetings[0]), minlength=len(a)) == 0
    b = Brackets(cid, owner, kind, lo.copy(), hi.copy(), dlo, dhi.copy(), alone)
    row, t, _ = net_guesses(s, vis, a, GUIDE_RTOL, meetings)
    rows, t = confirmed(s, vis, b, row, t, (GUIDE_RTOL,))
    guided = np.zeros(len(a), dtype=bool)
    guided[rows], lo[rows], hi[rows] = True, t, t
    for find in (own_contour_zeros, through_sheets):
        rest = np.flatnonzero(~guided)
        r = b.take(rest)
        rows, t = confirmed(s, vis, r, *find(s, vis, r))
        rows = rest[rows]
        guided[rows], lo[rows], hi[rows] = True, t, t
    # K-section on the count for the rest, K chosen as for the flips
    K = sections(view, np.ones(len(a), dtype=bool), s.views.k, vis)
    for _ in range(tol.BISECTION_MAX_STEPS):
        go = np.flatnonzero((hi - lo > DEPTH_RTOL * span) & ~guided)
        if not len(go):
            break
        rep, tm, first_differing = sub_points(lo, hi, go, K[go])
        xyz, _, xy = s.evaluate(cid[rep], tm, True)
        n = np.maximum(vis.sheets(xyz, xy, owner[rep], kind[rep], view=view[rep]), 1)
        new_lo, new_hi = first_differing(n != dlo[rep])
        lo[go[new_lo >= 0]] = tm[new_lo[new_lo >= 0]]
        moved = new_hi >= 0
        hi[go[moved]] = tm[new_hi[moved]]
        dhi[go[moved]] = n[new_hi[moved]]
    # both strokes end on the middle of the final bracket: they meet, with no gap
    lo = hi = 0.5 * (lo + hi)
    t = np.column_stack([lo, hi]).ravel()
    c = np.repeat(cid, 2)
    xyz, uv, xy = s.evaluate(c, t, True)
    ends = np.column_stack([dlo, dhi]).ravel()  # the depths counted on either side
    new = merge(s, np.repeat(a, 2), c, t, xyz, uv, xy, np.ones(len(t), dtype=bool))
    out = np.empty(len(s.t), dtype=np.int64)
    out[~new] = depth
    out[new] = ends
    return out
