"""Numpy maps built from formulas: the functions behind surfaces, curves,
profiles and level functions written as text (:mod:`lgraph.formula`).

A :class:`FormulaMap` evaluates a few formulas of the same variables (and,
with ``order``, their exact partial derivatives) in one shared program, and
pickles as its texts, so that scenes built from formulas go to worker
processes (animations, the gallery) like any other.  It is what
``ParametricSurface.from_formulas``, ``Curve.from_formulas``,
``Profile.from_formulas`` and the level functions of scene files
(:func:`formula_function`) are made of.

>>> import numpy as np
>>> f = FormulaMap(("cos(t)", "sin(t)", "t / 2"), ("t",))
>>> f(np.array([0.0, np.pi / 2])).round(12).tolist()
[[1.0, 0.0, 0.0], [0.0, 1.0, 0.785398163397]]
>>> FormulaMap(("cos(t)", "sin(t)", "t / 2"), ("t",), order=1)(np.array([0.0])).tolist()
[[-0.0, 1.0, 0.5]]
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import attrs
import numpy as np

from . import Formula, compile_formulas, formula

__all__ = [
    "FormulaMap",
    "constant_range",
    "constants_dict",
    "map_orders",
    "constant_value",
    "formula_function",
]


def _texts(value: Any) -> tuple[str, ...]:
    texts = tuple(value)
    if not texts or not all(isinstance(t, str) for t in texts):
        raise TypeError(f"FormulaMap: texts must be formula strings, got {value!r}")
    return texts


def constants_dict(value: Any) -> dict[str, float]:
    """Named constants as a dict of floats."""
    return {str(k): float(v) for k, v in dict(value or {}).items()}


@attrs.frozen(eq=False)
class FormulaMap:
    """The formulas ``texts`` of ``variables`` as one vectorized map.

    Parameters
    ----------
    texts : sequence of str
        One formula per output component (``x, y, z`` of a surface).
    variables : sequence of str
        Their variables, in the order the map takes its arguments.
    constants : mapping, optional
        Named constants the formulas may use (besides ``pi`` and ``e``).
    order : 0, 1 or 2
        0: the values; 1: the first partial derivatives (one result per
        variable); 2: the second ones (``(0, 0), (0, 1), (1, 1)`` for two
        variables), all exact (differentiated symbolically).
    stack : bool
        Stack the components of each result along a last axis (a point);
        otherwise a tuple of arrays (a profile's ``(rho, z)``).
    packed : bool
        The variables come as the last axis of one array (``xyz (..., 3)``).

    One result is returned as it is; several (the partial derivatives of a
    surface) as a tuple.
    """

    texts: tuple[str, ...] = attrs.field(converter=_texts)
    variables: tuple[str, ...] = attrs.field(converter=tuple)
    constants: Mapping[str, float] = attrs.field(factory=dict, converter=constants_dict)
    order: int = attrs.field(default=0, kw_only=True)
    stack: bool = attrs.field(default=True, kw_only=True)
    packed: bool = attrs.field(default=False, kw_only=True)
    _program: Any = attrs.field(init=False, repr=False, default=None)

    @order.validator
    def _check_order(self, _a: Any, v: Any) -> None:
        if v not in (0, 1, 2):
            raise ValueError(f"FormulaMap: order must be 0, 1 or 2, got {v!r}")

    def __attrs_post_init__(self) -> None:
        parsed = [formula(t, self.variables, self.constants) for t in self.texts]
        object.__setattr__(self, "_program", compile_formulas(parsed, derivatives=self.order))

    def __reduce__(self) -> Any:  # rebuilt from the texts in another process
        return (
            _rebuild,
            (self.texts, self.variables, dict(self.constants), self.order, self.stack, self.packed),
        )

    def __call__(self, *args: Any) -> Any:
        if self.packed:
            (xyz,) = args
            xyz = np.asarray(xyz, dtype=float)
            args = tuple(xyz[..., k] for k in range(xyz.shape[-1]))
        out = self._program(*args)
        m, nv = len(self.texts), len(self.variables)
        if self.order == 0:
            start, groups = 0, 1
        elif self.order == 1:
            start, groups = m, nv
        else:
            start, groups = m + m * nv, nv * (nv + 1) // 2
        results = [out[start + g * m : start + (g + 1) * m] for g in range(groups)]
        shaped = [_shape(r, self.stack) for r in results]
        return shaped[0] if groups == 1 else tuple(shaped)


def _shape(parts: list[np.ndarray], stack: bool) -> Any:
    if stack:
        return np.stack(np.broadcast_arrays(*parts), axis=-1) if len(parts) > 1 else parts[0]
    return tuple(parts) if len(parts) > 1 else parts[0]


def _rebuild(
    texts: tuple[str, ...],
    variables: tuple[str, ...],
    constants: dict[str, float],
    order: int,
    stack: bool,
    packed: bool,
) -> FormulaMap:
    return FormulaMap(texts, variables, constants, order=order, stack=stack, packed=packed)


def map_orders(
    texts: tuple[str, ...], variables: tuple[str, ...], constants: Any, stack: bool = True
) -> tuple[FormulaMap, FormulaMap, FormulaMap]:
    """The values, first and second derivatives of ``texts`` as three maps:
    what a surface, curve or profile of formulas is made of."""
    c = constants_dict(constants)
    return tuple(  # type: ignore[return-value]
        FormulaMap(texts, variables, c, order=k, stack=stack) for k in (0, 1, 2)
    )


def constant_value(
    value: Any, constants: Mapping[str, float] | None = None, what: str = ""
) -> float:
    """A number, or a formula of constants only (``"2*pi"``) evaluated.

    >>> round(constant_value("2*pi"), 12), constant_value(3)
    (6.28318530718, 3.0)
    """
    if isinstance(value, str):
        f: Formula = formula(value, (), constants)
        return float(f.value())
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise TypeError(f"{what or 'value'} must be a number or a formula, got {value!r}")
    return float(value)


def constant_range(
    value: Any, constants: Mapping[str, float] | None, what: str
) -> tuple[float, float]:
    """A pair ``(lo, hi)`` of numbers or formulas of ``constants``, evaluated."""
    try:
        lo, hi = value
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a pair (lo, hi), got {value!r}") from None
    return constant_value(lo, constants, what), constant_value(hi, constants, what)


def formula_function(
    text: str, argument: str = "xyz", *, constants: Mapping[str, float] | None = None
) -> FormulaMap:
    """A scalar function for :class:`~lgraph.LevelLines`: of the point
    (``argument="xyz"``: variables ``x, y, z``, called with ``xyz (..., 3)``)
    or of the parameters (``"uv"``: ``u, v``).

    >>> formula_function("x^2 - y^2")(np.array([[2.0, 1.0, 5.0]])).tolist()
    [3.0]
    """
    if argument == "xyz":
        return FormulaMap((text,), ("x", "y", "z"), constants_dict(constants), packed=True)
    if argument == "uv":
        return FormulaMap((text,), ("u", "v"), constants_dict(constants))
    raise ValueError(f"formula_function: argument must be 'xyz' or 'uv', got {argument!r}")
