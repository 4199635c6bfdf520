"""Adaptive sampling of curve batches (the renderer's first stage).

Samples of one batch live in flat arrays sorted by (curve index, t); every
chord's midpoint is kept within the chord tolerance of the true projected
curve.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import attrs
import numpy as np

from . import _tolerance as tol
from .geometry.transforms import Transform
from .projectors import Projector
from .surfaces._base import OFF

if TYPE_CHECKING:
    from .curves import CurveBatch

__all__ = ["Samples", "evaluate", "initial_samples", "merge", "refine", "owner_arrays"]


@attrs.define
class Samples:
    """Samples of one batch: flat arrays sorted by (curve index, t)."""

    entry: int
    batch: CurveBatch
    node: int
    transform: Transform
    cid: np.ndarray
    t: np.ndarray
    xyz: np.ndarray  # world
    uv: np.ndarray | None
    xy: np.ndarray
    hidden: np.ndarray = attrs.field(default=None)
    cause: np.ndarray = attrs.field(default=None)  # grouped quadric hiding each sample, or -1
    fresh: np.ndarray = attrs.field(default=None)  # not yet tested for visibility

    def __attrs_post_init__(self) -> None:
        n = len(self.t)
        self.hidden = np.zeros(n, dtype=bool)
        self.cause = np.full(n, -1, dtype=np.int64)
        self.fresh = np.ones(n, dtype=bool)


def evaluate(
    batch: CurveBatch,
    transform: Transform,
    projector: Projector | None,
    cid: np.ndarray,
    t: np.ndarray,
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """World points, parameters (or None) and projections of curves ``cid`` at
    ``t``; without a projector the projections are None."""
    xyz, uv = batch.evaluate(cid, t)
    xyz = np.asarray(xyz, dtype=float).reshape(-1, 3)
    if not transform.is_identity:
        xyz = transform.apply(xyz)
    return (
        xyz,
        (None if uv is None else np.asarray(uv, float).reshape(-1, 2)),
        None if projector is None else projector.project(xyz),
    )


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


def initial_samples(
    entry: int, batch: CurveBatch, node: int, transform: Transform, projector: Projector
) -> Samples:
    m = len(batch)
    k = tol.INITIAL_SAMPLES
    frac = np.linspace(0.0, 1.0, k)
    cid = np.repeat(np.arange(m), k)
    t = (batch.t0[:, None] + (batch.t1 - batch.t0)[:, None] * frac).ravel()
    xyz, uv, xy = evaluate(batch, transform, projector, cid, t)
    return Samples(entry, batch, node, transform, cid, t, xyz, uv, xy)


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

    def put(a: np.ndarray, v: np.ndarray) -> np.ndarray:
        v = np.broadcast_to(np.asarray(v, a.dtype), (k,) + a.shape[1:])
        return np.take(np.concatenate([a, v]), order, axis=0)

    s.cid = put(s.cid, cid)
    s.t = put(s.t, t)
    s.xyz = put(s.xyz, xyz)
    s.xy = put(s.xy, xy)
    if s.uv is not None:
        s.uv = put(s.uv, uv)
    s.hidden = put(s.hidden, False if hidden is None else hidden)
    s.cause = put(s.cause, -1)
    s.fresh = put(s.fresh, hidden is None)
    return new


def refine(
    s: Samples, projector: Projector, abs_tol: float, settled: np.ndarray | None = None
) -> None:
    """Refine until every chord's midpoint is within ``abs_tol`` of the curve.

    Chords between two ``settled`` samples (a mask) are left as they are.

    A chord whose deviation is ``dev`` is split into ``m = ceil(sqrt(dev /
    abs_tol))`` equal parts at once (the deviation of a smooth curve shrinks
    with the square of the chord).  The first split uses the deviation
    predicted by the second differences of the samples (uniformly spaced on
    each curve, as :func:`initial_samples` makes them), at no evaluation;
    then every chord is checked at its midpoint and the ones that fail are
    split again, until none fails.
    """
    span = s.batch.t1 - s.batch.t0
    check = s.cid[1:] == s.cid[:-1]
    if settled is not None:
        check &= ~(settled[1:] & settled[:-1])
    dev = _predicted_deviation(s.xy, s.cid)
    split = np.flatnonzero(check & (dev > abs_tol))
    if len(split):
        new = _split(s, projector, split, dev[split], abs_tol)
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
        _, _, xy = evaluate(s.batch, s.transform, projector, s.cid[idx], tm)
        dev = seg_distance(xy, s.xy[idx], s.xy[idx + 1])
        split = ~(dev <= abs_tol)  # also splits where dev is NaN
        if not split.any():
            return
        new = _split(s, projector, idx[split], dev[split], abs_tol)
        check = new[:-1] | new[1:]


def _predicted_deviation(xy: np.ndarray, cid: np.ndarray) -> np.ndarray:
    """Deviation of every chord from its curve predicted by the second
    differences at its two ends (``|p[i-1] - 2 p[i] + p[i+1]| / 8`` across the
    secant ``p[i+1] - p[i-1]``); 0 where there is none (curve ends)."""
    dev = np.zeros(max(len(xy) - 1, 0))
    if len(xy) < 3:
        return dev
    d2 = xy[:-2] - 2 * xy[1:-1] + xy[2:]
    sec = xy[2:] - xy[:-2]
    with np.errstate(invalid="ignore", divide="ignore"):
        perp = np.abs(d2[:, 0] * sec[:, 1] - d2[:, 1] * sec[:, 0]) / (8 * np.hypot(*sec.T))
    perp[~((cid[:-2] == cid[1:-1]) & (cid[1:-1] == cid[2:]) & np.isfinite(perp))] = 0.0
    dev[1:] = perp  # chord j from its first end, sample j
    np.maximum(dev[:-1], perp, out=dev[:-1])  # and from its second end, sample j + 1
    return dev


def _split(
    s: Samples, projector: Projector, idx: np.ndarray, dev: np.ndarray, abs_tol: float
) -> np.ndarray:
    """Split chords ``idx`` (deviation ``dev``) into equal parts in ``t``;
    returns the mask of new samples."""
    with np.errstate(invalid="ignore"):
        m = np.ceil(1.05 * np.sqrt(dev / abs_tol))
    m = np.clip(np.nan_to_num(m, nan=2.0), 2, tol.MAX_SPLIT).astype(np.int64)
    after = np.repeat(idx, m - 1)
    j = np.arange(len(after)) - np.repeat(np.cumsum(m - 1) - (m - 1), m - 1) + 1
    frac = j / np.repeat(m, m - 1)
    t = s.t[after] + frac * (s.t[after + 1] - s.t[after])
    c = s.cid[after]
    xyz, uv, xy = evaluate(s.batch, s.transform, projector, c, t)
    new = merge(s, after, c, t, xyz, uv, xy)
    if len(s.t) > tol.MAX_POINTS:
        raise ValueError(
            f"render: more than {tol.MAX_POINTS} points needed; lower the number of "
            "lines or raise the tolerance"
        )
    return new


def owner_arrays(s: Samples, n: int) -> tuple[np.ndarray, np.ndarray]:
    if s.batch.surface is None:
        return np.full(n, -1), np.full(n, OFF, np.int8)
    return np.full(n, s.node), np.full(n, s.batch.own, np.int8)
