"""Candidate points of visibility change: 2-D crossings of every curve with the projected net.

Along a curve, visibility can change only where its projection crosses the
projection of a contour or of a patch boundary of a hiding surface (or where
it meets its own surface's contour, which the ray tests of its own surface
follow).  The *net* is the sampled contours and boundaries of the hiding
nodes in each view.  Where one chord of a curve is crossed by the net two or
more times, a short hidden (or visible) piece may lie wholly between its two
samples; ``seed_net_crossings`` inserts one sample between every two
consecutive crossings of such a chord, so that every interval between
candidates carries a tested sample and ``locate_flips`` (:mod:`lgraph.render.flips`)
finds both of its ends.

The crossings are those of the polylines (each chord within the chord
tolerance of its curve): an interval shorter than the chord tolerance of the
figure may still be missed.  Contours that a node does not draw
(``contour=False``) are not part of the net.
"""

from __future__ import annotations

import numpy as np

from .sampling import Samples, merge

__all__ = ["NET_FAMILIES", "seed_net_crossings"]

#: the families whose curves form the net of a hiding node
NET_FAMILIES = frozenset({"contour", "boundary"})

#: grid cells per net chord (about): a few chords a cell
_CELLS_PER_CHORD = 0.5
#: at most this many (chord, cell) entries a view, so memory stays bounded
_MAX_ENTRIES = 4_000_000


def _net_curves(s: Samples, hiding: np.ndarray) -> np.ndarray:
    """Mask of the curves that belong to the net (contours and boundaries of
    hiding nodes)."""
    net = np.zeros(len(s.t0), dtype=bool)
    for batch, node, _, first in s.parts:
        if not hiding[node]:
            continue
        names = batch.curve_family
        if names is None:
            if batch.family in NET_FAMILIES:
                net[first : first + len(batch)] = True
        else:
            net[first : first + len(batch)] = [n in NET_FAMILIES for n in names]
    return net


def _cells(lo: np.ndarray, hi: np.ndarray, origin: np.ndarray, size: np.ndarray, g: int):
    """Cell ranges ``(cx0, cy0, cx1, cy1)`` of boxes ``lo..hi`` in a ``g x g`` grid."""
    c0 = np.clip(((lo - origin) / size).astype(np.int64), 0, g - 1)
    c1 = np.clip(((hi - origin) / size).astype(np.int64), 0, g - 1)
    return c0[:, 0], c0[:, 1], c1[:, 0], c1[:, 1]


