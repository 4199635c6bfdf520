"""Bounding boxes of a parametrized surface's patches, for the numeric ray test.

A ``HIT_LEAVES x HIT_LEAVES`` grid of parameter patches, each sampled 3 x 3
and bounded by the box of its samples padded by a bound on how far the
surface strays from them (second differences), and the boxes of their
ancestors up to one root box: a bounding-volume hierarchy, built once per
surface (cached, with the leaves' samples and paddings for their facets) and
refusing degenerate surfaces.  :func:`_candidates` descends it for many rays
at once (slab tests) and returns the leaf patches a ray may meet, which
:mod:`~lgraph.surfaces.parametric._hits` judges by their facets.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..._tolerance import HIT_CHUNK_RAYS, HIT_MAX_CANDIDATES
from .._memo import per_surface

if TYPE_CHECKING:
    from .._domain import Parametrized

#: leaves per parameter of the hit hierarchy (a power of two)
HIT_LEAVES = 64

#: a list while the renderer probes the cost of its ray tests
#: (:mod:`lgraph.render.prediction`): every descent of a hierarchy appends
#: ``(id of the surface, number of (ray, leaf box) pairs met)``
METER: list[tuple[int, int]] | None = None


def set_meter(meter: list[tuple[int, int]] | None) -> None:
    """Start (a list) or stop (None) metering the boxes met (:data:`METER`)."""
    global METER
    METER = meter


def _cell_pad(S: np.ndarray) -> np.ndarray:
    """Padding of the box of each patch sampled by a 3x3 grid ``S (..., 3, 3, 3)``:
    a bound on how far the surface strays from the samples' hull."""
    d1 = np.linalg.norm(S[..., 0, :, :] - 2 * S[..., 1, :, :] + S[..., 2, :, :], axis=-1).max(-1)
    d2 = np.linalg.norm(S[..., :, 0, :] - 2 * S[..., :, 1, :] + S[..., :, 2, :], axis=-1).max(-1)
    d12 = np.linalg.norm(
        S[..., 0, 0, :] - S[..., 2, 0, :] - S[..., 0, 2, :] + S[..., 2, 2, :], axis=-1
    )
    return 0.5 * (d1 + d2) + 0.25 * d12


class _Hierarchy:
    """Boxes of a ``HIT_LEAVES x HIT_LEAVES`` parameter grid and their ancestors."""

    def __init__(self, surface: Parametrized) -> None:
        d = surface.domain
        n = HIT_LEAVES
        self.n = n
        self.name = type(surface).__name__
        self.key = id(surface)
        self.lo1, self.lo2 = d.u1[0], d.u2[0]
        self.h1, self.h2 = d.span(0) / n, d.span(1) / n
        u1 = np.linspace(*d.u1, 2 * n + 1)
        u2 = np.linspace(*d.u2, 2 * n + 1)
        raw = surface.point(*np.meshgrid(u1, u2, indexing="ij"))
        P = np.where(np.isfinite(raw), raw, 0.0)
        lo, hi = surface.bounds()
        self.size = float(np.linalg.norm(np.asarray(hi) - np.asarray(lo)))
        # leaf samples (n, n, 3, 3, 3)
        ia = 2 * np.arange(n)[:, None] + np.arange(3)[None, :]
        S = P[ia[:, None, :, None], ia[None, :, None, :]]
        _check_regular(surface, P, S)
        pad = _cell_pad(S)[..., None] + 1e-9 * self.size
        blo = S.min(axis=(2, 3)) - pad
        bhi = S.max(axis=(2, 3)) + pad
        # every leaf's nine samples and padding, for the rays' triangle test
        # (NaN where the surface is not defined: such leaves are ambiguous)
        self.grid = raw
        self.periodic = tuple(g is True for g in d.periodic)
        self.leaf_samples = raw[ia[:, None, :, None], ia[None, :, None, :]].reshape(n * n, 9, 3)
        self.leaf_pad = pad.reshape(n * n)
        self.levels = [(blo, bhi)]
        while blo.shape[0] > 1:
            blo = np.minimum.reduce(
                [blo[0::2, 0::2], blo[1::2, 0::2], blo[0::2, 1::2], blo[1::2, 1::2]]
            )
            bhi = np.maximum.reduce(
                [bhi[0::2, 0::2], bhi[1::2, 0::2], bhi[0::2, 1::2], bhi[1::2, 1::2]]
            )
            self.levels.append((blo, bhi))
        self.levels.reverse()  # root first
        self.flat = [(a.reshape(-1, 3), b.reshape(-1, 3)) for a, b in self.levels]


