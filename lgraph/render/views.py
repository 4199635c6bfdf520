"""The views of one render pass: one projector, or several rendered together.

:func:`lgraph.render.render_views` renders a scene from many views (the
frames of an animation) in one pass: the curves of every view are samples
of one set of flat arrays (``Samples`` in :mod:`lgraph.render.sampling`), so
each stage of the pipeline costs a handful of numpy calls for all views
instead of for each.  Every sample knows its view; the projector's
operations are applied per view, each view's rows with that view's own
projector (the same arithmetic as a render of that view alone).

With one projector every operation is that projector's own call, so a
single render is unchanged.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

import numpy as np

from ..scene.projectors import CentralProjector, Projector, unit_rays

__all__ = ["Views", "as_views", "runs"]


class Views:
    """Projectors of the views rendered together, applied to rows of points
    that each carry a view index (``view``: an int array, or None for all
    rows in view 0)."""

    def __init__(self, projectors: Sequence[Projector]) -> None:
        self.projectors = tuple(projectors)
        if not self.projectors:
            raise ValueError("render_views: no views given")
        self.k = len(self.projectors)
        central = [isinstance(p, CentralProjector) for p in self.projectors]
        # views of one kind: their geometry gathered per row (the projectors'
        # own formulas, term by term, so each row gets the bits its view alone gives)
        self._kind = "central" if all(central) else "parallel" if not any(central) else None
        if self._kind == "parallel":
            self._plane = np.array([p._plane for p in self.projectors])
            self._toward = np.array([p.frame[2] for p in self.projectors])
        elif self._kind == "central":
            self._eye = np.array([p.eye for p in self.projectors])
            self._basis = np.array([p._basis for p in self.projectors])
            self._distance = np.array([p.distance for p in self.projectors])

    def groups(self, view: np.ndarray | int | None) -> Iterator[tuple[int, np.ndarray | slice]]:
        """``(k, rows)`` for every view ``k`` present among the rows (``view``:
        one per row, or one for all)."""
        if isinstance(view, (int, np.integer)):
            yield int(view), slice(None)
            return
        if self.k == 1 or view is None:
            yield 0, slice(None)
            return
        yield from runs(view)

    def project(self, xyz: np.ndarray, view: np.ndarray | None = None) -> np.ndarray:
        """Projections ``(n, 2)`` of points ``xyz``, each in its view."""
        if self.k == 1 or view is None:
            return self.projectors[0].project(xyz)
        if isinstance(view, (int, np.integer)):
            return self.projectors[view].project(xyz)
        if self._kind == "parallel":
            return _linear_map_rows(xyz, self._plane, view, 2)
        if self._kind == "central":
            q = _linear_map_rows(xyz - _rows(self._eye, view), self._basis, view, 3)
            with np.errstate(divide="ignore", invalid="ignore"):
                return q[:, :2] * (-self._distance[view] / q[:, 2])[:, None]
        out = np.empty((len(xyz), 2))
        for k, rows in self.groups(view):
            out[rows] = self.projectors[k].project(xyz[rows])
        return out

    def rays(
        self, xyz: np.ndarray, view: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """Unit directions toward the viewer and ray lengths (see
        :meth:`lgraph.Projector.rays`), each point in its view."""
        if self.k == 1 or view is None:
            return self.projectors[0].rays(xyz)
        if isinstance(view, (int, np.integer)):
            return self.projectors[view].rays(xyz)
        if self._kind == "parallel":
            return _rows(self._toward, view), np.full(len(xyz), np.inf)
        if self._kind == "central":
            return unit_rays(_rows(self._eye, view) - xyz)
        dirs, smax = np.empty((len(xyz), 3)), np.empty(len(xyz))
        for k, rows in self.groups(view):
            dirs[rows], smax[rows] = self.projectors[k].rays(xyz[rows])
        return dirs, smax

    def behind(self, xyz: np.ndarray, view: np.ndarray | None = None) -> np.ndarray:
        """Which points lie at or behind the eye of their (central) view."""
        out = np.zeros(len(xyz), dtype=bool)
        for k, rows in self.groups(view):
            p = self.projectors[k]
            if isinstance(p, CentralProjector):
                out[rows] = p.depth(xyz[rows]) <= 0
        return out


def runs(keys: np.ndarray) -> Iterator[tuple[int, np.ndarray | slice]]:
    """``(key, rows)`` for every distinct value of the int array ``keys``, in
    increasing order; ``rows`` is a slice when ``keys`` is sorted (samples
    come sorted by curve, so by view and by batch), else the row indices in
    their original order.

    >>> [(k, r) for k, r in runs(np.array([0, 0, 2]))]
    [(0, slice(0, 2, None)), (2, slice(2, 3, None))]
    >>> [(k, r.tolist()) for k, r in runs(np.array([1, 0, 1]))]
    [(0, [1]), (1, [0, 2])]
    """
    n = len(keys)
    if not n:
        return
    if keys[0] == keys[-1] and (keys == keys[0]).all():  # one key (a lone batch, a lone view)
        yield int(keys[0]), slice(0, n)
        return
    if np.all(keys[1:] >= keys[:-1]):
        order, ks = None, keys
    else:
        order = np.argsort(keys, kind="stable")
        ks = keys[order]
    cuts = (np.flatnonzero(ks[1:] != ks[:-1]) + 1).tolist()
    for lo, hi in zip([0, *cuts], [*cuts, n]):
        yield int(ks[lo]), slice(lo, hi) if order is None else order[lo:hi]


def _rows(table: np.ndarray, view: np.ndarray) -> np.ndarray:
    """``table[view]`` for a small ``(k, 3)`` table, gathered column by column
    (several times faster than one fancy index of the rows)."""
    out = np.empty((len(view), table.shape[1]))
    for i in range(table.shape[1]):
        out[:, i] = table[:, i][view]
    return out


def _linear_map_rows(xyz: np.ndarray, m: np.ndarray, view: np.ndarray, k: int) -> np.ndarray:
    """``linear_map(xyz[i], m[view[i]])`` for every row (``m``: ``(views, 3,
    k)``), term by term as :func:`lgraph.scene.projectors.linear_map` does, so
    that each row gets the bits of its view alone."""
    x, y, z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    out = np.empty((len(xyz), k))
    for j in range(k):
        out[:, j] = x * m[:, 0, j][view] + y * m[:, 1, j][view] + z * m[:, 2, j][view]
    return out


def as_views(projector: Projector | Views) -> Views:
    """``projector`` as :class:`Views` (one view), or the views themselves."""
    return projector if isinstance(projector, Views) else Views([projector])
