"""The contour of a surface of revolution in closed form per parallel.

On the parallel ``t`` the contour points solve ``z'(t) R0 cos(phi - psi0) = C(t)``
(see :mod:`lgraph.surfaces.revolution`), so ``phi = psi0 +- arccos(g(t))`` with
``g = C / (z' R0)`` wherever ``D(t) = (z' R0)^2 - C^2 >= 0``.  The ends of such
a ``t`` interval are folds (``D = 0``, found on the profile grid and refined to
machine precision) or ends of the profile.  Near a fold ``arccos g`` grows like
``sqrt(t - t_fold)``; the curves are therefore parametrized by ``sigma`` with
``t - t_fold ~ sigma^2``, which makes them smooth through their folds:

* fold to fold: one closed curve, ``t = ta + (tb - ta)(1 - cos sigma)/2``,
  ``0 <= sigma <= 2 pi``, the ``+`` branch where ``sin sigma >= 0``;
* fold to end (or end to fold): one open curve through the fold,
  ``|sigma| <= pi/2``;
* end to end: the two branches, each an open curve linear in ``t``.

A view along the axis makes whole parallels the contour: the roots of ``C``.
A partial turn (``angle_range`` shorter than ``2 pi``) cuts the curves to it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ...curves import CurveBatch
from .._patch import clip_intervals

if TYPE_CHECKING:
    from ...scene.projectors import Projector
    from ._protocol import Revolved

__all__ = ["contour", "view_terms", "contour_residual"]

_CLOSED, _FOLD_LO, _FOLD_HI, _PLUS, _MINUS = range(5)


def view_terms(surface: Revolved, projector: Projector) -> tuple[bool, float, float, float]:
    """``(central, w_a, R0, psi0)``: the view vector (parallel) or the eye
    (central) in the surface's frame, as axial part and polar form."""
    from ...scene.projectors import CentralProjector

    central = isinstance(projector, CentralProjector)
    w = np.asarray(projector.eye if central else projector.frame[2], float)
    e1, e2, a = surface.frame
    w1, w2 = float(w @ e1), float(w @ e2)
    return central, float(w @ a), float(np.hypot(w1, w2)), float(np.arctan2(w2, w1))


def _c_terms(
    surface: Revolved, t: np.ndarray, central: bool, wa: float
) -> tuple[np.ndarray, np.ndarray]:
    """``(C(t), z'(t))``."""
    dr, dz = surface.drz(t)
    if central:
        rho, z = surface.rz(t)
        return dz * rho + dr * (wa - z), dz
    return dr * wa, dz


def contour_residual(surface: Revolved, projector: Projector, uv: np.ndarray) -> np.ndarray:
    """``N . w / |w|`` at parameters ``uv (n, 2)`` from the closed-form terms
    (zero on the contour; for tests and diagnostics)."""
    central, wa, r0, psi0 = view_terms(surface, projector)
    t, phi = uv[:, 0], uv[:, 1]
    c, dz = _c_terms(surface, t, central, wa)
    dr, _ = surface.drz(t)
    num = dz * r0 * np.cos(phi - psi0) - c
    if central:
        w = np.asarray(projector.eye, float) - surface.point(t, phi)
        wn = np.linalg.norm(w, axis=-1)
    else:
        wn = 1.0
    return num / (np.hypot(dr, dz) * wn)


def _curves(surface: Revolved, d_of: Any, dd_of: Any) -> list[tuple[float, float, int, bool]]:
    """``(ta, tb, kind, closed)`` of every contour curve (``d_of``: ``D(t)``,
    ``dd_of``: ``(D, D')``; the folds by safeguarded Newton steps)."""
    from ._fast import newton

    g = surface._grid
    t = g["t"]
    dv = d_of(t)
    inside = dv >= 0
    j = np.nonzero(inside[1:] != inside[:-1])[0]
    span = surface.t_range[1] - surface.t_range[0]
    folds = t[j].copy()  # D = 0 at a node (a cusp edge at an end): the node itself
    open_ = np.flatnonzero(dv[j] != 0)
    if len(open_):
        k = j[open_]
        folds[open_] = newton(
            lambda x, sel: dd_of(x), t[k], t[k + 1], dv[k], dv[k + 1], 4e-16 * span, 0.0
        )
    # intervals (ta, tb, fold at ta, fold at tb) where D >= 0
    pieces: list[list[Any]] = []
    start: tuple[float, bool] | None = (float(t[0]), False) if inside[0] else None
    for k, tf in zip(j.tolist(), folds.tolist()):
        if not inside[k]:  # entering
            start = (tf, True)
        elif start is not None:
            pieces.append([start[0], tf, start[1], True])
            start = None
    if start is not None:
        pieces.append([start[0], float(t[-1]), start[1], False])
    if surface.profile_closed and pieces:
        if len(pieces) == 1 and not pieces[0][2] and not pieces[0][3]:  # D >= 0 all round
            lo, hi = pieces[0][:2]
            return [(lo, hi, _PLUS, True), (lo, hi, _MINUS, True)]
        first, last = pieces[0], pieces[-1]
        if len(pieces) > 1 and not first[2] and not last[3]:  # one interval across the seam
            pieces = [[last[0], first[1] + span, last[2], first[3]]] + pieces[1:-1]
    out: list[tuple[float, float, int, bool]] = []
    for ta, tb, fa, fb in pieces:
        if tb - ta <= 1e-12 * span:
            continue
        if fa and fb:
            out.append((ta, tb, _CLOSED, True))
        elif fa or fb:
            out.append((ta, tb, _FOLD_LO if fa else _FOLD_HI, False))
        else:
            out += [(ta, tb, _PLUS, False), (ta, tb, _MINUS, False)]
    return out


