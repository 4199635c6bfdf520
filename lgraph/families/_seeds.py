"""Seeds of numeric line families: where to start lines, and along which branch.

Shared by the complete families (:mod:`lgraph.families.numeric`) and the evenly
spaced ones (:mod:`lgraph.families._even`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .fieldlines import FieldLines

__all__: list[str] = []


def _center_seed(surface: Any, field: Any, stop: float) -> np.ndarray:
    """A seed near the middle of the domain where the field is well defined."""
    d = surface.domain
    f = np.array([0.5, 0.42, 0.58, 0.35, 0.65, 0.3, 0.7, 0.2, 0.8])
    c1 = d.u1[0] + d.span(0) * f
    c2 = d.u2[0] + d.span(1) * f[[0, 2, 1, 4, 3, 6, 5, 8, 7]]
    U = np.stack(np.meshgrid(c1, c2, indexing="ij"), -1).reshape(-1, 2)
    D, a, _ = field(surface, U)
    a = np.where(np.isfinite(a) & _stable(surface, field, U, D[:, 0])
                 & _stable(surface, field, U, D[:, 1]), a, -1.0)  # fmt: skip
    good = np.flatnonzero(a > 20 * stop)
    return U[good[0] if len(good) else int(np.argmax(a))]


def _stable(surface: Any, field: Any, seeds: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    """Whether the field's branch along ``dirs`` at ``seeds`` is resolved: the
    nearest branch a small step (1e-3 of the spans) away in each of four
    directions is within 20 degrees.  A seed on (or next to) a singular point
    fails: its direction would hang on rounding."""
    d = surface.domain
    m = len(seeds)
    step = 1e-3 * np.array([d.span(0), d.span(1)])
    offsets = np.array([[1, 0], [-1, 0], [0, 1], [0, -1]]) * step
    around = (seeds[None] + offsets[:, None]).reshape(-1, 2)
    # neighbours past an edge that is not glued are taken on the edge
    D, strength, G = field(surface, d.wrap(np.concatenate([seeds, around]), clip=True))
    ref = np.tile(dirs, (5, 1))
    Gr = np.stack([G[:, 0] * ref[:, 0] + G[:, 1] * ref[:, 1],
                   G[:, 1] * ref[:, 0] + G[:, 2] * ref[:, 1]], axis=1)  # fmt: skip
    nr = np.sqrt(np.einsum("ij,ij->i", ref, Gr))
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.abs(np.einsum("ibj,ij->ib", D, Gr)).max(axis=1) / nr
        ok = (c > np.cos(np.radians(20))) & np.isfinite(strength)
    return ok.reshape(5, m).all(axis=0)


def _spread(lines: FieldLines, k: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n`` parameters evenly spread in arc length along line ``k``, and the
    line's tangents there."""
    a, b = -lines.ends[1, k], lines.ends[0, k]
    frac = np.arange(n) / n if lines.closed[k] else (np.arange(n) + 0.5) / n
    t = a + (b - a) * frac
    uv = lines.uv_line(k, t)
    eps = 1e-6 * max(b - a, 1e-300)
    tangent = lines.uv_line(k, np.minimum(t + eps, b)) - lines.uv_line(k, np.maximum(t - eps, a))
    return uv, tangent


def _crossing(field: Any, surface: Any, uv: np.ndarray, tangent: np.ndarray) -> np.ndarray:
    """The field's branch at ``uv`` most transversal to ``tangent`` (both in
    the parameter plane): the lines that cross a transversal line."""
    D, _, G = field(surface, surface.domain.wrap(uv, clip=True))
    Gt = np.stack([G[:, 0] * tangent[:, 0] + G[:, 1] * tangent[:, 1],
                   G[:, 1] * tangent[:, 0] + G[:, 2] * tangent[:, 1]], axis=1)  # fmt: skip
    c = np.abs(np.einsum("ibj,ij->ib", D, Gt))
    return D[np.arange(len(uv)), (c[:, 1] < c[:, 0]).astype(int)]


def cell_centres(domain: Any, n: int) -> np.ndarray:
    """The centres ``(n * n, 2)`` of an ``n x n`` grid of cells over the
    parameter rectangle (never on an edge, a seam or a pole)."""
    f = (np.arange(n) + 0.5) / n
    axes = [domain.range(i)[0] + domain.span(i) * f for i in (0, 1)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 2)


def _grid(surface: Any, field: Any, stop: float, n: int = 24) -> tuple:
    """Grid points of the patch where the field is well defined: parameters,
    points and area weights (zero where the field is not)."""
    G = cell_centres(surface.domain, n)
    _, strength, g = field(surface, G)
    with np.errstate(invalid="ignore"):
        area = np.sqrt(np.maximum(g[:, 0] * g[:, 2] - g[:, 1] ** 2, 0.0))
        good = np.isfinite(strength) & (strength > 20 * stop) & np.isfinite(area)
    weight = np.where(good, area, 0.0)
    return G, surface.points(G), weight / max(weight.sum(), 1e-300)
