"""Level lines: the curves on a surface where a scalar function takes given values.

:class:`LevelLines` draws the sections of a surface by planes perpendicular to
a direction (heights), or the level sets of any function of the point or of
the parameters (for example the Gaussian curvature).  They are traced in the
parameter plane: marching squares on a parameter grid, every crossing refined
on its grid edge to machine precision, joined into curves (closed where they
close, also across periodic seams) and projected back onto ``f = value`` by
Newton's method wherever the renderer evaluates them
(:func:`lgraph.surfaces.parametric._zero_set.zero_set`).  Where the class knows the
section exactly it is used instead: plane sections of quadrics are conics
(:func:`lgraph.surfaces.quadrics._conic.plane_section`), and a surface offering
``level_lines(direction, values)`` (a surface of revolution cut across its
axis: parallels) answers itself.

>>> import lgraph as lg
>>> (b,) = LevelLines(values=[0.5]).batches(lg.Torus(2, 1), None)
>>> len(b), bool(b.closed.all())
(2, True)
>>> LevelLines(values=[])
Traceback (most recent call last):
...
ValueError: LevelLines: values must be a non-empty list of finite numbers, got []
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from .._budget import check_levels
from .._tolerance import LEVEL_CHUNK_NODES, MAX_LEVEL_GRID, MAX_LEVELS
from .._validate import count, vector3
from . import Family, register_family

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..scene.projectors import Projector
    from ..surfaces._base import Surface

__all__ = ["LevelLines", "NAMED_FUNCTIONS", "surface_function", "level_batches"]

#: Newton steps projecting a level-line point onto ``f = value``
NEWTON_STEPS = 8
#: ... until ``|f - value|`` is below this, relative to the spread of ``f``
LEVEL_FTOL = 1e-14
#: samples per parameter for the extent of ``f`` and the NaN check
EXTENT_GRID = 97


def gaussian_curvature(surface: Surface, u1: Any, u2: Any) -> np.ndarray:
    """``K = k1 k2``."""
    k1, k2 = surface.principal_curvatures(u1, u2)
    return k1 * k2


def mean_curvature(surface: Surface, u1: Any, u2: Any) -> np.ndarray:
    """``H = (k1 + k2) / 2`` (sign follows the surface normal)."""
    k1, k2 = surface.principal_curvatures(u1, u2)
    return 0.5 * (k1 + k2)


#: Functions of a surface known by name (scene files name them).
NAMED_FUNCTIONS: dict[str, Callable[..., np.ndarray]] = {
    "gaussian_curvature": gaussian_curvature,
    "mean_curvature": mean_curvature,
}


def _values(value: Any) -> tuple[float, ...] | None:
    if value is None:
        return None
    try:
        v = np.array(value, dtype=float).ravel()
    except (TypeError, ValueError):
        v = np.empty(0)
    if not len(v) or not np.all(np.isfinite(v)):
        raise ValueError(
            f"LevelLines: values must be a non-empty list of finite numbers, got {value!r}"
        )
    if len(v) > MAX_LEVELS:
        raise ValueError(
            f"LevelLines: values must be a list of at most {MAX_LEVELS} numbers, "
            f"got {len(v)} numbers"
        )
    return tuple(float(x) for x in v)


def _function(value: Any) -> Any:
    if value is None or callable(value):
        return value
    if isinstance(value, str) and value in NAMED_FUNCTIONS:
        return value
    allowed = ", ".join(repr(k) for k in NAMED_FUNCTIONS)
    raise ValueError(f"LevelLines: function must be callable or one of {allowed}, got {value!r}")


def surface_function(
    surface: Surface,
    function: Any = None,
    direction: Any = (0.0, 0.0, 1.0),
    argument: str = "point",
) -> Callable[[Any, Any], np.ndarray]:
    """``f(u1, u2)`` of a level-line family: the height along ``direction``
    (``function=None``), a named function of the surface, a function of the
    point (``argument="point"``) or of the parameters (``argument="uv"``)."""
    if function is None:
        d = np.asarray(direction, float)
        d = d / np.linalg.norm(d)
        return lambda u1, u2: surface.point(u1, u2) @ d
    if isinstance(function, str):
        named = NAMED_FUNCTIONS[function]
        return lambda u1, u2: named(surface, u1, u2)
    if argument == "uv":
        return lambda u1, u2: np.asarray(function(*np.broadcast_arrays(u1, u2)), float)
    return lambda u1, u2: np.asarray(function(surface.point(u1, u2)), float)


@attrs.frozen
class LevelLines(Family):
    """Level lines of the height along ``direction`` or of ``function``
    (family ``"level"``).

    Parameters
    ----------
    n : int
        Number of levels evenly spread over the range the function takes on
        the drawn patch (``n`` values splitting it into ``n + 1`` equal parts);
        ignored when ``values`` is given.  At most ``MAX_LEVELS`` (1000).
    direction : 3 numbers
        The planes are perpendicular to it (height ``x . direction / |direction|``).
    values : list of float, optional
        Explicit levels (at most ``MAX_LEVELS``).
    function : callable or str, optional
        A scalar function instead of the height: of the point
        (``function(xyz (..., 3)) -> (...)``, the default) or, with
        ``argument="uv"``, of the parameters (``function(u1, u2)``); or a name
        of ``NAMED_FUNCTIONS`` (``"gaussian_curvature"``, ``"mean_curvature"``).
    argument : "point" or "uv"
        What ``function`` takes.
    grid : int
        Parameter grid nodes per direction for tracing (finer finds smaller
        loops): 9 to ``MAX_LEVEL_GRID`` (1025), and the levels times
        ``(grid - 1)**2`` at most ``MAX_LEVEL_CELLS`` (4e7; docs page "Limits").

    >>> LevelLines(3, direction=(0, 0, 0))
    Traceback (most recent call last):
    ...
    ValueError: LevelLines: direction must be a non-zero vector, got (0, 0, 0)
    >>> LevelLines(1000, grid=1025)
    Traceback (most recent call last):
    ...
    ValueError: LevelLines: grid must be at most 201 with 1000 levels (levels x (grid - 1)^2
    at most 40000000 cells), got 1025
    """

    view_dependent: ClassVar[bool] = False  # cached per surface (lgraph.families.cache)

    n: int = attrs.field(default=9, validator=count("LevelLines", 0, MAX_LEVELS))
    # compared (and hashed) by value: families that differ only in their
    # direction or function must not share a cache entry
    direction: np.ndarray = attrs.field(
        default=(0.0, 0.0, 1.0),
        converter=lambda v: vector3("LevelLines", "direction", v, nonzero=True),
        eq=lambda v: tuple(v.tolist()),
    )
    values: tuple[float, ...] | None = attrs.field(default=None, converter=_values, kw_only=True)
    function: Callable[..., Any] | str | None = attrs.field(
        default=None, converter=_function, kw_only=True
    )
    argument: str = attrs.field(default="point", kw_only=True)
    grid: int = attrs.field(
        default=193, validator=count("LevelLines", 9, MAX_LEVEL_GRID), kw_only=True
    )

    def __attrs_post_init__(self) -> None:
        # the work, known from the parameters: levels x grid cells (lgraph._budget)
        if self.values is None:
            check_levels("LevelLines", self.n, self.grid, name="n", min_grid=9)
        else:
            check_levels("LevelLines", len(self.values), self.grid, min_grid=9)

    @argument.validator
    def _check_argument(self, _a: Any, v: Any) -> None:
        if v not in ("point", "uv"):
            raise ValueError(f"LevelLines: argument must be 'point' or 'uv', got {v!r}")

    def function_of(self, surface: Surface) -> Callable[[Any, Any], np.ndarray]:
        """The traced function ``f(u1, u2)`` on ``surface``."""
        return surface_function(surface, self.function, self.direction, self.argument)

    def levels(self, surface: Surface) -> tuple[np.ndarray, float]:
        """``(values, spread)``: the levels drawn on ``surface`` and the range of
        ``f`` over the patch.  Raises ValueError where ``f`` is not finite."""
        f = self.function_of(surface)
        d = surface.domain
        inset = [1e-7 * d.span(i) if any(d.poles[i]) else 0.0 for i in (0, 1)]
        a1 = np.linspace(d.u1[0] + inset[0], d.u1[1] - inset[0], EXTENT_GRID)
        a2 = np.linspace(d.u2[0] + inset[1], d.u2[1] - inset[1], EXTENT_GRID)
        U1, U2 = np.meshgrid(a1, a2, indexing="ij")
        with np.errstate(all="ignore"):
            F = np.asarray(f(U1, U2), float)
        if F.shape != U1.shape:
            raise ValueError(
                f"LevelLines: function must return one number per point, got shape {F.shape} "
                f"for {U1.shape} points"
            )
        bad = ~np.isfinite(F)
        if bad.any():
            i, j = np.argwhere(bad)[0]
            raise ValueError(
                f"LevelLines: function must be finite on the surface, got {F[i, j]} at "
                f"(u1, u2) = ({U1[i, j]:.6g}, {U2[i, j]:.6g})"
            )
        lo, hi = float(F.min()), float(F.max())
        spread = max(hi - lo, float(np.abs(F).max()), 1e-300)
        if self.values is not None:
            return np.array(self.values), spread
        return lo + (hi - lo) * np.arange(1, self.n + 1) / (self.n + 1), spread

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        if not getattr(surface, "parametric", True):  # an implicit surface: space curves
            return self._space_sections(surface)
        values, spread = self.levels(surface)
        if self.function is None:
            exact = _exact_sections(surface, self.direction, values)
            if exact is not None:
                return exact
        return level_batches(surface, self.function_of(surface), values, spread, self.grid)

    def _space_sections(self, surface: Any) -> list[CurveBatch]:
        """Plane sections of a surface without parameters (``ImplicitSurface``)."""
        if self.function is not None:
            raise ValueError(
                f"LevelLines: function needs a parametrized surface; {type(surface).__name__} "
                "draws plane sections only (give direction and n or values)"
            )
        d = np.asarray(self.direction, float) / np.linalg.norm(self.direction)
        if self.values is not None:
            values = np.array(self.values)
        else:
            lo, hi = surface.height_range(d)
            values = lo + (hi - lo) * np.arange(1, self.n + 1) / (self.n + 1)
        return surface.level_lines(d, values)  # type: ignore[no-any-return]


def level_batches(
    surface: Surface,
    f: Callable[[Any, Any], np.ndarray],
    values: Any,
    spread: float,
    grid: int = 193,
    family: str = "level",
) -> list[CurveBatch]:
    """Batches (one per value) of the numeric level lines ``f(u1, u2) = value``,
    projected onto the level to ``LEVEL_FTOL * spread`` when evaluated.

    The work is budgeted before it starts (``lgraph._budget.check_levels``:
    ``grid`` at most ``MAX_LEVEL_GRID``, the values times ``(grid - 1)**2`` at
    most ``MAX_LEVEL_CELLS``); ``f`` is evaluated on the grid in chunks of
    rows of at most ``LEVEL_CHUNK_NODES`` nodes (one call on grids up to 256)."""
    from ..surfaces.parametric._contour import project_to_zero, zero_set_batch
    from ..surfaces.parametric._zero_set import grid_parameters, zero_set

    values = np.atleast_1d(np.asarray(values, float)).ravel()
    grid = check_levels("level_batches", len(values), grid)
    on_grid = _on_grid(f, *grid_parameters(surface, grid))  # once for all values
    out = []
    for value in values.tolist():

        def g(u1: Any, u2: Any, value: float = value) -> np.ndarray:
            return f(u1, u2) - value

        curves = zero_set(surface, g, grid, values=on_grid - value)
        if not curves:
            continue

        def adjust(uv: np.ndarray, g: Any = g) -> np.ndarray:
            return project_to_zero(surface, g, uv, NEWTON_STEPS, LEVEL_FTOL * spread)

        out.append(zero_set_batch(surface, curves, adjust, family))
    return out


def _on_grid(f: Callable[[Any, Any], np.ndarray], U1: np.ndarray, U2: np.ndarray) -> np.ndarray:
    """``f(U1, U2)`` on a grid, in chunks of rows of at most ``LEVEL_CHUNK_NODES``
    nodes: the function's working memory (derivatives of a surface at every
    node, say) stays bounded however fine the grid."""
    rows = max(1, LEVEL_CHUNK_NODES // max(U1.shape[1], 1))
    if rows >= U1.shape[0]:
        return np.asarray(f(U1, U2), float)
    return np.concatenate(
        [
            np.asarray(f(U1[i : i + rows], U2[i : i + rows]), float)
            for i in range(0, U1.shape[0], rows)
        ]
    )


def _exact_sections(surface: Surface, direction: np.ndarray, values: np.ndarray) -> Any:
    """Closed-form plane sections where the class has them, else None."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    own = getattr(surface, "level_lines", None)
    if own is not None:
        res = own(d, values)
        if res is not None:
            return res
    from ..surfaces.quadrics.quadric import Quadric

    if isinstance(surface, Quadric):
        from ..surfaces.quadrics._conic import plane_section

        out = []
        for value in values.tolist():
            out += plane_section(surface, d, value, family="level")
        return out
    return None


register_family("level_lines", LevelLines, replace=True)
