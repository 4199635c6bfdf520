"""Evenly spaced field lines (``spacing="even"``): lines are trimmed where they
come closer than half the spacing to a line already drawn (Jobard and Lefer
1997), so lines neither bunch up (at umbilics, say) nor leave gaps.

The lines themselves are traced by :func:`lgraph.families.fieldlines.trace`; this
module only chooses seeds and trims.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..curves import CurveBatch
from ._seeds import _crossing, _grid, _spread
from .fieldlines import FieldLines, trace

__all__ = ["even_batches"]


def _line_samples(lines: FieldLines, step: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every line sampled about ``step`` apart in arc length: ``(t, xyz)``."""
    out = []
    for k in range(lines.m):
        a, b = -lines.ends[1, k], lines.ends[0, k]
        t = np.concatenate([-np.arange(0.0, -a, step)[:0:-1], np.arange(0.0, b, step), [b]])
        t = t[t >= a]
        out.append((t, lines.points(k, t)))
    return out


def _keep_pieces(
    lines: FieldLines,
    pieces: list,
    points: list,
    dsep: float,
    min_length: float,
    step: float,
    placed: bool = False,
) -> list[np.ndarray]:
    """Trim each line of ``lines`` (in order) where it comes closer than
    ``dsep / 2`` to lines already kept, keeping the run of samples through its
    seed; drop runs shorter than ``min_length``.  A closed line is kept whole.
    Lines from ``placed`` seeds (spread along a transversal) are always kept,
    at least ``dsep / 2`` either side of the seed.  Appends ``(lines, k, ta,
    tb, closed)`` to ``pieces`` and the kept samples to ``points``; returns the
    samples of dropped lines."""
    from scipy.spatial import cKDTree

    dtest = 0.5 * dsep
    dropped = []
    for k, (t, x) in enumerate(_line_samples(lines, step)):
        if len(t) < 2:
            dropped.append(x)
            continue
        if points:
            dist, _ = cKDTree(np.concatenate(points)).query(x)
            free = dist > dtest
        else:
            free = np.ones(len(t), bool)
        i = int(np.argmin(np.abs(t)))  # the seed
        if placed:
            free[np.abs(t) <= dtest] = True
        if not free[i]:
            dropped.append(x)
            continue
        if lines.closed[k]:
            pieces.append((lines, k, 0.0, float(lines.ends[0, k]), True))
            points.append(x)
            continue
        i0 = i1 = i
        while i0 > 0 and free[i0 - 1]:
            i0 -= 1
        while i1 < len(t) - 1 and free[i1 + 1]:
            i1 += 1
        ta = -float(lines.ends[1, k]) if i0 == 0 else float(t[i0])
        tb = float(lines.ends[0, k]) if i1 == len(t) - 1 else float(t[i1])
        if tb - ta < (0.0 if placed else min_length) or tb <= ta:
            dropped.append(x)
            continue
        pieces.append((lines, k, ta, tb, False))
        points.append(x[i0 : i1 + 1])
    return dropped


def _pieces_batch(surface: Any, family: str, pieces: list) -> CurveBatch:
    """One batch of trimmed field lines ``(lines, k, ta, tb, closed)``."""
    return CurveBatch.from_curves(
        surface,
        family,
        [p[2] for p in pieces],
        [p[3] for p in pieces],
        lambda c, t: pieces[c][0].uv_line(pieces[c][1], t),
        closed=[p[4] for p in pieces],
    )


def even_batches(
    surface: Any,
    field: Any,
    both: FieldLines,
    a: int,
    n1: int,
    n2: int,
    stop: float,
    family: str,
    singular: np.ndarray,
    lean: Any = None,
) -> list[CurveBatch]:
    """Evenly spaced lines: ``n1`` of branch ``a``, ``n2`` of the other.

    The separation ``dsep`` of a family is the length of the line of the other
    family through the centre (line ``1 - which`` of ``both``) divided by
    ``n``.  First seeds lie ``dsep`` apart along that line; then more seeds go
    where the surface is farther than ``0.9 dsep`` from every line of the
    family (farthest first, in rounds).  Each line is cut where it comes
    closer than ``dsep / 2`` to a line already drawn, keeping the part
    through its seed, and pieces shorter than ``dsep`` are dropped.
    """
    from scipy.spatial import cKDTree

    size = surface.size
    out = []
    G, GP, _ = _grid(surface, field, stop)
    for which, n in ((a, n1), (1 - a, n2)):
        if n <= 0:
            continue
        transversal = 1 - which
        L = both.ends[0, transversal] + both.ends[1, transversal]
        dsep = (L if L > 0.05 * size else size) / n
        step = dsep / 8
        if L > 0:
            seeds, tangent = _spread(both, transversal, n)
            dirs = _crossing(field, surface, seeds, tangent)
        else:
            seeds = both.uv_line(0, np.zeros(1))
            dirs = field(surface, seeds)[0][:, which]
        lines = trace(surface, field, seeds, dirs, stop=stop, singular=singular, lean=lean)
        pieces: list = []
        points: list = []
        _keep_pieces(lines, pieces, points, dsep, 1.5 * dsep, step, placed=True)
        if points:
            _, str_, _ = field(surface, G)
            # away from umbilics, where lines stop short anyway
            alive = np.isfinite(str_) & (str_ > max(50 * stop, 0.1))
            for _round in range(2):
                dist, _ = cKDTree(np.concatenate(points)).query(GP)
                dist = np.where(alive, dist, 0.0)
                chosen: list[int] = []
                for k in np.argsort(-dist):
                    if dist[k] <= 0.9 * dsep or len(chosen) >= n + 4:
                        break
                    if all(np.linalg.norm(GP[k] - GP[j]) > 2 * dsep for j in chosen):
                        chosen.append(int(k))
                if not chosen:
                    break
                alive[chosen] = False
                more = trace(surface, field, G[chosen], field(surface, G[chosen])[0][:, which],
                             stop=stop, singular=singular, lean=lean)  # fmt: skip
                dropped = _keep_pieces(more, pieces, points, dsep, dsep, step)
                if dropped:  # seeds on a dropped line would give it again
                    near, _ = cKDTree(np.concatenate(dropped)).query(GP)
                    alive &= near > 0.5 * dsep
        if pieces:
            out.append(_pieces_batch(surface, family, pieces))
    return out
