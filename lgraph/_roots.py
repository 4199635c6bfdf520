"""Vectorized bracketing root finding: one root in each of many brackets.

Every one-dimensional root problem of the renderer reduces to this: a scan
on a grid finds sign changes of a function, and each bracket ``[a, b]`` is
refined to machine precision -- the ray-ruling determinant and the contour
rulings of ruled surfaces (docs/mathematics.rst, "Ruled surfaces": ray test
and contour), the folds of the contour of a surface of revolution ("Surfaces
of revolution"), the crossings of a zero set with the edges of the marching
squares grid ("Level lines, parabolic lines, self-intersections").

:func:`bracketed_roots` hands the work to scipy's elementwise
``find_root`` (Chandrupatla's hybrid of inverse quadratic interpolation and
bisection, scipy >= 1.15): all brackets at once, each dropped from the work
as soon as it has converged.  It needs about a fifth of the function calls of
the Illinois iteration lgraph used before (benchmarks/bench_root_finding.py).
scipy is imported on the first call, not with lgraph.

>>> import numpy as np
>>> c = np.array([0.5, 1.0, 2.0])
>>> a, b = np.zeros(3), np.full(3, 2.0)
>>> f = lambda x, sel: np.cos(x) - c[sel] * x
>>> x = bracketed_roots(f, a, b, f(a, np.arange(3)), f(b, np.arange(3)), xtol=1e-15)
>>> bool(np.all(np.abs(np.cos(x) - c * x) < 1e-15))
True
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["bracketed_roots"]

#: iterations at most (each halves the bracket at least every few steps; the
#: tolerances below are met long before on any continuous function)
MAX_ITERATIONS = 200


def bracketed_roots(
    f: Callable[[np.ndarray, np.ndarray], np.ndarray],
    a: np.ndarray,
    b: np.ndarray,
    fa: np.ndarray,
    fb: np.ndarray,
    xtol: float,
    ftol: np.ndarray | float = 0.0,
) -> np.ndarray:
    """A root of ``f`` in each bracket ``[a[k], b[k]]``, all at once.

    Parameters
    ----------
    f : callable
        ``f(x, sel)``: the function of brackets number ``sel`` (an integer
        array) at the points ``x`` (same shape); called only for the brackets
        still active.
    a, b : (n,) arrays
        The brackets, ``a <= b``.
    fa, fb : (n,) arrays
        ``f`` at ``a`` and ``b``, of opposite signs or zero (a zero end is the
        root).  They are taken as given: ``f`` is not called at the ends, so a
        bracket found by a scan stays a bracket even where recomputing ``f``
        would round differently.
    xtol : float
        Absolute tolerance: a bracket narrower than ``xtol`` (plus four units
        in the last place of the root) has converged.
    ftol : float or (n,) array of positive floats
        A point where ``|f| <= ftol`` is a root (the rounding level of ``f``);
        0 (the default): only where ``f`` vanishes.

    Returns
    -------
    (n,) array
        The roots: of the final bracket's ends the one where ``|f|`` is
        smaller (the bracket's midpoint if ``f`` turned non-finite in it).
    """
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    fa = np.asarray(fa, float)
    fb = np.asarray(fb, float)
    n = len(a)
    if not n:
        return np.empty(0)
    if np.ndim(xtol) or not xtol >= 0:
        raise ValueError(f"bracketed_roots: xtol must be a non-negative number, got {xtol!r}")
    if np.ndim(ftol):
        scale = np.broadcast_to(np.asarray(ftol, float), (n,))
        if not np.all(scale > 0):
            raise ValueError("bracketed_roots: an array ftol must be positive everywhere")
        fatol = 1.0  # |f / ftol| <= 1
    else:
        if not ftol >= 0:
            raise ValueError(f"bracketed_roots: ftol must be non-negative, got {ftol!r}")
        scale, fatol = None, float(ftol)

    def g(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
        at_a, at_b = x == a[sel], x == b[sel]
        if np.all(at_a | at_b):  # the ends (scipy's first two calls): known values
            out = np.where(at_a, fa[sel], fb[sel])
        else:
            out = np.where(at_a, fa[sel], np.where(at_b, fb[sel], f(x, sel)))
        return out if scale is None else out / scale[sel]

    from scipy.optimize.elementwise import find_root

    res = find_root(
        g,
        (a, b),
        args=(np.arange(n),),
        tolerances={"xatol": float(xtol), "xrtol": 4 * np.finfo(float).eps, "fatol": fatol},
        maxiter=MAX_ITERATIONS,
    )
    x = np.asarray(res.x, float)
    bad = ~np.isfinite(x)
    if bad.any():
        lo, hi = (np.asarray(e, float) for e in res.bracket)
        x[bad] = 0.5 * (lo[bad] + hi[bad])
    return x
