"""attrs validators and converters with messages that name the bad parameter.

Every message reads ``"<Owner>: <name> must be <what is allowed>, got <value>"``.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from typing import Any

import numpy as np

from ._tolerance import MAX_CURVES

Validator = Callable[[Any, Any, Any], None]


def _is_real(value: Any) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def finite_positive(owner: str) -> Validator:
    """Validator: a positive finite real number."""

    def check(_inst: Any, attribute: Any, value: Any) -> None:
        if not (_is_real(value) and math.isfinite(value) and value > 0):
            raise ValueError(
                f"{owner}: {attribute.name} must be a positive finite number, got {value!r}"
            )

    return check


def at_most(owner: str, limit: float, why: str) -> Validator:
    """Validator: a number no larger than ``limit`` (``why`` says what breaks beyond)."""

    def check(_inst: Any, attribute: Any, value: Any) -> None:
        if _is_real(value) and value > limit:
            raise ValueError(
                f"{owner}: {attribute.name} must be at most {limit:g} ({why}), got {value!r}"
            )

    return check


def nonnegative_finite(owner: str) -> Validator:
    """Validator: a finite real number >= 0."""

    def check(_inst: Any, attribute: Any, value: Any) -> None:
        if not (_is_real(value) and math.isfinite(value) and value >= 0):
            raise ValueError(
                f"{owner}: {attribute.name} must be a finite number >= 0, got {value!r}"
            )

    return check


def finite_real(owner: str) -> Validator:
    """Validator: any finite real number."""

    def check(_inst: Any, attribute: Any, value: Any) -> None:
        if not (_is_real(value) and math.isfinite(value)):
            raise ValueError(f"{owner}: {attribute.name} must be a finite number, got {value!r}")

    return check


def count(owner: str, minimum: int = 0, maximum: int = MAX_CURVES) -> Validator:
    """Validator: an integer in ``[minimum, maximum]`` (guards against absurd counts)."""

    def check(_inst: Any, attribute: Any, value: Any) -> None:
        if not (
            isinstance(value, numbers.Integral)
            and not isinstance(value, bool)
            and minimum <= value <= maximum
        ):
            raise ValueError(
                f"{owner}: {attribute.name} must be an integer from {minimum} to {maximum}, "
                f"got {value!r}"
            )

    return check


def positive_finite(owner: str, name: str, value: Any) -> float:
    """``value`` (a numpy scalar too) as a float, if a positive finite real
    number; else ValueError naming ``owner`` and ``name``.

    >>> positive_finite("render_views", "chord", 0)
    Traceback (most recent call last):
    ...
    ValueError: render_views: chord must be a positive finite number, got 0
    """
    value = as_number(value)
    if not (_is_real(value) and math.isfinite(value) and value > 0):
        raise ValueError(f"{owner}: {name} must be a positive finite number, got {value!r}")
    return float(value)


def as_number(value: Any) -> Any:
    """Converter: numpy scalars to Python floats; leaves anything else for the validator."""
    if isinstance(value, np.generic) and np.issubdtype(type(value), np.number):
        return value.item()
    return value


def vector3(owner: str, name: str, value: Any, *, nonzero: bool = False) -> np.ndarray:
    """Check and convert a 3-vector of finite reals."""
    try:
        v = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{owner}: {name} must be 3 finite numbers, got {value!r}") from None
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{owner}: {name} must be 3 finite numbers, got {value!r}")
    if nonzero and not np.any(v):
        raise ValueError(f"{owner}: {name} must be a non-zero vector, got {value!r}")
    v.setflags(write=False)
    return v


def interval(owner: str, name: str, value: Any) -> tuple[float, float]:
    """Check and convert an interval ``(lo, hi)`` of finite reals with lo < hi."""
    try:
        lo, hi = (float(as_number(x)) for x in value)
    except (TypeError, ValueError):
        raise ValueError(
            f"{owner}: {name} must be a pair (lo, hi) of finite numbers, got {value!r}"
        ) from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(
            f"{owner}: {name} must be a pair (lo, hi) of finite numbers with lo < hi, got {value!r}"
        )
    return lo, hi


def one_of(owner: str, allowed: tuple[str, ...]) -> Validator:
    """Validator: one of the strings ``allowed``."""

    def check(_inst: Any, attribute: Any, value: Any) -> None:
        if not (isinstance(value, str) and value in allowed):
            choices = ", ".join(repr(a) for a in allowed)
            raise ValueError(f"{owner}: {attribute.name} must be one of {choices}, got {value!r}")

    return check
