"""Two-dimensional spatial indexes of the render pipeline, vectorized.

* ``BoxGrid``: a uniform grid over a few boxes (the projected boxes of
  the grouped quadrics), queried with many points: which boxes contain
  each point;
* ``box_pairs``: every overlapping pair of two sets of boxes (chords of
  curves against chords of the net, or against the ellipsoids' outlines),
  each pair found once.
"""

from __future__ import annotations

import numpy as np

__all__ = ["BoxGrid", "box_pairs"]

#: grid cells per box of the second set (about): a few boxes a cell
_CELLS_PER_CHORD = 0.5
#: at most this many (box, cell) entries a join, so memory stays bounded
_MAX_ENTRIES = 4_000_000


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


def box_pairs(
    alo: np.ndarray, ahi: np.ndarray, blo: np.ndarray, bhi: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs ``(i, j)`` of 2-D boxes ``alo[i]..ahi[i]`` and
    ``blo[j]..bhi[j]`` that overlap, each pair once: a uniform grid sized on
    the ``b`` boxes, every pair tested in the first cell of the overlap of
    their cell ranges (no sorting of pairs, no duplicates).

    >>> lo = np.array([[0.0, 0.0], [5.0, 5.0]]); hi = lo + 1
    >>> [a.tolist() for a in box_pairs(lo, hi, np.array([[0.5, 0.5]]), np.array([[6.0, 6.0]]))]
    [[0, 1], [0, 0]]
    """
    none = np.empty(0, np.int64)
    if not len(alo) or not len(blo):
        return none, none
    # column by column: numpy gathers rows of an (n, 2) array slowly
    ax0, ay0, ax1, ay1 = alo[:, 0], alo[:, 1], ahi[:, 0], ahi[:, 1]
    bx0, by0, bx1, by1 = blo[:, 0], blo[:, 1], bhi[:, 0], bhi[:, 1]
    lo = np.array([bx0.min(), by0.min()])
    hi = np.array([bx1.max(), by1.max()])
    # only a boxes that meet the b boxes' box can overlap one
    near = np.flatnonzero((ax1 >= lo[0]) & (ax0 <= hi[0]) & (ay1 >= lo[1]) & (ay0 <= hi[1]))
    if not len(near):
        return none, none
    ax0, ay0, ax1, ay1 = ax0[near], ay0[near], ax1[near], ay1[near]
    g = int(max(1, min(np.sqrt(_CELLS_PER_CHORD * len(blo)), 2048)))

    def cells(g: int) -> tuple:
        size = np.maximum((hi - lo) / g, 1e-300)
        cb = _cells(blo, bhi, lo, size, g)
        ca = _cells(np.column_stack([ax0, ay0]), np.column_stack([ax1, ay1]), lo, size, g)
        return cb, ca

    cells_b, cells_a = cells(g)
    count = lambda c: int(((c[2] - c[0] + 1) * (c[3] - c[1] + 1)).sum())  # noqa: E731
    while g > 1 and count(cells_b) + count(cells_a) > _MAX_ENTRIES:
        g = max(1, g // 2)
        cells_b, cells_a = cells(g)
    b_item, b_cell = _entries(*cells_b, g)
    a_item, a_cell = _entries(*cells_a, g)
    order = np.argsort(b_cell, kind="stable")
    b_item, b_cell = b_item[order], b_cell[order]
    start = np.searchsorted(b_cell, a_cell, "left")
    m = np.searchsorted(b_cell, a_cell, "right") - start
    pa = np.repeat(a_item, m)
    pb = b_item[np.repeat(start - np.cumsum(m) + m, m) + np.arange(int(m.sum()))]
    if len(a_item) > len(ax0) or len(b_item) > len(bx0):
        # a pair seen in several cells is kept in the first cell of their overlap
        pc = np.repeat(a_cell, m)
        first_x = np.maximum(cells_a[0][pa], cells_b[0][pb])
        first_y = np.maximum(cells_a[1][pa], cells_b[1][pb])
        once = pc == first_y * g + first_x
        pa, pb = pa[once], pb[once]
    overlap = (ax1[pa] >= bx0[pb]) & (ax0[pa] <= bx1[pb])
    overlap &= (ay1[pa] >= by0[pb]) & (ay0[pa] <= by1[pb])
    return near[pa[overlap]], pb[overlap]


class BoxGrid:
    """A uniform grid over the projected boxes ``(x0, y0, x1, y1)`` of the
    grouped quadrics in one view: the (point, quadric) pairs to test."""

    def __init__(self, box: np.ndarray) -> None:
        pad = 1e-9 * (np.ptp(box[:, [0, 2]]) + np.ptp(box[:, [1, 3]]) + 1.0)
        self.box = box + np.array([-pad, -pad, pad, pad])
        n = len(box)
        if n == 1:
            return  # no grid: the box test alone
        g = max(1, int(2 * np.sqrt(n)))
        x0, y0 = self.box[:, 0].min(), self.box[:, 1].min()
        x1, y1 = self.box[:, 2].max(), self.box[:, 3].max()
        self.grid = (g, x0, y0, max(x1 - x0, 1e-300) / g, max(y1 - y0, 1e-300) / g)
        cells: list[list[int]] = [[] for _ in range(g * g)]
        for i, (bx0, by0, bx1, by1) in enumerate(self.box):
            cx = self._cell(np.array([bx0, bx1]), 1)
            cy = self._cell(np.array([by0, by1]), 2)
            for yy in range(cy[0], cy[1] + 1):
                for xx in range(cx[0], cx[1] + 1):
                    cells[yy * g + xx].append(i)
        counts = np.array([len(c) for c in cells])
        self.cell_start = np.concatenate([[0], np.cumsum(counts)[:-1]])
        self.cell_count = counts
        self.cell_items = np.array([i for c in cells for i in c], dtype=np.int64)
        # the boxes' sides as contiguous columns (gathered faster than rows)
        self.sides = [np.ascontiguousarray(self.box[:, i]) for i in range(4)]

    def _cell(self, values: np.ndarray, axis: int) -> np.ndarray:
        g, origin, size = self.grid[0], self.grid[axis], self.grid[axis + 2]
        return np.clip(((values - origin) / size).astype(np.int64), 0, g - 1)

    def pairs(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(point, quadric) index pairs whose box contains the point."""
        if len(self.box) == 1:
            x0, y0, x1, y1 = self.box[0]
            x, y = xy[:, 0], xy[:, 1]
            pt = np.flatnonzero((x >= x0) & (x <= x1) & (y >= y0) & (y <= y1))
            return pt, np.zeros(len(pt), dtype=np.int64)
        g = self.grid[0]
        cell = self._cell(xy[:, 1], 2) * g + self._cell(xy[:, 0], 1)
        counts = self.cell_count[cell]
        pt = np.repeat(np.arange(len(xy)), counts)
        first = np.repeat(self.cell_start[cell] + counts - np.cumsum(counts), counts)
        q = self.cell_items[first + np.arange(len(pt))]
        x0, y0, x1, y1 = (side[q] for side in self.sides)
        x, y = xy[:, 0][pt], xy[:, 1][pt]
        inside = (x >= x0) & (x <= x1)
        inside &= (y >= y0) & (y <= y1)
        return pt[inside], q[inside]
