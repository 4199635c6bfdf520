"""Singularities: a mark family dotting the singular points of a surface.

A family of this kind draws no curves (:meth:`Singularities.batches` is
empty); it gives point marks instead (:meth:`Singularities.marks`), which
the scene places and hides like every :class:`~lgraph.Point` (the node's
transform moves them).  The points come from the surface's
``singular_points()``: for an :class:`~lgraph.AlgebraicSurface`, its nodes
found with certainty (:mod:`!lgraph.surfaces.implicit._singular`).

>>> import lgraph as lg
>>> len(Singularities().marks(lg.CayleyCubic()))
4
>>> Singularities(size=0)
Traceback (most recent call last):
...
ValueError: Singularities: size must be a positive finite number, got 0
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import attrs

from .._validate import finite_positive
from . import Family, register_family

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..scene.projectors import Projector
    from ..surfaces._base import Surface

__all__ = ["Singularities"]


@attrs.frozen
class Singularities(Family):
    """Dots (``size`` pt, ``style``'s colour) at the singular points of the
    surface (family ``"point"`` of the drawing); surfaces that know none
    mark nothing."""

    view_dependent: ClassVar[bool] = False

    size: float = attrs.field(default=4.0, validator=finite_positive("Singularities"))
    style: Any = attrs.field(default=None, kw_only=True)

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        return []

    def marks(self, surface: Any) -> list[Any]:
        """The point marks, in the surface's local coordinates."""
        from ..scene.objects.marks import Point

        find = getattr(surface, "singular_points", None)
        if find is None:
            return []
        return [Point(p, size=self.size, style=self.style) for p in find()]


register_family("singularities", Singularities, replace=True)
