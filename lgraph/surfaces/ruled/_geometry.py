"""Ruled surfaces: evaluation, the ``u1`` grid and the patch's bounds.

The base of the ruled-surface classes (:mod:`lgraph.surfaces.ruled`;
docs/mathematics.rst, "Ruled surfaces, general cylinders and cones"):
``x = y(u1) + u2 z(u1)`` with ``x1 = y' + u2 z'``, ``x2 = z``,
``x11 = y'' + u2 z''``, ``x12 = z'``, ``x22 = 0``, the unit director
``z = d/|d|`` and its derivatives from those of the director ``d`` a class
supplies (:meth:`_RuledGeometry._raw`).

The grid of ``u1`` on which :mod:`~lgraph.surfaces.ruled._hits`,
:mod:`~lgraph.surfaces.ruled._contour` and :mod:`~lgraph.surfaces.ruled._curvature` scan
for sign changes is computed once per surface:
its nodes are equidistributed in the total turning of ``z`` and of the tangent
of ``y`` plus the arc length of the patch's ``u2`` edges (about
``RULED_CELLS_PER_UNIT`` cells per radian and per patch diameter).  The patch
lies in the hull of its ``u2`` edges (rulings are straight), which bounds it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..._tolerance import RULED_CELLS_PER_UNIT as _CELLS_PER_UNIT
from ..._tolerance import RULED_MAX_CELLS as _MAX_CELLS
from ..._tolerance import RULED_MIN_CELLS as _MIN_CELLS
from ..._tolerance import RULED_PRE_SAMPLES as _PRE_SAMPLES
from ..._tolerance import RULED_XTOL as _XTOL
from ...curves import CurveBatch
from ...geometry.vectors import dot as _dot
from .._base import Domain, Surface


def _flips(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(row, cell) of every sign change between neighbouring columns."""
    s = values >= 0
    return np.nonzero(s[:, 1:] != s[:, :-1])


