"""Coincident surfaces: the same surface added twice (twins), and points of
one surface that lie on another (the tie rule of the ray tests)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from .. import _tolerance as tol

if TYPE_CHECKING:
    from ..surfaces._base import Surface
    from ._protocols import RenderNode

__all__ = ["lies_on", "twin_groups"]


def lies_on(surface: Surface, points: np.ndarray) -> np.ndarray:
    """Which local ``points`` lie on ``surface``'s implicit equation (within
    ``COINCIDENT_RTOL`` of its size, distance estimated as ``|F| / |grad F|``);
    all False for a surface without ``implicit``."""
    f = getattr(surface, "implicit", None)
    if f is None or not len(points):
        return np.zeros(len(points), dtype=bool)
    size = surface.size
    h = 1e-6 * size
    with np.errstate(all="ignore"):
        F = np.asarray(f(points), dtype=float)
        grad = np.stack(
            [(f(points + h * e) - f(points - h * e)) / (2 * h) for e in np.eye(3)], axis=-1
        )
        dist = np.abs(F) / np.linalg.norm(grad, axis=-1)
    return dist <= tol.COINCIDENT_RTOL * size


def twin_groups(nodes: tuple[RenderNode, ...]) -> np.ndarray:
    """For every node, the index of the first node holding the same surface
    (the same object or an equal one) under the same transform; -1 for nodes
    without a surface.  Hashable surfaces are grouped through a dict (linear
    in the number of nodes); others are compared with each other."""
    first = np.full(len(nodes), -1, dtype=np.int64)
    seen: dict[Any, int] = {}
    unhashable: list[int] = []
    for k, node in enumerate(nodes):
        s = node.surface
        if s is None:
            continue
        key = (type(s), s, node.transform)
        try:
            first[k] = seen.setdefault(key, k)
            continue
        except TypeError:  # a surface with array fields
            pass
        for j in unhashable:
            other = nodes[j]
            try:
                same = type(other.surface) is type(s) and (
                    other.surface is s or bool(other.surface == s)
                )
            except Exception:  # noqa: BLE001 - an __eq__ comparing arrays, ...: not twins
                same = False
            if same and other.transform == node.transform:
                first[k] = j
                break
        else:
            first[k] = k
            unhashable.append(k)
    return first