def _entries(cx0, cy0, cx1, cy1, g: int) -> tuple[np.ndarray, np.ndarray]:
    """(item, cell) pairs of every cell each box covers."""
    nx, ny = cx1 - cx0 + 1, cy1 - cy0 + 1
    count = nx * ny
    item = np.repeat(np.arange(len(cx0)), count)
    k = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
    nxr = nx[item]
    cell = (cy0[item] + k // nxr) * g + cx0[item] + k % nxr
    return item, cell


def chord_crossings(
    a0: np.ndarray, a1: np.ndarray, b0: np.ndarray, b1: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Which segments ``a0 a1`` cross segments ``b0 b1`` (row by row), and
    where along ``a`` (fraction in [0, 1]).

    >>> a0, a1 = np.array([[0.0, 0.0]]), np.array([[2.0, 0.0]])
    >>> hit, f = chord_crossings(a0, a1, np.array([[0.5, -1.0]]), np.array([[0.5, 1.0]]))
    >>> hit.tolist(), f.tolist()
    ([True], [0.25])
    """
    r, q = a1 - a0, b1 - b0
    den = r[:, 0] * q[:, 1] - r[:, 1] * q[:, 0]
    w = b0 - a0
    with np.errstate(divide="ignore", invalid="ignore"):
        fa = (w[:, 0] * q[:, 1] - w[:, 1] * q[:, 0]) / den
        fb = (w[:, 0] * r[:, 1] - w[:, 1] * r[:, 0]) / den
    hit = (den != 0) & (fa >= 0) & (fa <= 1) & (fb >= 0) & (fb <= 1)
    return hit, np.where(hit, fa, np.nan)


def _view_crossings(
    xy: np.ndarray, qi: np.ndarray, ni: np.ndarray, cid: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Crossings of query chords ``qi`` with net chords ``ni`` (chord ``i``
    runs from sample ``i`` to ``i + 1``) of one view: the query chord of each
    crossing and its fraction along it."""
    if not len(qi) or not len(ni):
        return np.empty(0, np.int64), np.empty(0)
    nlo = np.minimum(xy[ni], xy[ni + 1])
    nhi = np.maximum(xy[ni], xy[ni + 1])
    qlo = np.minimum(xy[qi], xy[qi + 1])
    qhi = np.maximum(xy[qi], xy[qi + 1])
    # only query chords whose box meets the net's box can cross it
    lo, hi = nlo.min(axis=0), nhi.max(axis=0)
    near = np.all((qhi >= lo) & (qlo <= hi), axis=1)
    qi, qlo, qhi = qi[near], qlo[near], qhi[near]
    if not len(qi):
        return np.empty(0, np.int64), np.empty(0)
    g = int(max(1, min(np.sqrt(_CELLS_PER_CHORD * len(ni)), 2048)))
    size = np.maximum((hi - lo) / g, 1e-300)
    cells_n = _cells(nlo, nhi, lo, size, g)
    cells_q = _cells(qlo, qhi, lo, size, g)
    count = lambda c: int(((c[2] - c[0] + 1) * (c[3] - c[1] + 1)).sum())  # noqa: E731
    while g > 1 and count(cells_n) + count(cells_q) > _MAX_ENTRIES:
        g = max(1, g // 2)
        size = np.maximum((hi - lo) / g, 1e-300)
        cells_n = _cells(nlo, nhi, lo, size, g)
        cells_q = _cells(qlo, qhi, lo, size, g)
    n_item, n_cell = _entries(*cells_n, g)
    q_item, q_cell = _entries(*cells_q, g)
    order = np.argsort(n_cell, kind="stable")
    n_item, n_cell = n_item[order], n_cell[order]
    start = np.searchsorted(n_cell, q_cell, "left")
    stop = np.searchsorted(n_cell, q_cell, "right")
    m = stop - start
    pq = np.repeat(q_item, m)
    pn = n_item[np.repeat(start - np.cumsum(m) + m, m) + np.arange(int(m.sum()))]
    # a pair seen in several cells is tested once: in the first cell of the
    # overlap of their cell ranges
    pc = np.repeat(q_cell, m)
    first_x = np.maximum(cells_q[0][pq], cells_n[0][pn])
    first_y = np.maximum(cells_q[1][pq], cells_n[1][pn])
    once = pc == first_y * g + first_x
    pq, pn = pq[once], pn[once]
    a, b = qi[pq], ni[pn]
    keep = cid[a] != cid[b]  # a curve does not cross itself into hiding
    a, b = a[keep], b[keep]
    hit, frac = chord_crossings(xy[a], xy[a + 1], xy[b], xy[b + 1])
    return a[hit], frac[hit]


def seed_net_crossings(s: Samples, hiding: np.ndarray) -> int:
    """Insert, into every chord that the net crosses twice or more, one
    untested sample between each two consecutive crossings (so that the
    interval between them is tested); ``hiding`` flags the nodes that hide.
    Returns the number of samples inserted."""
    net = _net_curves(s, hiding)
    if not net.any():
        return 0
    chord = np.flatnonzero(s.cid[1:] == s.cid[:-1])
    chord = chord[(s.t[chord + 1] - s.t[chord]) > 0]
    view = s.view[s.cid[chord]]
    is_net = net[s.cid[chord]]
    found_q, found_f = [], []
    for k in np.unique(view).tolist():
        in_view = view == k
        q, f = _view_crossings(s.xy, chord[in_view], chord[in_view & is_net], s.cid)
        found_q.append(q)
        found_f.append(f)
    q, f = np.concatenate(found_q), np.concatenate(found_f)
    if not len(q):
        return 0
    order = np.lexsort((f, q))
    q, f = q[order], f[order]
    pair = np.flatnonzero(q[1:] == q[:-1])  # consecutive crossings of one chord
    pair = pair[f[pair + 1] > f[pair]]
    if not len(pair):
        return 0
    after = q[pair]
    mid = 0.5 * (f[pair] + f[pair + 1])
    t = s.t[after] + mid * (s.t[after + 1] - s.t[after])
    c = s.cid[after]
    xyz, uv, xy = s.evaluate(c, t, True)
    merge(s, after, c, t, xyz, uv, xy)
    return len(after)
