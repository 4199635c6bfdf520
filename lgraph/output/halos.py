"""Halos: strokes cut geometrically around label boxes and point marks, on the page.

A label with a halo (``Label(..., halo=True)``) knocks the lines out of its
text's ink box grown by a gap in pt; a point mark with one, out of a disc of
its radius plus the gap.  The strokes are *split* -- every point inside a
region is removed and each segment that enters or leaves it ends exactly on
its edge -- rather than painted over in white, so the gap is there in every
backend, plotters and vpype included.  The boxes have their size in pt
whatever the figure's scale, so the cut is made on the page
(:meth:`lgraph.Drawing.page_points`, which every backend draws from), when
the page layout is known.

Along a segment ``a + t (b - a)``, ``0 <= t <= 1``, the removed part is one
interval ``(t_in, t_out)`` per region, both regions being convex: for a box,
the intersection of the slabs ``x0 < x < x1`` and ``y0 < y < y1`` (Liang and
Barsky's clipping); for a disc of centre ``c`` and radius ``r``, the roots of
``|a + t d - c|^2 = r^2``.  Regions are applied one after another, each to
all segments at once.

>>> pts = np.array([[0.0, 0.0], [10.0, 0.0]])
>>> out, ends = cut_polylines(pts, [2], boxes=np.array([[4.0, -1.0, 6.0, 1.0]]))
>>> out.tolist(), ends
([[0.0, 0.0], [4.0, 0.0], [nan, nan], [6.0, 0.0], [10.0, 0.0]], [5])
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["cut_polylines", "cut_strokes", "halo_regions", "box_intervals", "disc_intervals"]


def box_intervals(a: np.ndarray, b: np.ndarray, box: Sequence[float]) -> tuple[np.ndarray, ...]:
    """``(t_in, t_out)`` of segments ``a b`` (rows) inside the open box
    ``x0, y0, x1, y1``; empty where ``t_in >= t_out``.

    >>> t0, t1 = box_intervals(np.array([[0.0, 0.0]]), np.array([[4.0, 4.0]]), (1, 1, 2, 3))
    >>> t0.tolist(), t1.tolist()
    ([0.25], [0.5])
    """
    d = b - a
    t_in = np.zeros(len(a))
    t_out = np.ones(len(a))
    with np.errstate(divide="ignore", invalid="ignore"):
        for k, (lo, hi) in enumerate(((box[0], box[2]), (box[1], box[3]))):
            u0 = (lo - a[:, k]) / d[:, k]
            u1 = (hi - a[:, k]) / d[:, k]
            flat = d[:, k] == 0  # parallel to the slab: all in (strictly) or all out
            inside = (a[:, k] > lo) & (a[:, k] < hi)
            enter = np.where(flat, np.where(inside, -np.inf, np.inf), np.minimum(u0, u1))
            leave = np.where(flat, np.where(inside, np.inf, -np.inf), np.maximum(u0, u1))
            t_in = np.maximum(t_in, enter)
            t_out = np.minimum(t_out, leave)
    return t_in, t_out


def disc_intervals(
    a: np.ndarray, b: np.ndarray, centre: Sequence[float], radius: float
) -> tuple[np.ndarray, ...]:
    """``(t_in, t_out)`` of segments ``a b`` inside the open disc; empty where
    ``t_in >= t_out``.

    >>> t0, t1 = disc_intervals(np.array([[-2.0, 0.0]]), np.array([[2.0, 0.0]]), (0, 0), 1.0)
    >>> t0.tolist(), t1.tolist()
    ([0.25], [0.75])
    """
    d = b - a
    f = a - np.asarray(centre, float)
    qa = np.einsum("ij,ij->i", d, d)
    qb = 2 * np.einsum("ij,ij->i", f, d)
    qc = np.einsum("ij,ij->i", f, f) - radius * radius
    disc = qb * qb - 4 * qa * qc
    with np.errstate(divide="ignore", invalid="ignore"):
        sq = np.sqrt(np.where(disc > 0, disc, 0.0))
        t_in = np.where(qa > 0, (-qb - sq) / (2 * qa), np.where(qc < 0, -np.inf, np.inf))
        t_out = np.where(qa > 0, (-qb + sq) / (2 * qa), np.where(qc < 0, np.inf, -np.inf))
    t_in = np.where((qa > 0) & (disc <= 0), np.inf, t_in)
    return np.maximum(t_in, 0.0), np.minimum(t_out, 1.0)


def _cut_one(
    pts: np.ndarray, sid: np.ndarray, t_in: np.ndarray, t_out: np.ndarray, inside: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Remove from the polylines ``pts`` (stroke ``sid`` of each point) the
    parts ``(t_in, t_out)`` of each segment (point ``i`` to ``i + 1``) and the
    points ``inside``: where a part is removed, a NaN point breaks the line,
    and the segment keeps its ends on the region's edge."""
    n = len(pts)
    same = sid[:-1] == sid[1:]
    cut = same & (t_in < t_out)
    cut = np.concatenate([cut, [False]])
    t0 = np.concatenate([t_in, [0.0]])
    t1 = np.concatenate([t_out, [1.0]])
    d = np.concatenate([pts[1:] - pts[:-1], np.zeros((1, 2))])
    slots = np.empty((n, 4, 2))
    slots[:, 0] = pts
    with np.errstate(invalid="ignore"):  # t = inf where nothing is cut: not kept
        slots[:, 1] = pts + t0[:, None] * d
        slots[:, 3] = pts + t1[:, None] * d
    slots[:, 2] = np.nan
    keep = np.empty((n, 4), bool)
    keep[:, 0] = ~inside
    keep[:, 1] = cut & (t0 > 0) & ~inside
    keep[:, 2] = cut
    keep[:, 3] = cut & (t1 < 1)
    return slots[keep], np.repeat(sid, 4).reshape(n, 4)[keep]


