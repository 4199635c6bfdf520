"""Measuring written curves against the exact ones on the page, independently
of :mod:`lgraph.output.bezier` (used by tests/test_figures_bezier.py and
benchmarks/bench_bezier.py)."""

from __future__ import annotations

import numpy as np

import lgraph as lg


def exact(stroke: lg.Stroke, t: np.ndarray, scale: float, offset) -> np.ndarray:
    """The stroke's exact curve on the page at parameters ``t`` (from its
    batch, the node's transform and the projector, not from lgraph.output.bezier)."""
    c = stroke.curve
    tt = np.where(c.closed & (t > c.t1), t - (c.t1 - c.t0), t)
    x, _ = c.batch.evaluate(np.full(len(tt), c.index), tt)
    x = c.transform.apply(np.asarray(x, float).reshape(-1, 3))
    return c.projector.project(x) * scale + offset


def flatten(ctrl: np.ndarray, n: int = 64) -> np.ndarray:
    """``n`` points of each cubic Bézier segment of control points ``ctrl``."""
    p0, p1, p2, p3 = ctrl[:-1:3], ctrl[1::3], ctrl[2::3], ctrl[3::3]
    f = np.linspace(0, 1, n)[None, :, None]
    g = 1 - f
    q = g**3 * p0[:, None] + 3 * g * g * f * p1[:, None] + 3 * g * f * f * p2[:, None]
    return (q + f**3 * p3[:, None]).reshape(-1, 2)


def distance(points: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Distance of each point to the polyline (chunked brute force)."""
    a, b = poly[:-1], poly[1:]
    d = b - a
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    out = np.empty(len(points))
    for k in range(0, len(points), 256):
        q = points[k : k + 256, None, :]
        t = np.clip(np.einsum("kij,ij->ki", q - a, d) / dd, 0, 1)
        out[k : k + 256] = np.hypot(*(a + t[..., None] * d - q).transpose(2, 0, 1)).min(axis=1)
    return out


def deviation(ctrl_or_points: np.ndarray, stroke: lg.Stroke, bezier: bool, scale, offset) -> float:
    """Largest distance, both ways, between one written run (Bézier control
    points or a polyline) and its stroke's exact curve sampled 3000 times."""
    t = stroke.curve.t
    true = exact(stroke, np.linspace(t[0], t[-1], 3000), scale, offset)
    drawn = flatten(ctrl_or_points) if bezier else ctrl_or_points
    return max(distance(true, drawn).max(), distance(drawn, true).max())
