"""The 27 lines of the Clebsch diagonal cubic, in closed form.

In the chart of :data:`lgraph.surfaces.implicit.algebraic.CLEBSCH` (docs/algebraic.rst):

* 15 rational lines: the three through the Eckardt point ``(1, 1, 1) / 3``
  in the directions ``e_j - e_i``; the lines ``x_i = -1/3, x_j + x_k = 0``
  and ``x_i = 0, x_j + x_k = 1/3``; the six ``x_k = 0, x_j = 3 x_i - 1/3``;
* 12 lines over ``Q(sqrt 5)``: the six coordinate permutations of the line
  through ``(0, 5 + sqrt 5, 5 + 3 sqrt 5) / 30`` with direction ``(sqrt 5,
  3 + sqrt 5, -1)``, and of the line through ``(0, 3 - sqrt 5, 7 - 3 sqrt 5)
  / 6`` with direction ``(1, sqrt 5, sqrt 5 - 3)``.

>>> L = clebsch_lines()
>>> L.shape
(27, 6)
"""

from __future__ import annotations

import functools
import itertools

import numpy as np

__all__ = ["clebsch_lines"]


@functools.cache
def _lines() -> np.ndarray:
    r5 = np.sqrt(5.0)
    e = np.eye(3)
    lines = []  # (point, direction)
    third = np.full(3, 1 / 3)
    for i, j in ((0, 1), (0, 2), (1, 2)):
        lines.append((third, e[j] - e[i]))
    for i in range(3):
        j, k = (a for a in range(3) if a != i)
        lines.append((-e[i] / 3, e[k] - e[j]))  # x_i = -1/3, x_j + x_k = 0
        lines.append(((e[j] + e[k]) / 6, e[k] - e[j]))  # x_i = 0, x_j + x_k = 1/3
    for i, j in itertools.permutations(range(3), 2):
        lines.append((e[i] / 9, e[i] + 3 * e[j]))  # x_k = 0, x_j = 3 x_i - 1/3
    bases = [
        (np.array([0.0, 5 + r5, 5 + 3 * r5]) / 30, np.array([r5, 3 + r5, -1.0])),
        (np.array([0.0, 3 - r5, 7 - 3 * r5]) / 6, np.array([1.0, r5, r5 - 3])),
    ]
    for p, d in bases:
        for perm in itertools.permutations(range(3)):
            lines.append((p[list(perm)], d[list(perm)]))
    out = []
    for p, d in lines:
        d = d / np.linalg.norm(d)
        out.append(np.concatenate([p - (p @ d) * d, d]))  # the point nearest the origin
    return np.array(out)


def clebsch_lines() -> np.ndarray:
    """Rows ``(p, d)``: each line's point nearest the origin and unit direction."""
    return _lines().copy()
