"""Self-visibility on a closed convex surface of revolution, without ray tests.

A profile may *declare* (``Profile.convex``) an
interval of ``t`` on which ``z`` is strictly monotone (``sigma = sign z'``) and
``sigma (rho' z'' - z' rho'') >= 0``.  Then the radius ``R(z) = rho(t(z))`` is
concave in ``z`` (``R'' = (rho'' z' - rho' z'') / z'^3 <= 0``), so the solid
``|x - (x.a) a| <= R(x.a)`` is convex (a sublevel set of a convex function).
When the drawn surface is all of its boundary (poles at both ends of
``t_range``, a full turn), a point ``x`` on it is hidden by the surface itself
exactly when its ray toward the viewer enters the solid, i.e. when the ray
points inward, ``N . v < 0`` (``N`` the outward normal), and its end (the eye)
lies outside the solid; a contour point is never hidden.  So
``-N . v / |v|`` is a continuous *hiding margin*, positive exactly where the
surface hides its own point: the renderer finds the flips on it by root
finding (docs/mathematics.rst, "Surfaces of revolution", convex case).

``N = sigma (z' r - rho' a) / |P'|`` needs the point's ``t``: the closest point
of the profile to the point's meridian coordinates ``(rho, h)``, started from
the monotone grid of heights and refined by Newton's method.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..._own import CONTOUR, OFF

if TYPE_CHECKING:
    from ._protocol import Revolved

__all__ = ["convex_sign", "margin", "t_of_points"]

#: Newton steps for a point's parameter (quadratic convergence from a grid cell)
NEWTON_STEPS = 8


def convex_sign(surface: Revolved) -> int:
    """``sigma = sign z'`` when the surface is the whole boundary of a convex
    solid certified by its profile (see the module docstring), else 0."""
    g = surface._grid
    if "convex" in g:
        return g["convex"]
    sign = 0
    interval = getattr(surface.profile, "convex", None)
    lo, hi = surface.t_range
    if (
        interval is not None
        and interval[0] <= lo
        and hi <= interval[1]
        and all(surface.poles)
        and surface.domain.periodic[1]
    ):
        z = g["z"]
        sign = 1 if z[-1] > z[0] else -1
    g["convex"] = sign
    return sign


def _meridian(surface: Revolved, o: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Height ``h`` and distance ``r`` from the axis of points ``o``."""
    a = surface.frame[2]
    h = o @ a
    radial = o - h[:, None] * a
    return h, np.sqrt(np.einsum("ij,ij->i", radial, radial))


