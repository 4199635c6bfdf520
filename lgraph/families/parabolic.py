"""Parabolic lines: the curves where the Gaussian curvature vanishes.

They separate the elliptic points (``K > 0``) of a surface from its hyperbolic
ones (``K < 0``).  Closed forms where they exist:

* torus ``((R + r cos u2) cos u1, ..., r sin u2)``:
  ``K = cos u2 / (r (R + r cos u2))``, so ``K = 0`` on its top and bottom
  circles ``u2 = +-pi/2``;
* ring Dupin cyclide (parametrization of :class:`~lgraph.DupinCyclide`): the
  circles ``u2 = +-pi/2`` as well (there ``cos u2 = 0`` and the tangent plane is
  constant along the circle, so one principal curvature vanishes; checked
  against numeric fundamental forms in the tests);
* a surface of revolution: the parallels where ``z' = 0`` or the meridian has
  an inflection (``SurfaceOfRevolution.parabolic_lines``).

Any surface with a ``parabolic_lines()`` method answers itself; otherwise the
level set ``K = 0`` is traced numerically (:func:`lgraph.families.level.level_batches`).

>>> import numpy as np
>>> import lgraph as lg
>>> (b,) = ParabolicLines().batches(lg.Torus(2, 1), None)
>>> _, uv = b.evaluate(np.array([0, 1]), np.array([0.3, 0.3]))
>>> (uv[:, 1] / np.pi).round(12).tolist()
[-0.5, 0.5]
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from .._tolerance import MAX_LEVEL_GRID
from .._validate import count
from . import Family, register_family
from ._lines import parameter_line_batches

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..scene.projectors import Projector
    from ..surfaces._base import Surface

__all__ = ["ParabolicLines"]


def _circles_u2(surface: Surface) -> list[CurveBatch]:
    """The parameter lines ``u2 = -pi/2, pi/2``."""
    return parameter_line_batches(surface, [], [-np.pi / 2, np.pi / 2], "parabolic", "parabolic")


def _closed_form(surface: Surface) -> Any:
    from ..surfaces.classical.quartic import DupinCyclide, Torus

    if isinstance(surface, (Torus, DupinCyclide)):
        return _circles_u2
    return getattr(type(surface), "parabolic_lines", None)


@attrs.frozen
class ParabolicLines(Family):
    """The parabolic lines ``K = 0`` of a surface (family ``"parabolic"``):
    closed form for the torus, the Dupin cyclide and surfaces of revolution,
    numeric (level set of ``K`` on a ``grid x grid`` parameter grid, refined by
    Newton's method) otherwise; ``grid`` from 9 to ``MAX_LEVEL_GRID`` (1025).

    >>> ParabolicLines(grid=4097)
    Traceback (most recent call last):
    ...
    ValueError: ParabolicLines: grid must be an integer from 9 to 1025, got 4097
    """

    view_dependent: ClassVar[bool] = False  # cached per surface (lgraph.families.cache)

    grid: int = attrs.field(default=193, validator=count("ParabolicLines", 9, MAX_LEVEL_GRID))

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        exact = _closed_form(surface)
        if exact is not None:
            return exact(surface)
        from .level import gaussian_curvature, level_batches

        def k(u1: Any, u2: Any) -> np.ndarray:
            with np.errstate(all="ignore"):
                return gaussian_curvature(surface, u1, u2)

        d = surface.domain
        u1, u2 = np.meshgrid(np.linspace(*d.u1, 33), np.linspace(*d.u2, 33), indexing="ij")
        kk = k(u1, u2)
        spread = float(np.nanmax(np.abs(kk))) if np.isfinite(kk).any() else 1.0
        return level_batches(surface, k, [0.0], spread, self.grid, "parabolic")


register_family("parabolic_lines", ParabolicLines, replace=True)
