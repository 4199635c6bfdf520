"""Zero-set curves across twisted seams: pieces joined into curves of the cover.

Marching squares (:mod:`~lgraph.surfaces.parametric._zero_set`) treats a twisted parameter as an
ordinary closed interval, so a curve that crosses a twisted seam comes out
as pieces ending on the two glued edges.  :func:`join_pieces` joins the
pieces whose ends are glued to each other (``x(lo_i, t) = x(hi_i, a + b - t)``)
into one polyline in the cover (each piece moved into the copy of the
rectangle where the last one ended, :meth:`Domain.deck
<lgraph.surfaces._domain.Domain.deck>`); a chain that comes back to its
start is a closed curve, started in the middle of a piece (not on a seam).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["join_pieces", "unjump"]

#: ends of two pieces closer than this (in spans) under the gluing are one point
SEAM_MATCH_RTOL = 1e-6


def unjump(d: Any, p: np.ndarray) -> np.ndarray:
    """A polyline with the jumps across plain periodic seams removed (each
    jump of about one span undone)."""
    p = np.array(p, float, copy=True)
    for i in (0, 1):
        if d.periodic[i] is True and len(p) > 1:
            span = d.span(i)
            p[1:, i] += np.cumsum(-span * np.round(np.diff(p[:, i]) / span))
    return p


def _on_seam(d: Any, e: np.ndarray) -> np.ndarray:
    """Which points lie on a twisted edge of the rectangle."""
    on = np.zeros(len(e), bool)
    for i in (0, 1):
        if d.twisted[i]:
            lo, hi = d.range(i)
            tol = SEAM_MATCH_RTOL * (hi - lo)
            on |= (np.abs(e[:, i] - lo) <= tol) | (np.abs(e[:, i] - hi) <= tol)
    return on


def _links(d: Any, ends: np.ndarray) -> np.ndarray:
    """For every end (rows of ``ends``) the end glued to it, or -1."""
    m = len(ends)
    link = np.full(m, -1)
    seam = np.flatnonzero(_on_seam(d, ends))
    if len(seam) < 2:
        return link
    span = np.array([d.span(0), d.span(1)])
    a, b = ends[seam][:, None], ends[seam][None, :]
    dist = np.abs((d.nearest_image(np.broadcast_to(a, (len(seam),) * 2 + (2,)), b) - a) / span)
    dist = dist.max(axis=-1)
    np.fill_diagonal(dist, np.inf)
    best = np.argmin(dist, axis=1)
    ok = dist[np.arange(len(seam)), best] <= SEAM_MATCH_RTOL
    mutual = ok & (best[best] == np.arange(len(seam)))
    link[seam[mutual]] = seam[best[mutual]]
    return link


def join_pieces(d: Any, curves: list[tuple[np.ndarray, bool]]) -> list[tuple[np.ndarray, bool]]:
    """Zero-set curves ``(points, closed)`` of a domain with twisted
    parameters, the pieces that meet across a twisted seam joined (closed
    curves without their closing point; see the module docstring)."""
    out = [(p, c) for p, c in curves if c]
    pieces = [unjump(d, p) for p, c in curves if not c]
    if not pieces:
        return out
    ends = np.array([q for p in pieces for q in (p[0], p[-1])])
    link = _links(d, ends)
    seen = np.zeros(len(pieces), bool)

    def walk(k: int, forward: bool) -> tuple[np.ndarray, bool]:
        first = 2 * k if forward else 2 * k + 1
        chain = [pieces[k] if forward else pieces[k][::-1]]
        seen[k] = True
        last = first ^ 1
        while link[last] >= 0:
            f = int(link[last])
            j = f // 2
            if j == k and f == first:
                return np.concatenate(chain), True  # back at the start: closed
            if seen[j]:
                break
            seen[j] = True
            nxt = pieces[j] if f % 2 == 0 else pieces[j][::-1]
            S, t = d.deck(chain[-1][-1], nxt[0])
            chain.append(S * nxt[1:] + t)
            last = f ^ 1
        return np.concatenate(chain), False

    for k in range(len(pieces)):  # open curves start at an end that is not glued
        if seen[k]:
            continue
        if link[2 * k] < 0:
            out.append(walk(k, True))
        elif link[2 * k + 1] < 0:
            out.append(walk(k, False))
    for k in range(len(pieces)):  # what is left are loops
        if seen[k]:
            continue
        p, closed = walk(k, True)
        if closed and len(p) > 2:
            # drop the closing point, start in the middle of the first piece
            S, t = d.deck(p[-1], p[0])
            m = max(1, len(pieces[k]) // 2)
            p = np.concatenate([p[m:-1], S * p[:m] + t])
        out.append((p, closed))
    return out
