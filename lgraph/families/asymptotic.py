"""Asymptotic lines (``II(du) = 0``, where ``K < 0``): the closed forms of the
surfaces that have them (the rulings of doubly ruled quadrics), numeric
integration (:mod:`lgraph.families.numeric`) otherwise."""

from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

import attrs

from .._validate import count, one_of
from ..curvature import asymptotic_field
from ..curves import CurveBatch
from ..surfaces._base import Surface
from . import Family, register_family
from ._lines import SPACINGS

if TYPE_CHECKING:
    from ..scene.projectors import Projector

__all__ = ["AsymptoticLines"]


# ---------------------------------------------------------------------------
# asymptotic lines
# ---------------------------------------------------------------------------
@attrs.frozen
class AsymptoticLines(Family):
    """``n1`` and ``n2`` asymptotic lines (``II(du) = 0``) of the two families,
    on the part of the surface where the Gauss curvature is negative.

    Surfaces with closed forms supply ``asymptotic_lines(n1, n2)`` (the rulings
    of the hyperboloid of one sheet and the hyperbolic paraboloid); others are
    integrated numerically (:mod:`!lgraph.families.fieldlines`): complete lines by
    default, or trimmed to even spacing with ``spacing="even"``.  Integrated
    lines are budgeted like those of :class:`~lgraph.LinesOfCurvature`: at
    most ``MAX_FIELD_LINES`` (500) per family, ``MAX_EVEN_FIELD_LINES`` (100)
    with ``spacing="even"``.

    >>> AsymptoticLines(-1, 3)
    Traceback (most recent call last):
    ...
    ValueError: AsymptoticLines: n1 must be an integer from 0 to 100000, got -1
    """

    view_dependent: ClassVar[bool] = False

    n1: int = attrs.field(default=8, validator=count("AsymptoticLines"))
    n2: int = attrs.field(default=8, validator=count("AsymptoticLines"))
    spacing: str = attrs.field(
        default="complete", kw_only=True, validator=one_of("AsymptoticLines", SPACINGS)
    )

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        closed_form = getattr(surface, "asymptotic_lines", None)
        if closed_form is not None:  # e.g. the rulings of doubly ruled quadrics
            return [
                attrs.evolve(b, family="asymptotic", curve_family=None)
                for b in closed_form(self.n1, self.n2)
            ]
        from .numeric import field_line_batches

        return field_line_batches(
            surface, asymptotic_field, self.n1, self.n2, family="asymptotic", spacing=self.spacing
        )


register_family("asymptotic_lines", AsymptoticLines)
