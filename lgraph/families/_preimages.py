"""One preimage of each self-intersection curve, chosen along the traced polylines.

:mod:`lgraph.families.self_intersection` traces the crossings of a curve's
two preimages ``x(a) = x(b)`` with the cells of a parameter grid into
polylines of ``(a, b)`` pairs; here one preimage of every point is kept:
polylines whose partners lie on one already taken are dropped, and along a
polyline that holds partners of its own points (a Whitney umbrella's segment
through its pinch point; Boy's surface, where one closed preimage covers the
three loops through the triple point twice) the points met before their
partners are kept, each run carried on to where the partner changes sheets.
Distances are in grid cells, across the glued seams of the domain.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["one_preimage"]

#: a crossing's partner lies on a polyline when within this many cells of it
#: (the polyline's chords miss the curve by far less; another branch through a
#: triple point is this close only within a fraction of a cell of it)
PARTNER_CELLS = 0.25


def _cell_distances(a: np.ndarray, other: np.ndarray, h: np.ndarray, d: Any = None) -> np.ndarray:
    """Distances in cells (max norm) from each point of ``a`` to each of
    ``other``, across the glued seams of domain ``d`` if given: ``(len(a), len(other))``."""
    q = other[None, :, :]
    if d is not None and any(d.glued):
        q = d.nearest_image(a[:, None, :], q)
    return np.abs((a[:, None, :] - q) / h).max(axis=2)


def _near(a: np.ndarray, other: np.ndarray, h: np.ndarray, d: Any = None) -> np.ndarray:
    """For each point of ``a``: whether a point of ``other`` is within about a
    cell (across the glued seams of domain ``d``, if given)."""
    return _cell_distances(a, other, h, d).min(axis=1) <= 1.5


def _to_segments(
    p: np.ndarray, s0: np.ndarray, s1: np.ndarray, h: np.ndarray, d: Any = None
) -> np.ndarray:
    """Distances in cells from points ``p`` to segments ``s0, s1`` (broadcast,
    ``(..., 2)``; across glued seams of ``d``)."""
    if d is not None and any(d.glued):
        s1, p = d.nearest_image(s0, s1), d.nearest_image(s0, p)
    e, w = (s1 - s0) / h, (p - s0) / h
    with np.errstate(invalid="ignore", divide="ignore"):
        f = np.clip(np.nan_to_num(np.sum(w * e, -1) / np.sum(e * e, -1)), 0.0, 1.0)
    return np.linalg.norm(w - f[..., None] * e, axis=-1)


def _first_of_pairs(a: np.ndarray, b: np.ndarray, h: np.ndarray, d: Any = None) -> np.ndarray:
    """Along a polyline that holds both preimages of some of its points: which
    points to keep, so that of a point and its partner the one met first is kept.

    The partner of point ``k`` lies on segment ``j`` of the polyline when
    ``b[k]`` is within ``PARTNER_CELLS`` of it and, mutually, ``a[k]`` is that
    close to the partners' polyline there; a point is dropped when its partner
    comes before it.  On a Whitney umbrella's segment (the partner mirrored
    about the pinch point) the part up to the pinch point is kept; on a closed
    curve that is its own partner half way round, half of it; on Boy's
    surface, whose one preimage runs through pairs of partner arcs and through
    arcs whose partners lie elsewhere, one arc of each pair and the others.
    """
    if len(a) < 2:
        return np.ones(len(a), bool)
    k = np.arange(len(a))
    # the partner of each point to every segment of the polyline ...
    to_line = _to_segments(b[:, None], a[None, :-1], a[None, 1:], h, d)
    seg = to_line.argmin(axis=1)
    # ... and the point to the partners' polyline there, the other way round
    around = np.clip(seg[:, None] + np.arange(-1, 2), 0, len(a) - 2)
    back = _to_segments(a[:, None], b[around], b[around + 1], h, d).min(axis=1)
    mutual = (to_line[k, seg] <= PARTNER_CELLS) & (back <= PARTNER_CELLS)
    return ~(mutual & (seg + 1 < k))


def _cut(a: np.ndarray, b: np.ndarray, i0: int, i1: int, h: np.ndarray, d: Any) -> np.ndarray:
    """Where a kept run ends on the segment from its last point ``i0`` to the
    dropped ``i1``: at a crossing of the polyline with itself (a triple
    point's preimage, where the partner switches sheets), else at ``i1``.
    Returns the pair ``(a, b)`` there, ``(2, 2)``."""
    glued = d is not None and any(d.glued)
    img = d.nearest_image if glued else (lambda p, q: np.asarray(q, float))
    p0, p1 = a[i0], img(a[i0], a[i1])
    q0 = img(p0, a[:-1])
    q1 = img(q0, a[1:])
    e, f, w = (p1 - p0) / h, (q1 - q0) / h, (q0 - p0) / h
    det = e[0] * -f[:, 1] + f[:, 0] * e[1]
    with np.errstate(invalid="ignore", divide="ignore"):
        t = (w[:, 0] * -f[:, 1] + f[:, 0] * w[:, 1]) / det
        u = (e[0] * w[:, 1] - e[1] * w[:, 0]) / det
    m = np.arange(len(q0))
    hit = (t > 0) & (t <= 1) & (u >= 0) & (u <= 1) & (np.abs(m - min(i0, i1)) > 1)
    t_cut = float(t[hit].min()) if hit.any() else 1.0
    b1 = img(b[i0], b[i1])
    return np.stack([p0 + t_cut * (p1 - p0), b[i0] + t_cut * (b1 - b[i0])])


def one_preimage(
    lines: list, pts: dict, h: np.ndarray, d: Any = None
) -> list[tuple[np.ndarray, np.ndarray, bool]]:
    """Of the two preimages of each curve, one: ``(a, b, closed)`` pieces (the
    points and their partners).

    A traced polyline whose partners lie on another polyline already taken is
    that one's other preimage (dropped; the same curve seen from a neighbouring
    cell column is dropped the same way).  A polyline that holds partners of its
    own points (the preimages join, as at a Whitney umbrella's pinch point, or
    one closed preimage runs through both, as on Boy's surface) keeps the points
    met before their partners (:func:`_first_of_pairs`), each run carried on to
    where the partner switches (:func:`_cut`)."""
    a_all, b_all = pts["a"], pts["b"]
    taken: list[np.ndarray] = []
    out: list[tuple[np.ndarray, np.ndarray, bool]] = []
    for idx, closed in sorted(lines, key=lambda line: -len(line[0])):
        a, b = a_all[idx], b_all[idx]
        if any(_near(b, o, h, d).mean() > 0.5 or _near(a, o, h, d).all() for o in taken):
            continue
        taken.append(a)
        keep = _first_of_pairs(a, b, h, d)
        if keep.all():
            out.append((a, b, closed))
            continue
        if closed and keep[0] and keep[-1]:  # a run through the closing point: one piece
            shift = len(keep) - int(np.flatnonzero(~keep)[-1]) - 1
            a, b, keep = np.roll(a, shift, 0), np.roll(b, shift, 0), np.roll(keep, shift)
        edges = np.flatnonzero(np.diff(np.r_[0, keep.astype(int), 0]))
        for s0, s1 in zip(edges[::2], edges[1::2]):
            if s1 - s0 < 3:
                continue
            ends = [np.stack([a[s0:s1], b[s0:s1]], axis=1)]
            if s0 > 0:
                ends.insert(0, _cut(a, b, s0, s0 - 1, h, d)[None])
            if s1 < len(a):
                ends.append(_cut(a, b, s1 - 1, s1, h, d)[None])
            run = np.concatenate(ends)
            out.append((run[:, 0], run[:, 1], False))
    return out
