"""Where a curve passes through another sheet of its own surface.

A self-intersecting patch (Enneper's surface of extent 2, Boy's surface)
hides a curve on it from where the curve passes through another of its
sheets: there the ray toward the eye gains (or loses) a root at its very
origin.  When the self-intersection curve is not drawn, nothing in the net
marks these places, and K-section on the ray test found them, a dozen rounds
of costly tests.  Here the ray's root on that other sheet is followed
instead: found once at the end of the bracket where the sheet lies in front
(``nearest_roots``), then by Newton's
method on ``x(u) = p(t) + s v(t)`` from there for every ``t``; its ``s(t)``
is continuous and changes sign exactly where the curve passes through the
sheet, a root found on it by ``bracketed_roots`` with no
ray test.  Callers confirm each root with ray tests on either side
(``lgraph.render.flips.locate_flips``,
``lgraph.render.depth.occlusion_depth``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .. import _tolerance as tol
from .._own import OFF
from .._roots import bracketed_roots
from ..surfaces._base import Surface, numeric_ray_test
from ..surfaces.parametric._boxes import _hierarchy
from ..surfaces.parametric._hits import _newton, nearest_roots
from .brackets import Brackets
from .sampling import Samples

if TYPE_CHECKING:
    from .occlusion import Occlusion

__all__ = ["through_sheets"]

#: Newton iterations from the root at the bracket's front end (a chord is
#: short: 3 or 4 suffice where the root moves smoothly)
FOLLOW_STEPS = 12
#: the followed root is on another sheet where the sine of the angle between
#: its normal and the curve's own exceeds this (a root that has come onto the
#: curve's own sheet, at s = 0 for every t, is no crossing)
OTHER_SHEET_SINE = 1e-3
#: the followed root is first asked at this many points from the front end
#: of the chord to its back end
SUB_POINTS = 8


def through_sheets(s: Samples, vis: Occlusion, b: Brackets) -> tuple[np.ndarray, np.ndarray]:
    """Brackets ``b`` across which the curve may pass through a sheet of its
    own numeric surface, that sheet in front at the bracket's hidden (or
    deeper, by one sheet) end: the rows of the brackets where the ray's
    nearest root on the sheet, followed from that end, reaches the ray's
    origin, and the parameters where it does (to ``BISECTION_RTOL`` of the
    shortest span).  No ray test confirms them."""
    rows_out, t_out = [], []
    first = vis._on_first[b.owner + 1]
    one = np.ones(len(b.cid), dtype=bool) if b.after is None else np.abs(b.after - b.before) == 1
    front_hi = b.front_hi
    for j, surf, inv, _ in vis.items:
        rows = np.flatnonzero((first == j) & (b.kind != OFF) & one)
        if len(rows) and numeric_ray_test(surf):
            front = np.where(front_hi[rows], b.hi[rows], b.lo[rows])
            back = np.where(front_hi[rows], b.lo[rows], b.hi[rows])
            ok, t = _Follow(s, vis, surf, inv, b.cid[rows], b.kind[rows], front).zeros(back)
            rows_out.append(rows[ok])
            t_out.append(t)
    if not rows_out:
        return np.zeros(0, dtype=int), np.zeros(0)
    return np.concatenate(rows_out), np.concatenate(t_out)


class _Follow:
    """The root nearest to the ray's origin, at parameters ``front`` of
    curves ``cid`` on the numeric surface ``surf`` (node frame: ``inv``),
    followed along each curve by Newton's method."""

    def __init__(
        self, s: Samples, vis: Occlusion, surf: Surface, inv: object, cid: np.ndarray,
        kind: np.ndarray, front: np.ndarray,
    ) -> None:  # fmt: skip
        self.s, self.vis, self.surf, self.inv, self.cid = s, vis, surf, inv, cid
        self.front = front
        self.view = s.view[cid]
        o, v, smax, _ = self._rays(np.arange(len(cid)), front)
        self.uv0, self.s0 = nearest_roots(surf, o, v, smax, kind)
        d = surf.domain
        self.step = np.array([d.span(0) / 8, d.span(1) / 8])
        self.tol = 1e-10 * _hierarchy(surf).size

    def _rays(self, sel: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, ...]:
        x, uv, _ = self.s.evaluate(self.cid[sel], t, None)
        w, smax = self.vis.views.rays(x, self.view[sel])
        return self.inv.apply(x), self.inv.apply_vector(w), smax, uv

    def at(self, t: np.ndarray, sel: np.ndarray) -> np.ndarray:
        """``s`` of the followed roots of curves ``sel`` at ``t`` (NaN: lost,
        or come onto the curve's own sheet, where ``s = 0`` for every ``t``:
        the two normals parallel)."""
        o, v, _, uv = self._rays(sel, t)
        steps = np.tile(self.step, (len(sel), 1))
        uv_b, sv, conv = _newton(
            self.surf, o, v, self.uv0[sel], self.s0[sel], steps, self.tol, FOLLOW_STEPS
        )
        with np.errstate(all="ignore"):
            n_own = self.surf.normal(uv[:, 0], uv[:, 1])
            n_b = self.surf.normal(uv_b[:, 0], uv_b[:, 1])
            apart = np.linalg.norm(np.cross(n_own, n_b), axis=1) > OTHER_SHEET_SINE
        return np.where(conv & apart, sv, np.nan)

    def zeros(self, back: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Which curves' followed roots pass the origin between ``front`` and
        ``back`` (``s`` positive at the front, negative at the back), and where."""
        ok = np.flatnonzero(np.isfinite(self.s0) & (self.s0 > 0))
        # the root at SUB_POINTS points from the front to the back end: the
        # first where it has passed the origin is the new back end (the root
        # may leave the patch before the chord's end, e.g. near its edge)
        f = np.arange(1, SUB_POINTS + 1) / SUB_POINTS
        tt = self.front[ok, None] + (back[ok] - self.front[ok])[:, None] * f
        sv = self.at(tt.ravel(), np.repeat(ok, SUB_POINTS)).reshape(-1, SUB_POINTS)
        neg = sv < 0  # NaN (lost): not passed
        has = neg.any(axis=1)
        k = neg.argmax(axis=1)[has]
        ok, back = ok[has], tt[has, k]
        s_back = sv[has, k]
        if not len(ok):
            return ok, np.zeros(0)
        a, b = np.minimum(self.front[ok], back), np.maximum(self.front[ok], back)
        at_a = self.front[ok] < back
        fa = np.where(at_a, self.s0[ok], s_back)
        fb = np.where(at_a, s_back, self.s0[ok])
        span = np.abs(self.s.t1[self.cid[ok]] - self.s.t0[self.cid[ok]])
        xtol = tol.BISECTION_RTOL * float(span.min())
        t = bracketed_roots(lambda x, sel: self.at(x, ok[sel]), a, b, fa, fb, xtol=xtol)
        # a root on another sheet at the zero itself (beside a fold of the
        # curve's own sheet the root comes onto it, its normal turning parallel)
        real = np.isfinite(self.at(t, ok))
        return ok[real], t[real]
