"""Dash patterns as pieces of polylines, for backends without native dashes.

:func:`~lgraph.output.drawing.dash_polyline` cuts a polyline into the "on" intervals of a pattern
repeated along its arc length (the PNG backend and the plotter plugins use
it).  Arc length and linear interpolation only; no formula of
docs/mathematics.rst.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["dash_polyline", "MAX_DASHES"]


#: Most dashes :func:`dash_polyline` makes of one polyline (memory budget).
MAX_DASHES = 1_000_000


def dash_polyline(points: np.ndarray, pattern: Sequence[float]) -> list[np.ndarray]:
    """Split a polyline into its dashes (for backends without native dashes).

    ``pattern`` is a sequence of on/off lengths (in the units of ``points``)
    repeated along the arc length from the first point.  Each dash is an
    ``(m, 2)`` array: its interpolated start, the polyline's vertices inside
    it, and its interpolated end.  Fully vectorized: no Python loop over
    points or dashes.

    >>> pts = np.array([[0.0, 0.0], [10.0, 0.0]])
    >>> [d[:, 0].tolist() for d in dash_polyline(pts, (2, 3))]
    [[0.0, 2.0], [5.0, 7.0]]
    >>> [d.tolist() for d in dash_polyline([[0, 0], [2, 0], [2, 2]], (3, 0.5))]
    [[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0]], [[2.0, 1.5], [2.0, 2.0]]]
    """
    pts = np.asarray(points, float)
    pat = np.asarray(pattern, float)
    if len(pts) < 2 or len(pat) < 2:
        return []
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    total = arc[-1]
    period = float(pat.sum())
    if not (total > 0 and period > 0):
        return []
    # Start of every "on" interval: period index times period plus the offset
    # of that interval inside the pattern.
    on = pat[0::2]
    offsets = np.concatenate([[0.0], np.cumsum(pat)[1:-1:2]])
    n_periods = int(np.ceil(total / period)) + 1
    if n_periods * len(on) > MAX_DASHES:
        raise ValueError(
            f"dash_polyline: pattern {tuple(pat.tolist())} gives {n_periods * len(on)} dashes "
            f"along a polyline of length {total:g}; the limit is {MAX_DASHES} "
            "(lengthen the pattern)"
        )
    starts = (np.arange(n_periods)[:, None] * period + offsets[None, :]).ravel()
    ends = starts + np.tile(on, n_periods)
    keep = starts < total
    starts, ends = starts[keep], np.minimum(ends[keep], total)
    # Vertices strictly inside each dash: indices lo .. hi-1.
    lo = np.searchsorted(arc, starts, side="right")
    hi = np.searchsorted(arc, ends, side="left")
    counts = hi - lo + 2
    first = np.concatenate([[0], np.cumsum(counts)[:-1]])
    local = np.arange(counts.sum()) - np.repeat(first, counts)
    idx = np.clip(np.repeat(lo - 1, counts) + local, 0, len(pts) - 1)
    out = pts[idx]
    ends_t = np.column_stack([starts, ends])
    for axis in (0, 1):
        interp = np.interp(ends_t, arc, pts[:, axis])
        out[first, axis] = interp[:, 0]
        out[first + counts - 1, axis] = interp[:, 1]
    return np.split(out, first[1:])