class _RuledGeometry(Surface):
    """What a ruled surface is: evaluation, the ``u1`` grid, bounds.

    Subclasses supply :meth:`_raw`: the directrix, an (unnormalized) director
    ``d`` and their derivatives; ``z = d/|d|`` unless ``_unit`` is False.
    """

    _unit = True
    default_families = ("parameter_lines",)

    # -- to be supplied -----------------------------------------------------
    def _raw(self, u: np.ndarray, order: int) -> list[Any]:  # pragma: no cover
        """``[y, y', y'', d, d', d'']`` at ``u`` (entries above ``order`` may be None)."""
        raise NotImplementedError

    def _default_u2(self) -> tuple[float, float]:
        return (0.0, self._directrix_diameter())

    # -- set-up -------------------------------------------------------------
    def _setup(self) -> None:
        curve = self.directrix
        probe = self._raw(np.linspace(curve.t0, curve.t1, 257), 0)
        dn = np.linalg.norm(probe[3], axis=-1)
        if not np.all(np.isfinite(dn)) or not np.all(dn > 1e-12 * (dn.max() + 1e-300)):
            raise ValueError(
                f"{type(self).__name__}: the ruling direction must be a non-zero finite vector "
                "for every parameter value (does the directrix pass through the apex, or "
                "have a zero derivative?)"
            )
        if self.u2_range is None:
            object.__setattr__(self, "u2_range", self._default_u2())

    def _directrix_diameter(self) -> float:
        c = self.directrix
        y = c(np.linspace(c.t0, c.t1, 257))
        d = float(np.linalg.norm(y.max(axis=0) - y.min(axis=0)))
        return d if d > 0 else 1.0

    @property
    def domain(self) -> Domain:
        c = self.directrix
        return Domain((c.t0, c.t1), self.u2_range, periodic=(c.closed, False))

    # -- evaluation -----------------------------------------------------------
    def _rul(self, u: Any, order: int = 0) -> list[Any]:
        """``[y, y', y'', z, z', z'']`` at the flat array ``u``."""
        u = np.asarray(u, float)
        y, y1, y2, d, d1, d2 = self._raw(u, order)
        d = np.broadcast_to(d, u.shape + (3,))
        if not self._unit:
            z1 = None if order < 1 else np.broadcast_to(d1, d.shape)
            z2 = None if order < 2 else np.broadcast_to(d2, d.shape)
            return [y, y1, y2, d, z1, z2]
        rho = np.linalg.norm(d, axis=-1, keepdims=True)
        z = d / rho
        z1 = z2 = None
        if order >= 1:
            rho1 = _dot(d1, z)[..., None]
            z1 = (d1 - z * rho1) / rho
            if order >= 2:
                rho2 = (_dot(d2, z) + _dot(d1, z1))[..., None]
                z2 = (d2 - 2 * z1 * rho1 - z * rho2) / rho
        return [y, y1, y2, z, z1, z2]

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        """``y(u1) + u2 z(u1)``, broadcasting."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        y, _, _, z, _, _ = self._rul(u1.ravel(), 0)
        x = y + u2.reshape(-1, 1) * z
        return x.reshape(u1.shape + (3,))

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        """``x1 = y' + u2 z'`` and ``x2 = z``."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        y, y1, _, z, z1, _ = self._rul(u1.ravel(), 1)
        x1 = y1 + u2.reshape(-1, 1) * z1
        x2 = np.broadcast_to(z, x1.shape)
        return x1.reshape(u1.shape + (3,)), np.array(x2).reshape(u1.shape + (3,))

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``x11 = y'' + u2 z''``, ``x12 = z'``, ``x22 = 0``."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        _, _, y2, _, z1, z2 = self._rul(u1.ravel(), 2)
        x11 = y2 + u2.reshape(-1, 1) * z2
        shape = u1.shape + (3,)
        z1 = np.broadcast_to(z1, x11.shape)
        return x11.reshape(shape), np.array(z1).reshape(shape), np.zeros(shape)

    # -- the u1 grid (computed once) --------------------------------------------
    def _grid(self) -> dict[str, Any]:
        cache = self._cache
        if "grid" in cache:
            return cache["grid"]
        c = self.directrix
        lo, hi = self.u2_range
        u = np.linspace(c.t0, c.t1, _PRE_SAMPLES)
        y, y1, y2, z, z1, _ = self._rul(u, 2)
        y1 = np.broadcast_to(y1, y.shape)
        y2 = np.broadcast_to(y2, y.shape)
        z1 = np.broadcast_to(z1, y.shape)
        edges = np.concatenate([y + lo * z, y + hi * z])
        box_lo, box_hi = edges.min(axis=0), edges.max(axis=0)
        diam = float(np.linalg.norm(box_hi - box_lo)) or 1.0
        zz = _dot(z, z)
        turn_z = np.linalg.norm(np.cross(z, z1), axis=-1) / zz
        sp = _dot(y1, y1)
        with np.errstate(divide="ignore", invalid="ignore"):
            turn_t = np.linalg.norm(np.cross(y1, y2), axis=-1) / sp
        turn_t = np.where(sp > 1e-24 * (sp.max() + 1e-300), turn_t, 0.0)
        speed = np.linalg.norm(y1 + lo * z1, axis=-1) + np.linalg.norm(y1 + hi * z1, axis=-1)
        span = c.t1 - c.t0
        dens = turn_z + np.minimum(turn_t, 1e3 / span) + speed / diam + 4.0 / span
        mu = np.concatenate([[0.0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(u))])
        n = int(np.clip(math.ceil(_CELLS_PER_UNIT * mu[-1]), _MIN_CELLS, _MAX_CELLS))
        nodes = np.interp(np.linspace(0.0, mu[-1], n + 1), mu, u)
        nodes[0], nodes[-1] = c.t0, c.t1
        Y, Y1, _, Z, Z1, _ = self._rul(nodes, 1)
        Y1 = np.broadcast_to(Y1, Y.shape)
        Z = np.broadcast_to(Z, Y.shape)
        Z1 = np.broadcast_to(Z1, Y.shape)
        # bounds: the patch lies in the hull of its u2 edges (rulings are straight);
        # pad by the chord error of the sampled edges
        chord = max(
            float(np.abs(e[:-2] - 2 * e[1:-1] + e[2:]).max()) for e in (y + lo * z, y + hi * z)
        )
        pad = 0.01 * diam + chord
        grid = {
            "u": nodes,
            "Y": np.array(Y),
            "Y1": np.array(Y1),
            "Z": np.array(Z),
            "Z1": np.array(Z1),
            "YxZ": np.cross(Y, Z),
            "dYxZ": np.cross(Y1, Z) + np.cross(Y, Z1),
            "bounds": (box_lo - pad, box_hi + pad),
            "xtol": _XTOL * max(abs(c.t0), abs(c.t1), span),
            "zmax": float(np.linalg.norm(Z, axis=-1).max()),
        }
        cache["grid"] = grid
        return grid

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self._grid()["bounds"]
        return lo.copy(), hi.copy()

    @property
    def size(self) -> float:
        lo, hi = self._grid()["bounds"]
        return float(np.linalg.norm(hi - lo))

    def _ruling_batch(self, values: np.ndarray, family: str) -> CurveBatch:
        lo, hi = self.u2_range
        c1 = np.asarray(values, float)
        return CurveBatch.from_uv(
            self,
            family,
            np.full(len(c1), lo),
            np.full(len(c1), hi),
            lambda idx, t: np.column_stack([c1[idx], t]),
        )

    def _u2_line_batch(self, values: np.ndarray, family: str) -> CurveBatch:
        c = self.directrix
        c2 = np.asarray(values, float)
        return CurveBatch.from_uv(
            self,
            family,
            np.full(len(c2), c.t0),
            np.full(len(c2), c.t1),
            lambda idx, t: np.column_stack([t, c2[idx]]),
            closed=c.closed,
        )

    def describe(self) -> str:
        return repr(self)
