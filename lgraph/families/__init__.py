"""Line families: what to draw on a surface.

A family turns a surface (and the view, for view-dependent families such as
the contour) into :class:`~lgraph.curves.CurveBatch` objects.

>>> import lgraph as lg
>>> [len(b) for b in lg.ParameterLines(4, 6).batches(lg.Sphere(1), None)]
[10]
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Any, ClassVar

import attrs

from .._own import CONTOUR
from .._validate import count, finite_positive, one_of
from ..curves import CurveBatch
from ._lines import SPACINGS, parameter_line_batches  # noqa: F401 - re-exported for plugins

if TYPE_CHECKING:
    from ..scene.projectors import Projector
    from ..surfaces._base import Surface

__all__ = [
    "Family",
    "ParameterLines",
    "Contour",
    "LinesOfCurvature",
    "Umbilics",
    "register_family",
    "FAMILIES",
]


class Family:
    """Base class of line families.

    Every subclass's ``batches(surface, projector)`` first checks its
    arguments (a surface, and a projector or None), so a family handed
    something else says so in its own name:

    >>> ParameterLines(3, 3).batches("a sphere", None)
    Traceback (most recent call last):
    ...
    TypeError: ParameterLines.batches: surface must be a Surface, got str

    ``view_dependent`` says whether the curves change with the projector; a
    family that sets it False has its curves computed once per surface and
    reused for every view (:mod:`lgraph.families.cache`).  The default, True,
    is the safe one for families that do not say.
    """

    view_dependent: ClassVar[bool] = True

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        impl = cls.__dict__.get("batches")
        if impl is None or getattr(impl, "_checked", False):
            return

        @functools.wraps(impl)
        def batches(self: Family, surface: Any, projector: Any) -> list[CurveBatch]:
            _check_batches_args(type(self).__name__, surface, projector)
            return impl(self, surface, projector)

        batches._checked = True  # type: ignore[attr-defined]
        cls.batches = batches  # type: ignore[method-assign]

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        raise NotImplementedError  # pragma: no cover


def _check_batches_args(owner: str, surface: Any, projector: Any) -> None:
    # duck-typed: importing Surface here would make families and surfaces import each other
    # (the class is asked: an implicit surface's domain raises, it has none)
    if not (callable(getattr(surface, "point", None)) and hasattr(type(surface), "domain")):
        raise TypeError(f"{owner}.batches: surface must be a Surface, got {type(surface).__name__}")
    if projector is not None and not callable(getattr(projector, "project", None)):
        raise TypeError(
            f"{owner}.batches: projector must be a Projector or None, "
            f"got {type(projector).__name__}"
        )


@attrs.frozen
class ParameterLines(Family):
    """``n1`` lines ``u1 = const`` (family ``"u1"``) and ``n2`` lines ``u2 = const``
    (family ``"u2"``), evenly spread over the surface's drawn domain.

    >>> ParameterLines(-1, 2)
    Traceback (most recent call last):
    ...
    ValueError: ParameterLines: n1 must be an integer from 0 to 100000, got -1
    """

    view_dependent: ClassVar[bool] = False

    n1: int = attrs.field(default=10, validator=count("ParameterLines"))
    n2: int = attrs.field(default=10, validator=count("ParameterLines"))

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        return surface.parameter_lines(self.n1, self.n2)


@attrs.frozen
class Contour(Family):
    """The surface's contour for the current view (drawn by default)."""

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        if projector is None:
            return []
        out = []
        for b in surface.contour(projector):
            out.append(attrs.evolve(b, family="contour", own=CONTOUR, curve_family=None))
        return out


@attrs.frozen
class LinesOfCurvature(Family):
    """``n1`` and ``n2`` lines of curvature of the two principal families.

    Each surface class supplies its closed forms through
    ``surface.lines_of_curvature(n1, n2)``; other surfaces integrate the
    principal directions (:mod:`!lgraph.families.fieldlines`).  Numeric lines are
    complete (``spacing="complete"``, the default: each runs to the patch
    boundary, a pole or an umbilic, or closes) or trimmed where they come
    close to another line of their family (``spacing="even"``, evenly spaced
    streamlines).  Closed forms ignore ``spacing``.

    ``n1`` and ``n2`` are at most ``MAX_CURVES``; lines that are integrated
    at most ``MAX_FIELD_LINES`` (500) each, ``MAX_EVEN_FIELD_LINES`` (100)
    with ``spacing="even"``, checked before the work when the surface is
    known (docs page "Limits").

    >>> LinesOfCurvature(3, 3, spacing="dense")
    Traceback (most recent call last):
    ...
    ValueError: LinesOfCurvature: spacing must be one of 'complete', 'even', got 'dense'
    """

    view_dependent: ClassVar[bool] = False

    n1: int = attrs.field(default=10, validator=count("LinesOfCurvature"))
    n2: int = attrs.field(default=10, validator=count("LinesOfCurvature"))
    spacing: str = attrs.field(
        default="complete", kw_only=True, validator=one_of("LinesOfCurvature", SPACINGS)
    )

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        method = getattr(surface, "lines_of_curvature", None)
        if method is None:
            raise NotImplementedError(
                f"LinesOfCurvature: {type(surface).__name__} has no lines_of_curvature(n1, n2)"
            )
        if self.spacing != "complete" and getattr(method, "numeric", False):
            method = functools.partial(method, spacing=self.spacing)
        return [
            attrs.evolve(b, family="curvature", curve_family=None) for b in method(self.n1, self.n2)
        ]


@attrs.frozen
class Umbilics(Family):
    """Small circles marking the surface's umbilic points (family ``"umbilic"``).

    Uses ``surface.umbilic_marks(radius)``; ``radius`` defaults to 1.5 % of the
    patch size.  Surfaces without umbilics draw nothing.
    """

    view_dependent: ClassVar[bool] = False

    radius: float | None = attrs.field(default=None)

    @radius.validator
    def _check_radius(self, attribute: attrs.Attribute, value: float | None) -> None:
        if value is not None:
            finite_positive("Umbilics")(self, attribute, value)

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        marks = getattr(surface, "umbilic_marks", None)
        if marks is None:
            return []
        return [curve.batch(family="umbilic") for curve in marks(self.radius)]


#: Registry of family classes by name (plugins add to it).
FAMILIES: dict[str, Any] = {
    "parameter_lines": ParameterLines,
    "contour": Contour,
    "lines_of_curvature": LinesOfCurvature,
    "umbilics": Umbilics,
}


def register_family(name: str, cls: Any, *, replace: bool = False) -> None:
    """Register a family class under ``name``."""
    if name in FAMILIES and not replace:
        raise ValueError(f"register_family: a family named {name!r} is already registered")
    FAMILIES[name] = cls
