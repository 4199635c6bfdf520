"""What the renderer needs of a scene and of its nodes: two protocols.

:class:`lgraph.Scene` and :class:`lgraph.Node` (:mod:`lgraph.scene.graph`)
are them.  The scene imports the renderer (``Scene.render``), so the
renderer types its argument by these protocols instead of importing the
scene graph back (a type-only import circle).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol, TypeVar

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..families import Family
    from ..geometry.transforms import Transform
    from ..scene.objects.marks import Label, Point
    from ..scene.projectors import Projector
    from ..scene.style import Style
    from ..surfaces._base import Surface

__all__ = ["NodeT", "RenderNode", "Renderable"]


class RenderNode(Protocol):
    """A node as the renderer reads it (:class:`lgraph.Node`)."""

    @property
    def item(self) -> object: ...

    @property
    def surface(self) -> Surface | None: ...

    @property
    def families(self) -> tuple[Family, ...]: ...

    @property
    def transform(self) -> Transform: ...

    @property
    def style(self) -> Style | dict[str, Style]: ...

    @property
    def contour(self) -> bool: ...

    @property
    def hides(self) -> bool: ...

    @property
    def intersections(self) -> bool: ...

    def style_for(self, family: str) -> Style: ...


#: the scene's own node type (a scene's ``view_batches`` takes its nodes)
NodeT = TypeVar("NodeT", bound=RenderNode)


class Renderable(Protocol[NodeT]):
    """A scene as the renderer reads it (:class:`lgraph.Scene`): its nodes,
    groups flattened, the curve batches each draws in each view, its labels
    and point marks."""

    @property
    def nodes(self) -> tuple[NodeT, ...]: ...

    @property
    def labels(self) -> tuple[Label, ...]: ...

    @property
    def points(self) -> tuple[Point, ...]: ...

    def view_batches(
        self, node: NodeT, local_projectors: Sequence[Projector]
    ) -> list[list[CurveBatch]]: ...
