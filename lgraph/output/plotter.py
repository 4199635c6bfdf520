"""Plotter-clean geometry: merged paths, no fragments or duplicates, short pen-up travel.

A pen plotter draws every stroke as one pen-down move and travels pen-up between
them.  Rendered figures come in many pieces (a curve broken where it passes
behind a surface, a closed curve sampled from both ends, the same edge drawn by
two patches), so :func:`for_plotter` cleans a drawing in four steps, all
measured on the page (pt, or any length ``"0.1mm"``):

1. **duplicates**: parts of a stroke that lie within ``merge`` of a stroke
   already kept are removed (contours and longer strokes are kept first);
2. **merging**: strokes of the same layer, family and style whose ends lie
   within ``merge`` are joined (reversed where needed) into one path; a path
   whose ends meet is closed exactly; a path joined from strokes of different
   surfaces has ``surface`` and ``uv`` None;
3. **fragments**: paths shorter than ``min_length`` are dropped;
4. **order** (``sort=True``): per layer, nearest-neighbour tours over the
   paths (from a few extreme starts), reversing them where that helps, each
   improved by 2-opt moves (reversing a run of paths) until none shortens the
   pen-up travel; the shortest tour wins.

Every point of the original drawing stays within ``merge`` of the result
(except the dropped fragments).  The page geometry does not change: the result
has the layout (scale and offset) of the input.

>>> import numpy as np
>>> from lgraph.output.drawing import Drawing, Page, Stroke
>>> def stroke(*pts):
...     xy = np.array(pts, float)
...     return Stroke(xy=xy, xyz=np.c_[xy, np.zeros(len(xy))])
>>> d = Drawing(strokes=(stroke([0, 0], [10, 0]), stroke([20, 0], [10, 0]),
...                      stroke([0, 5], [20, 5]), stroke([0, 0], [10, 0])),
...             page=Page(margin=0, extent=20))
>>> clean = for_plotter(d, merge=0.01)
>>> [s.xy[:, 0].tolist() for s in clean.strokes]
[[0.0, 20.0], [20.0, 10.0, 0.0]]
>>> round(pen_up_length(d), 2), pen_up_length(clean)
(41.8, 5.0)
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import attrs
import numpy as np

from .._tolerance import DUPLICATE_MIN_END
from .layers import check_layer_mode, join_continued, layer_keys
from .units import UNITS, length_pt, to_unit

__all__ = ["for_plotter", "pen_up_length", "plotter_length"]

#: Largest number of following paths a 2-opt move may reverse at once.
TWO_OPT_WINDOW = 200

#: Most passes of 2-opt moves per layer (each pass is vectorized over the paths).
TWO_OPT_MAX_PASSES = 1000

#: Priority of families when duplicates are removed (lower is kept first).
_FAMILY_RANK = {"contour": 0, "boundary": 1}


def plotter_length(value: Any, name: str) -> float:
    """A length >= 0 in pt: a number (pt) or a string such as ``"0.1mm"``.

    >>> plotter_length("0.1mm", "merge") == 0.1 * UNITS["mm"]
    True
    >>> plotter_length(0, "merge")
    0.0
    >>> plotter_length(-1, "merge")
    Traceback (most recent call last):
    ...
    ValueError: for_plotter: merge must be a length >= 0 such as '0.1mm' or a number of pt, got -1
    """
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        if math.isfinite(value) and value == 0:
            return 0.0
    try:
        return length_pt(value, name)
    except ValueError:
        raise ValueError(
            f"for_plotter: {name} must be a length >= 0 such as '0.1mm' or a number of pt, "
            f"got {value!r}"
        ) from None


# -- pieces: (stroke, first vertex, last vertex + 1, reversed) ------------------------
def _runs(strokes: list[Any]) -> list[tuple[int, int, int]]:
    """Finite runs of two or more points of every stroke: (stroke index, start, stop)."""
    out = []
    for k, s in enumerate(strokes):
        xy = np.asarray(s.xy, float)
        if len(xy) < 2:
            continue
        ok = np.isfinite(xy).all(axis=1)
        if ok.all():
            out.append((k, 0, len(xy)))
            continue
        edges = np.diff(np.concatenate([[False], ok, [False]]).astype(np.int8))
        starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
        out.extend((k, int(a), int(b)) for a, b in zip(starts, stops) if b - a >= 2)
    return out


def _dedupe(pages: list[np.ndarray], rank: np.ndarray, tol: float) -> list[list[tuple[int, int]]]:
    """Vertex ranges of every run that survive duplicate removal.

    Each segment is sampled at spacing <= tol/2; a sample is covered when a
    kept sample of an earlier-ranked run lies within 3/4 tol.  A segment all of
    whose samples are covered is removed, so every point of it lies within
    3/4 tol + tol/4 = tol of what is kept.
    """
    from scipy.spatial import cKDTree

    seg = [np.linalg.norm(np.diff(p, axis=0), axis=1) for p in pages]
    nseg = np.array([len(s) for s in seg])
    lengths = np.concatenate(seg)
    per = np.maximum(1, np.ceil(lengths / (0.5 * tol))).astype(np.int64)
    last = np.zeros(len(lengths), bool)
    last[np.cumsum(nseg) - 1] = True
    group = per + last  # samples per segment (the last one of a run also gets its end)
    gstart = np.concatenate([[0], np.cumsum(group)[:-1]])
    total = int(group.sum())
    seg_of = np.repeat(np.arange(len(lengths)), group)
    local = np.arange(total) - gstart[seg_of]
    t = local / per[seg_of]  # 0 .. 1 (1 only for a run's end point)
    a = np.concatenate([p[:-1] for p in pages])
    b = np.concatenate([p[1:] for p in pages])
    samples = a[seg_of] + t[:, None] * (b[seg_of] - a[seg_of])
    run_of_seg = np.repeat(np.arange(len(pages)), nseg)
    run_of = run_of_seg[seg_of]
    pairs = cKDTree(samples).query_pairs(0.75 * tol, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    ri, rj = rank[run_of[i]], rank[run_of[j]]
    keep = ri != rj
    i, j, ri, rj = i[keep], j[keep], ri[keep], rj[keep]
    later, earlier = np.where(ri > rj, i, j), np.where(ri > rj, j, i)
    order = np.argsort(rank[run_of[later]], kind="stable")
    later, earlier = later[order], earlier[order]
    later_rank = rank[run_of[later]]
    kept_sample = np.zeros(total, bool)
    seg_first = np.concatenate([[0], np.cumsum(nseg)[:-1]])
    out: list[list[tuple[int, int]]] = [[] for _ in pages]
    for r in np.argsort(rank, kind="stable"):
        s0, s1 = seg_first[r], seg_first[r] + nseg[r]
        lo, hi = gstart[s0], gstart[s1 - 1] + group[s1 - 1]
        a0, a1 = np.searchsorted(later_rank, [rank[r], rank[r] + 1])
        cov = np.zeros(hi - lo, bool)
        hit = later[a0:a1][kept_sample[earlier[a0:a1]]]
        cov[hit - lo] = True
        gs = gstart[s0:s1] - lo
        seg_cov = np.logical_and.reduceat(cov, gs) & cov[gs + per[s0:s1]]
        seg_keep = ~_duplicates(seg_cov, lengths[s0:s1], tol)
        ks = np.repeat(seg_keep, group[s0:s1])
        ks[gs + per[s0:s1]] |= seg_keep  # a kept segment keeps its end sample
        kept_sample[lo:hi] = ks
        edges = np.diff(np.concatenate([[False], seg_keep, [False]]).astype(np.int8))
        starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
        out[r] = [(int(u), int(v) + 1) for u, v in zip(starts, stops)]  # vertex ranges
    return out


def _duplicates(covered: np.ndarray, lengths: np.ndarray, tol: float) -> np.ndarray:
    """Segments to remove: all of them when all are covered, else covered
    stretches at the ends at least DUPLICATE_MIN_END tolerances long (a
    covered stretch inside is a crossing or a tangency: it stays)."""
    if covered.all():
        return covered
    remove = np.zeros(len(covered), bool)
    arc = np.concatenate([[0.0], np.cumsum(lengths)])
    head = int(np.argmin(covered))  # covered segments before the first uncovered one
    tail = int(np.argmin(covered[::-1]))
    if arc[head] >= DUPLICATE_MIN_END * tol:
        remove[:head] = True
    if arc[-1] - arc[len(covered) - tail] >= DUPLICATE_MIN_END * tol:
        remove[len(covered) - tail :] = True
    return remove


def _chains(ends: np.ndarray, keys: list[Any], lengths: np.ndarray, tol: float) -> list[list]:
    """Join pieces whose ends lie within ``tol``: lists of (piece, reversed)."""
    from scipy.spatial import cKDTree

    n = len(keys)
    near: dict[int, list[int]] = {}
    if tol > 0 and n:
        pairs = cKDTree(ends).query_pairs(tol, output_type="ndarray")
        for p, q in pairs.tolist():
            if p // 2 != q // 2 and keys[p // 2] == keys[q // 2]:
                near.setdefault(p, []).append(q)
                near.setdefault(q, []).append(p)
    used = np.zeros(n, bool)
    out = []

    def extend(end: int) -> int | None:
        """An unused piece endpoint nearest to endpoint ``end``, or None."""
        cand = [q for q in near.get(end, ()) if not used[q // 2]]
        if not cand:
            return None
        d = np.linalg.norm(ends[cand] - ends[end], axis=1)
        return cand[int(np.argmin(d))]

    for first in np.argsort(-lengths, kind="stable").tolist():
        if used[first]:
            continue
        used[first] = True
        chain = [(first, False)]
        tail = 2 * first + 1  # the endpoint the chain ends at
        while (q := extend(tail)) is not None:
            used[q // 2] = True
            chain.append((q // 2, q % 2 == 1))  # entered at its end: reversed
            tail = q ^ 1
        head = 2 * first
        while (q := extend(head)) is not None:
            used[q // 2] = True
            chain.insert(0, (q // 2, q % 2 == 0))  # leaves at q: reversed if q is its start
            head = q ^ 1
        out.append(chain)
    return out


def _dist(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    return np.hypot(p[..., 0] - q[..., 0], p[..., 1] - q[..., 1])


def _nearest_neighbour(
    starts: np.ndarray, stops: np.ndarray, first: int, flip: bool
) -> tuple[np.ndarray, np.ndarray]:
    """Greedy tour from path ``first`` (reversed if ``flip``), entering each next
    path at its nearer end: (order, reversed flags)."""
    n = len(starts)
    left = np.ones(n, bool)
    order = np.empty(n, np.int64)
    rev = np.zeros(n, bool)
    order[0], rev[0], left[first] = first, flip, False
    pos = starts[first] if flip else stops[first]
    for k in range(1, n):
        idx = np.flatnonzero(left)
        ds, de = _dist(starts[idx], pos), _dist(stops[idx], pos)
        m = int(np.argmin(np.minimum(ds, de)))
        nxt = idx[m]
        order[k], rev[k], left[nxt] = nxt, de[m] < ds[m], False
        pos = starts[nxt] if rev[k] else stops[nxt]
    return order, rev


def _two_opt(
    order: np.ndarray, rev: np.ndarray, starts: np.ndarray, stops: np.ndarray
) -> tuple[np.ndarray, np.ndarray, float]:
    """Passes of 2-opt moves: reversing a run of consecutive paths (each path
    reversed too) where that shortens the travel; each pass applies the best
    non-overlapping moves.  Returns (order, reversed flags, travel)."""
    n = len(order)
    order, rev = order.copy(), rev.copy()
    s = np.where(rev[:, None], stops[order], starts[order])
    e = np.where(rev[:, None], starts[order], stops[order])
    w = min(TWO_OPT_WINDOW, n)
    i = np.arange(n)[:, None]
    j_all = i + np.arange(w)[None, :]
    ok = j_all < n
    j = np.minimum(j_all, n - 1)
    has_prev, has_next = i > 0, j_all < n - 1
    eps = 1e-9 * (1.0 + float(np.abs(s).max()))
    for _ in range(TWO_OPT_MAX_PASSES):
        prev_e, next_s = e[np.maximum(i - 1, 0)], s[np.minimum(j + 1, n - 1)]
        old = np.where(has_prev, _dist(prev_e, s[i]), 0) + np.where(
            has_next, _dist(e[j], next_s), 0
        )
        new = np.where(has_prev, _dist(prev_e, e[j]), 0) + np.where(
            has_next, _dist(s[i], next_s), 0
        )
        delta = np.where(ok, new - old, np.inf)
        best = np.argmin(delta, axis=1)
        gain = delta[np.arange(n), best]
        rows = np.flatnonzero(gain < -eps)
        if not len(rows):
            break
        busy = np.zeros(n + 2, bool)  # index k + 1 for path k; 0 and n + 1 are sentinels
        for r in rows[np.argsort(gain[rows])].tolist():
            a, b = r, r + int(best[r])
            if busy[a : b + 3].any():  # paths a-1 .. b+1
                continue
            busy[a : b + 3] = True
            order[a : b + 1] = order[a : b + 1][::-1].copy()
            rev[a : b + 1] = ~rev[a : b + 1][::-1]
            s[a : b + 1], e[a : b + 1] = e[a : b + 1][::-1].copy(), s[a : b + 1][::-1].copy()
    return order, rev, float(_dist(e[:-1], s[1:]).sum())


def _order(starts: np.ndarray, stops: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Order and orientation of paths (first/last points given) for short travel.

    Nearest-neighbour tours from the first path and from the paths with the
    leftmost, rightmost, lowest and highest ends (started there), each improved
    by 2-opt; the shortest wins, so the travel is never longer than that of the
    plain greedy tour from the first path.  Returns (order, reversed flags).
    """
    n = len(starts)
    if n <= 1:
        return np.arange(n), np.zeros(n, bool)
    ends = np.concatenate([starts, stops])  # index k: start of k; n + k: stop of k
    extremes = [np.argmin(ends[:, 0]), np.argmax(ends[:, 0]), np.argmin(ends[:, 1]),
                np.argmax(ends[:, 1])]  # fmt: skip
    seeds = dict.fromkeys([(0, False)] + [(int(k) % n, bool(k >= n)) for k in extremes])
    best = None
    for first, flip in seeds:
        result = _two_opt(*_nearest_neighbour(starts, stops, first, flip), starts, stops)
        if best is None or result[2] < best[2] - 1e-12:
            best = result
    return best[0], best[1]


