"""Fundamental forms, principal curvatures and directions, and the paper's
equation (3.3) for lines of curvature.

>>> import numpy as np
>>> import lgraph as lg
>>> k1, k2 = principal_curvatures(lg.Sphere(2.0), np.array([0.3]), np.array([1.0]))
>>> np.allclose(np.abs([k1[0], k2[0]]), 0.5)
True
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = [
    "fundamental_forms",
    "principal_curvatures",
    "principal_directions",
    "curvature_equation_angle",
    "numeric_lines_of_curvature",
    "principal_field",
    "asymptotic_field",
]


def fundamental_forms(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, ...]:
    """``(g11, g12, g22, L11, L12, L22)`` at ``(u1, u2)``."""
    g11, g12, g22 = surface.first_fundamental_form(u1, u2)
    L11, L12, L22 = surface.second_fundamental_form(u1, u2)
    return g11, g12, g22, L11, L12, L22


def principal_curvatures(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    """Principal curvatures ``k1 <= k2`` from the fundamental forms."""
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    g = g11 * g22 - g12 * g12
    H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
    K = (L11 * L22 - L12 * L12) / g
    root = np.sqrt(np.maximum(H * H - K, 0.0))
    return H - root, H + root


def _direction_for(k, g11, g12, g22, L11, L12, L22):  # noqa: ANN001, ANN202
    """Parameter direction ``(du1, du2)`` solving ``(L - k G) du = 0``."""
    a11, a12, a22 = L11 - k * g11, L12 - k * g12, L22 - k * g22
    # the kernel from the longer row: (a12, -a11) from the first, (a22, -a12)
    # from the second; |first|^2 - |second|^2 = a11^2 - a22^2
    first = np.abs(a11) >= np.abs(a22)
    out = np.empty(np.shape(a11) + (2,))
    out[..., 0] = np.where(first, a12, a22)
    out[..., 1] = -np.where(first, a11, a12)
    return out


def principal_directions(surface: Any, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    """Unit 3-D principal directions ``(e1, e2)`` for ``k1 <= k2``.

    At umbilics the directions are arbitrary (returned as NaN-free vectors of
    the parameter directions).
    """
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    k1, k2 = principal_curvatures(surface, u1, u2)
    x1, x2 = surface.derivatives(u1, u2)
    out = []
    for k, fallback in ((k1, x1), (k2, x2)):
        du = _direction_for(k, g11, g12, g22, L11, L12, L22)
        e = du[..., :1] * x1 + du[..., 1:] * x2
        n = np.linalg.norm(e, axis=-1, keepdims=True)
        bad = n[..., 0] <= 1e-300
        e = np.where(bad[..., None], fallback, e)
        n = np.linalg.norm(e, axis=-1, keepdims=True)
        out.append(e / n)
    return out[0], out[1]


def curvature_equation_angle(surface: Any, uv: np.ndarray, duv: np.ndarray) -> np.ndarray:
    """Angle (radians) between the 3-D direction ``x1 du1 + x2 du2`` and the
    nearest principal direction, computed from equation (3.3) of the paper.

    Equation (3.3): ``det [[L11 du1 + L12 du2, g11 du1 + g12 du2],
    [L21 du1 + L22 du2, g21 du1 + g22 du2]] = 0`` holds exactly along lines of
    curvature.  Rather than the raw determinant (whose scale depends on the
    parametrization) this returns the angle to the closer principal direction,
    with both principal directions obtained from (3.3) as a quadratic in
    ``du1 : du2``.
    """
    uv = np.asarray(uv, float)
    duv = np.asarray(duv, float)
    u1, u2 = uv[:, 0], uv[:, 1]
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    x1, x2 = surface.derivatives(u1, u2)
    # (3.3) expanded:  A du1^2 + B du1 du2 + C du2^2 = 0
    A = L11 * g12 - L12 * g11
    B = L11 * g22 - L22 * g11
    C = L12 * g22 - L22 * g12
    t = duv[:, :1] * x1 + duv[:, 1:] * x2
    t /= np.linalg.norm(t, axis=-1, keepdims=True)
    # the two roots as directions (du1, du2); robust to A or C = 0
    disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0.0))
    s = np.where(B >= 0, 1.0, -1.0)
    q = -0.5 * (B + s * disc)
    # roots of A r^2 + B r + C = 0 with r = du1/du2:  r1 = q/A, r2 = C/q
    # use homogeneous forms to avoid dividing: (du1, du2) = (q, A) and (C, q)
    d1 = np.stack([q, A], axis=-1)
    d2 = np.stack([C, q], axis=-1)
    angles = []
    for d in (d1, d2):
        e = d[:, :1] * x1 + d[:, 1:] * x2
        n = np.linalg.norm(e, axis=-1)
        with np.errstate(invalid="ignore", divide="ignore"):
            c = np.abs(np.einsum("ij,ij->i", e, t)) / n
        angles.append(np.where(n > 0, np.arccos(np.clip(c, 0.0, 1.0)), np.pi / 2))
    return np.minimum(angles[0], angles[1])


# ---------------------------------------------------------------------------
# numeric lines of curvature (and other direction-field lines)
# ---------------------------------------------------------------------------
#: stop a line where ``(k2 - k1) / (|k1| + |k2| + 1/size)`` falls below this (umbilic)
UMBILIC_RTOL = 2e-3


def principal_field(surface: Any, uv: np.ndarray, which: np.ndarray) -> tuple[np.ndarray, ...]:
    """Parameter-plane principal direction ``(du1, du2)`` of unit 3-D length for
    the principal curvature ``k1`` (``which == 0``) or ``k2`` (``which == 1``),
    and the anisotropy ``(k2 - k1) / (|k1| + |k2|)`` (0 at umbilics)."""
    u1, u2 = uv[:, 0], uv[:, 1]
    x1, x2 = surface.derivatives(u1, u2)
    g11 = np.einsum("ij,ij->i", x1, x1)
    g12 = np.einsum("ij,ij->i", x1, x2)
    g22 = np.einsum("ij,ij->i", x2, x2)
    n = np.empty_like(x1)  # x1 x x2 (np.cross costs ~30 us on small arrays)
    n[:, 0] = x1[:, 1] * x2[:, 2] - x1[:, 2] * x2[:, 1]
    n[:, 1] = x1[:, 2] * x2[:, 0] - x1[:, 0] * x2[:, 2]
    n[:, 2] = x1[:, 0] * x2[:, 1] - x1[:, 1] * x2[:, 0]
    n /= np.sqrt(np.einsum("ij,ij->i", n, n))[:, None]
    x11, x12, x22 = surface.second_derivatives(u1, u2)
    L11 = np.einsum("ij,ij->i", n, x11)
    L12 = np.einsum("ij,ij->i", n, x12)
    L22 = np.einsum("ij,ij->i", n, x22)
    g = g11 * g22 - g12 * g12
    H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
    K = (L11 * L22 - L12 * L12) / g
    root = np.sqrt(np.maximum(H * H - K, 0.0))
    k = np.where(which == 0, H - root, H + root)
    du = _direction_for(k, g11, g12, g22, L11, L12, L22)
    e = du[:, :1] * x1 + du[:, 1:] * x2
    with np.errstate(invalid="ignore", divide="ignore"):
        du = du / np.sqrt(np.einsum("ij,ij->i", e, e))[:, None]
        aniso = 2 * root / (np.abs(H - root) + np.abs(H + root))
    return du, aniso


def asymptotic_field(surface: Any, uv: np.ndarray, which: np.ndarray) -> tuple[np.ndarray, ...]:
    """Parameter-plane asymptotic direction (``II(du) = 0``) of unit 3-D length,
    one of two (``which``), and ``-K / (H^2 + |K|)`` (positive where ``K < 0``)."""
    u1, u2 = uv[:, 0], uv[:, 1]
    g11, g12, g22, L11, L12, L22 = fundamental_forms(surface, u1, u2)
    x1, x2 = surface.derivatives(u1, u2)
    g = g11 * g22 - g12 * g12
    K = (L11 * L22 - L12 * L12) / g
    H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
    disc = np.sqrt(np.maximum(L12 * L12 - L11 * L22, 0.0))
    sgn = np.where(which == 0, 1.0, -1.0)
    # L11 a^2 + 2 L12 a b + L22 b^2 = 0: (a, b) = (-L12 +- disc, L11) or (L22, -L12 -+ disc)
    va = np.stack([-L12 + sgn * disc, L11], axis=1)
    vb = np.stack([L22, -L12 - sgn * disc], axis=1)
    use_a = np.linalg.norm(va, axis=1) >= np.linalg.norm(vb, axis=1)
    du = np.where(use_a[:, None], va, vb)
    e = du[:, :1] * x1 + du[:, 1:] * x2
    with np.errstate(invalid="ignore", divide="ignore"):
        du = du / np.linalg.norm(e, axis=1, keepdims=True)
        strength = -K / (H * H + np.abs(K))
    return du, strength


def _smoothstep(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


class _FieldLines:
    """Lines of a direction field integrated together (one ``solve_ivp`` system).

    Each line runs forward and backward from its seed up to ``length`` (3-D arc
    length), stopping where the field's strength drops below ``stop`` or the
    line leaves a non-periodic side of the domain, and closing when it returns
    to its seed.
    """

    def __init__(
        self,
        surface: Any,
        field: Any,
        seeds: np.ndarray,
        which: np.ndarray,
        length: float,
        stop: float,
        rtol: float = 1e-10,
        atol: float = 1e-12,
    ) -> None:
        from scipy.integrate import solve_ivp

        self.surface = surface
        d = surface.domain
        self.domain = d
        seeds = np.asarray(seeds, float).reshape(-1, 2)
        m = len(seeds)
        self.m = m
        size = surface.size
        du0, _ = field(surface, seeds, which)
        # orientation: forward along the larger parameter component
        flip = np.where(np.abs(du0[:, 0]) >= np.abs(du0[:, 1]), du0[:, 0], du0[:, 1]) < 0
        du0[flip] *= -1
        span = np.array([d.span(0), d.span(1)])
        lo = np.array([d.u1[0], d.u2[0]])
        hi = np.array([d.u1[1], d.u2[1]])
        per = np.array(d.periodic)
        self.sols = []
        for sign in (1.0, -1.0):
            ref = sign * du0.copy()

            def rhs(_t: float, y: np.ndarray, ref: np.ndarray = ref) -> np.ndarray:
                uv = y.reshape(m, 2)
                du, strength = field(surface, uv, which)
                dot = np.einsum("ij,ij->i", du, ref)
                du = np.where((dot < 0)[:, None], -du, du)
                # slow down smoothly (no step-size havoc) past the stopping
                # places; the ends are cut exactly afterwards
                speed = _smoothstep((strength - stop) / stop)
                out = np.maximum(lo - uv, uv - hi) / span  # > 0 outside
                out = np.where(per, -1.0, out).max(axis=1)
                speed *= _smoothstep(1.0 - (out - 0.02) / 0.08)
                ok = np.isfinite(du).all(axis=1) & np.isfinite(speed)
                du = np.where(ok[:, None], du * np.where(ok, speed, 0.0)[:, None], 0.0)
                ref[ok & (speed > 0)] = du[ok & (speed > 0)]
                return du.ravel()

            sol = solve_ivp(
                rhs,
                (0.0, length),
                seeds.ravel(),
                method="DOP853",
                dense_output=True,
                rtol=rtol,
                atol=atol * max(d.span(0), d.span(1)),
            )
            self.sols.append(sol.sol)
        # where each half ends: sample, then refine the first stop by bisection
        self.ends = np.zeros((2, m))
        self.closed = np.zeros(m, bool)
        n = 4001
        t = np.linspace(0.0, length, n)
        start3 = surface.point(seeds[:, 0], seeds[:, 1])
        for h in (0, 1):
            Y = self.sols[h](t).reshape(m, 2, n).transpose(0, 2, 1)  # (m, n, 2)
            bad = self._stopped(Y.reshape(-1, 2), field, which, stop).reshape(m, n)
            # the first stop of every line, refined by bisection for all at once
            stops = bad.any(axis=1)
            first = np.argmax(bad, axis=1)
            a = np.where(first > 0, t[np.maximum(first - 1, 0)], 0.0)
            b = np.where(first > 0, t[first], 0.0)
            rows = np.arange(m)
            for _ in range(50):
                c = 0.5 * (a + b)
                yc = self.sols[h](c).reshape(m, 2, m)[rows, :, rows]  # line k at c[k]
                hit = self._stopped(yc, field, which, stop)
                b = np.where(hit, c, b)
                a = np.where(hit, a, c)
            self.ends[h] = np.where(stops, a, length)
            if h == 0:
                # closed loops: first return to the seed after leaving it
                P = surface.point(Y[..., 0], Y[..., 1])
                dist = np.linalg.norm(P - start3[:, None, :], axis=2)
                for k in range(m):
                    far = np.nonzero(dist[k] > 1e-2 * size)[0]
                    if not len(far):
                        continue
                    j0 = far[0]
                    near = np.nonzero(
                        (dist[k, j0:] < 0.5 * length / n * 3) & (t[j0:] <= self.ends[0, k])
                    )[0]
                    if not len(near):
                        continue
                    j = j0 + near[0]
                    tc = self._closest(k, start3[k], t[max(j - 2, 0)], t[min(j + 2, n - 1)])
                    if np.linalg.norm(self._point(0, k, tc) - start3[k]) < 1e-6 * size:
                        self.closed[k] = True
                        self.ends[0, k] = tc

        self.ends[1, self.closed] = 0.0  # a closed line is its forward loop

    def _stopped(self, uv: np.ndarray, field: Any, which: np.ndarray, stop: float) -> np.ndarray:
        d = self.domain
        w = which if len(which) == len(uv) else np.repeat(which, len(uv) // len(which))
        out = np.zeros(len(uv), bool)
        for i in (0, 1):
            if not d.periodic[i]:
                lo, hi = d.range(i)
                out |= (uv[:, i] < lo) | (uv[:, i] > hi)
        _, strength = field(self.surface, uv, w)
        return out | ~(strength > 2 * stop)

    def _point(self, h: int, k: int, t: Any) -> np.ndarray:
        uv = np.asarray(self.sols[h](t)).reshape(self.m, 2, -1)[k]
        return self.surface.point(uv[0], uv[1])

    def _closest(self, k: int, target: np.ndarray, a: float, b: float) -> float:
        from scipy.optimize import minimize_scalar

        res = minimize_scalar(
            lambda t: float(np.sum((self._point(0, k, t).ravel() - target) ** 2)),
            bounds=(a, b),
            method="bounded",
            options={"xatol": 1e-13 * max(b, 1.0)},
        )
        return float(res.x)

    def uv(self, k: int, t: np.ndarray) -> np.ndarray:
        """Parameters of line ``k`` at signed arc length ``t`` (< 0: backward)."""
        t = np.asarray(t, float)
        out = np.empty((len(t), 2))
        for h, sel in ((0, t >= 0), (1, t < 0)):
            if sel.any():
                tt = np.abs(t[sel])
                out[sel] = np.asarray(self.sols[h](tt)).reshape(self.m, 2, -1)[k].T
        return out

    def batch(self, family: str, keep: np.ndarray | None = None) -> Any:
        from .curves import CurveBatch

        ks = np.arange(self.m) if keep is None else np.asarray(keep)
        ks = ks[(self.ends[0, ks] + self.ends[1, ks]) > 0]
        return CurveBatch.from_curves(
            self.surface,
            family,
            -self.ends[1, ks],
            self.ends[0, ks],
            lambda c, t: self.uv(int(ks[c]), t),
            closed=self.closed[ks],
        )

    def samples(self, k: int, n: int = 200) -> np.ndarray:
        t = np.linspace(-self.ends[1, k], self.ends[0, k], n)
        uv = self.uv(k, t)
        return self.surface.point(uv[:, 0], uv[:, 1])


def _center_seed(surface: Any, field: Any, stop: float) -> np.ndarray:
    """A seed near the middle of the domain where the field is well defined."""
    d = surface.domain
    f = np.array([0.5, 0.42, 0.58, 0.35, 0.65, 0.3, 0.7, 0.2, 0.8])
    c1 = d.u1[0] + d.span(0) * f
    c2 = d.u2[0] + d.span(1) * f[[0, 2, 1, 4, 3, 6, 5, 8, 7]]
    U = np.stack(np.meshgrid(c1, c2, indexing="ij"), -1).reshape(-1, 2)
    _, a = field(surface, U, np.zeros(len(U), int))
    a = np.where(np.isfinite(a), a, -1.0)
    good = np.nonzero(a > 20 * stop)[0]
    k = good[0] if len(good) else int(np.argmax(a))
    return U[k]


def _spread(lines: _FieldLines, k: int, n: int) -> np.ndarray:
    """``n`` parameters evenly spread in arc length along line ``k``."""
    a, b = -lines.ends[1, k], lines.ends[0, k]
    if lines.closed[k]:
        t = a + (b - a) * np.arange(n) / n
    else:
        t = a + (b - a) * (np.arange(n) + 0.5) / n
    return lines.uv(k, t)


def _line_samples(lines: _FieldLines, step: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """Every line sampled about ``step`` apart in arc length: ``(t, xyz)`` per
    line, ``t`` increasing from the backward end to the forward end (all
    lines evaluated together, once per half)."""
    out = []
    halves = []
    for h in (0, 1):
        tmax = float(lines.ends[h].max())
        t = np.arange(0.0, tmax + step, step) if tmax > 0 else np.zeros(1)
        uv = np.asarray(lines.sols[h](t)).reshape(lines.m, 2, -1).transpose(0, 2, 1)
        halves.append((t, uv))
    d = lines.domain
    for k in range(lines.m):
        (tf, uf), (tb, ub) = halves
        f = tf <= lines.ends[0, k]
        b = (tb <= lines.ends[1, k]) & (tb > 0)
        t = np.concatenate([-tb[b][::-1], tf[f]])
        uv = np.concatenate([ub[k][b][::-1], uf[k][f]])
        uv = d.wrap(uv, clip=False)
        out.append((t, lines.surface.point(uv[:, 0], uv[:, 1])))
    return out


def _keep_pieces(
    lines: _FieldLines,
    pieces: list,
    points: list,
    dsep: float,
    min_length: float,
    step: float,
    placed: bool = False,
) -> list[np.ndarray]:
    """Trim each line of ``lines`` (in order) where it comes closer than
    ``dsep / 2`` to lines already kept, keeping the run of samples through its
    seed (evenly spaced streamlines, Jobard and Lefer 1997); drop runs shorter
    than ``min_length``.  A closed line is kept whole.  Lines from ``placed``
    seeds (spread along a transversal) are always kept, at least ``dsep / 2``
    either side of the seed.  Appends ``(lines, k, ta, tb, closed)`` to ``pieces``
    and the kept samples to ``points``; returns the samples of dropped lines."""
    from scipy.spatial import cKDTree

    dtest = 0.5 * dsep
    dropped = []
    for k, (t, x) in enumerate(_line_samples(lines, step)):
        if len(t) < 2:
            dropped.append(x)
            continue
        if points:
            dist, _ = cKDTree(np.concatenate(points)).query(x)
            free = dist > dtest
        else:
            free = np.ones(len(t), bool)
        i = int(np.argmin(np.abs(t)))  # the seed
        if placed:
            free[np.abs(t) <= dtest] = True
        if not free[i]:
            dropped.append(x)
            continue
        if lines.closed[k]:
            pieces.append((lines, k, 0.0, float(lines.ends[0, k]), True))
            points.append(x)
            continue
        i0 = i1 = i
        while i0 > 0 and free[i0 - 1]:
            i0 -= 1
        while i1 < len(t) - 1 and free[i1 + 1]:
            i1 += 1
        ta = -float(lines.ends[1, k]) if i0 == 0 else float(t[i0])
        tb = float(lines.ends[0, k]) if i1 == len(t) - 1 else float(t[i1])
        if tb - ta < (0.0 if placed else min_length) or tb <= ta:
            dropped.append(x)
            continue
        pieces.append((lines, k, ta, tb, False))
        points.append(x[i0 : i1 + 1])
    return dropped


def _pieces_batch(surface: Any, family: str, pieces: list) -> Any:
    """One batch of trimmed field lines ``(lines, k, ta, tb, closed)``."""
    from .curves import CurveBatch

    return CurveBatch.from_curves(
        surface,
        family,
        [p[2] for p in pieces],
        [p[3] for p in pieces],
        lambda c, t: pieces[c][0].uv(pieces[c][1], t),
        closed=[p[4] for p in pieces],
    )


def field_line_batches(
    surface: Any,
    field: Any,
    n1: int,
    n2: int,
    stop: float,
    family: str = "curvature",
    fill: bool = True,
) -> list:
    """Batches of about ``n1`` lines of the field's direction ``which = a`` and
    ``n2`` of ``which = 1 - a``, where ``a`` is chosen so that the first family
    runs roughly like the ``u1 = const`` lines at the centre of the domain.

    Evenly spaced lines: the separation ``dsep`` of a family is the length of
    the line of the other family through the centre divided by ``n``.  First
    seeds lie ``dsep`` apart along that line; then, if ``fill``, more seeds go
    where the surface is farther than ``0.9 dsep`` from every line of the
    family (farthest first, in rounds).  Each line is cut where it comes
    closer than ``dsep / 2`` (in space) to a line already drawn, keeping the
    part through its seed, and pieces shorter than ``dsep`` are dropped: lines
    neither bunch up (at umbilics, say) nor leave gaps, and no stray bits remain.
    """
    from scipy.spatial import cKDTree

    size = surface.size
    length = 3.0 * size
    c = _center_seed(surface, field, stop)
    both = _FieldLines(surface, field, np.array([c, c]), np.array([0, 1]), length, stop)
    du0, _ = field(surface, np.array([c, c]), np.array([0, 1]))
    x1, x2 = surface.derivatives(c[0], c[1])
    e = du0[:, :1] * x1 + du0[:, 1:] * x2
    a = 0 if abs(e[0] @ x2) / np.linalg.norm(x2) >= abs(e[1] @ x2) / np.linalg.norm(x2) else 1
    out = []
    d = surface.domain
    ng = 40
    g1 = (
        np.linspace(*d.u1, ng + 2)[1:-1]
        if not d.periodic[0]
        else d.u1[0] + d.span(0) * np.arange(ng) / ng
    )
    g2 = (
        np.linspace(*d.u2, ng + 2)[1:-1]
        if not d.periodic[1]
        else d.u2[0] + d.span(1) * np.arange(ng) / ng
    )
    G = np.stack(np.meshgrid(g1, g2, indexing="ij"), -1).reshape(-1, 2)
    GP = surface.point(G[:, 0], G[:, 1])
    for which, n in ((a, n1), (1 - a, n2)):
        if n <= 0:
            continue
        transversal = 1 - which  # the line of the other family through the centre
        L = both.ends[0, transversal] + both.ends[1, transversal]
        dsep = (L if L > 0.05 * size else size) / n
        step = dsep / 8
        seeds = _spread(both, transversal, n) if L > 0 else np.array([c])
        lines = _FieldLines(surface, field, seeds, np.full(len(seeds), which), length, stop)
        pieces: list = []
        points: list = []
        _keep_pieces(lines, pieces, points, dsep, 1.5 * dsep, step, placed=True)
        if fill and points:
            _, str_ = field(surface, G, np.full(len(G), which))
            # away from umbilics, where lines stop short anyway
            alive = np.isfinite(str_) & (str_ > max(50 * stop, 0.1))
            for _round in range(2):
                dist, _ = cKDTree(np.concatenate(points)).query(GP)
                dist = np.where(alive, dist, 0.0)
                chosen: list[int] = []
                for k in np.argsort(-dist):
                    if dist[k] <= 0.9 * dsep or len(chosen) >= n + 4:
                        break
                    if all(np.linalg.norm(GP[k] - GP[j]) > 2 * dsep for j in chosen):
                        chosen.append(int(k))
                if not chosen:
                    break
                alive[chosen] = False
                more = _FieldLines(surface, field, G[chosen], np.full(len(chosen), which),
                                   length, stop)  # fmt: skip
                dropped = _keep_pieces(more, pieces, points, dsep, dsep, step)
                if dropped:  # seeds on a dropped line would give it again
                    near, _ = cKDTree(np.concatenate(dropped)).query(GP)
                    alive &= near > 0.5 * dsep
        if pieces:
            out.append(_pieces_batch(surface, family, pieces))
    return out


def numeric_lines_of_curvature(surface: Any, n1: int, n2: int) -> list:
    """Lines of curvature of any surface, by integrating the principal direction
    field (``solve_ivp``, DOP853, dense output).

    ``n1`` lines of the family that runs like the ``u1 = const`` lines at the
    centre of the domain, ``n2`` of the other; lines stop at umbilics and at
    the domain boundary, and close when they return to their seed.

    >>> import lgraph as lg
    >>> b = numeric_lines_of_curvature(lg.Torus(3, 1), 2, 0)
    >>> bool(b[0].closed.all())
    True
    """
    return field_line_batches(surface, principal_field, n1, n2, UMBILIC_RTOL)
