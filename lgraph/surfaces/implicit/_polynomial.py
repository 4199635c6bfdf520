"""Polynomials in x, y, z: coefficients from formulas, values, derivatives, rays.

A polynomial is a dense array ``c[i, j, k]`` (the coefficient of ``x^i y^j
z^k``).  :func:`coefficients` builds it from a formula of the scene-file
language (:mod:`lgraph.formula`, never evaluated as Python) by expanding the
formula's expression graph -- sums, products, quotients by constants,
powers with non-negative integer exponents; anything else is refused -- or
from a mapping ``{(i, j, k): c}``.  Degree at most ``MAX_DEGREE``: checked
before every product, so a hostile formula (``(x + y + z + 1)^1000``) is
refused before it costs anything.

Along a ray ``o + s v`` a polynomial of degree ``d`` is a polynomial of
degree ``d`` in ``s`` (:meth:`Polynomial.along`): ``(o_x + s v_x)^i`` is
expanded by the binomial theorem and the three factors contracted with
``c``.

>>> p = Polynomial.from_source("x^2 + y^2 - z^2 - 1")
>>> p.degree, sorted(p.terms().items())
(2, [((0, 0, 0), -1.0), ((0, 0, 2), -1.0), ((0, 2, 0), 1.0), ((2, 0, 0), 1.0)])
>>> p.along(np.array([[0.0, 0, 0]]), np.array([[1.0, 0, 0]])).tolist()  # s^2 - 1
[[-1.0, 0.0, 1.0]]
>>> Polynomial.from_source("sin(x)")
Traceback (most recent call last):
...
ValueError: AlgebraicSurface: polynomial must be a polynomial in x, y, z (sums, products, \
integer powers, division by numbers), got 'sin' in 'sin(x)'
"""

from __future__ import annotations

from collections.abc import Mapping
from math import comb
from typing import Any

import numpy as np

__all__ = ["Polynomial", "MAX_DEGREE", "MAX_TERMS"]

#: highest total degree of a polynomial
MAX_DEGREE = 12
#: most terms of a coefficient mapping
MAX_TERMS = 455  # all monomials of degree <= 12
#: rays contracted in one call (memory: about (degree + 1)^3 floats a ray)
RAY_CHUNK = 20000


def _degree(c: np.ndarray) -> int:
    nz = np.argwhere(c != 0)
    return int(nz.sum(axis=1).max()) if len(nz) else 0


