"""The scene graph: nodes hold a surface or a free curve, its line families,
a transform and a style.  Rendering is a pure function of scene and projector.

A scene can be added to another scene (a group): ``outer.add(inner,
transform=T, style=S)``.  Groups nest to any depth; transforms compose
(outer after inner) and a group's style applies to the members that set
none.  Labels (:class:`~lgraph.Label`) and point marks
(:class:`~lgraph.Point`) are added the same way.

>>> import lgraph as lg
>>> scene = lg.Scene()
>>> node = scene.add(lg.Sphere(1), lg.ParameterLines(4, 8))
>>> d = scene.render(lg.ParallelProjector(direction=(1, 1, 1)))
>>> sorted({s.family for s in d.strokes})
['contour', 'u1', 'u2']
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any

import attrs

from .._tolerance import CHORD_TOLERANCE
from ..curves import Curve, CurveOnSurface
from ..families import FAMILIES, Contour, Family
from ..families.cache import family_batches
from ..geometry.transforms import IDENTITY, Transform
from ..output.drawing import Drawing
from ..output.page import Page
from ..surfaces._base import Surface
from .style import OUTLINE, HiddenStyle, Style, halo_gap

if TYPE_CHECKING:
    from .projectors import Projector

__all__ = ["Scene", "Node", "Group"]

#: families drawn as the outline (wider by default): the contour and the patch edges


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
    intersections: bool = True

    @property
    def surface(self) -> Surface | None:
        if isinstance(self.item, Surface):
            return self.item
        return None

    def style_for(self, family: str) -> Style:
        s = self.style
        if isinstance(s, Style):
            return s.evolve(width=s.width * 1.6) if family in OUTLINE else s
        if family in s:
            return s[family]
        base = s.get("default", Style())
        return base.evolve(width=base.width * 1.6) if family in OUTLINE else base


@attrs.frozen(eq=False)
class Group:
    """A scene placed inside another scene, with a transform and a style."""

    scene: Scene
    transform: Transform = attrs.field(default=None, converter=_transform)
    style: Style | dict[str, Style] | None = None


@attrs.frozen(eq=False)
class _Mark:
    """A label or point added to a scene, with its transform."""

    item: Any
    transform: Transform = attrs.field(default=None, converter=_transform)


def _group_style(style: Style | dict[str, Style] | None) -> Style | None:
    """The single style a group passes to labels and points (its colour)."""
    if style is None or isinstance(style, Style):
        return style
    return style.get("default")


class Scene:
    """A mutable collection of nodes; :meth:`render` turns it into a :class:`Drawing`.

    ``Scene(halo=True)`` gives every label and point mark that sets no
    ``halo`` of its own a halo (the lines cut around it, :mod:`lgraph.output.halos`);
    a number is the gap in pt.

    >>> import lgraph as lg
    >>> inner = lg.Scene()
    >>> _ = inner.add(lg.Sphere(1), lg.ParameterLines(2, 4))
    >>> _ = inner.add(lg.Label("$P$", at=(0, 0, 1)))
    >>> outer = lg.Scene()
    >>> _ = outer.add(inner, transform=lg.translate(3, 0, 0))
    >>> _ = outer.add(inner, transform=lg.translate(-3, 0, 0))
    >>> len(outer), [lab.at.tolist() for lab in outer.labels]
    (2, [[3.0, 0.0, 1.0], [-3.0, 0.0, 1.0]])
    """

    def __init__(self, *, halo: bool | float = False) -> None:
        #: the halo of the labels and point marks that set none
        #: (``Label(halo=None)``, the default): False (none), True (a gap of
        #: ``lgraph.scene.style.HALO_GAP`` = 1.5 pt) or a gap in pt; the scene
        #: rendered decides, for the members of its groups too
        gap = halo_gap(halo, "Scene")
        self.halo: float | bool = False if gap is None else gap
        self._entries: list[Node | Group | _Mark] = []
        self._unstyled: set[int] = set()  # ids of nodes added without a style

    def add(
        self,
        item: Any,
        *families: Family,
        transform: Transform | None = None,
        style: Style | dict[str, Style] | None = None,
        contour: bool = True,
        hides: bool = True,
        intersections: bool = True,
    ) -> Any:
        """Add a surface or curve with the given line families, a label, a
        point mark, or another scene (a group).

        A surface added with no family gets its class's ``default_families``
        (:class:`ParameterLines` for most).  Every surface draws its contour
        and the edges of its drawn patch (family ``"boundary"``) unless
        ``contour=False``; ``hides=False`` makes a surface transparent (its
        lines are drawn, it hides nothing).  Where two surfaces meet, the
        curves where they cut each other are drawn too (family
        ``"intersection"``, on the surface added first) unless either was
        added with ``intersections=False`` or the render asks for none.

        A :class:`Scene` is added as a group (returns a :class:`Group`): its
        members are moved by ``transform`` after their own transforms, and
        ``style`` applies to the members that set none.  A
        :class:`~lgraph.Label` or :class:`~lgraph.Point` is returned as given.
        """
        from .objects import Label, Point

        if isinstance(item, Scene):
            if families:
                raise TypeError("Scene.add: a group (a Scene) takes no line families")
            if item is self or self in item._descendants():
                raise ValueError("Scene.add: a scene cannot contain itself (a cycle of groups)")
            group = Group(item, transform, None if style is None else _style(style))
            self._entries.append(group)
            return group
        if isinstance(item, (Label, Point)):
            if families:
                raise TypeError(f"Scene.add: a {type(item).__name__} takes no line families")
            if style is not None:
                raise TypeError(
                    f"Scene.add: give a {type(item).__name__}'s look on the object itself "
                    "(Label(color=...), Point(style=...)), not as style="
                )
            self._entries.append(_Mark(item, transform))
            return item
        if not isinstance(item, (Surface, Curve, CurveOnSurface)):
            raise TypeError(
                "Scene.add: item must be a Surface or a Curve (or a Label, a Point, or a "
                "Scene added as a group), got " + type(item).__name__
            )
        for f in families:
            if not isinstance(f, Family):
                raise TypeError(
                    "Scene.add: families must be line families such as lg.ParameterLines(8, 16), "
                    f"got {type(f).__name__}"
                )
        for flag, value in (
            ("contour", contour),
            ("hides", hides),
            ("intersections", intersections),
        ):
            if not isinstance(value, bool):
                raise TypeError(f"Scene.add: {flag} must be True or False, got {value!r}")
        if isinstance(item, Surface) and not families:
            families = tuple(FAMILIES[name]() for name in item.default_families)
        node = Node(item, tuple(families), transform, style, contour, hides, intersections)
        if style is None:
            self._unstyled.add(id(node))
        self._entries.append(node)
        return node

    def _descendants(self) -> list[Scene]:
        out: list[Scene] = []
        for e in self._entries:
            if isinstance(e, Group):
                out.append(e.scene)
                out.extend(e.scene._descendants())
        return out

    def _flatten(
        self, transform: Transform, style: Style | dict[str, Style] | None
    ) -> Iterator[Any]:
        """Nodes, labels and points with composed transforms and inherited styles."""
        mark_style = _group_style(style)
        outer = not transform.is_identity

        def compose(t: Transform) -> Transform:
            return transform @ t if outer else t

        for e in self._entries:
            if isinstance(e, Group):
                inner = e.style if e.style is not None else style
                yield from e.scene._flatten(compose(e.transform), inner)
            elif isinstance(e, _Mark):
                t = compose(e.transform)
                if hasattr(e.item, "text"):
                    yield e.item.moved(t, None if mark_style is None else mark_style.color)
                else:
                    yield e.item.moved(t, mark_style)
            else:
                changes: dict[str, Any] = {}
                if outer:
                    changes["transform"] = transform @ e.transform
                if style is not None and id(e) in self._unstyled:
                    changes["style"] = style
                yield attrs.evolve(e, **changes) if changes else e
                for fam in e.families:  # mark families (Singularities): points on the surface
                    marks = getattr(fam, "marks", None)
                    if marks is not None and e.surface is not None:
                        for m in marks(e.surface):
                            yield m.moved(compose(e.transform), mark_style)
                label = getattr(e.item, "label", None)  # e.g. an Arrow's tip label
                if label is not None and hasattr(label, "text"):
                    yield label.moved(
                        compose(e.transform), None if mark_style is None else mark_style.color
                    )

    @property
    def nodes(self) -> tuple[Node, ...]:
        """All nodes, groups flattened (transforms composed, styles inherited)."""
        return tuple(x for x in self._flatten(IDENTITY, None) if isinstance(x, Node))

    @property
    def labels(self) -> tuple[Any, ...]:
        """All labels (:class:`~lgraph.Label`), groups flattened, in world coordinates."""
        from .objects import Label

        return tuple(x for x in self._flatten(IDENTITY, None) if isinstance(x, Label))

    @property
    def points(self) -> tuple[Any, ...]:
        """All point marks (:class:`~lgraph.Point`), groups flattened, in world coordinates."""
        from .objects import Point

        return tuple(x for x in self._flatten(IDENTITY, None) if isinstance(x, Point))

    def __iter__(self) -> Iterator[Node]:
        return iter(self.nodes)

    def __len__(self) -> int:
        return len(self.nodes)

    def batches(self, node: Node, local_projector: Projector) -> list:
        """The curve batches a node draws (in its local coordinates)."""
        return self.view_batches(node, [local_projector])[0]

    def view_batches(self, node: Node, local_projectors: Sequence[Projector]) -> list[list]:
        """The curve batches a node draws in each of several views (its local
        projectors); a view-independent batch is the same object in every
        view (the renderer evaluates it once for all of them)."""
        if node.surface is None:
            batch = node.item.batch()
            return [[batch] for _ in local_projectors]
        boundary = node.surface.boundary() if node.contour else []
        out = []
        for projector in local_projectors:
            batches = []
            for i, fam in enumerate(node.families):  # view-independent ones are cached
                batches.extend(family_batches(node, i, fam, projector))
            if node.contour:
                batches.extend(Contour().batches(node.surface, projector))
                batches.extend(boundary)
            out.append(batches)
        return out

    def _repr_svg_(self) -> str:
        """Inline display: the scene from :data:`lgraph.notebook.display.DEFAULT_VIEW`."""
        from ..notebook.display import scene_drawing

        return scene_drawing(self)._repr_svg_()

    def _repr_png_(self) -> bytes:
        from ..notebook.display import scene_drawing

        return scene_drawing(self)._repr_png_()

    def __repr__(self) -> str:
        return f"<Scene: {len(self.nodes)} nodes>"

    def render(
        self,
        projector: Projector,
        hidden_lines: bool = False,
        *,
        tolerance: float = CHORD_TOLERANCE,
        page: Page | tuple[float, float] | None = None,
        hidden_style: HiddenStyle | None = None,
        intersections: bool = True,
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
        hidden_style : Style, mapping or callable, optional
            Style of hidden parts (default thin, grey, dashed): one
            :class:`Style` for all; a mapping from family names to styles
            (``"default"`` for the rest; None: not drawn); or a callable
            ``(family, occlusion) -> Style | None``, where ``occlusion`` is the
            number of surface sheets in front (``Stroke.occlusion``), so
            that ``lambda f, k: thin if k == 1 else None`` draws what is hidden
            once and leaves out what lies deeper.
        intersections : bool
            Draw the curves where the surfaces of two nodes meet (family
            ``"intersection"``, on the node added first; default True).
            A node added with ``intersections=False`` draws none.
        """
        from ..render import render

        return render(
            self,
            projector,
            hidden_lines=hidden_lines,
            tolerance=tolerance,
            page=page,
            hidden_style=hidden_style,
            intersections=intersections,
        )
