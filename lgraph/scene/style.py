"""How drawn things look and sit: :class:`Style` (colour, width, dash), the
default look of hidden parts, and the anchors of text.

Kept apart from the display list (:mod:`lgraph.output.drawing`) so that scene objects,
backends and the renderer can use styles without importing each other.

>>> Style(width=1.0).width
1.0
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import attrs

from .._validate import finite_positive
from .colors import parse_color

__all__ = [
    "Style",
    "HIDDEN_STYLE",
    "OUTLINE",
    "ANCHORS",
    "HiddenStyle",
    "HiddenStyles",
    "hidden_style_rule",
    "HALO_GAP",
    "halo_gap",
]

#: Families drawn as a surface's outline (1.6 times as wide as its other lines).
OUTLINE = ("contour", "boundary", "arrow")


def _color(value: Any) -> tuple[float, float, float]:
    """Convert a colour to an RGB triple in [0, 1]: a CSS or matplotlib name,
    ``"#rrggbb"``, ``"#rgb"`` or ``(r, g, b)`` (:func:`lgraph.scene.colors.parse_color`)."""
    return parse_color(value)


def _dash(value: Any) -> tuple[float, ...] | None:
    if value is None:
        return None
    try:
        d = tuple(float(x) for x in value)
    except TypeError:
        raise ValueError(
            f"Style: dash must be None or a sequence of on/off lengths in pt, got {value!r}"
        ) from None
    if not d or len(d) % 2 or not all(math.isfinite(x) and x > 0 for x in d):
        raise ValueError(
            "Style: dash must be an even-length sequence of positive finite lengths in pt, "
            f"got {value!r}"
        )
    return d


@attrs.frozen
class Style:
    """How a stroke looks: colour, line width (pt) and dash pattern (pt).

    ``color`` is a CSS or matplotlib colour name (``"red"`` is ``#ff0000``,
    ``"tab:blue"``; :data:`lgraph.scene.colors.COLORS`), ``"#rrggbb"``, ``"#rgb"``
    or an ``(r, g, b)`` triple in [0, 1].

    >>> Style(width=1.0).width
    1.0
    >>> Style(color="#ff0000").color
    (1.0, 0.0, 0.0)
    >>> Style(width=0)
    Traceback (most recent call last):
    ...
    ValueError: Style: width must be a positive finite number, got 0
    """

    color: tuple[float, float, float] = attrs.field(default=(0.0, 0.0, 0.0), converter=_color)
    width: float = attrs.field(default=0.5, validator=finite_positive("Style"))
    dash: tuple[float, ...] | None = attrs.field(default=None, converter=_dash)

    def evolve(self, **changes: Any) -> Style:
        """A copy with some fields changed."""
        return attrs.evolve(self, **changes)


#: space between a label's ink box and its anchor point, in units of its size
#: (TikZ's inner sep is about 0.33 em)
LABEL_PAD = 0.25

#: The gap in pt between a label's ink box (a point mark's dot) and the lines
#: its halo cuts (``Label(..., halo=True)``; :mod:`lgraph.output.halos`)
HALO_GAP = 1.5


def halo_gap(value: Any, owner: str) -> float | None | bool:
    """A ``halo=`` value checked: None (follow the default), False (none),
    True (:data:`HALO_GAP`) or a gap in pt (a finite number >= 0).

    >>> halo_gap(True, "Label"), halo_gap(2, "Label"), halo_gap(None, "Label")
    (1.5, 2.0, None)
    >>> halo_gap(-1, "Label")
    Traceback (most recent call last):
    ...
    ValueError: Label: halo must be True, False, None or a gap in pt (a finite number >= 0), got -1
    """
    if value is None or value is False:
        return value
    if value is True:
        return HALO_GAP
    if isinstance(value, (int, float)) and math.isfinite(value) and value >= 0:
        return float(value)
    raise ValueError(
        f"{owner}: halo must be True, False, None or a gap in pt (a finite number >= 0), "
        f"got {value!r}"
    )


#: Default look of hidden parts (``hidden_lines=True``): thin and dashed.
HIDDEN_STYLE = Style(color=(0.35, 0.35, 0.35), width=0.3, dash=(2.0, 1.5))


#: anchor name -> the point of the text box put at the label's position, as
#: fractions (0 left/bottom, 1 right/top) of the box: TikZ's convention, so
#: ``anchor="sw"`` puts the text above and to the right of the point
ANCHORS: dict[str, tuple[float, float]] = {
    "center": (0.5, 0.5),
    "n": (0.5, 1.0),
    "ne": (1.0, 1.0),
    "e": (1.0, 0.5),
    "se": (1.0, 0.0),
    "s": (0.5, 0.0),
    "sw": (0.0, 0.0),
    "w": (0.0, 0.5),
    "nw": (0.0, 1.0),
}


@attrs.frozen
class HiddenStyles:
    """A ``hidden_style`` rule that can be pickled (for animations on worker
    processes and scene files): hidden strokes styled per family, with
    ``default`` for the others, and not drawn where more than
    ``max_occlusion`` sheets lie in front (None: no limit).

    >>> rule = HiddenStyles({"contour": Style(width=0.2)}, max_occlusion=1)
    >>> rule("contour", 1).width, rule("u1", 1) == HIDDEN_STYLE, rule("u1", 2)
    (0.2, True, None)
    """

    styles: Mapping[str, Style | None] = attrs.field(factory=dict, converter=dict)
    default: Style | None = None
    max_occlusion: int | None = None

    def __call__(self, family: str, occlusion: int) -> Style | None:
        if self.max_occlusion is not None and occlusion > self.max_occlusion:
            return None
        default = HIDDEN_STYLE if self.default is None else self.default
        return self.styles.get(family, default)


#: what ``hidden_style=`` accepts: one style, one per family, or a rule
HiddenStyle = Style | Mapping[str, Style | None] | Callable[[str, int], Style | None]


def hidden_style_rule(spec: Any, owner: str = "Scene.render") -> Callable[[str, int], Style | None]:
    """``hidden_style=`` as a rule ``(family, occlusion) -> Style | None``
    (None: the hidden stroke is not drawn).

    ``spec`` is None (:data:`HIDDEN_STYLE` for every hidden stroke), a
    :class:`Style` (for every one), a mapping from family names to styles or
    None (the key ``"default"``, else :data:`HIDDEN_STYLE`, for families it
    does not name), or a callable ``(family, occlusion)`` returning a style or
    None; ``occlusion`` is the number of sheets in front
    (``Stroke.occlusion``, 1 or more).

    >>> thin = Style(width=0.2, dash=(1, 1))
    >>> rule = hidden_style_rule(lambda family, occlusion: thin if occlusion == 1 else None)
    >>> rule("u1", 1) is thin, rule("u1", 2)
    (True, None)
    >>> hidden_style_rule({"contour": thin})("contour", 3) is thin
    True
    >>> hidden_style_rule({"contour": "thin"})
    Traceback (most recent call last):
    ...
    TypeError: Scene.render: hidden_style['contour'] must be a Style or None, got 'thin'
    """
    if spec is None or isinstance(spec, Style):
        style = HIDDEN_STYLE if spec is None else spec
        return lambda family, occlusion: style
    if isinstance(spec, Mapping):
        table: dict[str, Style | None] = {}
        for key, value in spec.items():
            if not isinstance(key, str):
                raise TypeError(f"{owner}: hidden_style keys must be family names, got {key!r}")
            if value is not None and not isinstance(value, Style):
                raise TypeError(
                    f"{owner}: hidden_style[{key!r}] must be a Style or None, got {value!r}"
                )
            table[key] = value
        default = table.get("default", HIDDEN_STYLE)
        return lambda family, occlusion: table.get(family, default)
    if callable(spec):

        def rule(family: str, occlusion: int) -> Style | None:
            style = spec(family, occlusion)
            if style is not None and not isinstance(style, Style):
                raise TypeError(
                    f"{owner}: hidden_style({family!r}, {occlusion}) must return a Style or "
                    f"None, got {style!r}"
                )
            return style

        return rule
    raise TypeError(
        f"{owner}: hidden_style must be a Style (e.g. lg.Style(color='grey', dash=(2, 1.5))), "
        "a mapping from family names to styles, a callable (family, occlusion) -> Style or "
        f"None, or None; got {spec!r}"
    )
