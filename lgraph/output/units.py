"""Physical lengths: ``"8.5cm"``, ``"200mm"``, ``"3in"``, ``"72pt"`` or a number of points.

Every backend and the scene files read figure sizes through :func:`length_pt`, so the
units accepted and the error messages are the same everywhere. Line widths and label
sizes are always in points and are never scaled with the figure.

>>> length_pt("8.5cm")
240.94488188976376
>>> length_pt("1in"), length_pt(12)
(72.0, 12.0)
>>> to_unit(72.0, "mm")
25.4
"""

from __future__ import annotations

import math
import numbers
import re
from typing import Any

#: Points per unit (1 pt = 1/72 in, the PostScript point used by PDF and TikZ's ``bp``).
UNITS: dict[str, float] = {
    "pt": 1.0,
    "in": 72.0,
    "cm": 72.0 / 2.54,
    "mm": 72.0 / 25.4,
}

_LENGTH = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z]*)\s*$")


def length_pt(value: Any, name: str = "width", *, zero: bool = False) -> float:
    """A positive finite length in points (``zero=True``: or 0, for margins).

    ``value`` is a number (points) or a string ``"<number><unit>"`` with a unit of
    :data:`UNITS` (``pt``, ``mm``, ``cm``, ``in``); spaces are allowed.

    Raises ``ValueError`` naming ``name`` for anything else.

    >>> length_pt("0mm", "margin", zero=True)
    0.0

    >>> length_pt(" 25.4 mm ")
    72.0
    >>> length_pt("8.5 parsecs")
    Traceback (most recent call last):
    ...
    ValueError: width must be a positive length such as '8.5cm' (units pt, ...), got '8.5 parsecs'
    """
    allowed = ", ".join(UNITS)
    kind = "non-negative" if zero else "positive"
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        points = float(value)
    elif isinstance(value, str) and (m := _LENGTH.match(value)):
        unit = m.group(2).lower() or "pt"
        if unit not in UNITS:
            raise ValueError(
                f"{name} must be a {kind} length such as '8.5cm' (units {allowed}), got {value!r}"
            )
        points = float(m.group(1)) * UNITS[unit]
    else:
        raise ValueError(
            f"{name} must be a {kind} length such as '8.5cm' (units {allowed}), got {value!r}"
        )
    if not (math.isfinite(points) and (points > 0 or (zero and points == 0))):
        raise ValueError(
            f"{name} must be a {kind} length such as '8.5cm' (units {allowed}), got {value!r}"
        )
    return points


def to_unit(points: float, unit: str) -> float:
    """Convert a length in points to ``unit`` (one of :data:`UNITS`).

    >>> round(to_unit(length_pt("8.5cm"), "cm"), 12)
    8.5
    """
    if unit not in UNITS:
        raise ValueError(f"unit must be one of {', '.join(UNITS)}, got {unit!r}")
    return points / UNITS[unit]
