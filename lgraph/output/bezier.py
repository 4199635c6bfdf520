r"""Exact curves at any size: strokes as cubic Bézier segments fitted to the true curve.

Every stroke the renderer makes remembers its curve (:class:`CurveRef`: the
curve batch, the curve's index, the node's transform, the projector, and the
curve parameter of each sample), so a backend can evaluate the exact
projected curve ``x(t)`` anywhere, not just at the samples.  A piece
``[t_a, t_b]`` of it becomes the cubic Hermite interpolant, written as a
Bézier segment with control points

.. math::

   P_0 = x(t_a), \quad P_1 = P_0 + \tfrac{\Delta t}{3} x'(t_a), \quad
   P_2 = P_3 - \tfrac{\Delta t}{3} x'(t_b), \quad P_3 = x(t_b),

``Δt = t_b - t_a``: its value and tangent agree with the curve's at both
ends, the curve's tangents being one-sided second-order differences on the
exact curve inside the piece (steps of ``1e-4 Δt``; one-sided, so a cusp or
a piece ending where visibility changes gets the tangent of its own side).
A segment is split in half (in ``t``) until the Bézier point at ``f`` is
within 0.95 ``precision`` of ``x(t_a + f Δt)`` at ``f = 1/16, ..., 15/16``:
that parametric distance bounds the distance between the two curves at the
test points (between them the error of a cubic fit varies slowly, hence the
margin).  The error
of Hermite interpolation falls as ``Δt^4`` (a polyline's as ``Δt^2``), so at
a poster's size a few segments replace many chords.  Stroke ends (visibility
transitions, halos) are segment ends: they stay exact.

>>> import lgraph as lg
>>> scene = lg.Scene()
>>> _ = scene.add(lg.Sphere(1), lg.ParameterLines(0, 1), contour=False)
>>> d = scene.render(lg.ParallelProjector(direction=(0, -1, 0)))
>>> runs = page_curve_runs(d, 0.01)
>>> pts, stroke, bezier = runs[0]
>>> bezier, (len(pts) - 1) % 3 == 0, len(pts) < len(stroke.xy)
(True, True, True)
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

__all__ = [
    "CurveRef",
    "fit_pieces",
    "page_curve_runs",
    "bezier_points",
    "halo_pieces",
    "unwrapped",
]

#: test points of a segment (fractions of its parameter interval) ...
_TESTS = np.arange(1, 16) / 16.0
#: ... where the error must be within this fraction of the precision (the
#: largest error may fall between them: measured at A0, 2 % beyond it)
_MARGIN = 0.95
#: the step of the one-sided differences, as a fraction of the segment
_STEP = 1e-4
#: at most this many rounds of halving (2**-40 of a piece)
_ROUNDS = 40
#: a piece starts as segments of about this many of its samples
_SEED_EVERY = 16
#: at most this many segments are refined in one round
_MAX_SEGMENTS = 2_000_000
#: bisection steps locating where a curve crosses a halo's edge
_HALO_STEPS = 50


@attrs.frozen(eq=False)
class CurveRef:
    """How to evaluate a stroke's exact curve: curve ``index`` of ``batch``,
    moved by ``transform`` and projected by ``projector``; ``t`` holds the
    curve parameter of each of the stroke's samples, increasing (a closed
    curve's run across its seam continues past ``t1``: :meth:`!wrap` takes
    such parameters modulo the period)."""

    batch: Any
    index: int
    transform: Any
    projector: Any
    t: np.ndarray
    t0: float = attrs.field(converter=float)
    t1: float = attrs.field(converter=float)
    closed: bool = attrs.field(default=False, converter=bool)

    def __reduce__(self) -> tuple[Any, tuple[()]]:
        # curve batches hold local functions: a pickled drawing (sent to
        # another process) keeps its samples and draws them as polylines
        return (_no_curve, ())

    def key(self) -> tuple[int, int, int]:
        """What curves evaluated in one call share."""
        return (id(self.batch), id(self.transform), id(self.projector))

    def wrap(self, t: np.ndarray) -> np.ndarray:
        if not self.closed:
            return t
        return np.where(t > self.t1, t - (self.t1 - self.t0), t)


def unwrapped(t: np.ndarray, lens: np.ndarray, period: np.ndarray) -> np.ndarray:
    """Curve parameters ``t`` of consecutive strokes (``lens[k]`` samples
    each, on a curve of ``period[k]``) made increasing along each stroke:
    where a closed curve's run crosses its seam (``t`` drops back), the
    period is added from there on.

    >>> unwrapped(np.array([5.0, 6.0, 1.0, 2.0, 0.0, 1.0]), np.array([4, 2]), np.array([6.0, 6.0]))
    array([5., 6., 7., 8., 0., 1.])
    """
    if not len(t):
        return t
    sid = np.repeat(np.arange(len(lens)), lens)
    wraps = np.concatenate([[0], (np.diff(t) < 0) & (sid[1:] == sid[:-1])]).astype(np.int64)
    count = np.cumsum(wraps)
    first = np.minimum(np.concatenate([[0], np.cumsum(lens)[:-1]]), len(t) - 1).astype(np.int64)
    count -= count[first][sid]
    return t + count * np.asarray(period, float)[sid]


def _no_curve() -> None:
    """What a pickled :class:`CurveRef` becomes."""
    return None


class _Curves:
    """The curves of :class:`CurveRef` objects as arrays, grouped by what is
    evaluated in one call (batch, transform, projector)."""

    def __init__(self, refs: list[CurveRef]) -> None:
        self.refs = refs
        self.index = np.array([r.index for r in refs], dtype=np.int64)
        self.closed = np.array([r.closed for r in refs], dtype=bool)
        self.t1 = np.array([r.t1 for r in refs], dtype=float)
        self.period = self.t1 - np.array([r.t0 for r in refs], dtype=float)
        groups: dict[tuple[int, int, int], int] = {}
        self.group = np.array([groups.setdefault(r.key(), len(groups)) for r in refs])
        self.first = {g: refs[k] for k, g in reversed(list(enumerate(self.group.tolist())))}

    def xy(self, which: np.ndarray, t: np.ndarray) -> np.ndarray:
        """Projection coordinates of curve ``which[i]`` at ``t[i]``."""
        out = np.full((len(t), 2), np.nan)
        gid = self.group[which]
        for g, ref in self.first.items():
            rows = np.flatnonzero(gid == g)
            if not len(rows):
                continue
            w = which[rows]
            tt = np.where(
                self.closed[w] & (t[rows] > self.t1[w]), t[rows] - self.period[w], t[rows]
            )
            with np.errstate(all="ignore"):
                x, _ = ref.batch.evaluate(self.index[w], tt)
                x = np.asarray(x, float).reshape(-1, 3)
                if not ref.transform.is_identity:
                    x = ref.transform.apply(x)
                out[rows] = np.asarray(ref.projector.project(x), float).reshape(-1, 2)
        return out


def bezier_points(p0: np.ndarray, d0: np.ndarray, p3: np.ndarray, d3: np.ndarray, dt: np.ndarray):
    """The control points ``P1, P2`` of the Hermite cubics (ends ``p0, p3``,
    derivatives ``d0, d3`` in ``t``, intervals ``dt``)."""
    k = (dt / 3.0)[:, None]
    return p0 + k * d0, p3 - k * d3


def _cubic(p0, p1, p2, p3, f: np.ndarray) -> np.ndarray:
    """Points of the cubics (rows) at fractions ``f`` (``(m,)``): ``(n, m, 2)``."""
    f = f[None, :, None]
    g = 1.0 - f
    return (
        g**3 * p0[:, None] + 3 * g * g * f * p1[:, None] + 3 * g * f * f * p2[:, None]
        + f**3 * p3[:, None]
    )  # fmt: skip


def _segments(curves: _Curves, which, ta, tb):
    """Ends, tangents and test points of the segments ``[ta, tb]`` of curves
    ``which``: one evaluation of all their points."""
    dt = tb - ta
    h = _STEP * dt
    n, m = len(ta), len(_TESTS)
    params = np.concatenate(
        [
            ta,
            ta + h,
            ta + 2 * h,
            tb,
            tb - h,
            tb - 2 * h,
            (ta[:, None] + dt[:, None] * _TESTS).ravel(),
        ]
    )
    who = np.concatenate([np.tile(which, 6), np.repeat(which, m)])
    xy = curves.xy(who, params)
    a, a1, a2, b, b1, b2 = (xy[k * n : (k + 1) * n] for k in range(6))
    tests = xy[6 * n :].reshape(n, m, 2)
    with np.errstate(all="ignore"):
        da = (-3 * a + 4 * a1 - a2) / (2 * h)[:, None]
        db = (3 * b - 4 * b1 + b2) / (2 * h)[:, None]
    p1, p2 = bezier_points(a, da, b, db, dt)
    return a, p1, p2, b, tests


def fit_pieces(
    refs: list[CurveRef], pieces: list[tuple[int, np.ndarray]], tol: float
) -> list[np.ndarray | None]:
    """Bézier control polygons ``(3k + 1, 2)`` (projection coordinates) of
    ``pieces``: ``(ref index, breakpoints)`` with the piece's first and last
    parameter and the parameters it starts split at; each segment within
    ``tol`` of the exact curve.  None for a piece whose curve gives no
    finite points (its polyline is drawn instead)."""
    if not pieces:
        return []
    curves = _Curves(refs)
    owner = np.concatenate([np.full(len(b) - 1, k) for k, (_, b) in enumerate(pieces)])
    which = np.concatenate([np.full(len(b) - 1, r) for r, b in pieces])
    ta = np.concatenate([b[:-1] for _, b in pieces])
    tb = np.concatenate([b[1:] for _, b in pieces])
    done: list[tuple[np.ndarray, ...]] = []
    for rnd in range(_ROUNDS + 1):
        if not len(ta):
            break
        p0, p1, p2, p3, tests = _segments(curves, which, ta, tb)
        err = np.hypot(*(_cubic(p0, p1, p2, p3, _TESTS) - tests).transpose(2, 0, 1)).max(axis=1)
        ok = err <= _MARGIN * tol
        # the last round, too many segments, or no finite curve here (the
        # piece falls back to its polyline): accepted as they are
        last = rnd == _ROUNDS or len(ta) > _MAX_SEGMENTS
        good = ok | last | ~np.isfinite(err)
        done.append((owner[good], ta[good], p0[good], p1[good], p2[good], p3[good]))
        bad = ~good
        mid = 0.5 * (ta[bad] + tb[bad])
        owner = np.repeat(owner[bad], 2)
        which = np.repeat(which[bad], 2)
        ta, tb = np.column_stack([ta[bad], mid]).ravel(), np.column_stack([mid, tb[bad]]).ravel()
    own, t, q0, q1, q2, q3 = (np.concatenate(c) for c in zip(*done))
    order = np.lexsort((t, own))
    own, q0, q1, q2, q3 = own[order], q0[order], q1[order], q2[order], q3[order]
    out: list[np.ndarray | None] = []
    starts = np.searchsorted(own, np.arange(len(pieces)))
    stops = np.searchsorted(own, np.arange(len(pieces)), side="right")
    for k in range(len(pieces)):
        a, b = starts[k], stops[k]
        ctrl = np.stack([q0[a:b], q1[a:b], q2[a:b]], axis=1).reshape(-1, 2)
        poly = np.vstack([ctrl, q3[b - 1 : b]])
        out.append(poly if len(poly) > 1 and np.isfinite(poly).all() else None)
    return out


def _seeds(t: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Breakpoints of a piece ``[lo, hi]`` of a stroke sampled at ``t``:
    its ends and every ``_SEED_EVERY``-th sample inside."""
    inner = np.unique(t[(t > lo) & (t < hi)])[_SEED_EVERY // 2 :: _SEED_EVERY]
    return np.concatenate([[lo], inner, [hi]])


def page_curve_runs(drawing: Any, precision_pt: float) -> list[tuple[np.ndarray, Any, bool]]:
    """The strokes of ``drawing`` on its page (pt, y up) in drawing order,
    as ``(points, stroke, is_bezier)``: Bézier control polygons within
    ``precision_pt`` of the exact curves for the strokes that know their
    curve (``Stroke.curve``), the page polylines
    (:func:`!lgraph.output.backends._common.page_runs`) for the others (point
    marks, drawings built by hand or cleaned for plotters).  Halos cut the curves
    where they cross the regions' edges (located on the exact curve)."""
    from .backends._common import page_runs
    from .halos import halo_regions

    scale, offset, _, _ = drawing._layout()
    order = sorted(range(len(drawing.strokes)), key=lambda i: drawing.strokes[i].visible)
    strokes = [drawing.strokes[i] for i in order]
    fits = [s for s in strokes if _fits(s)]
    fit_ids = {id(s) for s in fits}
    boxes, discs = halo_regions(drawing)
    refs = [s.curve for s in fits]
    pieces: list[tuple[int, np.ndarray]] = []
    owner: list[int] = []
    for k, s in enumerate(fits):
        t = np.asarray(s.curve.t, float)
        spans = [(t[0], t[-1])]
        if len(boxes) or len(discs):
            spans = halo_pieces(s.curve, t, np.asarray(s.xy) * scale + offset, scale, offset,
                                boxes, discs)  # fmt: skip
        for lo, hi in spans:
            if hi > lo:
                pieces.append((k, _seeds(t, lo, hi)))
                owner.append(k)
    polys = fit_pieces(refs, pieces, precision_pt / scale)
    by_stroke: dict[int, list[np.ndarray]] = {}
    fallback: set[int] = set()
    for k, poly in zip(owner, polys):
        if poly is None:
            fallback.add(id(fits[k]))
        else:
            by_stroke.setdefault(id(fits[k]), []).append(poly * scale + offset)
    lines: dict[int, list[np.ndarray]] = {}
    if len(fit_ids) < len(strokes) or fallback:
        for pts, s in page_runs(drawing):
            if id(s) not in fit_ids or id(s) in fallback:
                lines.setdefault(id(s), []).append(pts)
    out: list[tuple[np.ndarray, Any, bool]] = []
    for s in strokes:
        if id(s) in by_stroke and id(s) not in fallback:
            out.extend((p, s, True) for p in by_stroke[id(s)])
        else:
            out.extend((p, s, False) for p in lines.pop(id(s), []))
    return out


def _fits(stroke: Any) -> bool:
    """Whether a stroke can be fitted: it knows its curve, for every sample."""
    c = getattr(stroke, "curve", None)
    return (
        c is not None
        and len(c.t) == len(stroke.xy) >= 2
        and stroke.family != "point"
        and c.t[-1] > c.t[0]
        and bool(np.all(np.diff(c.t) >= 0))  # repeated samples (a flip located twice) pass
    )


def halo_pieces(
    curve: CurveRef,
    t: np.ndarray,
    page: np.ndarray,
    scale: float,
    offset: Any,
    boxes: np.ndarray,
    discs: np.ndarray,
) -> list[tuple[float, float]]:
    """The parameter intervals of a stroke (samples at ``t``, ``page`` their
    page points) outside the halos' regions, their ends located on the exact
    curve by bisection: where a sample and the next lie on either side of a
    region's edge, or where the chord between two outer samples crosses a
    region and the curve at the middle of that crossing is inside."""
    from .halos import box_intervals, disc_intervals

    curves = _Curves([curve])

    def inside(q: np.ndarray) -> np.ndarray:
        x, y = q[:, 0], q[:, 1]
        out = np.zeros(len(q), bool)
        for x0, y0, x1, y1 in boxes:
            out |= (x > x0) & (x < x1) & (y > y0) & (y < y1)
        for cx, cy, r in discs:
            out |= np.hypot(x - cx, y - cy) < r
        return out

    def at(tt: np.ndarray) -> np.ndarray:
        return curves.xy(np.zeros(len(tt), np.int64), tt) * scale + offset

    ins = inside(page)
    a, b = page[:-1], page[1:]
    lo_in, hi_in = np.full(len(a), np.inf), np.full(len(a), -np.inf)
    for box in boxes:
        t0, t1 = box_intervals(a, b, box)
        hit = t0 < t1
        lo_in, hi_in = (
            np.where(hit, np.minimum(lo_in, t0), lo_in),
            np.where(hit, np.maximum(hi_in, t1), hi_in),
        )
    for cx, cy, r in discs:
        t0, t1 = disc_intervals(a, b, (cx, cy), r)
        hit = t0 < t1
        lo_in, hi_in = (
            np.where(hit, np.minimum(lo_in, t0), lo_in),
            np.where(hit, np.maximum(hi_in, t1), hi_in),
        )
    ta, tb = t[:-1], t[1:]
    through = ~ins[:-1] & ~ins[1:] & (lo_in < hi_in)
    with np.errstate(invalid="ignore"):  # inf - inf where a chord misses every region
        mid = ta + 0.5 * (lo_in + hi_in) * (tb - ta)
    through_i = np.flatnonzero(through)
    if len(through_i):
        really = inside(at(mid[through_i]))
        through_i = through_i[really]
    # brackets (outside end, inside end) of every crossing, sorted along t
    enter = np.flatnonzero(~ins[:-1] & ins[1:])
    leave = np.flatnonzero(ins[:-1] & ~ins[1:])
    out_t = np.concatenate([ta[enter], tb[leave], ta[through_i], tb[through_i]])
    in_t = np.concatenate([tb[enter], ta[leave], mid[through_i], mid[through_i]])
    kind = np.concatenate([np.ones(len(enter)), -np.ones(len(leave)), np.ones(len(through_i)),
                           -np.ones(len(through_i))])  # fmt: skip
    for _ in range(_HALO_STEPS):  # all crossings at once
        m = 0.5 * (out_t + in_t)
        is_in = inside(at(m))
        out_t, in_t = np.where(is_in, out_t, m), np.where(is_in, m, in_t)
    edge = out_t
    order = np.argsort(edge, kind="stable")
    edge, kind = edge[order], kind[order]
    spans, start = [], (None if ins[0] else float(t[0]))
    for e, k in zip(edge.tolist(), kind.tolist()):
        if k > 0 and start is not None:
            spans.append((start, e))
            start = None
        elif k < 0:
            start = e
    if start is not None and not ins[-1]:
        spans.append((start, float(t[-1])))
    return spans
