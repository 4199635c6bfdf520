"""Intersection curves drawn by default: where the surfaces of two nodes meet.

For every pair of surface nodes whose boxes (in the world) overlap, the
curves where they meet are drawn as family ``"intersection"``:

* where one of the two surfaces has an implicit equation ``F = 0``
  (quadrics, the torus, quartics: ``Surface.implicit``), on the other one as
  the zero set of ``F`` along it, ``F(x(u1, u2)) = 0`` in its parameter
  plane (``lgraph.families.level.level_batches``: sign changes on a
  grid of 193 x 193 parameters, then Newton's method at every evaluation):
  the points lie exactly on the parametrized surface and on the implicit
  one to ``1e-14`` of the range of ``F``;
* otherwise by marching on both parameter planes
  (:func:`~lgraph.intersection_curves`), with
  Newton's method onto both surfaces at every evaluation.

The other surface is moved into the drawing node's frame, so the curves
live in that node's local coordinates like every family's.  They do not
depend on the view and are cached with the other families
(:mod:`lgraph.families.cache`): a turntable finds them once.  A loop of the
curve smaller than a cell of the grid of parameters can be missed.

A node added with ``intersections=False``, or ``render(...,
intersections=False)``, draws none; the same surface added twice in the
same place (a twin) meets itself everywhere and is skipped.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from ..families import Family
from ..families.cache import family_batches
from ..families.intersection import IntersectionCurve
from ..families.level import level_batches
from ..geometry.transforms import Transform
from ..geometry.vectors import box_corners
from ..surfaces._base import Domain, Surface

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..scene.projectors import Projector
    from ._protocols import RenderNode

__all__ = ["Meeting", "Placed", "intersection_batches", "meeting_pairs"]


@attrs.frozen
class Placed(Surface):
    """``surface`` moved by ``transform`` (``x -> matrix @ x + offset``):
    the same parameters, the same domain, exact derivatives.

    >>> import lgraph as lg
    >>> p = Placed(lg.Sphere(1.0), lg.translate(0, 0, 2))
    >>> bool(np.allclose(p.point(0.3, 0.2), lg.Sphere(1.0).point(0.3, 0.2) + [0, 0, 2]))
    True
    """

    surface: Surface
    transform: Transform

    @property
    def domain(self) -> Domain:
        return self.surface.domain

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        return self.transform.apply(self.surface.point(u1, u2))

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        x1, x2 = self.surface.derivatives(u1, u2)
        return self.transform.apply_vector(x1), self.transform.apply_vector(x2)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return _moved_box(self.surface, self.transform)


@attrs.frozen
class Meeting(Family):
    """The curves where the surface meets ``other``, given with the
    ``placement`` that moves ``other``'s local coordinates into the
    surface's (family ``"intersection"``).  Equal by value, so the family
    cache finds it again in the next render.

    >>> import lgraph as lg
    >>> m = Meeting(lg.Sphere(1.0), lg.translate(0.5, 0, 0))
    >>> (batch,) = m.batches(lg.Sphere(1.0), None)
    >>> xyz, _ = batch.evaluate(np.zeros(5, int), np.linspace(batch.t0[0], batch.t1[0], 5))
    >>> bool(np.allclose(xyz[:, 0], 0.25))  # the plane x = 1/4 between the centres
    True
    """

    view_dependent: ClassVar[bool] = False

    other: Surface
    placement: Transform

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        implicit = getattr(self.other, "implicit", None)
        if not getattr(surface, "parametric", True):  # an implicit surface: space curves
            return surface.meeting_curves(self.other, self.placement)  # type: ignore[attr-defined]
        if implicit is None:
            # marching steps may try points outside a patch: no warnings from there
            with np.errstate(all="ignore"):
                return IntersectionCurve(Placed(self.other, self.placement)).batches(surface, None)
        to_other = self.placement.inverse()

        def f(u1: Any, u2: Any) -> np.ndarray:
            return np.asarray(implicit(to_other.apply(surface.point(u1, u2))), float)

        d = surface.domain
        g1, g2 = np.meshgrid(np.linspace(*d.u1, 33), np.linspace(*d.u2, 33), indexing="ij")
        with np.errstate(all="ignore"):
            values = f(g1, g2)
        values = values[np.isfinite(values)]
        # the scale of F on the patch: Newton stops within 1e-14 of it
        spread = float(np.ptp(values)) if len(values) else 0.0
        return level_batches(surface, f, [0.0], spread or 1.0, family="intersection")


def _moved_box(surface: Surface, transform: Transform) -> tuple[np.ndarray, np.ndarray]:
    """The box of ``surface``'s box moved by ``transform``."""
    c = transform.apply(box_corners(*surface.bounds()))
    return c.min(axis=0), c.max(axis=0)


def meeting_pairs(nodes: tuple[RenderNode, ...], first: np.ndarray) -> list[tuple[int, int]]:
    """Pairs ``(i, j)``, ``i < j``, of surface nodes whose world boxes
    overlap (the surfaces may meet), twins left out; ``first`` from
    :func:`~lgraph.render.twins.twin_groups`."""
    cand = [k for k, n in enumerate(nodes) if n.surface is not None and first[k] == k]
    if len(cand) < 2:
        return []
    boxes = np.array(
        [np.concatenate(_moved_box(nodes[k].surface, nodes[k].transform)) for k in cand]
    )
    lo, hi = boxes[:, :3], boxes[:, 3:]
    # sorted by the lower x: each box meets only the boxes starting before its end
    order = np.argsort(lo[:, 0], kind="stable")
    lo, hi = lo[order], hi[order]
    stop = np.searchsorted(lo[:, 0], hi[:, 0], "right")
    pairs = []
    for i in range(len(cand)):
        j = np.arange(i + 1, stop[i])
        j = j[np.all((lo[j] <= hi[i]) & (hi[j] >= lo[i]), axis=1)]
        pairs.extend((cand[order[i]], cand[order[k]]) for k in j.tolist())
    return [(min(p), max(p)) for p in pairs]


def intersection_batches(
    nodes: tuple[RenderNode, ...], pairs: list[tuple[int, int]]
) -> dict[int, list[tuple[CurveBatch, int]]]:
    """The intersection curves of the node ``pairs`` that may meet
    (:func:`meeting_pairs`): per node index, the batches it draws and, with
    each, the other node they lie on."""
    out: dict[int, list[tuple[CurveBatch, int]]] = {}
    for a, b in pairs:
        if not getattr(nodes[b].surface, "parametric", True):
            a, b = b, a  # traced in space on the implicit surface (ImplicitSurface)
        elif (
            getattr(nodes[a].surface, "parametric", True)
            and getattr(nodes[b].surface, "implicit", None) is None
            and (getattr(nodes[a].surface, "implicit", None) is not None)
        ):
            a, b = b, a  # drawn on the parametrized one, as a zero set of the implicit one
        on, other = nodes[a], nodes[b]
        family = Meeting(other.surface, on.transform.inverse() @ other.transform)
        out.setdefault(a, []).extend((bt, b) for bt in family_batches(on, -1, family, None))
    return out