def _t_guess(surface: Revolved, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Linear interpolation of ``t`` in the height grid (monotone ``z``), and
    the grid cell (index into the grid's cells) each height falls in."""
    g = surface._grid
    t, z = g["t"], g["z"]
    up = z[-1] > z[0]
    if not up:
        t, z = t[::-1], z[::-1]
    k = np.clip(np.searchsorted(z, h) - 1, 0, len(z) - 2)
    with np.errstate(invalid="ignore", divide="ignore"):
        f = np.clip((h - z[k]) / (z[k + 1] - z[k]), 0.0, 1.0)
    x = t[k] + np.nan_to_num(f) * (t[k + 1] - t[k])
    return x, (k if up else len(z) - 2 - k)


def meridian_coordinates(
    surface: Revolved, o: np.ndarray, v: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Height ``h = o . a`` and distance ``r`` from the axis of points ``o``,
    and (given ``v``) ``r^ . v`` with ``r^`` the radial unit vector (any unit
    vector at the axis, where ``z' = 0``)."""
    a = surface.frame[2]
    h = o @ a
    radial = o - h[:, None] * a
    r = np.sqrt(np.einsum("ij,ij->i", radial, radial))
    if v is None:
        return h, r, None
    rv = np.einsum("ij,ij->i", radial, v)
    np.divide(rv, r, out=rv, where=r > 0)
    return h, r, rv


def t_of_points(
    surface: Revolved, h: np.ndarray, r: np.ndarray, x: np.ndarray | None = None
) -> np.ndarray:
    """The parameter ``t`` of points with meridian coordinates ``(r, h)`` on a
    profile with monotone ``z``: the closest profile point, by Newton's method
    on ``(P(t) - q) . P'(t) = 0`` from linear interpolation of the height grid
    (or from ``x``; Gauss-Newton: the residual ``P - q`` vanishes at the root,
    so the ``(P - q) . P''`` term of the derivative is dropped without losing
    the quadratic convergence)."""
    x = _t_guess(surface, h)[0] if x is None else np.array(x, dtype=float)
    lo, hi = surface.t_range
    # a step this small leaves an error of its square: the last one needed
    last = 1e-8 * (hi - lo)
    idx = np.arange(len(x))
    for _ in range(NEWTON_STEPS):
        xi = x[idx]
        rho, zz = surface.rz(xi)
        dr, dz = surface.drz(xi)
        speed2 = dr * dr + dz * dz
        with np.errstate(invalid="ignore", divide="ignore"):
            step = ((rho - r[idx]) * dr + (zz - h[idx]) * dz) / speed2
        step[~np.isfinite(step)] = 0.0
        x[idx] = np.clip(xi - step, lo, hi)
        idx = idx[np.abs(step) > last]
        if not len(idx):
            break
    return x


def _normal_rate(surface: Revolved) -> np.ndarray:
    """Per grid cell, a bound on how much ``N . v`` (unit ``v``) can change
    between two parameters in the cell: the largest turning rate of the
    normal at its nodes, ``|rho' z'' - z' rho''| / |P'|^2``, times the cell's
    width, with a factor 4 for the turning between the nodes (cached)."""
    g = surface._grid
    if "normal_rate" not in g:
        ddr, ddz = surface.ddrz(g["t"])
        with np.errstate(invalid="ignore", divide="ignore"):
            rate = np.abs(g["drho"] * ddz - g["dz"] * ddr) / (g["drho"] ** 2 + g["dz"] ** 2)
        rate = np.nan_to_num(rate, nan=np.inf)
        g["normal_rate"] = 4 * np.maximum(rate[:-1], rate[1:]) * np.diff(g["t"])
    return g["normal_rate"]


def _eye_inside(surface: Revolved, ends: np.ndarray) -> np.ndarray:
    """Which points ``ends`` lie inside the convex solid (bisection for the
    radius at their height; only points inside the bounding cylinder)."""
    g = surface._grid
    out = np.zeros(len(ends), bool)
    if "reach2" not in g:  # the solid lies in the ball of this squared radius
        g["reach2"] = 1.01 * float(np.max(g["rho"] ** 2 + g["z"] ** 2)) + 1e-300
    near = np.flatnonzero(np.einsum("ij,ij->i", ends, ends) <= g["reach2"])
    if not len(near):
        return out
    h, r = _meridian(surface, ends[near])
    z = g["z"]
    zlo, zhi = min(z[0], z[-1]), max(z[0], z[-1])
    keep = (h > zlo) & (h < zhi) & (r < g["rho"].max())
    cand, h, r = near[keep], h[keep], r[keep]
    if not len(cand):
        return out
    lo = np.full(len(cand), surface.t_range[0])
    hi = np.full(len(cand), surface.t_range[1])
    up = z[-1] > z[0]
    for _ in range(64):  # z(t) monotone: bisection for z(t) = h
        mid = 0.5 * (lo + hi)
        above = (surface.rz(mid)[1] > h) == up
        hi = np.where(above, mid, hi)
        lo = np.where(above, lo, mid)
    out[cand] = r < surface.rz(0.5 * (lo + hi))[0]
    return out


def margin(
    surface: Revolved,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray,
    uv: np.ndarray | None = None,
    exact: bool = True,
) -> np.ndarray:
    """Hiding margin of points on a certified convex surface: positive exactly
    where the surface hides its own point (``own`` ON); -1 for contour points
    and where the eye is inside the solid; NaN for points off the surface.
    ``uv``: the points' parameters when known (else found from the points);
    ``exact=False``: only the sign is wanted (the ray test), so points whose
    sign is settled by their grid cell skip finding their exact ``t``."""
    sigma = convex_sign(surface)
    o = np.asarray(origins, float).reshape(-1, 3)
    v = np.asarray(directions, float).reshape(-1, 3)
    own = np.asarray(own)
    out = np.full(len(o), np.nan)
    out[own == CONTOUR] = -1.0
    on = np.flatnonzero((own != OFF) & (own != CONTOUR))
    if not len(on) or not sigma:
        return out
    if len(on) < len(o):
        o, v = o[on], v[on]
    h, r, rv = meridian_coordinates(surface, o, v)
    va = v @ surface.frame[2]
    vn = np.sqrt(np.einsum("ij,ij->i", v, v))

    def at(t: np.ndarray, sel: np.ndarray | slice) -> np.ndarray:
        dr, dz = surface.drz(t)
        with np.errstate(invalid="ignore", divide="ignore"):
            return -sigma * (dz * rv[sel] - dr * va[sel]) / (np.hypot(dr, dz) * vn[sel])

    if uv is not None:
        t = np.asarray(uv, float).reshape(-1, 2)[on, 0]
        m = at(t, slice(None))
        unknown = np.flatnonzero(~np.isfinite(t))
    elif exact:
        t = _t_guess(surface, h)[0]
        unknown = np.arange(len(t))
        m = np.empty(len(t))
    else:
        # the grid cell of the height holds the point's t: where the margin at the
        # interpolated t is farther from zero than its rate times the cell width,
        # its sign is already right; only the others need t exactly
        t, k = _t_guess(surface, h)
        m = at(t, slice(None))
        unknown = np.flatnonzero(np.abs(m) <= _normal_rate(surface)[k])
    if len(unknown):
        t[unknown] = t_of_points(surface, h[unknown], r[unknown], t[unknown])
        m[unknown] = at(t[unknown], unknown)
    sm = np.broadcast_to(np.asarray(smax, float), (len(out),))[on]
    fin = np.flatnonzero(np.isfinite(sm))
    if len(fin):
        inside = _eye_inside(surface, o[fin] + sm[fin, None] * v[fin])
        m[fin[inside]] = -1.0
    out[on] = m
    return out
