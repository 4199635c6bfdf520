"""The cost of the ray tests, predicted before they run (issue #25, part 5).

The numeric ray test of a parametrized surface (:mod:`lgraph.surfaces.parametric._hits`)
starts Newton's method in every patch box a ray meets; its cost grows with
the rays tested times the boxes each ray meets (a surface that oscillates
or winds over itself meets dozens a ray, an ordinary one a few).  Before the
first ray tests, :func:`probe_ray_tests` tests an evenly spread probe of the
first samples, counts the boxes their rays meet per surface, and multiplies
by the number of rays predicted: the samples the refinement is predicted to
reach (:func:`predict_points`, aliased curves probed densely) and the later
stages' ray tests (:func:`later_work`: the sheets counted in front of
hidden samples, the visibility flips located by K-section); a prediction
over ``MAX_RAY_BOXES`` is refused at once with :class:`RayBudgetError`,
naming the costly part, the node whose boxes cost, the family that takes
most samples and the knobs that help.  The check is repeated with what is
known later: after the first samples' ray tests (the flips between them),
before the refined samples' ray tests, and before the flips are located
(the flips counted).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from .. import _tolerance as tol
from ..surfaces._base import numeric_ray_test
from ..surfaces.parametric._boxes import set_meter
from .brackets import sections
from .sampling import Samples, _at, _culprit, _predicted_deviation, check_points

__all__ = ["RayBudgetError", "RayMeter", "Work", "later_work", "predict_points", "probe_ray_tests"]


class RayBudgetError(ValueError):
    """The ray tests of a render are predicted to meet more than
    ``MAX_RAY_BOXES`` patch boxes of numeric surfaces (minutes of work).

    Raised before the work, from a probe of ``RAY_PROBE`` samples (or the
    ray tests so far) and the predicted numbers of samples, hidden samples
    and visibility flips; the message names each costly part with its share
    and knob (fewer lines or a larger tolerance for the samples;
    ``contour=True`` or ``hidden_lines=False`` for the sheets counted at
    every hidden sample; fewer lines for the flips), the node whose patch
    boxes cost (a narrower ``u1_range``/``u2_range`` for a surface winding
    over itself) and the family that takes most of its samples.
    """


class RayMeter:
    """The patch boxes met by the metered ray tests of one render, per surface."""

    def __init__(self, nodes: Sequence[Any]) -> None:
        self.nodes = nodes
        self.boxes: dict[int, int] = {}
        self.rays = 0

    def run(self, classify: Callable[..., None], s: Any, vis: Any, rows: Any = None) -> None:
        """``classify(s, vis, rows)`` (all fresh samples when ``rows`` is None), metered."""
        n = int(s.fresh.sum()) if rows is None else len(rows)
        meter: list[tuple[int, int]] = []
        set_meter(meter)
        try:
            classify(s, vis, rows)
        finally:
            set_meter(None)
        self.rays += n
        for key, k in meter:
            self.boxes[key] = self.boxes.get(key, 0) + k

    def check(
        self,
        samples: int,
        source: str,
        later: Callable[[], Sequence[Work]] | None = None,
        s: Any = None,
    ) -> None:
        """Refuse ray tests of ``samples`` more samples, and the ray tests of
        the later stages (``later()``: counting sheets, locating flips,
        :func:`later_work`; asked only when numeric surfaces were metered),
        predicted to meet more than ``MAX_RAY_BOXES`` boxes (at the boxes a
        ray metered so far); ``s``: the samples, whose predicted counts
        (``s.predicted``) name the family that takes most."""
        if not self.rays or not self.boxes:
            return
        total = sum(self.boxes.values())
        per_ray = total / self.rays
        parts = [w for w in (later() if later is not None else ()) if w.rays > 0]
        if samples:
            what = f"the ray tests of {samples} {source} samples"
            parts.insert(0, Work(samples, what, _FEWER, "samples"))
        rays = sum(w.rays for w in parts)
        work = rays * per_ray
        if work <= tol.MAX_RAY_BOXES:
            return
        key = max(self.boxes, key=self.boxes.__getitem__)
        nodes = self.nodes
        node = next((k for k, n in enumerate(nodes) if id(n.surface) == key), None)
        what = "a numeric surface" if node is None else f"node {node} ({_short(nodes[node].item)})"
        per = self.boxes[key] / self.rays
        if len(parts) == 1:
            head, knobs = parts[0].what, parts[0].knob
        else:
            head = ", ".join(w.what for w in parts[:-1]) + " and " + parts[-1].what
            knobs = "; ".join(
                f"{100 * w.rays / rays:.0f} % are {w.what}: {w.knob}"
                for w in sorted(parts, key=lambda w: -w.rays)
            )
        raise RayBudgetError(
            f"Scene.render: {head} would meet about {work:.3g} patch boxes of numeric "
            f"surfaces ({per_ray:.3g} a ray, measured on the ray tests of {self.rays} samples); "
            f"the limit is {tol.MAX_RAY_BOXES} (lgraph._tolerance.MAX_RAY_BOXES); {knobs}; most "
            f"are the ray tests against the patch boxes of {what}, {per:.3g} a ray (an ordinary "
            "surface meets a few; one that oscillates or winds over itself, dozens: narrow "
            "that surface's u1_range/u2_range and repeat it with transforms)"
            f"{_family(s, node)}"
        )


_FEWER = "draw fewer lines or raise tolerance (fewer samples)"


class Work(NamedTuple):
    """Ray tests of a later stage of the render, predicted: how many, what
    they do, and the knob that makes them fewer."""

    rays: float
    what: str
    knob: str
    kind: str  # "samples", "sheets" or "flips"


def later_work(
    s: Any,
    vis: Any,
    nodes: Sequence[Any],
    hidden_lines: bool,
    every: bool,
    samples: float | None = None,
    tested: np.ndarray | None = None,
    exact: bool = False,
) -> list[Work]:
    """The ray tests of the stages after the samples' own, predicted from
    the samples tested so far (``tested``: their rows; all tested samples
    when None): counting the sheets in front of every hidden sample (with
    hidden lines, when ``every``: a hiding node that draws no contour, or
    surfaces meeting without their intersection drawn), at the hidden
    fraction of the tested samples times ``samples`` (the samples predicted,
    or those there are); and locating the visibility flips that no margin
    search closes (those not caused by an ellipsoid), each by K-section to
    ``BISECTION_RTOL`` of its curve's span (:func:`~lgraph.render.flips.sections`).
    The flips are those between the tested samples, times the aliasing
    scale of their curves (``s.alias``: an aliased curve's flips, like its
    samples, grow with its resolution) unless ``exact`` (the samples are
    all there: the flips are counted).  Not predicted: the changes of depth
    located along hidden runs, and the sheets counted at the ends of hidden
    runs when not ``every``."""
    out = []
    if tested is None:
        tested = np.flatnonzero(~s.fresh)
    if not len(tested):
        return out
    n = len(s.t) if samples is None else samples
    if hidden_lines and every:
        hidden = float(s.hidden[tested].mean()) * n
        why = [j for j in getattr(vis, "twins", {}) if not nodes[j].contour]
        knob = (
            f"contour=True on node {why[0]} (a hiding node without its contour makes every "
            "hidden sample counted, not the ends of hidden runs), or hidden_lines=False"
            if why
            else "intersections=True (surfaces that meet without their intersection drawn "
            "make every hidden sample counted), or hidden_lines=False"
        )
        what = f"counting the sheets in front of about {hidden:.0f} hidden samples"
        out.append(Work(hidden, what, knob, "sheets"))
    tested_all = bool((~s.fresh).all()) and len(tested) == len(s.t)
    if not tested_all:
        return out  # flips need neighbouring samples, all tested
    f = np.flatnonzero((s.cid[1:] == s.cid[:-1]) & (s.hidden[1:] != s.hidden[:-1]))
    hid_end = np.where(s.hidden[f], f, f + 1)
    f = f[s.cause[hid_end] < 0]  # flips caused by an ellipsoid: margin searches
    if not len(f):
        return out
    c = s.cid[f]
    weight = np.ones(len(f)) if exact or s.alias is None else s.alias[c]
    per_curve = np.bincount(s.cid, minlength=len(s.t0)) if exact else s.predicted
    k = sections(s.view[c], np.ones(len(c), dtype=bool), s.views.k, vis).astype(float)
    flips = float(weight.sum())
    k = np.maximum(k, 2.0)
    bits = np.log2(1.0 / (tol.BISECTION_RTOL * np.maximum(per_curve[c], 1.0)))
    rays = float((weight * np.ceil(np.maximum(bits, 1.0) / np.log2(k)) * (k - 1)).sum())
    out.append(
        Work(
            rays,
            f"locating about {flips:.0f} visibility flips ({rays / flips:.3g} ray tests each)",
            "draw fewer lines (the flips are where the curves cross the surfaces' outlines; "
            "hidden_lines=False does not remove them)",
            "flips",
        )
    )
    return out


def probe_ray_tests(
    s: Any,
    vis: Any,
    meter: RayMeter,
    predicted: int,
    classify: Callable[..., None],
    later: Callable[[np.ndarray], Sequence[Work]] | None = None,
    counting: bool = False,
) -> None:
    """Before the first ray tests: test an evenly spread probe of
    ``RAY_PROBE`` fresh samples of ``s`` (kept: they are not tested again)
    and refuse the render when ``predicted`` samples, and the ray tests
    ``later(probe rows)`` of the later stages, would meet more than
    ``MAX_RAY_BOXES`` patch boxes.

    Renders predicted to need so few samples that even ``HIT_MAX_CANDIDATES
    / HIT_CHUNK_RAYS`` boxes a ray (the most a chunk of rays may meet) per
    numeric surface stay within the budget are not probed (twice the
    samples when ``counting``: every hidden sample's sheets are counted
    too)."""
    fresh = np.flatnonzero(s.fresh)
    numeric = sum(1 for n in meter.nodes if n.hides and numeric_ray_test(n.surface))
    most = tol.HIT_MAX_CANDIDATES / tol.HIT_CHUNK_RAYS * (2 if counting else 1)
    if len(fresh) <= tol.RAY_PROBE or predicted * most * numeric <= tol.MAX_RAY_BOXES:
        return
    rows = fresh[np.linspace(0, len(fresh) - 1, tol.RAY_PROBE).astype(np.int64)]
    meter.run(classify, s, vis, rows)
    meter.check(predicted, "predicted", None if later is None else lambda: later(rows), s)


def _family(s: Any, node: int | None) -> str:
    """Which family of node ``node`` takes most predicted samples (from
    ``s.predicted``), for the messages; '' when unknown."""
    if s is None or node is None or getattr(s, "predicted", None) is None:
        return ""
    rows, fams = [], []
    for part in s.parts:
        if part.node == node:
            rows.append(np.arange(part.first, part.first + len(part.batch)))
            names = part.batch.curve_family
            if names is None:
                names = [part.batch.family] * len(part.batch)
            fams.append(np.asarray(names, dtype=object))
    if not rows:
        return ""
    rows = np.concatenate(rows)
    u, inverse = np.unique(np.concatenate(fams), return_inverse=True)
    inverse = inverse.ravel()
    weights = np.bincount(inverse, weights=s.predicted[rows], minlength=len(u))
    i = int(np.argmax(weights))
    share = weights[i] / max(weights.sum(), 1.0)
    alias = getattr(s, "alias", None)
    aliased = ""
    if alias is not None and np.any(alias[rows[inverse == i]] > 1):
        aliased = (
            f", whose curves oscillate faster than their first {tol.INITIAL_SAMPLES} samples "
            "resolve"
        )
    return (
        f"; family {str(u[i])!r} of node {node} takes {100 * share:.0f} % of its predicted "
        f"samples{aliased}"
    )


def predict_points(s: Samples, abs_tol: float | np.ndarray) -> int:
    """The number of samples :func:`refine` is predicted to reach, from the
    first samples alone (before any ray test or refinement); a prediction
    more than ``POINTS_PREDICTION_MARGIN`` times ``MAX_POINTS`` is refused
    at once (PointBudgetError naming the family and node that would take
    most samples).

    A chord deviating ``dev`` from its curve needs about ``sqrt(dev /
    abs_tol)`` pieces (the deviation of a smooth curve shrinks with the
    square of the chord; ``dev`` from the second differences of the evenly
    spaced first samples, as in :func:`refine`).  A chord's prediction is
    capped at ``MAX_SPLIT * MAX_REFINE_PASSES`` pieces, what refinement adds
    at most to a chord whose deviation never shrinks (a jump of the curve),
    so jumps are not taken for smooth curves needing millions of samples.

    Curves that oscillate faster than their first samples resolve (aliased)
    need far more: a few curves of every family are sampled densely
    (:func:`_alias_scale`), and the families whose need grows with the
    density are predicted from the densest level.  ``s.predicted`` keeps the
    prediction per curve and ``s.alias`` the aliased curves' scale (None:
    none is), for the later budgets (:mod:`lgraph.render.prediction`).

    >>> from lgraph import Curve, ParallelProjector, Transform
    >>> c = Curve(lambda t: np.stack([np.cos(t), np.sin(t), 0 * t], -1), 0, 6.28)
    >>> s = Samples([(0, c.batch(), Transform())], ParallelProjector(direction=(0, 0, 1)))
    >>> predict_points(s, 1e-6)  # refine(s, 1e-6) then gives 4097
    2337
    >>> w = Curve(lambda t: np.stack([t, 0.01 * np.sin(400 * t), 0 * t], -1), 0, 6.28)
    >>> s = Samples([(0, w.batch(), Transform())], ParallelProjector(direction=(0, 0, 1)))
    >>> predict_points(s, 1e-5) > 15000  # 400 waves: refine(s, 1e-5) then gives 22923
    True
    """
    dev = _predicted_deviation(s.xy, s.cid, s.t)
    within = s.cid[1:] == s.cid[:-1]
    cap = tol.MAX_SPLIT * tol.MAX_REFINE_PASSES
    with np.errstate(invalid="ignore", divide="ignore"):
        need = 1.05 * np.sqrt(dev / _at(abs_tol, s.cid[:-1]))
    need = np.where(within, np.clip(np.nan_to_num(need, nan=0.0, posinf=0.0), 0, cap), 0.0)
    m = np.clip(np.ceil(need), 1, cap).astype(np.int64)
    scale = _alias_scale(s, abs_tol, need, m)
    s.alias = scale
    mm = m if scale is None else np.where(within, m * scale[s.cid[:-1]], 1.0)
    total = len(s.t) + int(np.ceil((mm - 1).sum()))
    s.predicted = 1.0 + np.bincount(s.cid[:-1][within], weights=mm[within], minlength=len(s.t0))
    if total > tol.POINTS_PREDICTION_MARGIN * tol.MAX_POINTS:
        idx = np.flatnonzero(mm > 1)
        culprit = _culprit(s, idx, mm[idx])
        if scale is not None and _culprit_aliased(s, idx, mm[idx], scale):
            culprit = culprit[:-1] + _ALIASED + ")"
        check_points(total, refining=True, culprit=culprit, predicted=True)
    return total


_ALIASED = (
    "; its curves oscillate faster than their first "
    f"{tol.INITIAL_SAMPLES} samples resolve, predicted from denser samples of a few of them"
)


def _culprit_aliased(s: Samples, idx: np.ndarray, m: np.ndarray, scale: np.ndarray) -> bool:
    """Whether the part taking most new samples of chords ``idx`` is aliased
    (its prediction scaled by :func:`_alias_scale`)."""
    part = s.part[s.cid[idx]]
    p = int(np.argmax(np.bincount(part, weights=m - 1, minlength=len(s.parts))))
    rows = s.cid[idx][part == p]
    return bool(np.any(scale[rows] > 1))


def _alias_scale(
    s: Samples, abs_tol: float | np.ndarray, need: np.ndarray, m: np.ndarray
) -> np.ndarray | None:
    """Per curve, how many times more samples it needs than its first
    samples' chords predict (``need``: pieces a chord needs, ``m``: their
    ceilings), or None when no probed family is aliased.

    ``ALIAS_PROBE_CURVES`` curves of every family of every batch (evenly
    spread; not exact ellipses, which cannot alias) are sampled
    ``ALIAS_STEP`` times as densely as at first, in one evaluation call a
    batch.  The need of a curve (the sum of ``need`` over its chords) stays
    about the same at any density once the curve is resolved (on the
    gallery: within 1.14 times); a curve whose need grows more than
    ``ALIAS_GROWTH`` times is aliased, and is sampled ``ALIAS_STEP`` times
    denser again, ``ALIAS_LEVELS`` levels in all (an aliased sampling may
    look smooth at one density and not at the next, so every level is
    taken), its need the largest of any level.  A family with an aliased
    probe is scaled by its probes' counts (the first count with the need of
    the densest level) over their first counts.  Ordinary scenes pay one
    evaluation call a batch of ``4 * 96`` points (each level's points hold
    the last level's); an oscillation faster
    than the densest level (``(INITIAL_SAMPLES - 1) * ALIAS_STEP **
    ALIAS_LEVELS`` chords a curve) resolves is still predicted too low.
    """
    k = tol.INITIAL_SAMPLES
    n_curves = len(s.t0)
    if len(s.t) != n_curves * k:  # not the first samples
        return None
    cand = s.t1 > s.t0
    if s.ellipses is not None:
        cand &= ~np.isfinite(s.ellipses[:, 0, 0])
    if not cand.any():
        return None
    fam, n_fam = _family_codes(s)
    probe = _probe_curves(fam, cand)
    per = np.append(need, 0.0).reshape(n_curves, k)[:, :-1].sum(axis=1)[probe]
    first = 1 + np.append(m, 0).reshape(n_curves, k)[:, :-1].sum(axis=1)[probe]
    cap = tol.MAX_SPLIT * tol.MAX_REFINE_PASSES
    est = per.copy()
    flagged = np.zeros(len(probe), dtype=bool)
    cur = np.arange(len(probe))
    step = tol.ALIAS_STEP
    # the last level's projections (every ``step``-th point of the next level)
    known = s.xy.reshape(n_curves, k, 2)[probe]
    n = k
    for level in range(tol.ALIAS_LEVELS):
        n = (n - 1) * step + 1
        if len(cur) * n > tol.ALIAS_MAX_POINTS:  # the densest levels: fewer curves
            keep = np.unique(np.linspace(0, len(cur) - 1, max(tol.ALIAS_MAX_POINTS // n, 1)))
            cur, known = cur[keep.astype(np.int64)], known[keep.astype(np.int64)]
        c = probe[cur]
        frac = np.linspace(0.0, 1.0, n)
        t = (s.t0[c][:, None] + (s.t1 - s.t0)[c][:, None] * frac).ravel()
        cc = np.repeat(c, n)
        new = np.tile(np.arange(n) % step != 0, len(c))  # the points not known yet
        xy = np.empty((len(t), 2))
        xy[~new] = known.reshape(-1, 2)
        xy[new] = s.evaluate(cc[new], t[new], True)[2]
        dev = _predicted_deviation(xy, cc, t)
        with np.errstate(invalid="ignore", divide="ignore"):
            q = 1.05 * np.sqrt(dev / _at(abs_tol, cc[:-1]))
        q = np.clip(np.nan_to_num(q, nan=0.0, posinf=0.0), 0, cap)  # a jump: as at first
        got = np.append(q, 0.0).reshape(len(c), n)[:, :-1].sum(axis=1)
        known = xy.reshape(len(c), n, 2)
        if level == 0:  # a resolved curve's need stays put (the gallery: within 1.14)
            keep = got > tol.ALIAS_GROWTH * per[cur] + 1.0
            flagged[cur] = keep
            cur, got, known = cur[keep], got[keep], known[keep]
            if not len(cur):
                return None
        est[cur] = np.maximum(est[cur], got)
    if not flagged.any():
        return None
    counts = np.where(flagged, first + np.maximum(est - per, 0.0), first)
    f = fam[probe]
    aliased = np.bincount(f, weights=flagged, minlength=n_fam) > 0
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.bincount(f, weights=counts, minlength=n_fam) / np.bincount(
            f, weights=first, minlength=n_fam
        )
    ratio = np.where(aliased & (ratio > 1), ratio, 1.0)
    return ratio[fam]


def _family_codes(s: Samples) -> tuple[np.ndarray, int]:
    """Per curve, a code of its (batch part, family), and the number of codes."""
    fam = np.empty(len(s.t0), dtype=np.int64)
    n = 0
    for part in s.parts:
        rows = slice(part.first, part.first + len(part.batch))
        names = part.batch.curve_family
        if names is None:
            fam[rows] = n
            n += 1
        else:
            u, inverse = np.unique(np.asarray(names, dtype=object), return_inverse=True)
            fam[rows] = n + inverse.ravel()
            n += len(u)
    return fam, n


def _probe_curves(fam: np.ndarray, cand: np.ndarray) -> np.ndarray:
    """Up to ``ALIAS_PROBE_CURVES`` curves of every family code ``fam`` among
    the curves ``cand`` (a mask), evenly spread; sorted."""
    c = np.flatnonzero(cand)
    c = c[np.argsort(fam[c], kind="stable")]
    _, start, count = np.unique(fam[c], return_index=True, return_counts=True)
    p = tol.ALIAS_PROBE_CURVES
    pos = start[:, None] + ((np.arange(p) + 0.5) * count[:, None] / p).astype(np.int64)
    return np.unique(c[pos])


def _short(item: Any) -> str:
    """A short repr of a node's item (a ParametricSurface's repr holds its function)."""
    text = repr(item)
    return text if len(text) <= 60 else f"{type(item).__name__}(...)"
