"""The scene: what is drawn and how it is seen.

``graph.py`` the scene graph (:class:`Scene`, :class:`Node`, :class:`Group`),
``projectors.py`` the eye, ``style.py`` and ``colors.py`` how strokes look,
``objects/`` the figure objects that are not surfaces of study (labels,
points, arrows, parallelograms).

``Scene``, ``Node`` and ``Group`` are importable from here, loaded when first
used: a module that needs only a :class:`~lgraph.Style` (the display list, the
renderer) imports ``lgraph.scene.style`` without the scene graph, which
itself imports the display list.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .graph import Group, Node, Scene

__all__ = ["Scene", "Node", "Group"]


def __getattr__(name: str) -> Any:
    if name not in __all__:
        raise AttributeError(f"module 'lgraph.scene' has no attribute {name!r}")
    value = getattr(importlib.import_module(".graph", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
