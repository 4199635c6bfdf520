"""The cost of the ray tests, predicted before they run (issue #25, part 5).

The numeric ray test of a parametrized surface (:mod:`lgraph.surfaces.parametric._hits`)
starts Newton's method in every patch box a ray meets; its cost grows with
the samples tested times the boxes each ray meets (a surface that oscillates
or winds over itself meets dozens a ray, an ordinary one a few).  Before the
first ray tests, :func:`probe_ray_tests` tests an evenly spread probe of the
first samples, counts the boxes their rays meet per surface, and multiplies
by the number of samples the refinement is predicted to reach
(:func:`~lgraph.render.sampling.predict_points`); a prediction over
``MAX_RAY_BOXES`` is refused at once with :class:`RayBudgetError`, naming the
node whose boxes cost and the knobs that help.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from .. import _tolerance as tol
from ..surfaces._base import Surface
from ..surfaces.parametric._boxes import set_meter

__all__ = ["RayBudgetError", "RayMeter", "probe_ray_tests"]


class RayBudgetError(ValueError):
    """The ray tests of a render are predicted to meet more than
    ``MAX_RAY_BOXES`` patch boxes of numeric surfaces (minutes of work).

    Raised before the first ray test, from a probe of ``RAY_PROBE`` samples
    and the predicted number of samples; the message names the node whose
    patch boxes cost, the samples and boxes a ray, and the knobs: fewer lines
    or a larger tolerance (fewer samples), ``contour=False``, or a narrower
    ``u1_range``/``u2_range`` (a surface winding over itself).
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

    def check(self, samples: int, source: str) -> None:
        """Refuse ray tests of ``samples`` more samples predicted to meet more
        than ``MAX_RAY_BOXES`` boxes (at the boxes a ray metered so far)."""
        if not self.rays or not self.boxes:
            return
        total = sum(self.boxes.values())
        work = samples * total / self.rays
        if work <= tol.MAX_RAY_BOXES:
            return
        key = max(self.boxes, key=self.boxes.__getitem__)
        nodes = self.nodes
        node = next((k for k, n in enumerate(nodes) if id(n.surface) == key), None)
        what = "a numeric surface" if node is None else f"node {node} ({_short(nodes[node].item)})"
        per = self.boxes[key] / self.rays
        raise RayBudgetError(
            f"Scene.render: the ray tests of {samples} {source} samples would meet about "
            f"{work:.3g} patch boxes of numeric surfaces ({total / self.rays:.3g} a ray, "
            f"measured on the ray tests of {self.rays} samples); the limit is "
            f"{tol.MAX_RAY_BOXES} (lgraph._tolerance.MAX_RAY_BOXES); most are the ray tests "
            f"against the patch boxes of {what}, {per:.3g} a ray (an ordinary surface meets "
            "a few; one that oscillates or winds over itself, dozens): draw fewer lines or "
            "raise tolerance (fewer samples), or narrow that surface's u1_range/u2_range "
            "and repeat it with transforms"
        )


def probe_ray_tests(
    s: Any,
    vis: Any,
    meter: RayMeter,
    predicted: int,
    classify: Callable[..., None],
) -> None:
    """Before the first ray tests: test an evenly spread probe of
    ``RAY_PROBE`` fresh samples of ``s`` (kept: they are not tested again)
    and refuse the render when ``predicted`` samples would meet more than
    ``MAX_RAY_BOXES`` patch boxes.

    Renders predicted to need so few samples that even ``HIT_MAX_CANDIDATES
    / HIT_CHUNK_RAYS`` boxes a ray (the most a chunk of rays may meet) per
    numeric surface stay within the budget are not probed."""
    fresh = np.flatnonzero(s.fresh)
    numeric = sum(1 for n in meter.nodes if n.hides and _numeric(n.surface))
    most = tol.HIT_MAX_CANDIDATES / tol.HIT_CHUNK_RAYS
    if len(fresh) <= tol.RAY_PROBE or predicted * most * numeric <= tol.MAX_RAY_BOXES:
        return
    rows = fresh[np.linspace(0, len(fresh) - 1, tol.RAY_PROBE).astype(np.int64)]
    meter.run(classify, s, vis, rows)
    meter.check(predicted, "predicted")


def _numeric(surface: Any) -> bool:
    """Whether ``surface`` is tested by the numeric ray test (the default)."""
    return surface is not None and type(surface).hits is Surface.hits


def _short(item: Any) -> str:
    """A short repr of a node's item (a ParametricSurface's repr holds its function)."""
    text = repr(item)
    return text if len(text) <= 60 else f"{type(item).__name__}(...)"
