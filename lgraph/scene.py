"""The scene graph: nodes hold a surface or a free curve, its line families,
a transform and a style.  Rendering is a pure function of scene and projector.

>>> import lgraph as lg
>>> scene = lg.Scene()
>>> node = scene.add(lg.Sphere(1), lg.ParameterLines(4, 8))
>>> d = scene.render(lg.ParallelProjector(direction=(1, 1, 1)))
>>> sorted({s.family for s in d.strokes})
['contour', 'u1', 'u2']
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

import attrs

from ._tolerance import CHORD_TOLERANCE
from .curves import Curve, CurveOnSurface
from .drawing import Drawing, Page, Style
from .families import FAMILIES, Contour, Family
from .geometry.transforms import IDENTITY, Transform
from .surfaces._base import Surface

if TYPE_CHECKING:
    from .projectors import Projector

__all__ = ["Scene", "Node"]

#: families drawn as the outline (wider by default): the contour and the patch edges
_OUTLINE = ("contour", "boundary")


def _transform(value: Any) -> Transform:
    if value is None:
        return IDENTITY
    if not isinstance(value, Transform):
        raise TypeError(
            "Scene.add: transform must be a Transform (lg.translate, lg.rotate, ... "
            f"composed with @) or None, got {type(value).__name__}"
        )
    return value


def _style(value: Any) -> Style | dict[str, Style]:
    if value is None:
        return Style()
    if isinstance(value, Style):
        return value
    if isinstance(value, dict):
        for k, v in value.items():
            if not isinstance(v, Style):
                raise TypeError(f"Scene.add: style[{k!r}] must be a Style, got {type(v).__name__}")
        return dict(value)
    raise TypeError(
        "Scene.add: style must be a Style, a dict family -> Style, or None, "
        f"got {type(value).__name__}"
    )


@attrs.frozen(eq=False)
class Node:
    """One object of the scene: a surface or curve with families, transform, style.

    ``style`` is a :class:`Style` for all of the node's lines (the contour and
    the patch boundary are drawn 1.6 times as wide), or a dict mapping family names (``"contour"``,
    ``"u1"``, ``"curvature"``, ...) to styles, with the key ``"default"`` for the rest.
    """

    item: Any
    families: tuple[Family, ...] = ()
    transform: Transform = attrs.field(default=None, converter=_transform)
    style: Style | dict[str, Style] = attrs.field(default=None, converter=_style)
    contour: bool = True
    hides: bool = True

    @property
    def surface(self) -> Surface | None:
        if isinstance(self.item, Surface):
            return self.item
        return None

    def style_for(self, family: str) -> Style:
        s = self.style
        if isinstance(s, Style):
            return s.evolve(width=s.width * 1.6) if family in _OUTLINE else s
        if family in s:
            return s[family]
        base = s.get("default", Style())
        return base.evolve(width=base.width * 1.6) if family in _OUTLINE else base


class Scene:
    """A mutable collection of nodes; :meth:`render` turns it into a :class:`Drawing`."""

    def __init__(self) -> None:
        self._nodes: list[Node] = []

    def add(
        self,
        item: Any,
        *families: Family,
        transform: Transform | None = None,
        style: Style | dict[str, Style] | None = None,
        contour: bool = True,
        hides: bool = True,
    ) -> Node:
        """Add a surface or curve with the given line families.

        A surface added with no family gets its class's ``default_families``
        (:class:`ParameterLines` for most).  Every surface draws its contour
        and the edges of its drawn patch (family ``"boundary"``) unless
        ``contour=False``; ``hides=False`` makes a surface transparent (its
        lines are drawn, it hides nothing).
        """
        if not isinstance(item, (Surface, Curve, CurveOnSurface)):
            raise TypeError(
                "Scene.add: item must be a Surface or a Curve, got " + type(item).__name__
            )
        for f in families:
            if not isinstance(f, Family):
                raise TypeError(
                    "Scene.add: families must be line families such as lg.ParameterLines(8, 16), "
                    f"got {type(f).__name__}"
                )
        if isinstance(item, Surface) and not families:
            families = tuple(FAMILIES[name]() for name in item.default_families)
        node = Node(item, tuple(families), transform, style, contour, hides)
        self._nodes.append(node)
        return node

    @property
    def nodes(self) -> tuple[Node, ...]:
        return tuple(self._nodes)

    def __iter__(self) -> Iterator[Node]:
        return iter(self._nodes)

    def __len__(self) -> int:
        return len(self._nodes)

    def batches(self, node: Node, local_projector: Projector) -> list:
        """The curve batches a node draws (in its local coordinates)."""
        out = []
        if node.surface is not None:
            for fam in node.families:
                out.extend(fam.batches(node.surface, local_projector))
            if node.contour:
                out.extend(Contour().batches(node.surface, local_projector))
                out.extend(node.surface.boundary())
        else:
            out.append(node.item.batch())
        return out

    def render(
        self,
        projector: Projector,
        hidden_lines: bool = False,
        *,
        tolerance: float = CHORD_TOLERANCE,
        page: Page | tuple[float, float] | None = None,
        hidden_style: Style | None = None,
    ) -> Drawing:
        """Render the scene: sample, test visibility, split at exact transitions.

        Parameters
        ----------
        projector : Projector
            The view (:class:`ParallelProjector` or :class:`CentralProjector`).
        hidden_lines : bool
            Also return hidden parts (``visible=False``), drawn thin and dashed.
        tolerance : float
            Largest deviation of a drawn polyline from the true projected curve,
            as a fraction of the figure's diagonal.
        page : Page or (width, height) in pt, optional
            Page geometry; default crops the page to the figure.
        hidden_style : Style, optional
            Style of hidden parts (default thin, grey, dashed).
        """
        from .visibility import render

        return render(
            self,
            projector,
            hidden_lines=hidden_lines,
            tolerance=tolerance,
            page=page,
            hidden_style=hidden_style,
        )
