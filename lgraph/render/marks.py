"""Render stage for labels and point marks: project their anchors and hide them.

An anchor is hidden when the ray from it toward the viewer meets a surface of
the scene (the same exact test as for the samples of the lines,
``lgraph.render.occlusion.Occlusion``).  Visible ones are placed; hidden ones
are left out, or kept and marked hidden with ``hidden_lines=True``; objects
with ``always=True`` are placed as visible wherever they are.  A point mark
becomes a stroke of family ``"point"``: two equal points drawn with round
caps, a dot of diameter ``size`` in every backend.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .._own import OFF
from ..output.drawing import PlacedLabel, Stroke
from ..scene.projectors import CentralProjector, Projector
from ..scene.style import Style

__all__ = ["place_marks", "auto_anchor"]

_COMPASS = ("w", "sw", "s", "se", "e", "ne", "n", "nw")


def auto_anchor(dx: float, dy: float) -> str:
    """The anchor that puts text on the side ``(dx, dy)`` points to.

    >>> auto_anchor(1.0, 0.0), auto_anchor(0.0, 1.0), auto_anchor(-1.0, -1.0)
    ('w', 's', 'ne')
    """
    if dx == 0 and dy == 0:
        return "center"
    k = round(math.atan2(dy, dx) / (math.pi / 4)) % 8
    return _COMPASS[k]


def _placed(
    kind: str,
    marks: tuple[Any, ...],
    projector: Projector,
    occlusion: Any,
    hidden_lines: bool,
    view: int,
    rule: Callable[[str, int], Style | None],
) -> list[tuple[Any, np.ndarray, np.ndarray, int, Style | None]]:
    """``(mark, xyz, xy, depth, hidden style)`` of the marks that are drawn, in
    order: ``depth`` the sheets in front (0: visible), the style from ``rule``
    for hidden marks (a hidden mark whose rule gives None is not drawn)."""
    if not marks:
        return []
    xyz = np.array([m.at for m in marks], dtype=float)
    xy = _project(kind, xyz, projector)
    n = len(xyz)
    owner, own = np.full(n, -1), np.full(n, OFF, dtype=np.int8)
    hid = occlusion.hidden(xyz, xy, owner, own, view=view)
    hid &= ~np.array([bool(m.always) for m in marks])
    depth = np.zeros(n, dtype=np.int64)
    if hidden_lines and hid.any():
        i = np.flatnonzero(hid)
        depth[i] = np.maximum(occlusion.sheets(xyz[i], xy[i], owner[i], own[i], view=view), 1)
    out = []
    for m, p, q, h, k in zip(marks, xyz, xy, hid.tolist(), depth.tolist()):
        if not h:
            out.append((m, p, q, 0, None))
        elif hidden_lines and (style := rule(kind, k)) is not None:
            out.append((m, p, q, k, style))
    return out


def _project(kind: str, xyz: np.ndarray, projector: Projector) -> np.ndarray:
    if isinstance(projector, CentralProjector) and len(xyz):
        behind = projector.depth(xyz) <= 0
        if behind.any():
            raise ValueError(
                f"CentralProjector: a {kind} at {xyz[np.argmax(behind)].tolist()} lies at or "
                "behind the eye; move the eye farther away"
            )
    return projector.project(xyz).reshape(-1, 2)


def place_marks(
    labels: tuple[Any, ...],
    points: tuple[Any, ...],
    projector: Projector,
    occlusion: Any,
    hidden_lines: bool,
    rule: Callable[[str, int], Style | None],
    view: int = 0,
    halo: float | bool = False,
) -> tuple[list[PlacedLabel], list[Stroke]]:
    """Placed labels and point strokes of a scene's (world-coordinate) marks,
    seen by ``projector``, view ``view`` of ``occlusion``; hidden ones styled
    by ``rule(family, occlusion)`` (families ``"label"`` and ``"point"``);
    ``halo`` is the halo of the marks that set none (``Scene(halo=...)``)."""

    def gap(own: float | bool | None) -> float | None:
        value = halo if own is None else own
        return None if value is False else float(value)

    placed: list[PlacedLabel] = []
    for lab, p, q, k, hs in _placed(
        "label", labels, projector, occlusion, hidden_lines, view, rule
    ):
        anchor = lab.anchor
        if anchor == "auto":
            step = 1e-6 * max(1.0, float(np.linalg.norm(p)))
            d = projector.project(p + step * lab.direction / np.linalg.norm(lab.direction))
            anchor = auto_anchor(*(np.asarray(d) - q).tolist())
        color = lab.color if lab.color is not None else (0.0, 0.0, 0.0)
        style = Style(color=hs.color if k else color)
        placed.append(
            PlacedLabel(
                lab.text, q, p, not k, anchor, lab.offset, lab.size, style, halo=gap(lab.halo)
            )
        )
    strokes: list[Stroke] = []
    for pt, p, q, k, hs in _placed("point", points, projector, occlusion, hidden_lines, view, rule):
        base = hs if k else (pt.style or Style())
        style = Style(color=base.color, width=pt.size)
        strokes.append(
            Stroke(
                xy=np.array([q, q]),
                xyz=np.array([p, p]),
                visible=not k,
                family="point",
                style=style,
                occlusion=k,
                halo=gap(getattr(pt, "halo", None)),
            )  # fmt: skip
        )
    return placed, strokes
