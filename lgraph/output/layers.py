"""Layers: the strokes of a drawing grouped for one pen each.

Pen-plotter tools (vpype, AxiDraw, Inkscape) and TeX styles want the strokes
of a figure in named groups, one colour and line width per group.  A layer is
a family of curves (``layers="family"``: ``contour``, ``u1``, ``curvature``,
...) or a surface (``layers="surface"``: ``ellipsoid``, ``sphere-2``, free
curves in ``curves``); hidden parts always get their own layer (``hidden``),
or with ``layers="occlusion"`` one layer per occlusion depth (``visible``,
``hidden-1``, ``hidden-2``, ...: ``Stroke.occlusion``), so that a
plotter can draw what lies behind one sheet and leave the rest.
Strokes of one group drawn in different styles are split into several layers
(``u1``, ``u1-2``; per surface ``ellipsoid``, ``ellipsoid-contour``), so every
layer has exactly one style.  With
``layers=None`` everything is one layer, ``all`` (if all strokes share a style).

Layers are numbered from 1 in the order the strokes are drawn (hidden parts
first, as :meth:`Drawing.page_strokes` yields them); names contain no spaces
and never start with ``%`` or ``!`` (AxiDraw reads those as commands).

>>> import numpy as np
>>> from lgraph.output.drawing import Drawing, Stroke
>>> def s(family, visible=True):
...     return Stroke(xy=np.zeros((2, 2)), xyz=np.zeros((2, 3)), family=family, visible=visible)
>>> d = Drawing(strokes=(s("contour"), s("u1"), s("u1", visible=False), s("contour")))
>>> [(layer.number, layer.name, len(layer.runs)) for layer in drawing_layers(d)]
[(1, 'hidden', 1), (2, 'contour', 2), (3, 'u1', 1)]
>>> drawing_layers(d, "pens")
Traceback (most recent call last):
...
ValueError: layers must be 'family', 'surface', 'occlusion' or None, got 'pens'
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

import attrs
import numpy as np

__all__ = [
    "Layer",
    "LAYER_MODES",
    "check_layer_mode",
    "drawing_layers",
    "join_continued",
    "layer_keys",
]

#: Accepted values of every ``layers=`` option.
LAYER_MODES = ("family", "surface", "occlusion", None)


@attrs.frozen(eq=False)
class Layer:
    """One layer: its number (from 1), name, style, and its ``(points, stroke)``
    runs in drawing order (page points, as ``lgraph.output.backends._common.page_runs``
    yields them: a stroke broken by non-finite points gives several runs)."""

    number: int
    name: str
    style: Any
    runs: tuple[tuple[Any, Any], ...]

    @property
    def label(self) -> str:
        """``"N name"``: the Inkscape / AxiDraw / vpype layer label."""
        return f"{self.number} {self.name}"


def check_layer_mode(value: Any, owner: str = "layers") -> str | None:
    """Validate a ``layers=`` option: ``"family"``, ``"surface"``,
    ``"occlusion"`` or None.

    >>> check_layer_mode("surface")
    'surface'
    """
    if value is None or (isinstance(value, str) and value in LAYER_MODES):
        return value
    prefix = "" if owner == "layers" else f"{owner}: "
    raise ValueError(
        f"{prefix}layers must be 'family', 'surface', 'occlusion' or None, got {value!r}"
    )


def _clean(name: str) -> str:
    """A layer name: no spaces, no leading ``%`` or ``!``, never empty."""
    name = re.sub(r"\s+", "-", str(name).strip()).lstrip("%!") or "layer"
    return name


def _group_names(strokes: Iterable[Any], mode: str | None) -> list[str]:
    """The group (before splitting by style) of every stroke."""
    surfaces: dict[int, str] = {}
    taken: dict[str, int] = {}
    out = []
    for s in strokes:
        if mode == "occlusion":
            out.append(f"hidden-{max(int(s.occlusion), 1)}" if not s.visible else "visible")
        elif not s.visible:
            out.append("hidden")
        elif mode == "family":
            out.append(_clean(s.family))
        elif mode == "surface":
            if s.surface is None:
                out.append("curves")
                continue
            key = id(s.surface)
            if key not in surfaces:
                base = _clean(type(s.surface).__name__.lower())
                taken[base] = taken.get(base, 0) + 1
                surfaces[key] = base if taken[base] == 1 else f"{base}-{taken[base]}"
            out.append(surfaces[key])
        else:
            out.append("all")
    return out


def layer_keys(strokes: Iterable[Any], mode: str | None = "family") -> list[str]:
    """The layer name of every stroke (strokes in drawing order).

    A group whose strokes have different styles is split: its first style
    keeps the group's name, the next ones get ``-2``, ``-3``, ... (per surface:
    the family of their first stroke, ``ellipsoid-contour``).

    >>> import numpy as np
    >>> from lgraph.output.drawing import Stroke, Style
    >>> a = Stroke(xy=np.zeros((2, 2)), xyz=np.zeros((2, 3)), family="u1")
    >>> b = Stroke(xy=np.zeros((2, 2)), xyz=np.zeros((2, 3)), family="u1", style=Style(width=2))
    >>> layer_keys([a, b, a])
    ['u1', 'u1-2', 'u1']
    """
    mode = check_layer_mode(mode)
    strokes = list(strokes)
    groups = _group_names(strokes, mode)
    styles: dict[str, dict[Any, str]] = {}
    taken: set[str] = set(groups)
    out = []
    for group, s in zip(groups, strokes):
        seen = styles.setdefault(group, {})
        if s.style not in seen:
            name = group
            if seen:  # a further style: per surface named after its family, else numbered
                name = f"{group}-{_clean(s.family)}" if mode == "surface" else f"{group}-2"
                k = 2
                while name in taken:
                    k += 1
                    name = f"{group}-{k}"
            taken.add(name)
            seen[s.style] = name
        out.append(seen[s.style])
    return out


def drawing_layers(
    drawing: Any, mode: str | None = "family", runs: list[tuple[Any, ...]] | None = None
) -> list[Layer]:
    """The layers of ``drawing`` in drawing order (see the module docstring).

    Only runs of at least two finite points are placed; each layer's runs
    keep their drawing order.  ``runs`` (optional) are the runs to group
    instead of the page polylines: tuples whose second item is the stroke
    (``(points, stroke, is_bezier)`` of :func:`lgraph.output.bezier.page_curve_runs`).
    """
    from .backends._common import page_runs

    items = list(page_runs(drawing)) if runs is None else list(runs)
    names = layer_keys([item[1] for item in items], mode)
    members: dict[str, list[Any]] = {}
    for name, item in zip(names, items):
        members.setdefault(name, []).append(item)
    return [
        Layer(number=i + 1, name=name, style=group[0][1].style, runs=tuple(group))
        for i, (name, group) in enumerate(members.items())
    ]


def join_continued(strokes: list, scale: float, keep_depth: bool) -> list:
    """Consecutive strokes that continue one line -- one family, surface,
    visibility and style, the second starting within 1e-6 pt of the page
    where the first ends: a hidden line split where the number of sheets in
    front changes -- joined into one (with the first one's ``occlusion``),
    so that they are one path to the plotter; kept apart with
    ``keep_depth`` (layers per occlusion depth)."""
    out: list = []
    for t in strokes:
        s = out[-1] if out else None
        if (
            s is not None
            and not t.visible
            and not s.visible
            and s.family == t.family
            and s.surface is t.surface
            and s.style == t.style
            and (not keep_depth or s.occlusion == t.occlusion)
            and len(s.xy)
            and len(t.xy)
            and float(np.linalg.norm(np.asarray(s.xy[-1]) - t.xy[0])) * scale <= 1e-6
        ):
            uv = None if s.uv is None or t.uv is None else np.concatenate([s.uv, t.uv[1:]])
            out[-1] = attrs.evolve(
                s,
                xy=np.concatenate([s.xy, t.xy[1:]]),
                xyz=np.concatenate([s.xyz, t.xyz[1:]]) if len(s.xyz) and len(t.xyz) else s.xyz,
                uv=uv,
                curve=None,  # two runs of samples: no one curve parameter
            )
        else:
            out.append(t)
    return out