def cut_polylines(
    pts: np.ndarray,
    ends: Sequence[int],
    boxes: np.ndarray | None = None,
    discs: np.ndarray | None = None,
    whole: np.ndarray | None = None,
) -> tuple[np.ndarray, list[int]]:
    """The polylines ``pts`` (stroke ``k`` is ``pts[ends[k - 1]:ends[k]]``)
    with the open ``boxes`` (rows ``x0, y0, x1, y1``) and ``discs`` (rows
    ``cx, cy, r``) cut out; returns the new points and ends (a cut stroke
    gets NaN points where it is broken; one removed whole keeps only NaNs).
    The strokes where ``whole`` (one bool a stroke) is true are not cut.
    """
    pts = np.asarray(pts, float)
    sid = np.repeat(np.arange(len(ends)), np.diff(np.concatenate([[0], ends])).astype(int))
    fixed = np.zeros(len(ends), bool) if whole is None else np.asarray(whole, bool)
    regions = [("box", r) for r in ([] if boxes is None else np.asarray(boxes, float))]
    regions += [("disc", r) for r in ([] if discs is None else np.asarray(discs, float))]
    for kind, r in regions:  # a few labels and marks: one vectorized pass each
        if len(pts) < 2:
            break
        a, b = pts[:-1], pts[1:]
        with np.errstate(invalid="ignore"):
            if kind == "box":
                t_in, t_out = box_intervals(a, b, r)
                x, y = pts[:, 0], pts[:, 1]
                inside = (x > r[0]) & (x < r[2]) & (y > r[1]) & (y < r[3])
            else:
                t_in, t_out = disc_intervals(a, b, r[:2], r[2])
                inside = np.hypot(pts[:, 0] - r[0], pts[:, 1] - r[1]) < r[2]
        t_in = np.where(np.isnan(t_in) | fixed[sid[:-1]], np.inf, t_in)
        t_out = np.where(np.isnan(t_out), -np.inf, t_out)
        inside &= ~fixed[sid]
        if not (inside.any() or (t_in < t_out).any()):
            continue
        pts, sid = _cut_one(pts, sid, t_in, t_out, inside)
    counts = np.bincount(sid, minlength=len(ends))
    return pts, np.cumsum(counts).tolist()


def halo_regions(drawing: Any) -> tuple[np.ndarray, np.ndarray]:
    """``drawing``'s regions to cut on the page (pt, y up): boxes ``(k, 4)``
    (the labels' ink boxes grown by their halos) and discs ``(m, 3)``
    ``cx, cy, r`` (point marks: half the dot's width plus the halo)."""
    scale, offset, _, _ = drawing._layout()
    boxes = [
        box + (-lab.halo, -lab.halo, lab.halo, lab.halo)
        for box, lab in zip(drawing.label_boxes(), drawing.labels)
        if lab.halo is not None
    ]
    discs = [
        (*(np.asarray(s.xy[0], float) * scale + offset), s.style.width / 2 + s.halo)
        for s in drawing.strokes
        if getattr(s, "halo", None) is not None and len(s.xy)
    ]
    return np.array(boxes, float).reshape(-1, 4), np.array(discs, float).reshape(-1, 3)


def cut_strokes(
    drawing: Any, pts: np.ndarray, ends: list[int], strokes: list[Any]
) -> tuple[np.ndarray, list[int], list[Any]]:
    """The page points of ``drawing``'s strokes (``Drawing.page_points``)
    cut by its halos; point marks stay whole, and strokes left with fewer
    than two points are dropped."""
    boxes, discs = halo_regions(drawing)
    whole = np.array([s.family == "point" or getattr(s, "halo", None) is not None for s in strokes])
    pts, ends = cut_polylines(pts, ends, boxes, discs, whole)
    counts = np.diff(np.concatenate([[0], ends])).astype(int)
    if (counts < 2).any():
        good = np.flatnonzero(counts >= 2)
        starts = np.concatenate([[0], ends[:-1]]).astype(int)
        pts = np.concatenate([pts[starts[k] : ends[k]] for k in good] or [np.empty((0, 2))])
        ends = np.cumsum(counts[good]).tolist()
        strokes = [strokes[k] for k in good]
    return pts, ends, strokes
