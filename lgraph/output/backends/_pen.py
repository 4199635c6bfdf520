"""The L-shaped pen that draws lines 2 supersampled pixels wide in PNG,
GIF and other raster output (:mod:`lgraph.output.backends.png`).

Pillow draws a line ``width=2`` as one polygon a segment with its corners
rounded to whole pixels, and its weight then depends on the direction: 1.17
pixels of ink per unit of length at 10 degrees, 2.24 at 60, which shows as
lines fading with their direction.  The pen's three 1-pixel lines weigh
2-2.24 at every angle and draw in about two thirds of the time.  No
derivation of docs/mathematics.rst: pixel offsets and Bresenham lines.

>>> import numpy as np
>>> pen = Pen(lambda p, small: p, np.array([[0.5, 0.5], [4.2, 2.9]]), True)
>>> [line.tolist() for line in pen.lines]  # the points, back moved in x, the segment moved down
[[[0.0, 0.0], [4.0, 2.0]], [[5.0, 2.0], [1.0, 0.0]], [[0.0, 1.0], [4.0, 3.0]]]
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["Pen"]


class Pen:
    """The L-shaped pen's three lines through the points ``px`` (supersampled
    pixels), each for all points at once, as ``to_pillow(points, small)``
    gives them: the truncated points; the same moved one pixel in x, in
    reverse order; and the two ends of every segment moved one pixel down
    where it falls, up where it rises (level, upright and empty segments count
    as falling: either way they are 2 pixels thick).  The ends of a
    polyline's segments make one polyline: a joint adds no pixel (nothing, or
    a 3-pixel upright through a point the first line draws)."""

    def __init__(
        self, to_pillow: Callable[[np.ndarray, bool], Any], px: np.ndarray, small: bool
    ) -> None:
        base = np.trunc(px)
        self.n = len(base)
        ends = np.empty((max(self.n - 1, 0), 2, 2))
        ends[:, 0], ends[:, 1] = base[:-1], base[1:]
        d = ends[:, 1] - ends[:, 0]
        ends[:, :, 1] += np.where(d[:, 0] * d[:, 1] < 0, -1.0, 1.0)[:, None]  # rising: up
        moved = (base + (1.0, 0.0))[::-1]
        self.lines = [to_pillow(a, small) for a in (base, moved, ends.reshape(-1, 2))]
        self.k = 1 if small else 2  # rows or list items a point

    def draw(self, draw: Any, a: int, b: int, ink: tuple[int, ...] | int) -> None:
        """The three lines of the polyline through points ``a .. b - 1``, with
        ``draw`` (a ``PIL.ImageDraw.ImageDraw``).

        They go straight to pillow's core drawing object (what
        ``ImageDraw.line`` calls for a 1-pixel line), with the ink looked up
        once: a frame draws hundreds of these short lines."""
        k, n = self.k, self.n
        core = draw.draw
        ink = core.draw_ink(ink)
        for xy, (s, e) in zip(self.lines, ((a, b), (n - b, n - a), (2 * a, 2 * b - 2))):
            core.draw_lines(xy[k * s : k * e], ink, 1)
