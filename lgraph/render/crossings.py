"""Candidate points of visibility change: 2-D crossings of every curve with the projected net.

Along a curve, visibility can change only where its projection crosses the
projection of a contour or of a patch boundary of a hiding surface, or of
a curve where two surfaces meet or a surface meets itself (or where it
meets its own surface's contour, which the ray tests of its own surface
follow).  The *net* is the sampled contours and boundaries of the hiding
nodes in each view, the intersection curves, and the self-intersection
curves of the nodes that draw them (``SelfIntersection``).  Where one
chord of a curve is crossed by the net two or more times, a short hidden
(or visible) piece may lie wholly between its two samples;
``seed_net_crossings`` inserts one sample between every two consecutive
crossings of such a chord, so that every interval between candidates
carries a tested sample and ``locate_flips`` (:mod:`lgraph.render.flips`)
finds both of its ends.  Chords that pass near their own surface's contour
without crossing it are refined until they cross or part
(``near_misses``).

For the grouped ellipsoids the net is exact: their outlines are conics in
the image (``Occlusion.outlines``), crossed
with each chord in closed form; a chord lying on an ellipsoid is crossed
only with the outlines that meet its own (the image of a convex solid is
convex), which keeps the work near the number of chords that matter.  For
every other surface the crossings are those of the polylines (each chord
within the chord tolerance of its curve): an interval shorter than the chord
tolerance of the figure, behind another node's contour, may still be missed
there (docs/mathematics.rst says precisely what), and contours that such a
node does not draw (``contour=False``) are not part of its net.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from .boxes import box_pairs
from .sampling import Samples, merge

if TYPE_CHECKING:
    from .occlusion import Occlusion

__all__ = [
    "NET_FAMILIES",
    "near_misses",
    "net_crossings",
    "net_meetings",
    "seed_net_crossings",
]

#: the families whose curves form the net of a hiding node asked one by one
NET_FAMILIES = frozenset({"contour", "boundary"})
#: where a curve enters another surface's solid: part of the net of every node
MEETING_FAMILY = "intersection"
#: where a surface passes through itself: part of the net of its node when drawn
SELF_MEETING_FAMILY = "self_intersection"
#: passes of refining chords that pass near their own surface's contour
#: without crossing it (``near_misses``): the pieces a helicoid hides
#: beside its contour's cusps, where line and contour run 1e-4 apart
NEAR_PASSES = 4


def _curves_of(s: Samples, families: Callable[[int], set[str]]) -> np.ndarray:
    """Mask of the curves whose family is in ``families(node)``."""
    out = np.zeros(len(s.t0), dtype=bool)
    for batch, node, _, first in s.parts:
        wanted = families(node)
        names = batch.curve_family
        if names is None:
            out[first : first + len(batch)] = batch.family in wanted
        else:
            out[first : first + len(batch)] = [n in wanted for n in names]
    return out


def _net_curves(s: Samples, hiding: set[int], meetings: bool = True) -> np.ndarray:
    """Mask of the curves that belong to the sampled net: contours and
    boundaries of the nodes ``hiding``, and (``meetings``) the intersection
    and self-intersection curves of all."""
    meet = {MEETING_FAMILY, SELF_MEETING_FAMILY} if meetings else set()
    return _curves_of(s, lambda node: (NET_FAMILIES | meet) if node in hiding else meet)


def chord_crossings(
    a0: np.ndarray, a1: np.ndarray, b0: np.ndarray, b1: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Which segments ``a0 a1`` cross segments ``b0 b1`` (row by row), and
    where along ``a`` and along ``b`` (fractions in [0, 1]).

    >>> a0, a1 = np.array([[0.0, 0.0]]), np.array([[2.0, 0.0]])
    >>> hit, f, g = chord_crossings(a0, a1, np.array([[0.5, -1.0]]), np.array([[0.5, 1.0]]))
    >>> hit.tolist(), f.tolist(), g.tolist()
    ([True], [0.25], [0.5])
    """
    r, q = a1 - a0, b1 - b0
    den = r[:, 0] * q[:, 1] - r[:, 1] * q[:, 0]
    w = b0 - a0
    with np.errstate(divide="ignore", invalid="ignore"):
        fa = (w[:, 0] * q[:, 1] - w[:, 1] * q[:, 0]) / den
        fb = (w[:, 0] * r[:, 1] - w[:, 1] * r[:, 0]) / den
    hit = (den != 0) & (fa >= 0) & (fa <= 1) & (fb >= 0) & (fb <= 1)
    return hit, np.where(hit, fa, np.nan), np.where(hit, fb, np.nan)


