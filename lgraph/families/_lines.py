"""The parameter lines of a patch as one curve batch, and the spacings of the
numeric line families: what the surface base class's defaults share with the
families, kept below both (issue #30).

:func:`parameter_line_batches` is re-exported by :mod:`lgraph.families`, the
path plugins import it from.  It types its surface by
:class:`~lgraph.surfaces._domain.Parametrized` (every
:class:`~lgraph.Surface` is one), so that it need not import the base class
that calls it.

>>> import lgraph as lg
>>> [len(b) for b in parameter_line_batches(lg.Sphere(1), [0.0, 1.0], [0.5])]
[3]
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..curves import CurveBatch

if TYPE_CHECKING:
    from ..surfaces._domain import Domain, Parametrized

__all__ = ["SPACINGS", "parameter_line_batches"]

#: how a numeric line family spreads its lines (``spacing=``): complete lines,
#: or lines trimmed where they come close to another (evenly spaced)
SPACINGS = ("complete", "even")


def _glued_lines(d: Domain, i: int, c: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lines ``u_i = c`` (running along ``u_j``) as ``(c, turns, closed)``: a
    line crossing a twisted seam of ``u_j`` comes back as ``u_i = a + b - c``
    and closes after two turns (one if ``c`` is the middle); a line whose
    continuation is another line of ``c`` is left out (it is drawn as part
    of the first)."""
    j = 1 - i
    if not d.twisted[j]:
        return c, np.ones(len(c)), np.full(len(c), d.glued[j])
    span = d.span(i)
    m = d.mirror(i, c)
    if d.glued[i]:
        m = d.range(i)[0] + np.mod(m - d.range(i)[0], span)

    def same(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        q = (a - b) / span
        if d.glued[i]:
            q = q - np.round(q)
        return np.abs(q) <= 1e-12

    self_mirror = same(c, m)
    keep = np.ones(len(c), bool)
    for k in range(len(c)):
        if keep[k] and not self_mirror[k]:
            keep[k + 1 :] &= ~same(c[k + 1 :], m[k])
    return c[keep], np.where(self_mirror[keep], 1.0, 2.0), np.ones(int(keep.sum()), bool)


def parameter_line_batches(
    surface: Parametrized,
    values1: np.ndarray,
    values2: np.ndarray,
    family1: str = "u1",
    family2: str = "u2",
) -> list[CurveBatch]:
    """One batch with the lines ``u1 = values1[k]`` (family ``family1``) and
    ``u2 = values2[k]`` (``family2``); empty if there are none.  A line that
    crosses a twisted seam continues, mirrored, as one stroke
    (:class:`~lgraph.surfaces._domain.Domain`)."""
    d = surface.domain
    c1, turns1, closed1 = _glued_lines(d, 0, np.asarray(values1, float).ravel())
    c2, turns2, closed2 = _glued_lines(d, 1, np.asarray(values2, float).ravel())
    n1, n2 = len(c1), len(c2)
    if not n1 + n2:
        return []
    const = np.concatenate([c1, c2])
    # lines along a twisted parameter start half-way (their ends are not on the seam)
    start = [d.range(j)[0] + 0.5 * d.span(j) * d.twisted[j] for j in (0, 1)]

    def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
        first = idx < n1  # a line u1 = const, running along u2
        c = const[idx]
        out = np.empty((len(c), 2))
        out[:, 0] = np.where(first, c, t)
        out[:, 1] = np.where(first, t, c)
        return d.wrap(out, clip=False) if d.twisted[0] or d.twisted[1] else out

    names = (family1,) * n1 + (family2,) * n2
    return [
        CurveBatch.from_uv(
            surface,
            family1 if n1 else family2,
            np.concatenate([np.full(n1, start[1]), np.full(n2, start[0])]),
            np.concatenate([start[1] + turns1 * d.span(1), start[0] + turns2 * d.span(0)]),
            uv,
            closed=np.concatenate([closed1, closed2]),
            curve_family=None if family1 == family2 else names,
        )
    ]
