"""Surfaces as a user writes them (a numpy function ``point(u, v)`` only):
shared by tests/test_singular_edges.py and benchmarks/bench_user_surfaces.py."""

from __future__ import annotations

import numpy as np


def stack(*c):
    """The coordinates ``c`` broadcast and stacked on a last axis of 3."""
    return np.stack(np.broadcast_arrays(*c), -1)


def enneper(u, v):
    return stack(u - u**3 / 3 + u * v**2, v - v**3 / 3 + v * u**2, u**2 - v**2)


def dini(u, v, a=1.0, b=0.2):
    """Dini's surface; its cuspidal edge is ``v = pi/2``."""
    z = a * (np.cos(v) + np.log(np.tan(v / 2))) + b * u
    return stack(a * np.cos(u) * np.sin(v), a * np.sin(u) * np.sin(v), z)


def boy(u, v):
    """Apery's Boy surface over the square ``(0, pi)^2`` (the edge ``v = pi/2``
    collapsed to a point)."""
    r2 = np.sqrt(2.0)
    cv2 = np.cos(v) ** 2
    d = 2 - r2 * np.sin(3 * u) * np.sin(2 * v)
    x = (r2 * cv2 * np.cos(2 * u) + np.cos(u) * np.sin(2 * v)) / d
    y = (r2 * cv2 * np.sin(2 * u) - np.sin(u) * np.sin(2 * v)) / d
    return stack(x, y, 3 * cv2 / d)
