"""Budgets: the size of an expensive operation, estimated and refused before the work.

Every operation whose cost grows with an input (geodesic length, the step and
grid of intersection curves, animation frame counts, ...) calls one of these
checks at its entry point; each raises a ValueError that names the parameter,
its value and the limit.  The limits themselves live in
:mod:`lgraph._tolerance`; the docs page "Limits" lists them all.

>>> check_frames("animate", 36)
36
>>> check_frames("animate", 10**6)
Traceback (most recent call last):
...
ValueError: animate: frames must be an integer from 1 to 100000, got 1000000
"""

from __future__ import annotations

import itertools
import math
import numbers
from collections.abc import Sized
from typing import Any

from . import _tolerance as tol

__all__ = [
    "check_field_lines",
    "check_frames",
    "check_geodesic",
    "check_intersection",
    "check_levels",
    "check_parameters",
    "check_surface",
    "frame_list",
]


def _real(owner: str, name: str, value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{owner}: {name} must be {what}, got {type(value).__name__}")
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{owner}: {name} must be {what}, got {value!r}")
    return v


def _int(owner: str, name: str, value: Any, lo: int, hi: int) -> int:
    if not isinstance(value, numbers.Integral) or isinstance(value, bool) or not lo <= value <= hi:
        raise ValueError(f"{owner}: {name} must be an integer from {lo} to {hi}, got {value!r}")
    return int(value)


def check_surface(owner: str, name: str, value: Any) -> Any:
    """``value`` must be a :class:`~lgraph.surfaces._base.Surface` (TypeError otherwise)."""
    # duck-typed (point and domain): importing Surface would make the surfaces,
    # which use these budgets, and this module import each other
    if not (callable(getattr(value, "point", None)) and hasattr(type(value), "domain")):
        raise TypeError(f"{owner}: {name} must be a Surface, got {type(value).__name__}")
    return value


def check_parameters(owner: str, surface: Any, u1: Any, u2: Any) -> None:
    """``surface`` a Surface and ``u1, u2`` finite numbers or arrays of them."""
    import numpy as np

    check_surface(owner, "surface", surface)
    for name, value in (("u1", u1), ("u2", u2)):
        try:
            a = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(
                f"{owner}: {name} must be a finite number or an array of them, got {value!r}"
            ) from None
        if not np.all(np.isfinite(a)):
            raise ValueError(
                f"{owner}: {name} must be a finite number or an array of them, got {value!r}"
            )


def check_frames(owner: str, frames: Any) -> int:
    """A frame count of an animation or orbit: an integer in 1..``MAX_FRAMES``."""
    return _int(owner, "frames", frames, 1, tol.MAX_FRAMES)


def frame_list(owner: str, views: Any) -> list[Any]:
    """The views of an animation as a list of at most ``MAX_FRAMES``.

    The length of a sized collection (a list, ``lg.orbit(...)``) is checked
    before anything is read; any other iterable (a generator,
    ``itertools.repeat``) is read lazily and refused as soon as it yields one
    view more than ``MAX_FRAMES``, so an endless generator costs no more than
    the limit.  An empty ``views`` gives ``[]`` (the caller says what it
    wants instead); something not iterable raises TypeError.

    Parameters
    ----------
    owner : str
        Who asks (the start of the error message).
    views : iterable
        The views, one per frame.

    Returns
    -------
    list
        The views read.

    >>> frame_list("animate", iter(range(3)))
    [0, 1, 2]
    >>> frame_list("animate", itertools.count())
    Traceback (most recent call last):
    ...
    ValueError: animate: frames must be an integer from 1 to 100000, got more than 100000 views
    """
    limit = tol.MAX_FRAMES
    more = f"{owner}: frames must be an integer from 1 to {limit}, got more than {limit} views"
    if isinstance(views, Sized):
        try:
            n = len(views)
        except OverflowError:  # a length beyond sys.maxsize (range(10**20))
            raise ValueError(more) from None
        if n:
            check_frames(owner, n)
    out = list(itertools.islice(iter(views), limit + 1))
    if len(out) > limit:
        raise ValueError(more)
    return out


def check_levels(owner: str, levels: int, grid: Any, *, name: str = "values",
                 min_grid: int = 2) -> int:  # fmt: skip
    """The budget of level lines traced by marching squares.

    ``levels`` (named ``name`` in the message) at most ``MAX_LEVELS``,
    ``grid`` an integer in ``min_grid..MAX_LEVEL_GRID`` (the memory: about
    250 bytes a node), and ``levels * (grid - 1)**2`` (the cells marched, the
    time) at most ``MAX_LEVEL_CELLS``.  Returns the grid as an int.

    >>> check_levels("LevelLines", 1000, 193)
    193
    >>> check_levels("LevelLines", 1000, 1025)
    Traceback (most recent call last):
    ...
    ValueError: LevelLines: grid must be at most 201 with 1000 levels (levels x (grid - 1)^2 \
at most 40000000 cells), got 1025
    """
    if levels > tol.MAX_LEVELS:
        raise ValueError(
            f"{owner}: {name} must be at most {tol.MAX_LEVELS} levels, got {levels} levels"
        )
    g = _int(owner, "grid", grid, min_grid, tol.MAX_LEVEL_GRID)
    if levels * (g - 1) ** 2 > tol.MAX_LEVEL_CELLS:
        largest = math.isqrt(tol.MAX_LEVEL_CELLS // max(levels, 1)) + 1
        raise ValueError(
            f"{owner}: grid must be at most {largest} with {levels} levels (levels x "
            f"(grid - 1)^2 at most {tol.MAX_LEVEL_CELLS} cells), got {g}"
        )
    return g


def check_field_lines(owner: str, n1: int, n2: int, spacing: str = "complete") -> None:
    """The budget of numerically integrated field lines (lines of curvature or
    asymptotic lines of a surface without closed forms): ``n1`` and ``n2`` at
    most ``MAX_FIELD_LINES``, or ``MAX_EVEN_FIELD_LINES`` with
    ``spacing="even"``.

    >>> check_field_lines("LinesOfCurvature", 14, 14)
    >>> check_field_lines("LinesOfCurvature", 14, 200, "even")
    Traceback (most recent call last):
    ...
    ValueError: LinesOfCurvature: n2 must be an integer from 0 to 100 for lines integrated \
numerically with spacing='even', got 200
    """
    limit = tol.MAX_EVEN_FIELD_LINES if spacing == "even" else tol.MAX_FIELD_LINES
    for name, n in (("n1", n1), ("n2", n2)):
        if n > limit:
            raise ValueError(
                f"{owner}: {name} must be an integer from 0 to {limit} for lines integrated "
                f"numerically with spacing={spacing!r}, got {n}"
            )


def check_geodesic(owner: str, surface: Any, uv0: Any, direction: Any, length: Any) -> float:
    """Validate a geodesic's arguments; ``length`` is limited to
    ``MAX_GEODESIC_TURNS`` times the surface's size (its bounding-box diagonal).
    Returns the length as a float."""
    check_surface(owner, "surface", surface)
    for name, value in (("uv0", uv0), ("direction", direction)):
        try:
            pair = [float(x) for x in value]
        except (TypeError, ValueError):
            raise ValueError(
                f"{owner}: {name} must be a pair of finite numbers, got {value!r}"
            ) from None
        if len(pair) != 2 or not all(map(math.isfinite, pair)):
            raise ValueError(f"{owner}: {name} must be a pair of finite numbers, got {value!r}")
    if not any(float(x) for x in direction):
        raise ValueError(f"{owner}: direction must be non-zero, got {direction!r}")
    length = _real(owner, "length", length, "a positive finite number")
    if not length > 0:
        raise ValueError(f"{owner}: length must be a positive finite number, got {length!r}")
    limit = tol.MAX_GEODESIC_TURNS * surface.size
    if length > limit:
        raise ValueError(
            f"{owner}: length {length:g} exceeds the limit of {tol.MAX_GEODESIC_TURNS} times "
            f"the surface's size ({limit:g})"
        )
    return length


def check_intersection(owner: str, a: Any, b: Any, grid: Any, step: Any) -> None:
    """Validate the arguments of an intersection of surfaces ``a`` and ``b``:
    ``grid`` (seed grid per parameter) in ``8..MAX_INTERSECTION_GRID``, ``step``
    (marching step, None for the default) positive and at least
    ``size / MAX_MARCH_STEPS`` times 20 (one curve at most ``MAX_MARCH_STEPS``
    steps)."""
    check_surface(owner, "surface", a)
    check_surface(owner, "other", b)
    try:
        same = a is b or bool(a == b)
    except Exception:  # noqa: BLE001 - an __eq__ comparing arrays: not provably equal
        same = False
    if same:
        raise ValueError(
            f"{owner}: the two surfaces are the same ({a!r}); they meet along an area, not a curve"
        )
    _int(owner, "grid", grid, 8, tol.MAX_INTERSECTION_GRID)
    if step is None:
        return
    h = _real(owner, "step", step, "a positive finite number or None")
    if not h > 0:
        raise ValueError(f"{owner}: step must be a positive finite number or None, got {step!r}")
    smallest = 20 * max(a.size, b.size) / tol.MAX_MARCH_STEPS
    if h < smallest:
        raise ValueError(
            f"{owner}: step {h:g} needs more than {tol.MAX_MARCH_STEPS} marching steps per "
            f"curve; the smallest step for these surfaces is {smallest:g}"
        )