def for_plotter(
    drawing: Any,
    merge: Any = "0.1mm",
    min_length: Any = "0.3mm",
    sort: bool = True,
    *,
    layers: str | None = "family",
    width: float | str | None = None,
) -> Any:
    """A copy of ``drawing`` cleaned for a pen plotter (see the module docstring).

    Parameters
    ----------
    drawing : Drawing
    merge : length, default ``"0.1mm"``
        Tolerance on the page (pt or ``"0.05mm"``, ``"0.01in"``): ends closer
        than this are joined; parts closer than this to a kept stroke are
        duplicates.  0 joins only ends that coincide exactly and removes nothing.
    min_length : length, default ``"0.3mm"``
        Paths shorter than this on the page are dropped (0 keeps all).
    sort : bool, default True
        Order the paths of each layer for short pen-up travel.
    layers : "family", "surface" or None
        The layers within which paths are sorted (as the SVG backend groups them).
    width : length, optional
        The width the drawing will be saved at (``save("x.svg", width="200mm")``,
        see :meth:`lgraph.Drawing.sized`): ``merge`` and ``min_length`` are then
        lengths on that page.  Default: on the drawing's own page.

    Returns
    -------
    Drawing
        Same page geometry; strokes keep ``xy``, ``xyz``, ``uv`` (reversed
        where a path is), family, surface, style and visibility.
    """
    tol = plotter_length(merge, "merge")
    shortest = plotter_length(min_length, "min_length")
    if width is not None:  # lengths on the plotted page -> on the drawing's page
        length_pt(width, "for_plotter: width")
        shrink = drawing._layout()[0] / drawing.sized(width=width)._layout()[0]
        tol, shortest = tol * shrink, shortest * shrink
    if not isinstance(sort, bool):
        raise ValueError(f"for_plotter: sort must be True or False, got {sort!r}")
    mode = check_layer_mode(layers, "for_plotter")
    scale, offset, _, _ = drawing._layout()
    strokes = join_continued(list(drawing.strokes), scale, keep_depth=mode == "occlusion")
    runs = _runs(strokes)
    if not runs:
        return _same_layout(drawing, ())
    pages = [np.asarray(strokes[k].xy, float)[a:b] * scale + offset for k, a, b in runs]
    arc = np.array([np.linalg.norm(np.diff(p, axis=0), axis=1).sum() for p in pages])

    # 1. duplicates: visible before hidden, contour and boundary first, long before short
    if tol > 0:
        fam = np.array([_FAMILY_RANK.get(strokes[k].family, 2) for k, _, _ in runs])
        vis = np.array([0 if strokes[k].visible else 1 for k, _, _ in runs])
        rank = np.empty(len(runs), np.int64)
        rank[np.lexsort((-arc, fam, vis))] = np.arange(len(runs))
        ranges = _dedupe(pages, rank, tol)
    else:
        ranges = [[(0, len(p))] for p in pages]
    pieces = [(k, a + u, a + v) for (k, a, _), rr in zip(runs, ranges) for u, v in rr]
    ppages = [np.asarray(strokes[k].xy, float)[a:b] * scale + offset for k, a, b in pieces]
    plen = np.array([np.linalg.norm(np.diff(p, axis=0), axis=1).sum() for p in ppages])

    # 2. merge pieces of one layer, family and style (a path over two surfaces has none)
    lkeys = layer_keys([strokes[k] for k, _, _ in pieces], mode)
    keys = [
        (lk, s.visible, s.family, s.style)
        for lk, s in zip(lkeys, (strokes[k] for k, _, _ in pieces))
    ]
    ends = np.array([[p[0], p[-1]] for p in ppages]).reshape(-1, 2)
    chains = _chains(ends, keys, plen, tol)

    # 3. paths: concatenated vertex ranges; drop fragments; close closed ones
    paths = []
    for chain in chains:
        parts = [(*pieces[c], r) for c, r in chain]
        pts = np.concatenate([ppages[c][::-1] if r else ppages[c] for c, r in chain])
        if np.linalg.norm(np.diff(pts, axis=0), axis=1).sum() < shortest:
            continue
        paths.append((parts, pts, keys[chain[0][0]][0]))

    # 4. order per layer; layers in the drawing's order (hidden parts first, as
    # page_strokes yields them), so they keep their numbers and names in the SVG
    ordered: list[tuple[list, bool]] = []
    present = {name for _, _, name in paths}
    by_page = sorted(range(len(pieces)), key=lambda i: strokes[pieces[i][0]].visible)
    layer_names = [n for n in dict.fromkeys(lkeys[i] for i in by_page) if n in present]
    for name in layer_names:
        members = [p for p in paths if p[2] == name]
        if sort:
            first = np.array([p[1][0] for p in members])
            last = np.array([p[1][-1] for p in members])
            order, rev = _order(first, last)
            ordered.extend((members[i][0], bool(r)) for i, r in zip(order, rev))
        else:
            ordered.extend((m[0], False) for m in members)

    out = [_build(parts, flip, strokes, pages_tol=tol, scale=scale) for parts, flip in ordered]
    return _same_layout(drawing, out)


