r"""Labels and point marks: text and dots anchored at 3-D points.

A :class:`Label` is text anchored at a 3-D point; a :class:`Point` is a dot
there.  Both are added with ``scene.add`` (also inside groups, where the
group's transform moves them) and are hidden exactly like the lines: the
renderer casts the anchor's ray toward the viewer against every surface of
the scene.  A hidden label or point is left out, or, with
``hidden_lines=True``, kept and marked hidden (drawn in the hidden style);
``always=True`` draws it regardless.

Text between ``$...$`` is TeX mathematics (see :mod:`lgraph.output._text`).  No formula of
docs/mathematics.rst: the renderer's visibility test is that of the lines
(docs/mathematics.rst, "Visibility transitions").

>>> import lgraph as lg
>>> lab = lg.Label("$\\kappa_n N$", at=(0, 0, 1.2), anchor="sw", offset=(2, 2))
>>> lab.anchor, lab.offset, lab.size
('sw', (2.0, 2.0), 10.0)
>>> lg.Label("$x_1", at=(0, 0, 0))
Traceback (most recent call last):
...
ValueError: Label '$x_1': unbalanced $ (mathematics goes between a pair of $...$)
>>> lg.Label("P", at=(0, float("nan"), 0))
Traceback (most recent call last):
...
ValueError: Label 'P': at must be three finite numbers, got (0, nan, 0)
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from ..._validate import _is_real
from ...output._text import check_text, quote
from ..style import ANCHORS, Style, _color, halo_gap

__all__ = ["Label", "Point", "ANCHORS"]


def _name(label: Any) -> str:
    text = getattr(label, "text", None)
    return f"Label {quote(text)}" if isinstance(text, str) else "Label"


def _point3(owner: str, name: str, value: Any) -> np.ndarray:
    try:
        p = np.array(value, dtype=float)
    except (TypeError, ValueError):
        p = None
    if p is None or p.shape != (3,) or not np.all(np.isfinite(p)):
        shown = tuple(value) if isinstance(value, (list, tuple)) else value
        raise ValueError(f"{owner}: {name} must be three finite numbers, got {shown!r}")
    p.setflags(write=False)
    return p


@attrs.frozen(eq=False)
class Label:
    r"""Text anchored at a 3-D point.

    Parameters
    ----------
    text : str
        The text; ``$...$`` encloses TeX mathematics (``"$\\kappa_1$"``,
        ``"point $P$"``).  One line of at most ``MAX_LABEL_LENGTH`` (1000)
        characters, no control characters, groups (``{...}``,
        ``\\left...\\right``, ``\\sqrt[...]``) nested at most
        ``MAX_LABEL_DEPTH`` (10) deep, and no TeX command that reaches files
        or the shell, defines commands or changes how TeX reads text
        (``lgraph.output._text.check_tex``: the TikZ backend hands the text to TeX).
    at : 3 numbers
        The anchor point (in the coordinates of the scene it is added to).
    offset : (dx, dy), default (0, 0)
        Shift of the text from the projected anchor, in pt (y upwards).
    anchor : str, default "center"
        Which point of the text's box sits at the (offset) anchor:
        ``"center"``, ``"n"``, ``"ne"``, ``"e"``, ``"se"``, ``"s"``, ``"sw"``,
        ``"w"``, ``"nw"`` (TikZ's convention: ``"sw"`` puts the text above
        right), or ``"auto"`` with ``direction``: the text goes on the side
        that ``direction`` points to in the picture (labels at arrow tips).
    size : float, default 10
        Font size in pt (never scaled with the figure).
    color : colour, optional
        Text colour; default: the enclosing group's style colour, else black.
    always : bool, default False
        Draw the label even where its anchor is hidden.
    direction : 3 numbers, optional
        Used by ``anchor="auto"``.
    halo : bool, float or None, default None
        Cut the lines under the text: every stroke is split where it enters
        the text's ink box grown by a gap (True: ``lgraph.scene.style.HALO_GAP``,
        1.5 pt; a number: that gap in pt), geometrically, so the gap is in
        every backend, plotters included (:mod:`lgraph.output.halos`).  None: the
        scene's default (``Scene(halo=...)``, no halo unless set); False: none.
    """

    text: str = attrs.field()
    at: np.ndarray = attrs.field(kw_only=True)
    offset: tuple[float, float] = attrs.field(default=(0.0, 0.0), kw_only=True)
    anchor: str = attrs.field(default="center", kw_only=True)
    size: float = attrs.field(default=10.0, kw_only=True)
    color: tuple[float, float, float] | None = attrs.field(default=None, kw_only=True)
    always: bool = attrs.field(default=False, kw_only=True)
    direction: np.ndarray | None = attrs.field(default=None, kw_only=True)
    halo: bool | float | None = attrs.field(default=None, kw_only=True)

    def __attrs_post_init__(self) -> None:
        name = _name(self)
        object.__setattr__(self, "halo", halo_gap(self.halo, name))
        check_text("Label", self.text, typeset=False)  # TeX may hold the document's macros
        set_ = object.__setattr__
        set_(self, "at", _point3(name, "at", self.at))
        try:
            off = tuple(float(x) for x in self.offset)
        except (TypeError, ValueError):
            off = ()
        if len(off) != 2 or not all(math.isfinite(x) for x in off):
            raise ValueError(
                f"{name}: offset must be two finite numbers (dx, dy) in pt, got {self.offset!r}"
            )
        set_(self, "offset", off)
        if self.anchor not in ANCHORS and self.anchor != "auto":
            raise ValueError(
                f"{name}: anchor must be one of {', '.join(ANCHORS)} or 'auto', got {self.anchor!r}"
            )
        if not (_is_real(self.size) and math.isfinite(self.size) and self.size > 0):
            raise ValueError(
                f"{name}: size must be a positive finite number of pt, got {self.size!r}"
            )
        set_(self, "size", float(self.size))
        if self.color is not None:
            try:
                set_(self, "color", _color(self.color))
            except ValueError as exc:
                raise ValueError(f"{name}: {str(exc).removeprefix('Style: ')}") from None
        if not isinstance(self.always, bool):
            raise ValueError(f"{name}: always must be True or False, got {self.always!r}")
        if self.direction is not None:
            d = _point3(name, "direction", self.direction)
            if not np.any(d):
                raise ValueError(f"{name}: direction must be a non-zero vector")
            set_(self, "direction", d)
        elif self.anchor == "auto":
            raise ValueError(f"{name}: anchor='auto' needs a direction")

    def moved(self, transform: Any, color: Any = None) -> Label:
        """This label with ``transform`` applied (and ``color`` if it has none)."""
        changes: dict[str, Any] = {}
        if not transform.is_identity:
            changes["at"] = transform.apply(self.at)
            if self.direction is not None:
                changes["direction"] = transform.apply_vector(self.direction)
        if self.color is None and color is not None:
            changes["color"] = color
        return attrs.evolve(self, **changes) if changes else self


@attrs.frozen(eq=False)
class Point:
    """A dot at a 3-D point, hidden like a label.

    Parameters
    ----------
    at : 3 numbers
        Its position.
    size : float, default 3
        Diameter in pt.
    style : Style, optional
        Its colour (the width is ``size``); default: the enclosing group's
        style, else black.
    always : bool, default False
        Draw it even where it is hidden.
    halo : bool, float or None, default None
        Cut the lines around the dot: a disc of its radius plus a gap (True:
        1.5 pt, or a number of pt), as for :class:`Label`; None: the scene's
        default.

    >>> import lgraph as lg
    >>> lg.Point((1, 0, 0), size=-1)
    Traceback (most recent call last):
    ...
    ValueError: Point: size must be a positive finite number of pt, got -1
    """

    at: np.ndarray = attrs.field(converter=lambda v: _point3("Point", "at", v))
    size: float = attrs.field(default=3.0, kw_only=True)
    style: Style | None = attrs.field(default=None, kw_only=True)
    always: bool = attrs.field(default=False, kw_only=True)
    halo: bool | float | None = attrs.field(default=None, kw_only=True)

    def __attrs_post_init__(self) -> None:
        object.__setattr__(self, "halo", halo_gap(self.halo, "Point"))
        if not (_is_real(self.size) and math.isfinite(self.size) and self.size > 0):
            raise ValueError(
                f"Point: size must be a positive finite number of pt, got {self.size!r}"
            )
        object.__setattr__(self, "size", float(self.size))
        if self.style is not None and not isinstance(self.style, Style):
            raise TypeError(
                f"Point: style must be a Style or None, got {type(self.style).__name__}"
            )
        if not isinstance(self.always, bool):
            raise ValueError(f"Point: always must be True or False, got {self.always!r}")

    def moved(self, transform: Any, style: Any = None) -> Point:
        """This point with ``transform`` applied (and ``style`` if it has none)."""
        changes: dict[str, Any] = {}
        if not transform.is_identity:
            changes["at"] = transform.apply(self.at)
        if self.style is None and style is not None:
            changes["style"] = style
        return attrs.evolve(self, **changes) if changes else self
