"""Where animation frames look: the common window of all views, and the
chord tolerance a raster frame's pixels can show.

Every frame of an animation shows the same window of the projection plane
(the union, over all views, of the scene's projected extent), so the figure
keeps its place and scale (:func:`~lgraph.animation.frames.frame_window`).  A
raster frame of a known size can then be sampled only as finely as its
pixels show (:func:`pixel_chord`, used by ``lg.animate(...,
render_options={"tolerance": "pixel"})``).  No derivation of
docs/mathematics.rst: bounding boxes and a scale factor.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .._tolerance import PIXEL_TOLERANCE
from ..output.drawing import Drawing
from ..output.page import Page, page_layout
from ..scene.projectors import Projector

__all__ = ["frame_window", "pixel_chord", "PIXEL_TOLERANCE"]


#: Grid of parameter values per surface (per side) for the common frame window.
_WINDOW_GRID = 41


def _scene_points(scene: Any) -> np.ndarray:
    """World points spread over every node: a parameter grid on each surface's
    drawn patch, samples along each free curve, the anchors of labels and
    point marks."""
    pts = []
    for node in scene.nodes:
        if node.surface is not None and not getattr(node.surface, "parametric", True):
            p = node.surface.sample_points()  # an implicit surface: points of F = 0
        elif node.surface is not None:
            d = node.surface.domain
            u1 = np.linspace(*d.u1, _WINDOW_GRID)
            u2 = np.linspace(*d.u2, _WINDOW_GRID)
            g1, g2 = np.meshgrid(u1, u2)
            p = np.asarray(node.surface.point(g1.ravel(), g2.ravel()), float).reshape(-1, 3)
        else:
            b = node.item.batch()
            n = _WINDOW_GRID * 4
            idx = np.repeat(np.arange(len(b)), n)
            s = np.tile(np.linspace(0.0, 1.0, n), len(b))
            t = b.t0[idx] + s * (b.t1[idx] - b.t0[idx])
            p = np.asarray(b.evaluate(idx, t)[0], float).reshape(-1, 3)
        pts.append(node.transform.apply(p))
    marks = [np.asarray(m.at, float).reshape(1, 3) for m in (*scene.labels, *scene.points)]
    pts.extend(marks)  # label anchors and point marks (in world coordinates already)
    if not pts:
        return np.zeros((1, 3))
    allp = np.concatenate(pts)
    return allp[np.isfinite(allp).all(axis=1)]


def frame_window(
    scene: Any, views: Sequence[Projector], pad: float = 0.04
) -> tuple[float, float, float, float]:
    """The projection-plane window ``(xmin, ymin, xmax, ymax)`` that holds the
    scene in every view, padded by ``pad`` times its larger side.

    >>> import lgraph as lg
    >>> scene = lg.Scene()
    >>> _ = scene.add(lg.Sphere(1))
    >>> [round(v, 2) for v in frame_window(scene, lg.orbit(frames=8), pad=0)]
    [-1.0, -1.0, 1.0, 1.0]
    """
    pts = _scene_points(scene)
    xy = np.concatenate([view.project(pts) for view in views]) if len(views) else pts[:0, :2]
    x, y = xy[:, 0], xy[:, 1]  # column by column (a reduction along axis 0 is slow)
    ok = np.isfinite(x) & np.isfinite(y)
    if ok.any():
        x, y = x[ok], y[ok]
        lo, hi = np.array([x.min(), y.min()]), np.array([x.max(), y.max()])
    else:
        lo, hi = np.zeros(2), np.ones(2)
    size = max(float((hi - lo).max()), 1e-12)
    lo, hi = lo - pad * size, hi + pad * size
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


def pixel_chord(page: Page, window: tuple[float, float, float, float]) -> float:
    """The chord tolerance, a length in the projection plane, that keeps every
    chord within ``PIXEL_TOLERANCE`` (0.25, ``lgraph/_tolerance.py``) pixels
    of its curve in a raster frame of ``page`` (width and height in pixels)
    showing ``window``: a quarter of a pixel at the frame's scale
    (``render_views(..., chord=...)``; used by ``lg.animate(...,
    render_options={"tolerance": "pixel"})``).

    Labels, which take room on the page, only shrink the scale: the chords
    stay within a quarter pixel.

    A window 4 units wide fills the 451.2 px between the margins, so a pixel
    is 1/112.8 of a unit:

    >>> from lgraph.output.page import Page
    >>> chord = pixel_chord(Page(width=480.0, height=343.0, margin=14.4), (-2.0, -1.0, 2.0, 1.0))
    >>> round(chord * 112.8, 12)
    0.25
    """
    scale = page_layout(Drawing((), page=page, window=window))[0]
    return PIXEL_TOLERANCE / scale
