"""Adaptive sampling of curve batches (the renderer's first stage).

All samples of a scene live in one set of flat arrays sorted by (curve, t):
the curves of every batch of every node get consecutive global ids, so each
stage of the renderer is a handful of numpy calls for the whole scene
whatever the number of batches.  Every chord's midpoint is kept within the
chord tolerance of the true projected curve.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from .. import _tolerance as tol
from ..families import cache as family_cache
from ..geometry.transforms import Transform
from ..scene.projectors import Projector
from ..surfaces._base import OFF
from .views import Views, as_views, runs

if TYPE_CHECKING:
    from ..curves import CurveBatch

__all__ = [
    "Part",
    "PointBudgetError",
    "Samples",
    "check_points",
    "merge",
    "refine",
]


class Part(NamedTuple):
    """One curve batch of one scene node; its curves are ``first ...``."""

    batch: CurveBatch
    node: int
    transform: Transform
    first: int


class Samples:
    """The samples of all curves of a scene, sorted by (curve id, t).

    Per curve: ``part`` (index into ``parts``), ``t0``, ``t1``, ``closed``,
    ``owner`` (node of its surface, or -1) and ``kind`` (ownership code of the
    ray tests).  Per sample: ``cid``, ``t``, ``xyz`` (world), ``uv`` (NaN for
    curves without parameters), ``xy`` (projection), ``hidden``, ``cause``
    (grouped quadric hiding it, or -1) and ``fresh`` (not yet tested).
    """

    def __init__(
        self, batches: list[tuple[int, CurveBatch, Transform, int]], projector: Projector | Views
    ) -> None:
        # (node, batch, transform, view); the view may be left out (view 0)
        entries = [(n, b, tr, v[0] if v else 0) for n, b, tr, *v in batches]
        sizes = [len(b) for _, b, _, _ in entries]
        firsts = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(int).tolist()
        self.parts = [Part(b, n, tr, f) for (n, b, tr, _), f in zip(entries, firsts)]
        self.views = as_views(projector)
        #: per curve: its view (index into ``views.projectors``)
        self.view = np.repeat([v for _, _, _, v in entries], sizes)
        # a batch drawn in several views (the same node's cached family) is one
        # source: the same curves in every view
        src: dict[tuple[int, int], int] = {}
        self.src = np.array(
            [src.setdefault((p.node, id(p.batch)), i) for i, p in enumerate(self.parts)]
        )
        # evaluation groups: a source, or the sources whose batches share a
        # kernel (the contours of one surface in every view) or a batch (a
        # cached family drawn by equal surfaces of several nodes): one call
        # each.  Nodes are joined only when their transforms share a matrix:
        # each row then gets ``x @ M.T`` and its own node's offset, the
        # arithmetic of ``Transform.apply``
        group: dict[tuple[bytes | None, int], int] = {}
        self.group = np.array(
            [
                group.setdefault(
                    (
                        None if p.transform.is_identity else p.transform.matrix.tobytes(),
                        id(p.batch.kernel[0] if p.batch.kernel else p.batch),
                    ),
                    int(j),
                )
                for p, j in zip(self.parts, self.src)
            ]
        )
        self.part = np.repeat(np.arange(len(entries)), sizes)
        #: per curve: its evaluation group and its row there (its index in its
        #: batch, or in its group's stacked kernel parameters)
        self.cgroup = self.group[self.part]
        self.lcid = np.arange(sum(sizes)) - np.repeat(firsts, sizes)
        self.kparams = self._stack_kernels()
        self._offsets(sizes)
        self.t0 = np.concatenate([b.t0 for _, b, _, _ in entries])
        self.t1 = np.concatenate([b.t1 for _, b, _, _ in entries])
        self.closed = np.concatenate([b.closed for _, b, _, _ in entries])
        self.owner = np.repeat([-1 if b.surface is None else n for n, b, _, _ in entries], sizes)
        kinds = [OFF if b.surface is None else b.own for _, b, _, _ in entries]
        self.kind = np.repeat(kinds, sizes).astype(np.int8)
        #: per curve, its exact ellipse in world coordinates (NaN: none), or None
        self.ellipses = None
        if any(b.ellipses is not None for _, b, _, _ in entries):
            self.ellipses = np.full((len(self.t0), 3, 3), np.nan)
            for (_, b, tr, _), first in zip(entries, firsts):
                if b.ellipses is not None:
                    e = b.ellipses @ tr.matrix.T  # centre and both axes as vectors
                    e[:, 0] += tr.offset  # the centre moves with the offset too
                    self.ellipses[first : first + len(b)] = e
        # initial samples: uniform in t on every curve
        k = tol.INITIAL_SAMPLES
        self.cid = np.repeat(np.arange(len(self.t0)), k)
        frac = np.linspace(0.0, 1.0, k)
        self.t = (self.t0[:, None] + (self.t1 - self.t0)[:, None] * frac).ravel()
        self.no_uv: set[int] = set()  # groups whose curves have no parameters
        n = len(self.t)
        self.xyz, self.uv = np.empty((n, 3)), np.full((n, 2), np.nan)
        for g, params in self.kparams.items():  # stacked kernels: one call a group
            batch = self.parts[g].batch
            rows = np.concatenate(
                [
                    np.arange(part.first * k, (part.first + len(part.batch)) * k)
                    for i, part in enumerate(self.parts)
                    if self.group[i] == g and self.src[i] == i
                ]
            )
            x, self.uv[rows] = batch.kernel[0](params[self.lcid[self.cid[rows]]], self.t[rows])
            self.xyz[rows] = self._moved(g, x, self.cid[rows])
        for p, ((_, b, tr, _), first) in enumerate(zip(entries, firsts)):
            rows = slice(first * k, (first + len(b)) * k)
            if self.group[p] in self.kparams and self.src[p] == p:
                continue  # done above
            if self.src[p] != p:  # the same batch in an earlier view: its samples
                src = slice(firsts[self.src[p]] * k, (firsts[self.src[p]] + len(b)) * k)
                self.xyz[rows], self.uv[rows] = self.xyz[src], self.uv[src]
                continue
            x, u = family_cache.derived(b, ("initial samples", k), _Initial(b, self.t[rows], k))
            self.xyz[rows] = x if tr.is_identity else tr.apply(x)
            if u is None:
                self.no_uv.add(int(self.group[p]))
            else:
                self.uv[rows] = u
        self.xy = self.views.project(self.xyz, self.view[self.cid])
        self.hidden = np.zeros(n, dtype=bool)
        self.cause = np.full(n, -1, dtype=np.int64)
        self.fresh = np.ones(n, dtype=bool)

    def _stack_kernels(self) -> dict[int, np.ndarray]:
        """For every group of two or more sources sharing a kernel, their
        kernel parameters stacked (group -> array); each curve's ``lcid``
        becomes its row there."""
        stacked = {}
        for g, rows in runs(self.group):
            if self.parts[g].batch.kernel is None:
                continue
            members = np.arange(len(self.parts))[rows]
            sources = [int(i) for i in members if self.src[i] == i]
            if len(sources) < 2:
                continue
            params = [self.parts[i].batch.kernel[1] for i in sources]
            stacked[g] = np.concatenate(params)
            offset = dict(zip(sources, np.cumsum([0, *map(len, params[:-1])]).tolist()))
            for i in members.tolist():  # a part's rows follow its source's in the stack
                first, n = self.parts[i].first, len(self.parts[i].batch)
                self.lcid[first : first + n] += offset[int(self.src[i])]
        return stacked

    def _offsets(self, sizes: list[int]) -> None:
        """``joined``: the groups of several moved nodes; ``coffset``: per
        curve, its node's offset, by column (None when no group is joined)."""
        nodes: dict[int, set[int]] = {}
        for i, p in enumerate(self.parts):
            if not p.transform.is_identity:
                nodes.setdefault(int(self.group[i]), set()).add(p.node)
        self.joined = {g for g, ns in nodes.items() if len(ns) > 1}
        self.coffset = None
        if self.joined:  # column by column: gathered faster than rows
            offsets = np.array([p.transform.offset for p in self.parts]).reshape(-1, 3)
            self.coffset = [np.repeat(offsets[:, i], sizes) for i in range(3)]

    def _moved(self, g: int, x: np.ndarray, cid: np.ndarray) -> np.ndarray:
        """Points ``x`` of curves ``cid`` of group ``g`` in world coordinates."""
        transform = self.parts[g].transform
        if transform.is_identity:
            return x
        if g not in self.joined:
            return transform.apply(x)
        # each row with its own node's offset; ``x @ I`` is ``x`` exactly (the
        # zero terms add nothing), so translations skip the product
        m = transform.matrix
        y = x if np.array_equal(m, np.eye(3)) else x @ m.T
        out = np.empty_like(y)
        for i in range(3):
            np.add(y[:, i], self.coffset[i][cid], out=out[:, i])
        return out

    def evaluate(
        self, cid: np.ndarray, t: np.ndarray, project: object
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """World points, parameters (NaN where a curve has none) and, unless
        ``project`` is None, projections (each curve in its view) of curves
        ``cid`` at ``t``; one call per batch involved (a batch drawn in
        several views is called once)."""
        n = len(t)
        xyz, uv = np.empty((n, 3)), np.full((n, 2), np.nan)
        if not n:
            return xyz, uv, None if project is None else np.empty((n, 2))
        for g, rows in runs(self.cgroup[cid]):
            batch = self.parts[g].batch
            if g in self.kparams:
                x, u = batch.kernel[0](self.kparams[g][self.lcid[cid[rows]]], t[rows])
            else:
                x, u = batch.evaluate(self.lcid[cid[rows]], t[rows])
            xyz[rows] = self._moved(g, np.asarray(x, dtype=float).reshape(-1, 3), cid[rows])
            if u is None:
                self.no_uv.add(g)
            else:
                uv[rows] = np.asarray(u, float).reshape(-1, 2)
        return xyz, uv, None if project is None else self.views.project(xyz, self.view[cid])

    def after(self, cid: np.ndarray, t: np.ndarray) -> np.ndarray:
        """The sample each point ``(cid[i], t[i])`` comes right after (-1:
        before the first); the samples are sorted by (curve, t)."""
        scale = 0.5 / (self.t1 - self.t0)
        keys = self.cid + (self.t - self.t0[self.cid]) * scale[self.cid]
        return np.searchsorted(keys, cid + (t - self.t0[cid]) * scale[cid], side="right") - 1

    def owners(self, rows: np.ndarray | slice) -> tuple[np.ndarray, np.ndarray]:
        """Owner nodes and ownership codes of samples ``rows``."""
        c = self.cid[rows]
        return self.owner[c], self.kind[c]


class _Initial:
    """The initial samples of ``batch`` (at ``t``, ``k`` a curve) in its local
    frame: view-independent, so kept with a cached batch
    (``lgraph.families.cache.derived``)."""

    def __init__(self, batch: CurveBatch, t: np.ndarray, k: int) -> None:
        self.batch, self.t, self.k = batch, t, k

    def __call__(self) -> tuple[np.ndarray, np.ndarray | None]:
        idx = np.repeat(np.arange(len(self.batch)), self.k)
        x, u = self.batch.evaluate(idx, self.t)
        x = np.asarray(x, dtype=float).reshape(-1, 3)
        return x, None if u is None else np.asarray(u, float).reshape(-1, 2)


def seg_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points ``p`` to segments ``ab`` (all (n, 2)).

    >>> p = np.array([[1.0, 1.0], [3.0, 0.0]])
    >>> seg_distance(p, np.zeros((2, 2)), np.array([[2.0, 0.0], [2.0, 0.0]]))
    array([1., 1.])
    """
    abx, aby = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    apx, apy = p[:, 0] - a[:, 0], p[:, 1] - a[:, 1]
    den = abx * abx + aby * aby
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(den > 0, (apx * abx + apy * aby) / den, 0.0)
    np.clip(s, 0.0, 1.0, out=s)
    return np.hypot(apx - s * abx, apy - s * aby)


def merge(s: Samples, after: np.ndarray, cid, t, xyz, uv, xy, hidden=None) -> np.ndarray:  # noqa: ANN001
    """Insert new samples into ``s``, each right after sample ``after[i]``
    (``after`` sorted; equal entries keep their given order).  Returns a mask of
    the new points in the merged arrays.

    New points without ``hidden`` flags are marked fresh (untested).  Same
    result as ``np.insert`` on every array, but the order is worked out once
    and each array costs one gather (``np.take``).
    """
    n, k = len(s.t), len(after)
    new = np.zeros(n + k, dtype=bool)
    new[np.asarray(after) + 1 + np.arange(k)] = True
    order = np.empty(n + k, dtype=np.int64)  # merged row -> row of [old; new]
    order[~new] = np.arange(n)
    order[new] = np.arange(n, n + k)

    def put(a: np.ndarray, v: np.ndarray | float | bool) -> np.ndarray:
        if not isinstance(v, np.ndarray) or v.shape != (k,) + a.shape[1:]:
            v = np.full((k,) + a.shape[1:], v, dtype=a.dtype)
        return np.take(np.concatenate([a, v]), order, axis=0)

    s.cid = put(s.cid, cid)
    s.t = put(s.t, t)
    s.xyz = put(s.xyz, xyz)
    s.xy = put(s.xy, xy)
    s.uv = put(s.uv, uv)
    s.hidden = put(s.hidden, False if hidden is None else hidden)
    s.cause = put(s.cause, -1)
    s.fresh = put(s.fresh, hidden is None)
    return new


def refine(s: Samples, abs_tol: float | np.ndarray, settled: np.ndarray | None = None) -> None:
    """Refine until every chord's midpoint is within ``abs_tol`` of the curve
    (a length, or one per curve: each view has its own).

    Chords between two ``settled`` samples (a mask) are left as they are.

    A chord whose deviation is ``dev`` is split into ``m = ceil(sqrt(dev /
    abs_tol))`` equal parts at once (the deviation of a smooth curve shrinks
    with the square of the chord).  The first split uses the deviation
    predicted by the second differences of the samples where they are evenly
    spaced (the initial samples are), at no evaluation; then every chord is
    checked at its midpoint and the ones that fail are split again, until
    none fails.
    """
    span = s.t1 - s.t0
    check = s.cid[1:] == s.cid[:-1]
    if settled is not None:
        check &= ~(settled[1:] & settled[:-1])
    dev = _predicted_deviation(s.xy, s.cid, s.t)
    split = np.flatnonzero(check & (dev > _at(abs_tol, s.cid[:-1])))
    if len(split):
        new = _split(s, split, dev[split], abs_tol)
        flag = np.ones(len(new), dtype=bool)  # sub-chords of checked chords
        flag[~new] = np.append(check, False)
        check = flag[:-1]
    for _ in range(tol.MAX_REFINE_PASSES):
        seg = check & (s.cid[1:] == s.cid[:-1])
        seg &= (s.t[1:] - s.t[:-1]) > 1e-12 * span[s.cid[:-1]]
        idx = np.flatnonzero(seg)
        if not len(idx):
            return
        tm = 0.5 * (s.t[idx] + s.t[idx + 1])
        _, _, xy = s.evaluate(s.cid[idx], tm, True)
        dev = seg_distance(xy, np.take(s.xy, idx, axis=0), np.take(s.xy, idx + 1, axis=0))
        split = ~(dev <= _at(abs_tol, s.cid[idx]))  # also splits where dev is NaN
        if not split.any():
            return
        new = _split(s, idx[split], dev[split], abs_tol)
        check = new[:-1] | new[1:]


class PointBudgetError(ValueError):
    """A render would hold more than ``MAX_POINTS`` sample points.

    Raised before the initial sampling when the curves' first samples alone
    exceed the budget; before any ray test when the deviations of the first
    samples' chords predict a refined count more than
    ``POINTS_PREDICTION_MARGIN`` times the budget
    (:func:`~lgraph.render.prediction.predict_points`);
    and, the exact backstop, before every refinement pass that would exceed
    it.  The message names the family and node that would take most of the
    new samples and the knob that helps (the tolerance, the line counts,
    ``contour=False``).
    """


def check_points(
    n: int, refining: bool = False, culprit: str = "", predicted: bool = False
) -> None:
    """Refuse, before any work, a sampling that would hold more than
    ``MAX_POINTS`` points (the render's memory budget); ``predicted``: ``n``
    is the estimate of :func:`~lgraph.render.prediction.predict_points`,
    refused when it is more than ``POINTS_PREDICTION_MARGIN`` times the
    budget.

    >>> check_points(10)
    >>> check_points(10**9)  # doctest: +IGNORE_EXCEPTION_DETAIL
    Traceback (most recent call last):
    PointBudgetError: Scene.render: the curves need 1000000000 sample points; ...
    """
    limit = tol.MAX_POINTS * (tol.POINTS_PREDICTION_MARGIN if predicted else 1)
    if n > limit:
        why = (
            "raise tolerance or draw fewer lines"
            if refining
            else "draw fewer lines (lower the counts of the families)"
        )
        need = f"need {n} sample points"
        if predicted:  # refined samples grow as 1 / sqrt(tolerance)
            need = (
                f"would need about {n} sample points (predicted from the first "
                f"{tol.INITIAL_SAMPLES} samples of each curve, before any refinement)"
            )
            why = (
                f"raise tolerance (about {(n / tol.MAX_POINTS) ** 2:.3g} times) or draw fewer lines"
            )
        raise PointBudgetError(
            f"Scene.render: the curves {need}{culprit}; the limit is "
            f"{tol.MAX_POINTS} (lgraph._tolerance.MAX_POINTS); {why}"
        )


def _culprit(s: Samples, idx: np.ndarray, m: np.ndarray) -> str:
    """Which family of which node the split of chords ``idx`` into ``m``
    parts each would add most samples to, for the budget's message."""
    part = s.part[s.cid[idx]]
    added = np.bincount(part, weights=m - 1, minlength=len(s.parts))
    p = int(np.argmax(added))
    batch, node, _, first = s.parts[p]
    names = batch.curve_family
    family, mine = batch.family, added[p]
    if names is not None:  # the family of most of the part's new samples
        rows = s.cid[idx][part == p] - first
        fams, inverse = np.unique(np.asarray(names, dtype=object)[rows], return_inverse=True)
        per = np.bincount(inverse.ravel(), weights=(m - 1)[part == p], minlength=len(fams))
        family, mine = str(fams[np.argmax(per)]), per.max()
    what = type(batch.surface).__name__ if batch.surface is not None else "a free curve"
    share = mine / max(added.sum(), 1)
    knob = "; contour=False on that node leaves its contour out" if family == "contour" else ""
    return (
        f" ({100 * share:.0f} % of the new ones for family {family!r} of node {node}, {what}{knob})"
    )


def _predicted_deviation(xy: np.ndarray, cid: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Deviation of every chord from its curve predicted by the second
    differences at its two ends (``|p[i-1] - 2 p[i] + p[i+1]| / 8`` across the
    secant ``p[i+1] - p[i-1]``, where ``t`` is evenly spaced); 0 where there
    is none (curve ends, uneven spacing)."""
    dev = np.zeros(max(len(xy) - 1, 0))
    if len(xy) < 3:
        return dev
    d2 = xy[:-2] - 2 * xy[1:-1] + xy[2:]
    sec = xy[2:] - xy[:-2]
    with np.errstate(invalid="ignore", divide="ignore"):
        perp = np.abs(d2[:, 0] * sec[:, 1] - d2[:, 1] * sec[:, 0]) / (8 * np.hypot(*sec.T))
    dt = np.diff(t)
    even = np.abs(dt[1:] - dt[:-1]) <= 1e-9 * (np.abs(dt[1:]) + np.abs(dt[:-1]))
    perp[~((cid[:-2] == cid[1:-1]) & (cid[1:-1] == cid[2:]) & even & np.isfinite(perp))] = 0.0
    dev[1:] = perp  # chord j from its first end, sample j
    np.maximum(dev[:-1], perp, out=dev[:-1])  # and from its second end, sample j + 1
    return dev


def _at(abs_tol: float | np.ndarray, cid: np.ndarray) -> float | np.ndarray:
    """The chord tolerance for curves ``cid``."""
    return abs_tol if np.ndim(abs_tol) == 0 else abs_tol[cid]


def _split(s: Samples, idx: np.ndarray, dev: np.ndarray, abs_tol: float | np.ndarray) -> np.ndarray:
    """Split chords ``idx`` (deviation ``dev``) into equal parts in ``t``;
    returns the mask of new samples."""
    with np.errstate(invalid="ignore"):
        m = np.ceil(1.05 * np.sqrt(dev / _at(abs_tol, s.cid[idx])))
    m = np.clip(np.nan_to_num(m, nan=2.0), 2, tol.MAX_SPLIT).astype(np.int64)
    total = len(s.t) + int(m.sum() - len(m))
    if total > tol.MAX_POINTS:
        check_points(total, refining=True, culprit=_culprit(s, idx, m))
    after = np.repeat(idx, m - 1)
    j = np.arange(len(after)) - np.repeat(np.cumsum(m - 1) - (m - 1), m - 1) + 1
    frac = j / np.repeat(m, m - 1)
    t = s.t[after] + frac * (s.t[after + 1] - s.t[after])
    c = s.cid[after]
    xyz, uv, xy = s.evaluate(c, t, True)
    new = merge(s, after, c, t, xyz, uv, xy)
    return new
