"""lgraph's bracketing root finder (scipy's elementwise ``find_root``) vs the
Illinois iteration it replaced (issue 12).

Run:  python benchmarks/bench_root_finding.py [--repeat 7] [--n 20000]

The problem is the one the ruled surfaces solve for every ray: a root of a
smooth function in each of many brackets, here ``f_k(x) = cos(x) - c_k x`` on
``[0, 2]`` (one root each, c_k in (0.5, 3)), solved to 1e-15 of the bracket.
Three solvers: the vectorized Illinois (modified regula falsi) iteration that
lgraph used until issue 12 (``_illinois`` below, verbatim from
``lgraph/surfaces/ruled/__init__.py`` at 72b481e: the baseline), lgraph's
``lgraph._roots.bracketed_roots`` (scipy's ``find_root``, Chandrupatla's
method, behind lgraph's calling convention ``f(x, sel)`` with the end values
given), and scipy's ``find_root`` called directly.  Reported: medians of the
wall time, the number of calls of ``f``, and the largest error against a
reference polished by Newton.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from typing import Any

import numpy as np


def _illinois(
    f: Any,
    a: np.ndarray,
    b: np.ndarray,
    fa: np.ndarray,
    fb: np.ndarray,
    xtol: np.ndarray | float,
    ftol: np.ndarray | float = 0.0,
) -> np.ndarray:
    """Roots of ``f`` in the brackets ``[a, b]`` (``fa``, ``fb`` of opposite signs
    or zero), all at once: Illinois (modified regula falsi) with a fall-back to
    bisection when a step gains little.  ``f(x, sel)`` evaluates bracket
    numbers ``sel`` at ``x``; iteration stops when the bracket is narrower than
    ``xtol`` or ``|f| <= ftol`` (the rounding level of ``f``)."""
    a, b = np.array(a, float), np.array(b, float)
    fa, fb = np.array(fa, float), np.array(fb, float)
    n = len(a)
    xtol = np.broadcast_to(np.asarray(xtol, float), (n,))
    ftol = np.broadcast_to(np.asarray(ftol, float), (n,))
    x = np.where(fa == 0, a, np.where(fb == 0, b, np.nan))
    active = np.isnan(x)
    side = np.zeros(n, np.int8)
    slow = np.zeros(n, np.int8)
    for _ in range(200):
        idx = np.nonzero(active)[0]
        if not len(idx):
            break
        A, B, FA, FB = a[idx], b[idx], fa[idx], fb[idx]
        with np.errstate(divide="ignore", invalid="ignore"):
            c = (A * FB - B * FA) / (FB - FA)
        bis = (slow[idx] >= 2) | ~((c > A) & (c < B))
        c = np.where(bis, 0.5 * (A + B), c)
        fc = np.asarray(f(c, idx), float)
        right = (fc < 0) == (FA < 0)  # the root lies in [c, B]
        na, nb = np.where(right, c, A), np.where(right, B, c)
        nfa, nfb = np.where(right, fc, FA), np.where(right, FB, fc)
        kept = np.where(right, 1, -1).astype(np.int8)  # which end survived
        twice = (kept == side[idx]) & ~bis
        nfb = np.where(twice & right, 0.5 * nfb, nfb)
        nfa = np.where(twice & ~right, 0.5 * nfa, nfa)
        side[idx] = kept
        slow[idx] = np.where((nb - na) > 0.5 * (B - A), slow[idx] + 1, 0)
        a[idx], b[idx], fa[idx], fb[idx] = na, nb, nfa, nfb
        small = np.abs(fc) <= ftol[idx]
        done = small | ((nb - na) <= xtol[idx])
        x[idx[done]] = np.where(small[done], c[done], 0.5 * (na[done] + nb[done]))
        active[idx[done]] = False
    rest = np.isnan(x)
    x[rest] = 0.5 * (a[rest] + b[rest])
    return x


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--n", type=int, default=20000)
    args = parser.parse_args(argv)
    from scipy.optimize.elementwise import find_root

    from lgraph._roots import bracketed_roots

    rng = np.random.default_rng(3)
    c = rng.uniform(0.5, 3.0, args.n)
    a, b = np.zeros(args.n), np.full(args.n, 2.0)
    # reference: bisection to the last bit, then Newton
    lo, hi = a.copy(), b.copy()
    for _ in range(200):
        m = 0.5 * (lo + hi)
        pos = np.cos(m) - c * m > 0
        lo, hi = np.where(pos, m, lo), np.where(pos, hi, m)
    ref = 0.5 * (lo + hi)
    for _ in range(3):
        ref -= (np.cos(ref) - c * ref) / (-np.sin(ref) - c)

    names = ("Illinois (before)", "lgraph bracketed_roots", "scipy find_root")
    calls = dict.fromkeys(names, 0)
    fa, fb = np.cos(a) - c * a, np.cos(b) - c * b

    def illinois() -> np.ndarray:
        def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
            calls[names[0]] += 1
            return np.cos(x) - c[sel] * x

        return _illinois(f, a, b, fa, fb, xtol=2e-15)

    def ours() -> np.ndarray:
        def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
            calls[names[1]] += 1
            return np.cos(x) - c[sel] * x

        return bracketed_roots(f, a, b, fa, fb, xtol=2e-15)

    def theirs() -> np.ndarray:
        def f(x: np.ndarray, cc: np.ndarray) -> np.ndarray:
            calls[names[2]] += 1
            return np.cos(x) - cc * x

        res = find_root(f, (a, b), args=(c,), tolerances={"xatol": 2e-15, "xrtol": 0.0})
        return res.x

    times: dict[str, list[float]] = {name: [] for name in names}
    errors: dict[str, float] = {}
    for _ in range(args.repeat):
        for name, fn in zip(names, (illinois, ours, theirs)):
            calls[name] = 0
            t = time.perf_counter()
            x = fn()
            times[name].append(time.perf_counter() - t)
            errors[name] = float(np.abs(x - ref).max())
    print(f"{args.n} brackets, medians of {args.repeat} alternating runs")
    print("| solver | time (ms) | calls of f | largest error |")
    print("|---|---|---|---|")
    for name in names:
        print(f"| {name} | {1e3 * statistics.median(times[name]):.1f} | {calls[name]} | "
              f"{errors[name]:.1e} |")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
