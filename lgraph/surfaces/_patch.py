"""Curves on bounded patches of unbounded surfaces: clipping and even spreading.

A surface patch is described by a continuous *margin* function of space points
that is ``>= 0`` exactly on the drawn patch (for example ``height - |z|``).
:func:`clip_intervals` cuts curves ``t -> x(t)`` to the parameter intervals
where the margin is non-negative: a fixed grid finds sign changes, bisection
locates each to machine precision.  :func:`spread` picks curve parameters
evenly spaced by arc length along transversal curves, so families of lines
look evenly distributed.

>>> import numpy as np
>>> def margin(idx, t):
...     return 0.5 - np.abs(np.cos(t))
>>> cid, a, b, closed = clip_intervals(margin, np.array([0.0]), np.array([2 * np.pi]),
...                                    np.array([True]))
>>> np.round(a, 9).tolist(), np.round(b, 9).tolist()
([1.047197551, 4.188790205], [2.094395102, 5.235987756])
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..curves import CurveBatch

__all__ = ["clip_intervals", "spread", "curve_batch"]

from .._tolerance import CLIP_BISECTIONS, CLIP_SAMPLES


def clip_intervals(
    margin: Callable[[np.ndarray, np.ndarray], np.ndarray],
    t0: np.ndarray,
    t1: np.ndarray,
    closed: np.ndarray,
    samples: int = CLIP_SAMPLES,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Parameter intervals where ``margin(idx, t) >= 0`` on curves ``t0[k] <= t <= t1[k]``.

    Returns ``(cid, a, b, closed)``: for each interval the index of its curve,
    its ends and whether it is a whole closed curve.  For a closed curve
    (period ``t1 - t0``) an interval through the seam is returned as one
    interval ``[a, b]`` with ``b > t1``.
    """
    t0 = np.asarray(t0, float)
    t1 = np.asarray(t1, float)
    closed = np.broadcast_to(np.asarray(closed, bool), t0.shape)
    m = len(t0)
    frac = np.linspace(0.0, 1.0, samples)
    grid = t0[:, None] + (t1 - t0)[:, None] * frac
    rows = np.repeat(np.arange(m), samples)
    with np.errstate(invalid="ignore"):
        inside = (np.asarray(margin(rows, grid.ravel())) >= 0).reshape(m, samples)
    ci, ki = np.nonzero(inside[:, 1:] != inside[:, :-1])
    lo, hi = grid[ci, ki], grid[ci, ki + 1]
    in_lo = inside[ci, ki]
    for _ in range(CLIP_BISECTIONS):
        mid = 0.5 * (lo + hi)
        with np.errstate(invalid="ignore"):
            same = (np.asarray(margin(ci, mid)) >= 0) == in_lo
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    edge = np.where(in_lo, lo, hi)  # the end that lies on the patch
    out: list[tuple[int, float, float, bool]] = []
    starts = np.searchsorted(ci, np.arange(m + 1))
    for c in range(m):
        ev = edge[starts[c] : starts[c + 1]]
        entering = ~in_lo[starts[c] : starts[c + 1]]
        if not len(ev):
            if inside[c, 0]:
                out.append((c, t0[c], t1[c], bool(closed[c])))
            continue
        pieces = []
        cur = t0[c] if inside[c, 0] else None
        for e, ent in zip(ev.tolist(), entering.tolist()):
            if ent:
                cur = e
            elif cur is not None:
                pieces.append((cur, e))
                cur = None
        if cur is not None:
            pieces.append((cur, t1[c]))
        if closed[c] and inside[c, 0] and inside[c, -1] and len(pieces) > 1:
            first = pieces.pop(0)
            last = pieces.pop()
            pieces.append((last[0], first[1] + (t1[c] - t0[c])))
        tiny = 1e-9 * (t1[c] - t0[c])
        out.extend((c, a, b, False) for a, b in pieces if b - a > tiny)
    if not out:
        empty = np.empty(0)
        return np.empty(0, int), empty, empty, np.empty(0, bool)
    cid, a, b, cl = zip(*out)
    return np.array(cid, int), np.array(a, float), np.array(b, float), np.array(cl, bool)


def spread(
    transversals: Callable[[np.ndarray], np.ndarray],
    lo: float,
    hi: float,
    n: int,
    mode: str = "open",
) -> np.ndarray:
    """``n`` parameter values in ``[lo, hi]`` evenly spaced by arc length.

    ``transversals(s)`` returns points ``(len(s), 3)`` or ``(k, len(s), 3)`` of
    one or several curves crossing the family; their arc lengths are summed.
    ``mode``: ``"open"`` leaves out both (degenerate) ends (midpoints of ``n``
    equal parts), ``"ends"`` includes both ends, ``"periodic"`` spaces ``n``
    values around a closed curve starting at ``lo``.

    >>> import numpy as np
    >>> circle = lambda s: np.stack([np.cos(s), np.sin(s), 0 * s], axis=-1)
    >>> np.round(spread(circle, 0, np.pi, 2, "ends"), 6).tolist()
    [0.0, 3.141593]
    """
    if n <= 0:
        return np.empty(0)
    s = np.linspace(lo, hi, 2049)
    pts = np.asarray(transversals(s), float)
    if pts.ndim == 2:
        pts = pts[None]
    seg = np.linalg.norm(np.diff(pts, axis=1), axis=-1).sum(axis=0)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    total = arc[-1]
    if not total > 0:
        arc = s - lo
        total = hi - lo
    if mode == "open":
        target = (np.arange(n) + 0.5) / n * total
    elif mode == "ends":
        target = np.array([0.5 * total]) if n == 1 else np.linspace(0.0, total, n)
    elif mode == "periodic":
        target = np.arange(n) / n * total
    else:  # pragma: no cover - internal misuse
        raise ValueError(f"spread: unknown mode {mode!r}")
    return np.interp(target, arc, s)


def curve_batch(
    surface: Any,
    family: str,
    func: Callable[[np.ndarray, np.ndarray], np.ndarray],
    params: Any,
    t0: Any,
    t1: Any,
    closed: Any = False,
    clip: bool = True,
) -> list[CurveBatch]:
    """A batch of curves ``x = func(params[k], t)``, ``t0[k] <= t <= t1[k]``,
    cut to the drawn patch of ``surface`` (its ``patch_margin``) when ``clip``
    and the surface is not closed.

    ``params`` is an ``(m, p)`` array of per-curve constants; ``func`` gets the
    rows belonging to each evaluated point and returns ``(n, 3)`` points.
    """
    params = np.asarray(params, float)
    if params.ndim == 1:
        params = params[:, None]
    m = len(params)
    if m == 0:
        return []
    t0 = np.broadcast_to(np.asarray(t0, float), (m,)).copy()
    t1 = np.broadcast_to(np.asarray(t1, float), (m,)).copy()
    closed = np.broadcast_to(np.asarray(closed, bool), (m,)).copy()
    if clip and not getattr(surface, "closed", True):
        cid, t0, t1, closed = clip_intervals(
            lambda idx, t: surface.patch_margin(func(params[idx], t)), t0, t1, closed
        )
        params = params[cid]
        if not len(params):
            return []

    def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x = func(params[idx], np.asarray(t, float))
        return x, surface.uv_of(x)

    return [CurveBatch(family, t0, t1, evaluate, closed=closed, surface=surface)]