def _pad(c: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    out = np.zeros(shape)
    out[: c.shape[0], : c.shape[1], : c.shape[2]] = c
    return out


def _add(a: np.ndarray, b: np.ndarray, sign: float = 1.0) -> np.ndarray:
    shape = tuple(max(x, y) for x, y in zip(a.shape, b.shape))
    return _pad(a, shape) + sign * _pad(b, shape)


def _mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    if np.count_nonzero(a) > np.count_nonzero(b):
        a, b = b, a
    out = np.zeros(tuple(x + y - 1 for x, y in zip(a.shape, b.shape)))
    for i, j, k in np.argwhere(a != 0).tolist():  # a few terms; each an array operation
        out[i : i + b.shape[0], j : j + b.shape[1], k : k + b.shape[2]] += a[i, j, k] * b
    return out


class _Expander:
    """Expands a formula's node list into coefficient arrays, checking degrees."""

    def __init__(self, owner: str, name: str, text: str, max_degree: int) -> None:
        self.owner, self.name, self.text, self.max_degree = owner, name, text, max_degree

    def fail(self, what: str) -> ValueError:
        return ValueError(
            f"{self.owner}: {self.name} must be a polynomial in x, y, z (sums, products, "
            f"integer powers, division by numbers), got {what} in {self.text!r}"
        )

    def check(self, degree: int) -> None:
        if degree > self.max_degree:
            raise ValueError(
                f"{self.owner}: {self.name} must have degree at most {self.max_degree}, "
                f"got degree {degree} or more in {self.text!r}"
            )

    def expand(self, nodes: tuple) -> np.ndarray:
        vals: list[np.ndarray] = []
        degs: list[int] = []
        axis = {"x": 0, "y": 1, "z": 2}
        for node in nodes:
            op, args = node[0], node[1:]
            if op == "const":
                c, d = np.full((1, 1, 1), float(args[0])), 0
            elif op == "var":
                c = np.zeros((2, 2, 2))
                c[tuple(1 if i == axis[args[0]] else 0 for i in range(3))] = 1.0
                d = 1
            elif op in ("add", "sub"):
                a, b = args
                c = _add(vals[a], vals[b], 1.0 if op == "add" else -1.0)
                d = max(degs[a], degs[b])
            elif op == "neg":
                c, d = -vals[args[0]], degs[args[0]]
            elif op == "mul":
                a, b = args
                self.check(degs[a] + degs[b])
                c, d = _mul(vals[a], vals[b]), degs[a] + degs[b]
            elif op == "div":
                a, b = args
                den = vals[b]
                if degs[b] != 0 or np.count_nonzero(den) != 1 or den.flat[0] == 0:
                    raise self.fail("a division by a non-constant (or by zero)")
                c, d = vals[a] / den.flat[0], degs[a]
            elif op == "pow":
                a, b = args
                e = vals[b].flat[0] if degs[b] == 0 and vals[b].size == 1 else None
                if e is None or e != int(e) or e < 0:
                    raise self.fail("a power that is not a non-negative integer")
                e = int(e)
                self.check(degs[a] * e)
                c, d = np.ones((1, 1, 1)), 0
                for _ in range(e):  # e <= max_degree unless the base is constant
                    c, d = _mul(c, vals[a]), d + degs[a]
                    if d == 0 and e > self.max_degree:
                        c = np.full((1, 1, 1), float(vals[a].flat[0]) ** e)
                        break
            else:
                raise self.fail(repr(op))
            vals.append(c)
            degs.append(d)
        return vals[-1]


class Polynomial:
    """A polynomial in ``x, y, z`` with its exact first and second derivatives."""

    def __init__(self, c: np.ndarray) -> None:
        c = np.asarray(c, float)
        d = _degree(c)
        self.degree = d
        self.c = _pad(c[: d + 1, : d + 1, : d + 1], (d + 1,) * 3)
        k = np.arange(d + 1, dtype=float)
        self.d1 = [self._diff(self.c, i, k) for i in range(3)]
        self.d2 = [[self._diff(self.d1[i], j, k) for j in range(3)] for i in range(3)]
        self._first = np.stack([self.c, *self.d1])
        self._second = np.stack([self.d2[i][j] for i in range(3) for j in range(i, 3)])

    @staticmethod
    def _diff(c: np.ndarray, axis: int, k: np.ndarray) -> np.ndarray:
        shape = [1, 1, 1]
        shape[axis] = len(k)
        out = np.roll(c * k.reshape(shape), -1, axis=axis)
        idx = [slice(None)] * 3
        idx[axis] = -1
        out[tuple(idx)] = 0.0
        return out

    @classmethod
    def from_source(
        cls, source: Any, owner: str = "AlgebraicSurface", name: str = "polynomial",
        max_degree: int = MAX_DEGREE, constants: Mapping[str, float] | None = None,
    ) -> Polynomial:  # fmt: skip
        """From a formula string or a mapping ``{(i, j, k): c}``."""
        if isinstance(source, str):
            from ...formula import formula

            f = formula(source, ("x", "y", "z"), constants)
            return cls(_Expander(owner, name, source, max_degree).expand(f._nodes))
        if isinstance(source, Mapping):
            return cls(_from_mapping(source, owner, name, max_degree))
        raise TypeError(
            f"{owner}: {name} must be a formula string or a mapping {{(i, j, k): c}}, "
            f"got {type(source).__name__}"
        )

    def terms(self) -> dict[tuple[int, int, int], float]:
        """The non-zero coefficients ``{(i, j, k): c}``."""
        return {(int(i), int(j), int(k)): float(self.c[i, j, k]) for i, j, k in np.argwhere(self.c)}

    def _powers(self, p: np.ndarray) -> list[np.ndarray]:
        """``x^0 .. x^d`` for each coordinate (products, not ``pow``)."""
        out = []
        for i in range(3):
            P = np.empty(p.shape[:-1] + (self.degree + 1,))
            P[..., 0] = 1.0
            for k in range(1, self.degree + 1):
                P[..., k] = P[..., k - 1] * p[..., i]
            out.append(P)
        return out

    def _eval(self, c: np.ndarray, P: list[np.ndarray]) -> np.ndarray:
        """Polynomials ``c`` (``(m, d+1, d+1, d+1)``) at the points of the
        power tables ``P``: ``(..., m)``."""
        t = np.einsum("mijk,...k->...mij", c, P[2])
        t = np.einsum("...mij,...j->...mi", t, P[1])
        return np.einsum("...mi,...i->...m", t, P[0])

    def value(self, p: Any) -> np.ndarray:
        """Values at points ``(..., 3)``."""
        P = self._powers(np.asarray(p, float))
        return self._eval(self.c[None], P)[..., 0]

    def value_gradient(self, p: Any) -> tuple[np.ndarray, np.ndarray]:
        """Values and exact gradients at points ``(..., 3)``, in one pass."""
        P = self._powers(np.asarray(p, float))
        v = self._eval(self._first, P)
        return v[..., 0], v[..., 1:]

    def gradient(self, p: Any) -> np.ndarray:
        """Exact gradients ``(..., 3)``."""
        return self.value_gradient(p)[1]

    def hessian(self, p: Any) -> np.ndarray:
        """Exact Hessians ``(..., 3, 3)``."""
        P = self._powers(np.asarray(p, float))
        v = self._eval(self._second, P)  # xx, xy, xz, yy, yz, zz
        return v[..., [0, 1, 2, 1, 3, 4, 2, 4, 5]].reshape(v.shape[:-1] + (3, 3))

    def along(self, o: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Coefficients ``(n, degree + 1)`` (ascending powers of ``s``) of the
        polynomial along the rays ``o + s v`` (``(n, 3)`` each)."""
        o, v = np.asarray(o, float), np.asarray(v, float)
        n, d = len(o), self.degree
        out = np.empty((n, d + 1))
        e = np.arange(d + 1)
        Ii, A = np.meshgrid(e, e, indexing="ij")  # power i of an axis, power a of s
        C = np.where(A <= Ii, np.array([[comb(i, a) for a in e] for i in e], float), 0.0)
        tri = A <= Ii
        total = np.add.outer(np.add.outer(e, e), e).ravel()
        gather = (total[:, None] == e[None, :]).astype(float)  # a + b + c = p
        for start in range(0, n, RAY_CHUNK):
            sl = slice(start, start + RAY_CHUNK)
            P = []
            for axis in range(3):
                op = o[sl, axis, None] ** e
                vp = v[sl, axis, None] ** e
                P.append(np.where(tri, C * op[:, np.maximum(Ii - A, 0)] * vp[:, A], 0.0))
            t = np.einsum("ijk,nkc->nijc", self.c, P[2])
            t = np.einsum("nijc,njb->nibc", t, P[1])
            t = np.einsum("nibc,nia->nabc", t, P[0])
            out[sl] = t.reshape(len(t), -1) @ gather
        return out


def _from_mapping(source: Mapping, owner: str, name: str, max_degree: int) -> np.ndarray:
    if len(source) > MAX_TERMS:
        raise ValueError(f"{owner}: {name} must have at most {MAX_TERMS} terms, got {len(source)}")
    items = []
    for key, value in source.items():
        ok = isinstance(key, tuple) and len(key) == 3
        ok = ok and all(isinstance(i, (int, np.integer)) and not isinstance(i, bool) for i in key)
        if not ok or min(key) < 0:
            raise ValueError(
                f"{owner}: {name} keys must be exponents (i, j, k) of x, y, z (integers >= 0), "
                f"got {key!r}"
            )
        if sum(key) > max_degree:
            raise ValueError(
                f"{owner}: {name} must have degree at most {max_degree}, got the term {key!r}"
            )
        try:
            c = float(value)
        except (TypeError, ValueError):
            c = float("nan")
        if not np.isfinite(c):
            raise ValueError(f"{owner}: {name} coefficients must be finite numbers, got {value!r}")
        items.append((key, c))
    d = max((sum(k) for k, _ in items), default=0)
    c = np.zeros((d + 1,) * 3)
    for (i, j, k), v in items:
        c[i, j, k] += v
    return c
