"""The cost of the ray tests, predicted before they run (issue #25, part 5).

The numeric ray test of a parametrized surface (:mod:`lgraph.surfaces.parametric._hits`)
starts Newton's method in every patch box a ray meets; its cost grows with
the rays tested times the boxes each ray meets (a surface that oscillates
or winds over itself meets dozens a ray, an ordinary one a few).  Before the
first ray tests, :func:`probe_ray_tests` tests an evenly spread probe of the
first samples, counts the boxes their rays meet per surface, and multiplies
by the number of rays predicted: the samples the refinement is predicted to
reach (:func:`~lgraph.render.sampling.predict_points`) and the later
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
from ..surfaces._base import Surface
from ..surfaces.parametric._boxes import set_meter
from .flips import sections

__all__ = ["RayBudgetError", "RayMeter", "Work", "later_work", "probe_ray_tests"]


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
    numeric = sum(1 for n in meter.nodes if n.hides and _numeric(n.surface))
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


def _numeric(surface: Any) -> bool:
    """Whether ``surface`` is tested by the numeric ray test (the default)."""
    return surface is not None and type(surface).hits is Surface.hits


def _short(item: Any) -> str:
    """A short repr of a node's item (a ParametricSurface's repr holds its function)."""
    text = repr(item)
    return text if len(text) <= 60 else f"{type(item).__name__}(...)"