def _view_crossings(
    xy: np.ndarray, qi: np.ndarray, ni: np.ndarray, cid: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Crossings of query chords ``qi`` with net chords ``ni`` (chord ``i``
    runs from sample ``i`` to ``i + 1``) of one view: the query chord of each
    crossing and its fraction along it, the net chord and its fraction."""
    q0, q1, n0, n1 = (np.take(xy, i, axis=0) for i in (qi, qi + 1, ni, ni + 1))
    pq, pn = box_pairs(
        np.minimum(q0, q1), np.maximum(q0, q1), np.minimum(n0, n1), np.maximum(n0, n1)
    )
    a, b = qi[pq], ni[pn]
    # a net curve may pass behind another part of itself (a contour crossing
    # its own image at a T-junction): a chord meets the same curve's other
    # chords, but not itself nor its neighbours (nor, at a closed curve's
    # seam, a chord that shares an end with it: crossings strictly inside)
    same = cid[a] == cid[b]
    keep = ~same | (np.abs(a - b) > 1)
    a, b, same = a[keep], b[keep], same[keep]
    hit, fa, fb = chord_crossings(*(np.take(xy, i, axis=0) for i in (a, a + 1, b, b + 1)))
    hit &= ~same | ((fa > 0) & (fa < 1) & (fb > 0) & (fb < 1))
    return a[hit], fa[hit], b[hit], fb[hit]


def _conic_roots(
    xy: np.ndarray, qi: np.ndarray, C: np.ndarray, origin: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Where chords ``qi`` cross the outline conic ``C`` (one ``(3, 3)``, or
    one a chord): the chord of each crossing and its fraction along it, the
    roots in (0, 1) of the quadratic ``f(s) = y(s) C y(s)`` along the chord."""
    xs, ys = xy[:, 0], xy[:, 1]  # columns first: gathered faster
    xa, ya = xs[qi], ys[qi]
    x0, y0 = xa - origin[0], ya - origin[1]  # the conics' coordinates
    rx, ry = xs[qi + 1] - xa, ys[qi + 1] - ya
    if C.ndim == 2:
        C = C[None]
    c00, c01, c02 = C[:, 0, 0], C[:, 0, 1], C[:, 0, 2]
    c11, c12, c22 = C[:, 1, 1], C[:, 1, 2], C[:, 2, 2]
    # y(s) = a + s r with a = (x0, y0, 1), r = (rx, ry, 0)
    alpha = c00 * rx * rx + 2 * c01 * rx * ry + c11 * ry * ry
    beta = 2 * (c00 * x0 * rx + c01 * (x0 * ry + y0 * rx) + c11 * y0 * ry + c02 * rx + c12 * ry)
    gamma = c00 * x0 * x0 + 2 * c01 * x0 * y0 + c11 * y0 * y0 + 2 * (c02 * x0 + c12 * y0) + c22
    disc = beta * beta - 4 * alpha * gamma
    with np.errstate(all="ignore"):
        w = -0.5 * (beta + np.copysign(np.sqrt(disc), beta))  # the stable pair
        s1, s2 = w / alpha, gamma / w
    ok1 = (disc > 0) & (s1 > 0) & (s1 < 1)
    ok2 = (disc > 0) & (s2 > 0) & (s2 < 1)
    return np.concatenate([qi[ok1], qi[ok2]]), np.concatenate([s1[ok1], s2[ok2]])


def _outline_crossings(
    s: Samples, vis: Occlusion, k: int, chord: np.ndarray
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Crossings of chords ``chord`` (all of view ``k``) with the outlines
    of the grouped ellipsoids other than their own.

    A chord between two points of an ellipsoid lies inside that ellipsoid's
    outline (the image of a convex solid is convex), so it can meet only the
    outlines that meet its own: those chords are taken per pair of
    ellipsoids whose tight outline boxes overlap, from the contiguous range
    of their node's chords, one conic at a time.  Every other chord is
    joined with all outline boxes through :func:`box_pairs`."""
    C, box, origin = vis.outlines(k), vis.outline_boxes(k), vis.image_origin(k)
    qn = np.full(int(vis.q_node.max()) + 1, -1)
    qn[vis.q_node] = np.arange(vis.nq)
    cid = s.cid[chord]
    owner = s.owner[cid]
    qo = np.where((owner >= 0) & (owner < len(qn)), qn[np.clip(owner, 0, len(qn) - 1)], -1)
    qo[s.kind[cid] == 0] = -1  # OFF: not on its ellipsoid
    free = np.flatnonzero(qo < 0)
    # the pairs of ellipsoids whose outline boxes meet (twins aside)
    meet = (box[:, None, 0] <= box[None, :, 2]) & (box[:, None, 2] >= box[None, :, 0])
    meet &= (box[:, None, 1] <= box[None, :, 3]) & (box[:, None, 3] >= box[None, :, 1])
    meet &= vis.first[vis.q_node][:, None] != vis.first[vis.q_node][None, :]  # not twins
    if not len(free) and not meet.any():  # every chord inside its own outline only
        return [], []
    ok = np.isfinite(box[:, 0])
    xs, ys = s.xy[:, 0], s.xy[:, 1]  # columns first: gathered faster
    xa, xb, ya, yb = xs[chord], xs[chord + 1], ys[chord], ys[chord + 1]
    x0, y0 = np.minimum(xa, xb), np.minimum(ya, yb)
    x1, y1 = np.maximum(xa, xb), np.maximum(ya, yb)
    found_q, found_f = [], []
    if len(free):
        pc, pq = box_pairs(
            np.column_stack([x0[free], y0[free]]),
            np.column_stack([x1[free], y1[free]]),
            np.where(ok[:, None], box[:, :2], np.inf),
            np.where(ok[:, None], box[:, 2:], -np.inf),
        )
        q, f = _conic_roots(s.xy, chord[free[pc]], C[pq], origin)
        found_q.append(q)
        found_f.append(f)
    # chords on ellipsoid j, against every ellipsoid q whose outline box meets j's
    on = np.flatnonzero(qo >= 0)
    if not len(on):
        return found_q, found_f
    order = on[np.argsort(qo[on], kind="stable")]  # already sorted, as a rule
    starts = np.searchsorted(qo[order], np.arange(vis.nq), "left")
    stops = np.searchsorted(qo[order], np.arange(vis.nq), "right")
    # every (chord, outline) pair at once: the chords of ellipsoid j repeated
    # for each outline q meeting j's, then culled by q's box; one root call
    # (the same arithmetic per row as one conic at a time)
    js, qs = np.nonzero(meet & (stops > starts)[:, None])
    if not len(js):
        return found_q, found_f
    n = stops[js] - starts[js]
    pos = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n) + np.repeat(starts[js], n)
    rows, q = order[pos], np.repeat(qs, n)
    bx0, by0, bx1, by1 = (box[:, i][q] for i in range(4))
    keep = (x1[rows] >= bx0) & (x0[rows] <= bx1) & (y1[rows] >= by0) & (y0[rows] <= by1)
    if keep.any():
        qq, f = _conic_roots(s.xy, chord[rows[keep]], np.take(C, q[keep], axis=0), origin)
        found_q.append(qq)
        found_f.append(f)
    return found_q, found_f


def net_crossings(
    s: Samples, vis: Occlusion, query: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Every crossing of a chord with the net: the chord (its first sample)
    and the fraction along it, for the chords ``query`` (default: all).
    The net: the exact outline conics of the grouped ellipsoids
    (``Occlusion.outlines``) and the sampled contours and boundaries of
    every other hiding surface.  A curve is not crossed with its own
    surface's outline (its own contour crossings are seeded by
    :func:`~lgraph.render.flips.seed_crossings` or followed by the
    own-surface tests)."""
    q, f, _, _ = net_meetings(s, vis, query)
    return q, f


def net_meetings(
    s: Samples, vis: Occlusion, query: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`net_crossings` with what each chord crosses: the query chord,
    its fraction, and the net chord crossed and its fraction (-1 and NaN
    for an ellipsoid's outline conic)."""
    empty = np.empty(0, np.int64), np.empty(0)
    net = _net_curves(s, set(vis.twins))  # the surfaces asked one by one
    if not net.any() and not vis.nq:
        return empty + empty
    chord = np.flatnonzero(s.cid[1:] == s.cid[:-1])
    chord = chord[(s.t[chord + 1] - s.t[chord]) > 0]
    query = chord if query is None else query
    qview = s.view[s.cid[query]]
    net_chord = chord[net[s.cid[chord]]]
    net_view = s.view[s.cid[net_chord]]
    found: list[tuple[np.ndarray, ...]] = []
    for k in np.unique(qview).tolist():
        q_k = query[qview == k]
        if len(net_chord):
            found.append(_view_crossings(s.xy, q_k, net_chord[net_view == k], s.cid))
        if vis.nq:
            for q, f in zip(*_outline_crossings(s, vis, k, q_k)):
                found.append((q, f, np.full(len(q), -1), np.full(len(q), np.nan)))
    if not found:
        return empty + empty
    q, f, b, g = (np.concatenate(parts) for parts in zip(*found))
    return q, f, b, g


def seed_net_crossings(
    s: Samples, vis: Occlusion, near: np.ndarray | None = None, passes: int | None = None
) -> int:
    """Insert, into every chord that the net crosses twice or more
    (:func:`net_crossings`), one untested sample between each two
    consecutive crossings (so that the interval between them is tested).

    With ``near`` (per view: twice the chord tolerance), chords that a net
    chord passes within ``near`` of without crossing it (``near_misses``)
    are refined too, both of them: the true curves, each within the chord
    tolerance of its polyline, may cross there twice (a piece hidden by a
    fold or beside a cusp of a contour, along which the two run nearly
    parallel).  The query chord gets samples at its closest approach and at
    its middle, the net chord at its middle; this repeats (``passes``
    times at most) on the new chords, whose polylines lie ever closer to
    their curves, until every such pair crosses or parts.  Returns the
    number of samples inserted."""
    total = 0
    passes = NEAR_PASSES if passes is None else passes
    if not passes:
        near = None
    for k in range(passes if near is not None else 1):
        # crossings once (as many passes would halve the chord between two
        # crossings at a tangency again and again), near misses each pass
        q, f = net_crossings(s, vis) if k == 0 else (np.empty(0, np.int64), np.empty(0))
        after, mid = np.empty(0, np.int64), np.empty(0)
        if len(q):
            order = np.lexsort((f, q))
            q, f = q[order], f[order]
            pair = np.flatnonzero(q[1:] == q[:-1])  # consecutive crossings of one chord
            pair = pair[f[pair + 1] > f[pair]]
            after, mid = q[pair], 0.5 * (f[pair] + f[pair + 1])
        if near is not None:
            nq, nf, nn = near_misses(s, vis, near)
            half = np.full(len(nq) + len(nn), 0.5)
            after = np.concatenate([after, nq, nq, nn])
            mid = np.concatenate([mid, nf, half])
        if not len(after):
            break
        key = np.round(mid, 9)
        order = np.lexsort((key, after))
        after, mid = after[order], mid[order]
        new = np.ones(len(after), dtype=bool)
        new[1:] = (after[1:] != after[:-1]) | (key[order][1:] != key[order][:-1])
        after, mid = after[new], mid[new]
        t = s.t[after] + mid * (s.t[after + 1] - s.t[after])
        c = s.cid[after]
        xyz, uv, xy = s.evaluate(c, t, True)
        merge(s, after, c, t, xyz, uv, xy)
        total += len(after)
        if near is None:
            break
    return total


def near_misses(
    s: Samples, vis: Occlusion, near: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Chords that a sampled net chord passes within ``near[view]`` of
    without crossing: the chord (its first sample) and the fraction along it
    of the closest approach, once per chord (the closest of its near net
    chords), and the net chords met so (each once); the net here is the
    sampled contours and boundaries.  Coincident polylines
    (a distance of 1e-9 of ``near`` or less: the same curve twice) and
    chords shorter than 1e-6 of ``near`` are left out.  The outline conics
    of grouped ellipsoids are exact and take no part."""
    none = np.empty(0, np.int64), np.empty(0), np.empty(0, np.int64)
    # the sampled contours and boundaries (intersection curves are traced to
    # 1e-14 on both surfaces, and refining chords beside them to tiny lengths
    # lost the closed-form outline crossings that mark changes of depth)
    net = _net_curves(s, set(vis.twins), meetings=False)
    if not net.any():
        return none
    contour = _curves_of(s, lambda _node: {"contour"})
    chord = np.flatnonzero(s.cid[1:] == s.cid[:-1])
    chord = chord[(s.t[chord + 1] - s.t[chord]) > 0]
    xy = s.xy
    length = np.abs(np.take(xy, chord + 1, axis=0) - np.take(xy, chord, axis=0)).max(axis=1)
    view = s.view[s.cid[chord]]
    chord, view = chord[length > 1e-6 * near[view]], view[length > 1e-6 * near[view]]
    net_chord = chord[net[s.cid[chord]]]
    net_view = s.view[s.cid[net_chord]]
    sag = _sagittas(s, near)
    found_q, found_f, found_d, found_n = [], [], [], []
    for k in np.unique(view).tolist():
        q_k, n_k = chord[view == k], net_chord[net_view == k]
        if not len(n_k):
            continue
        pad = float(near[k])
        q0, q1, n0, n1 = (np.take(xy, i, axis=0) for i in (q_k, q_k + 1, n_k, n_k + 1))
        pq, pn = box_pairs(
            np.minimum(q0, q1) - pad,
            np.maximum(q0, q1) + pad,
            np.minimum(n0, n1),
            np.maximum(n0, n1),
        )
        a, b = q_k[pq], n_k[pn]
        # a curve beside its own surface's contour (a fold, a cusp of the
        # contour): the ray tests of the other surfaces follow their nets
        ca, cb = s.cid[a], s.cid[b]
        keep = (ca != cb) & (s.owner[ca] == s.owner[cb]) & (s.owner[ca] >= 0) & contour[cb]
        a, b = a[keep], b[keep]
        d, f = _approach(*(np.take(xy, i, axis=0) for i in (a, a + 1, b, b + 1)))
        # each polyline lies within its chords' sagitta of its curve: nearer
        # than both, the curves may cross; else they part (refined chords
        # have smaller sagittas, so this ends)
        reach = np.minimum(sag[a] + sag[b], pad)
        # an approach at an end of the chord is at a tested sample (a line
        # that ends on a boundary touches it there)
        ok = (d < reach) & (d > 1e-9 * pad) & (f > 0) & (f < 1)
        found_q.append(a[ok])
        found_f.append(f[ok])
        found_d.append(d[ok])
        found_n.append(b[ok])
    if not found_q:
        return none
    q, f, d = (np.concatenate(x) for x in (found_q, found_f, found_d))
    order = np.lexsort((d, q))  # the closest approach of each chord
    q, f = q[order], f[order]
    first = np.ones(len(q), dtype=bool)
    first[1:] = q[1:] != q[:-1]
    return q[first], f[first], np.unique(np.concatenate(found_n))


def _sagittas(s: Samples, near: np.ndarray) -> np.ndarray:
    """For every chord ``i`` (samples ``i``, ``i + 1``), a bound on how far its
    curve strays from it in the image: twice the larger of the sagittas
    estimated from the second differences at its two ends (scaled to the
    chord's length), at most ``near / 2`` (the chord tolerance); a curve of
    two samples gets that."""
    n = len(s.t)
    xy, cid = s.xy, s.cid
    half = 0.5 * np.asarray(near, dtype=float)[s.view[cid]]
    out = half.copy()
    if n < 3:
        return out
    inner = (cid[:-2] == cid[1:-1]) & (cid[1:-1] == cid[2:])
    h0 = np.linalg.norm(xy[1:-1] - xy[:-2], axis=1)
    h1 = np.linalg.norm(xy[2:] - xy[1:-1], axis=1)
    # deviation of the middle sample from the chord of its neighbours
    d2 = np.abs(
        (xy[2:] - xy[:-2])[:, 0] * (xy[1:-1] - xy[:-2])[:, 1]
        - (xy[2:] - xy[:-2])[:, 1] * (xy[1:-1] - xy[:-2])[:, 0]
    ) / np.maximum(h0 + h1, 1e-300)
    scale = np.maximum(h0, h1) / np.maximum(h0 + h1, 1e-300)
    at = np.where(inner, d2 * scale, np.inf)  # sample i + 1 as the middle
    # chord i has its ends at samples i and i + 1: the estimates there
    left = np.concatenate([[np.inf], at])  # middle sample i
    right = np.concatenate([at, [np.inf]])  # middle sample i + 1
    est = np.maximum(left[: n - 1], right[: n - 1])
    # an end without neighbours on both sides: the other end's estimate
    est = np.where(np.isfinite(est), est, np.minimum(left[: n - 1], right[: n - 1]))
    est = np.where(np.isfinite(est), 2 * est, half[: n - 1])
    out[: n - 1] = np.minimum(est, half[: n - 1])
    return out


def _approach(
    a0: np.ndarray, a1: np.ndarray, b0: np.ndarray, b1: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Distance between segments ``a0 a1`` and ``b0 b1`` (row by row; 0 where
    they cross) and the fraction along ``a`` of their closest approach.

    >>> d, f = _approach(np.array([[0.0, 0.0]]), np.array([[2.0, 0.0]]),
    ...                  np.array([[0.5, 0.1]]), np.array([[0.5, 1.0]]))
    >>> d.round(12).tolist(), f.tolist()
    ([0.1], [0.25])
    """
    r = a1 - a0
    rr = np.einsum("ij,ij->i", r, r)
    rr = np.where(rr > 0, rr, 1.0)
    # the ends of b against a
    fa = [np.clip(np.einsum("ij,ij->i", p - a0, r) / rr, 0, 1) for p in (b0, b1)]
    da = [np.linalg.norm(a0 + f[:, None] * r - p, axis=1) for f, p in zip(fa, (b0, b1))]
    # the ends of a against b (the approach then lies at an end of a: 0 or 1)
    q = b1 - b0
    qq = np.einsum("ij,ij->i", q, q)
    qq = np.where(qq > 0, qq, 1.0)
    db = [
        np.linalg.norm(b0 + np.clip(np.einsum("ij,ij->i", p - b0, q) / qq, 0, 1)[:, None] * q - p,
                       axis=1)
        for p in (a0, a1)
    ]  # fmt: skip
    d = np.stack([da[0], da[1], db[0], db[1]])
    f = np.stack([fa[0], fa[1], np.zeros(len(r)), np.ones(len(r))])
    best = np.argmin(d, axis=0)
    cols = np.arange(len(r))
    hit, _, _ = chord_crossings(a0, a1, b0, b1)
    return np.where(hit, 0.0, d[best, cols]), f[best, cols]