def contour(surface: Revolved, projector: Projector) -> list[CurveBatch]:
    """The contour curves of ``surface`` for ``projector`` (local frame), one batch."""
    central, wa, r0, psi0 = view_terms(surface, projector)
    scale = np.hypot(r0, wa)
    if r0 <= 1e-12 * scale:  # view along the axis: whole parallels
        from ...families._lines import parameter_line_batches

        roots = surface._roots_in_t(lambda x: _c_terms(surface, x, central, wa)[0])
        roots = roots[~surface._at_pole(roots)]
        return parameter_line_batches(surface, roots, [], "contour", "contour")

    def d_of(x: np.ndarray) -> np.ndarray:
        c, dz = _c_terms(surface, x, central, wa)
        return (dz * r0) ** 2 - c * c

    def dd_of(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        # D' = 2 z' z'' R0^2 - 2 C C', C' = rho'' w_a (parallel view) or
        # z'' rho + rho'' (e_a - z) (central: the z' rho' terms cancel)
        c, dz = _c_terms(surface, x, central, wa)
        ddr, ddz = surface.ddrz(x)
        if central:
            rho, z = surface.rz(x)
            dc = ddz * rho + ddr * (wa - z)
        else:
            dc = ddr * wa
        return (dz * r0) ** 2 - c * c, 2 * (dz * ddz * r0 * r0 - c * dc)

    curves = _curves(surface, d_of, dd_of)
    if not curves:
        return []
    ta, tb, kind, closed = (np.array(v) for v in zip(*curves))
    t_lo, period = surface.t_range[0], surface.t_range[1] - surface.t_range[0]
    lo = np.where(kind == _CLOSED, 0.0, np.where(kind >= _PLUS, 0.0, -np.pi / 2))
    hi = np.where(kind == _CLOSED, 2 * np.pi, np.where(kind >= _PLUS, 1.0, np.pi / 2))

    def uv(idx: np.ndarray, s: np.ndarray) -> np.ndarray:
        a, b, k = ta[idx], tb[idx], kind[idx]
        one_minus = 1 - np.cos(s)
        t = np.select(
            [k == _CLOSED, k == _FOLD_LO, k == _FOLD_HI],
            [a + (b - a) * one_minus / 2, a + (b - a) * one_minus, b - (b - a) * one_minus],
            a + (b - a) * s,
        )
        t = np.clip(t, a, b)
        if surface.profile_closed:
            t = t_lo + np.mod(t - t_lo, period)
        sign = np.select(
            [k == _CLOSED, k <= _FOLD_HI, k == _PLUS],
            [np.mod(s, 2 * np.pi) <= np.pi, s >= 0, True],
            False,
        )
        c, dz = _c_terms(surface, t, central, wa)
        den = dz * r0
        with np.errstate(invalid="ignore", divide="ignore"):
            q = np.where(den == 0, 0.0, c / np.where(den == 0, 1.0, den))
        phi = psi0 + np.where(sign, 1.0, -1.0) * np.arccos(np.clip(q, -1.0, 1.0))
        return np.stack([t, phi], axis=-1)

    d = surface.domain
    mid = 0.5 * sum(surface.angle_range)

    def _centred(phi: np.ndarray) -> np.ndarray:
        # angles within pi of the middle of the drawn turn
        return mid + np.mod(phi - mid + np.pi, 2 * np.pi) - np.pi

    cid = np.arange(len(ta))
    if not d.periodic[1]:
        half = 0.5 * (surface.angle_range[1] - surface.angle_range[0])

        def margin(idx: np.ndarray, s: np.ndarray) -> np.ndarray:
            return half - np.abs(_centred(uv(idx, s)[:, 1]) - mid)

        cid, lo, hi, closed = clip_intervals(margin, lo, hi, closed)
        if not len(cid):
            return []

    def uv_all(idx: np.ndarray, s: np.ndarray) -> np.ndarray:
        p = uv(cid[idx], s)
        if not d.periodic[1]:
            p[:, 1] = _centred(p[:, 1])
        return d.wrap(p)

    return [CurveBatch.from_uv(surface, "contour", lo, hi, uv_all, closed=closed)]