def _check_regular(surface: Parametrized, P: np.ndarray, S: np.ndarray) -> None:
    """Refuse a degenerate surface before any ray is cast at it.

    ``P`` is the sample grid over the whole domain and ``S`` the 3x3 samples of
    every leaf patch.  All points equal, or a leaf patch whose nine samples
    span no area (collapsed to a point or a curve: not a regular patch), make
    every ray meet every such patch (the hit test would subdivide without
    end).  Poles are fine: a patch touching a pole still spans an area.
    """
    name = type(surface).__name__
    ext = float(np.ptp(P.reshape(-1, 3), axis=0).max())
    if not ext > 0:
        raise ValueError(
            f"{name}: the surface is degenerate: all its points are equal "
            f"({P.reshape(-1, 3)[0].tolist()}); it has no area to draw"
        )
    a = S[..., 2, 2, :] - S[..., 0, 0, :]
    b = S[..., 2, 0, :] - S[..., 0, 2, :]
    c = S[..., 2, 1, :] - S[..., 0, 1, :]
    e = S[..., 1, 2, :] - S[..., 1, 0, :]
    area = np.maximum(
        np.linalg.norm(np.cross(a, b), axis=-1), np.linalg.norm(np.cross(c, e), axis=-1)
    )
    flat = area <= 1e-12 * ext * ext
    if flat.any():
        i, j = np.argwhere(flat)[0]
        d = surface.domain
        h1, h2 = d.span(0) / flat.shape[0], d.span(1) / flat.shape[1]
        u1, u2 = d.u1[0] + i * h1, d.u2[0] + j * h2
        raise ValueError(
            f"{name}: the surface is not regular on part of its domain: the patch "
            f"u1 in [{u1:.6g}, {u1 + h1:.6g}], u2 in [{u2:.6g}, {u2 + h2:.6g}] "
            f"({int(flat.sum())} of {flat.size} patches) collapses to a point or a curve; "
            "restrict u1_range/u2_range to where the surface is regular"
        )


def _hierarchy(surface: Parametrized) -> _Hierarchy:
    """The surface's hierarchy, built once per surface object."""
    return per_surface(surface, "hierarchy", lambda: _Hierarchy(surface))


def _inverse(v: np.ndarray) -> np.ndarray:
    """``1 / v`` with zero components replaced by a huge finite value."""
    with np.errstate(divide="ignore"):
        return np.where(v == 0, 1e300, 1.0 / np.where(v == 0, 1.0, v))


def _slab(o: np.ndarray, inv: np.ndarray, lo: np.ndarray, hi: np.ndarray, smax: np.ndarray) -> Any:
    """Ray/box test for ``0 <= s <= smax`` (``inv = _inverse(v)``); returns
    (hit, s_enter, s_exit)."""
    with np.errstate(invalid="ignore", over="ignore"):
        t1 = (lo - o) * inv
        t2 = (hi - o) * inv
    a = np.minimum(t1, t2)
    b = np.maximum(t1, t2)
    tmin = np.maximum(np.maximum(a[:, 0], a[:, 1]), np.maximum(a[:, 2], 0.0))
    tmax = np.minimum(np.minimum(b[:, 0], b[:, 1]), np.minimum(b[:, 2], smax))
    return tmax >= tmin, tmin, tmax


def _candidates(H: _Hierarchy, o: np.ndarray, v: np.ndarray, smax: np.ndarray) -> Any:
    """(ray, i, j, s_enter, s_exit) of leaves whose boxes the rays meet."""
    inv = _inverse(v)
    r = np.arange(len(o))
    k = np.zeros(len(o), int)  # flat box index at the current level
    s0 = s1 = None
    di = np.array([0, 1, 0, 1])
    dj = np.array([0, 0, 1, 1])
    for lvl, (blo, bhi) in enumerate(H.flat):
        ok, s0, s1 = _slab(o[r], inv[r], blo[k], bhi[k], smax[r])
        r, k, s0, s1 = r[ok], k[ok], s0[ok], s1[ok]
        if len(r) > HIT_MAX_CANDIDATES * max(1.0, len(o) / HIT_CHUNK_RAYS):
            raise ValueError(
                f"{H.name}: rays meet more than {HIT_MAX_CANDIDATES // HIT_CHUNK_RAYS} patch "
                "boxes each on average (the limit): the surface winds over itself too many "
                "times or is nearly degenerate; draw one turn (narrow u1_range/u2_range) "
                "and repeat it with transforms"
            )
        if lvl + 1 < len(H.flat):
            m = 1 << lvl  # boxes per row at this level
            i, j = k // m, k % m
            r = np.repeat(r, 4)
            k = ((2 * i)[:, None] + di).ravel() * (2 * m) + ((2 * j)[:, None] + dj).ravel()
    n = H.n
    if METER is not None:
        METER.append((H.key, len(r)))
    return r, k // n, k % n, s0, s1