def _build(parts: list, flip: bool, strokes: list, *, pages_tol: float, scale: float) -> Any:
    """One stroke from vertex ranges of original strokes (reversed as a whole if ``flip``)."""
    if flip:
        parts = [(k, a, b, not r) for k, a, b, r in parts[::-1]]
    s0 = strokes[parts[0][0]]

    def cat(attr: str) -> np.ndarray | None:
        arrays = []
        for k, a, b, r in parts:
            v = getattr(strokes[k], attr)
            if v is None:
                return None
            v = np.asarray(v)[a:b]
            arrays.append(v[::-1] if r else v)
        return np.concatenate(arrays)

    xy, xyz, uv = cat("xy"), cat("xyz"), cat("uv")
    surface = s0.surface
    if any(strokes[k].surface is not surface for k, _, _, _ in parts):
        surface, uv = None, None  # a path over several surfaces: no one parameter plane
    # drop a vertex repeated where two pieces meet exactly
    same = np.r_[False, (np.abs(np.diff(xy, axis=0)) == 0).all(axis=1)]
    # close a path whose ends meet within the tolerance
    closing = len(xy) > 2 and pages_tol > 0 and 0 < np.hypot(*(xy[-1] - xy[0])) * scale <= pages_tol
    keep = ~same
    xy, xyz = xy[keep], xyz[keep]
    uv = uv[keep] if uv is not None else None
    if closing and np.linalg.norm(np.diff(xy, axis=0), axis=1).sum() * scale > 2 * pages_tol:
        xy, xyz = np.vstack([xy, xy[:1]]), np.vstack([xyz, xyz[:1]])
        uv = np.vstack([uv, uv[:1]]) if uv is not None else None
    return attrs.evolve(s0, xy=xy, xyz=xyz, uv=uv, surface=surface, curve=None)


def _same_layout(drawing: Any, strokes: Any) -> Any:
    new = attrs.evolve(drawing, strokes=tuple(strokes))
    new._cache["layout"] = drawing._layout()
    return new


def pen_up_length(drawing: Any, unit: str = "pt", *, layers: str | None = "family") -> float:
    """Total pen-up travel on the page: within each layer, from the end of each
    path to the start of the next, in drawing order (as vpype measures it).

    ``unit`` is one of ``pt``, ``mm``, ``cm``, ``in``.
    """
    if unit not in UNITS:
        raise ValueError(f"pen_up_length: unit must be one of {', '.join(UNITS)}, got {unit!r}")
    mode = check_layer_mode(layers, "pen_up_length")
    from .backends._common import finite_runs

    items = [(run, s) for pts, s in drawing.page_strokes() for run in finite_runs(pts)]
    if not items:
        return 0.0
    names = layer_keys([s for _, s in items], mode)
    total = 0.0
    last: dict[str, np.ndarray] = {}
    for (run, _), name in zip(items, names):
        if name in last:
            total += float(np.hypot(*(run[0] - last[name])))
        last[name] = run[-1]
    return to_unit(total, unit)
