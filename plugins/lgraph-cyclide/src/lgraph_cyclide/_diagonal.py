"""``DiagonalLines``: curves running diagonally through the parameter rectangle.

Curve ``k`` is ``u1 = lo1 + t span1``, ``u2 = lo2 + (k/n + turns t) span2``
for ``0 <= t <= 1``: on a torus-like surface (both parameters periodic) a
closed curve winding ``turns`` times around; on a sphere-like surface (only
``u2`` periodic) a spiral from one end of ``u1`` to the other.

>>> import lgraph as lg
>>> [len(b) for b in DiagonalLines(5).batches(lg.Sphere(1), None)]
[5]
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from lgraph import CurveBatch, Family

__all__ = ["DiagonalLines"]


def _count(_inst: Any, attribute: Any, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 100_000:
        raise ValueError(
            f"DiagonalLines: {attribute.name} must be an integer from 0 to 100000, got {value!r}"
        )


def _turns(_inst: Any, attribute: Any, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value == 0 or abs(value) > 1000:
        raise ValueError(
            f"DiagonalLines: turns must be a non-zero integer from -1000 to 1000, got {value!r}"
        )


@attrs.frozen
class DiagonalLines(Family):
    """``n`` diagonal curves (family ``"diagonal"``) winding ``turns`` times in ``u2``.

    Needs a surface whose ``u2`` is periodic (spheres, ellipsoids, tori, cyclides).
    """

    n: int = attrs.field(default=12, validator=_count)
    turns: int = attrs.field(default=1, validator=_turns)

    def batches(self, surface: Any, projector: Any) -> list[CurveBatch]:
        d = surface.domain
        if not d.periodic[1]:
            raise NotImplementedError(
                f"DiagonalLines: {type(surface).__name__} is not periodic in u2"
            )
        if self.n == 0:
            return []
        (lo1, hi1), (lo2, hi2) = d.u1, d.u2
        span1, span2 = hi1 - lo1, hi2 - lo2
        offsets = np.arange(self.n) / self.n
        turns = self.turns

        def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            u2 = lo2 + np.mod((offsets[idx] + turns * t) * span2, span2)
            return np.column_stack([lo1 + t * span1, u2])

        return [
            CurveBatch.from_uv(
                surface, "diagonal", np.zeros(self.n), np.ones(self.n), uv, closed=d.periodic[0]
            )
        ]
