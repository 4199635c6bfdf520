"""The L-shaped pen that draws lines 2 supersampled pixels wide in PNG,
GIF and other raster output (:mod:`lgraph.backends.png`).

Pillow draws a line ``width=2`` as one polygon a segment with its corners
rounded to whole pixels, and its weight then depends on the direction: 1.17
pixels of ink per unit of length at 10 degrees, 2.24 at 60, which shows as
lines fading with their direction.  The pen's three 1-pixel lines weigh
2-2.24 at every angle and draw in a third of the time.  No derivation of
docs/mathematics.rst: pixel offsets and Bresenham lines.

>>> import numpy as np
>>> pen = Pen(lambda p, small: p, np.array([[0.5, 0.5], [4.2, 2.9]]), True, [(0, 2)])
>>> pen.xy.tolist()  # the points, back moved in x, the segment moved down
[[0.0, 0.0], [4.0, 2.0], [5.0, 2.0], [1.0, 0.0], [0.0, 1.0], [4.0, 3.0]]
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["PEN_2", "Pen"]


#: A stroke 2 supersampled pixels wide is drawn with an L-shaped pen: three
#: 1-pixel lines, through the points pillow truncates to, through them moved
#: one pixel in x, and through them moved one pixel in y, down where the
#: polyline falls (y grows with x, in pixel coordinates) and up where it
#: rises, so that the pen's corner points across the line.  Its weight is
#: 2-2.24 pixels per unit of length at every angle; pillow's own 2-pixel
#: lines (one polygon a segment, corners rounded to whole pixels) vary from
#: 1.17 (at 10 degrees) to 2.24, which shows as lines fading with their
#: direction, and take three times as long.
PEN_2 = ((1, 0), (0, 1), (0, -1))


class Pen:
    """The L-shaped pen's strokes of the polylines ``bounds`` (``(start, stop)``
    of their points in ``px``, supersampled pixels), one polyline each, as
    ``to_pillow(points, small)`` gives them: the truncated points, back through them
    moved one pixel in x, then each segment moved one pixel down where the
    polyline falls (up where it rises).  The joints add no pixel (a step of
    one pixel, a 3-pixel upright through a point already drawn, or nothing),
    so one call draws the three lines of :data:`PEN_2`.  Level, upright and
    empty segments count as falling (either way they are 2 pixels thick)."""

    def __init__(
        self,
        to_pillow: Callable[[np.ndarray, bool], Any],
        px: np.ndarray,
        small: bool,
        bounds: list[tuple[int, int]],
    ) -> None:
        base = np.trunc(px)
        n = max(len(px) - 1, 0)
        d = np.diff(base, axis=0)
        down = np.where(d[:, 0] * d[:, 1] < 0, -1.0, 1.0)  # rising: up
        # each polyline of m points: m forward, m back (moved in x), then the
        # two ends of each of its m - 1 segments (moved in y)
        a0 = np.array([a for a, _ in bounds], dtype=np.int64)
        m = np.array([b - a for a, b in bounds], dtype=np.int64)
        size = 4 * m - 2
        ends = np.cumsum(size)
        run = np.repeat(np.arange(len(bounds)), size)
        q = np.arange(int(ends[-1]) if len(ends) else 0) - np.repeat(ends - size, size)
        mr, ar = m[run], a0[run]
        k = np.maximum(q - 2 * mr, 0)  # in the third part: segment k // 2, its end k % 2
        seg = np.minimum(ar + k // 2, max(n - 1, 0))
        point = np.where(
            q < mr, ar + q, np.where(q < 2 * mr, ar + 2 * mr - 1 - q, ar + k // 2 + k % 2)
        )
        shift = np.zeros((len(q), 2))
        shift[:, 0] = (q >= mr) & (q < 2 * mr)
        shift[:, 1] = np.where(q >= 2 * mr, down[seg] if n else 0.0, 0.0)
        self.xy = to_pillow(base[point] + shift, small)
        self.k = 1 if small else 2  # rows or list items a point
        self.span = dict(zip(a0.tolist(), zip((ends - size).tolist(), ends.tolist())))

    def draw(self, draw: Any, a: int, ink: tuple[int, ...] | int) -> None:
        """The pen's stroke of the polyline starting at point ``a``."""
        s, e = self.span[a]
        draw.line(self.xy[self.k * s : self.k * e], fill=ink, width=1)
