"""Which lines a numeric line family draws (:func:`field_line_batches`).

* Where the parameter lines are the field's lines (``g12 = L12 = 0`` for lines
  of curvature, the paper's Proposition 4.1; ``L11 = L22 = 0`` for asymptotic
  lines) the parameter lines are drawn: exact.
* Otherwise lines are complete by default: candidates are traced together
  (:func:`lgraph.families.fieldlines.trace`) through seeds spread along a transversal
  line through the middle of the patch and over a coarse grid, and ``n`` are
  picked to cover the patch as evenly as they allow, none twice.
  ``spacing="even"`` instead trims lines where they come closer than half
  the spacing to another (evenly spaced streamlines, ``lgraph.families._even``).
* Lines of curvature end at umbilics (:func:`umbilics`).

Derivation: ``docs/mathematics.rst``, "Numeric line families".

>>> import lgraph as lg
>>> from lgraph.curvature import principal_field
>>> batches = field_line_batches(lg.MonkeySaddle(), principal_field, 3, 3)
>>> sum(len(b) for b in batches)
6
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._budget import check_field_lines
from .._tolerance import FIELD_DUPLICATE_RTOL, PARAMETER_LINES_RTOL
from ..curvature import _frame, asymptotic_field, principal_field
from ..curves import CurveBatch
from ._lines import SPACINGS, parameter_line_batches
from ._seeds import _center_seed, _crossing, _grid, _spread, _stable, cell_centres
from .fieldlines import FieldLines, trace

__all__ = ["field_line_batches", "numeric_lines_of_curvature", "umbilics"]


def forms_of(surface: Any) -> Any:
    """``forms(uv) -> (g11, g12, g22, L11, L12, L22)`` at rows of ``uv``: the
    surface's own ``fundamental_forms(u1, u2)`` where it has one (closed
    forms, such as the monkey saddle's), else from its derivatives."""
    own = getattr(surface, "fundamental_forms", None)
    if own is not None:
        return lambda uv: own(uv[:, 0], uv[:, 1])

    def forms(uv: np.ndarray) -> tuple[np.ndarray, ...]:
        _x1, _x2, g, L = _frame(surface, uv)
        return g + L

    return forms


def principal_oriented(surface: Any, stop: float) -> Any:
    """``oriented(uv, ref)`` of :func:`~lgraph.families.fieldlines.trace` for the principal field
    (:func:`lgraph.curvature.principal_field`, the same formulas) in few array
    operations: both branches at once as ``(2, n)`` arrays, each normalized
    only after the branch nearest ``ref`` is chosen."""
    forms = forms_of(surface)
    sign = np.array([[-1.0], [1.0]])

    def oriented(uv: np.ndarray, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        g11, g12, g22, L11, L12, L22 = forms(uv)
        with np.errstate(invalid="ignore", divide="ignore"):
            g = g11 * g22 - g12 * g12
            H = (g11 * L22 - 2 * g12 * L12 + g22 * L11) / (2 * g)
            K = (L11 * L22 - L12 * L12) / g
            root = np.sqrt(np.maximum(H * H - K, 0.0))
            # strength = 2 root / (|H - root| + |H + root|) = root / max(|H|, root) > stop
            strong = root > stop * np.abs(H)
            k = H + sign * root  # (2, n): k1 <= k2
            # the kernel of L - k G from its longer row (lgraph.curvature._direction_for)
            a11, a12, a22 = L11 - k * g11, L12 - k * g12, L22 - k * g22
            first = np.abs(a11) >= np.abs(a22)
            d0 = np.where(first, a12, a22)
            d1 = np.where(first, -a11, -a12)
            norm = np.sqrt(g11 * d0 * d0 + 2 * g12 * d0 * d1 + g22 * d1 * d1)
            r0, r1 = ref[:, 0], ref[:, 1]
            c = (d0 * (g11 * r0 + g12 * r1) + d1 * (g12 * r0 + g22 * r1)) / norm
            b = np.abs(c[1]) > np.abs(c[0])
            cb = np.where(b, c[1], c[0])
            scale = np.where(cb < 0, -1.0, 1.0) / np.where(b, norm[1], norm[0])
            out = np.empty_like(uv)
            out[:, 0] = np.where(b, d0[1], d0[0]) * scale
            out[:, 1] = np.where(b, d1[1], d1[0]) * scale
            ok = np.isfinite(out).all(axis=1) & strong & (np.abs(cb) > 0.5)
        out[~ok] = 0.0
        return out, ok

    return oriented


def lean_oriented(field: Any) -> Any:
    """The ``lean`` factory of :func:`~lgraph.families.fieldlines.trace` for
    ``field`` (``None`` where there is none)."""
    return principal_oriented if field is principal_field else None


def _parameter_lines_are_field_lines(surface: Any, field: Any) -> bool:
    """Whether the parameter lines are the field's lines, checked on a grid:
    ``g12 = L12 = 0`` (lines of curvature, the paper's Proposition 4.1) or
    ``L11 = L22 = 0`` (asymptotic lines)."""
    d = surface.domain
    g = cell_centres(d, 24)
    _x1, _x2, (g11, g12, g22), (L11, L12, L22) = _frame(surface, g)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = np.sqrt(g11 * g22)
        kappa = (np.abs(L11) / g11 + np.abs(L22) / g22 + 2 * np.abs(L12) / scale).max()
        if field is asymptotic_field:
            small = (np.abs(L11) / g11 + np.abs(L22) / g22) / kappa
            return bool(np.all(small <= PARAMETER_LINES_RTOL)) and bool(kappa > 0)
        small = np.maximum(np.abs(g12) / scale, np.abs(L12) / scale / kappa)
    return bool(np.all(small <= PARAMETER_LINES_RTOL))


def _umbilic_residual(surface: Any, uv: np.ndarray, kappa: float) -> np.ndarray:
    """``(A, B, C)`` of equation (3.3) (``A du1^2 + B du1 du2 + C du2^2 = 0``),
    scaled: all three vanish exactly at umbilics (flat ones included)."""
    g11, g12, g22, L11, L12, L22 = forms_of(surface)(uv)
    scale = (g11 * g22 * kappa)[:, None]
    return np.stack([L11 * g12 - L12 * g11, L11 * g22 - L22 * g11, L12 * g22 - L22 * g12],
                    axis=1) / scale  # fmt: skip


def umbilics(surface: Any, n: int = 24) -> np.ndarray:
    """Parameters ``(k, 2)`` of the umbilics of the drawn patch (flat ones
    included): local minima of the residual of (3.3) on an ``n x n`` grid,
    refined by Gauss-Newton steps (finite-difference Jacobian), kept where
    the residual vanishes to 1e-9.

    >>> import lgraph as lg
    >>> umbilics(lg.MonkeySaddle()).round(9).tolist()
    [[0.0, 0.0]]
    """
    from scipy.ndimage import minimum_filter

    d = surface.domain
    span = np.array([d.span(0), d.span(1)])
    lo = np.array([d.u1[0], d.u2[0]])
    G = cell_centres(d, n)
    _x1, _x2, (g11, _g12, g22), (L11, L12, L22) = _frame(surface, G)
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.abs(L11) / g11 + np.abs(L22) / g22 + 2 * np.abs(L12) / np.sqrt(g11 * g22)
    kappa = float(np.nanmax(k)) if np.isfinite(k).any() else 0.0
    if not kappa > 0:
        return np.empty((0, 2))
    r = np.linalg.norm(_umbilic_residual(surface, G, kappa), axis=1)
    r = np.where(np.isfinite(r), r, np.inf).reshape(n, n)
    mode = ["wrap" if p is True else "nearest" for p in d.periodic]
    low = np.flatnonzero(((r == minimum_filter(r, size=3, mode=mode)) & (r < 0.5)).ravel())
    u = G[low[np.argsort(r.ravel()[low])][:64]]
    h = 1e-6 * span
    hi = lo + span
    for _ in range(12):  # Gauss-Newton on the three residuals (iterates kept in the rectangle)
        u = d.clip(u)
        f = _umbilic_residual(surface, d.wrap(u, clip=False), kappa)
        # forward differences, backward at the upper edges that are not glued
        back = (u + h > hi) & ~np.array(d.glued)
        e = np.where(back, -h, h)
        J = np.stack([(_umbilic_residual(surface, d.wrap(u + e * ax, clip=False), kappa) - f)
                      / e[:, i : i + 1] for i, ax in enumerate(np.eye(2))], axis=2)  # fmt: skip
        M = np.einsum("kia,kib->kab", J, J)  # normal equations, solved by hand (2 x 2)
        b = -np.einsum("kia,ki->ka", J, f)
        det = M[:, 0, 0] * M[:, 1, 1] - M[:, 0, 1] * M[:, 1, 0]
        with np.errstate(invalid="ignore", divide="ignore"):
            adj_b = np.stack([M[:, 1, 1] * b[:, 0] - M[:, 0, 1] * b[:, 1],
                              M[:, 0, 0] * b[:, 1] - M[:, 1, 0] * b[:, 0]], axis=1)  # fmt: skip
            step = adj_b / det[:, None]
        step = np.clip(np.nan_to_num(step), -0.1 * span, 0.1 * span)
        moved = d.clip(u + step) - u  # (iterates pushed past an edge stay on it)
        u = u + step
        if not np.abs(moved / span).max(initial=0.0) > 1e-14:  # every iterate has settled
            break
    u = d.wrap(d.clip(u), clip=False)
    f = np.linalg.norm(_umbilic_residual(surface, u, kappa), axis=1)
    inside = np.all((u >= lo) & (u <= lo + span), axis=1)
    u = u[(f < 1e-9) & inside]
    keep: list[np.ndarray] = []
    for p in u[np.lexsort((u[:, 1], u[:, 0]))]:
        if all(np.abs((p - d.nearest_image(p, q)) / span).max() > 1e-6 for q in keep):
            keep.append(p)
    return np.array(keep).reshape(-1, 2)


def _dense(lines: FieldLines, ks: Any, step: float) -> tuple[np.ndarray, ...]:
    """Points about ``step`` apart along lines ``ks``, the line of each and
    its arc length (all lines evaluated in one call)."""
    ks = np.asarray(ks, int)
    if not len(ks):
        return np.empty((0, 3)), np.empty(0, int), np.empty(0)
    a, b = -lines.ends[1, ks], lines.ends[0, ks]
    counts = np.maximum(np.ceil((b - a) / step).astype(int) + 1, 2)
    ids = np.repeat(ks, counts)
    first = np.repeat(np.cumsum(counts) - counts, counts)
    frac = (np.arange(len(ids)) - first) / np.repeat(counts - 1, counts)
    t = np.repeat(a, counts) + frac * np.repeat(b - a, counts)
    uv = lines.domain.wrap(lines.uv(ids, t), clip=False)
    return lines.surface.point(uv[:, 0], uv[:, 1]), ids, t


def _select(surface: Any, lines: FieldLines, cand: np.ndarray, n: int, grid: tuple) -> list[int]:
    """``n`` of the traced lines ``cand`` spread as evenly over the patch as
    they allow, none retracing another.

    Greedy: each pick is the candidate line that minimizes the area-weighted
    mean squared distance of the patch (grid points) to the lines picked so
    far (the first pick is the most central line).  Energies are compared
    rounded to 1e-9, ties go to the earlier candidate: the choice does not
    hang on the last bits of floating point.
    """
    size = float(surface.size)
    _G, GP, weight = grid
    coarse = 2e-2 * size
    cand = [int(k) for k in cand if lines.ends[0, k] + lines.ends[1, k] > 0]
    if not cand:
        return []
    p, ids, t_of = _dense(lines, cand, coarse)
    # squared distance of every grid point to every candidate: the least
    # |p|^2 - 2 p.g over each candidate's points, plus |g|^2 (chunks of ~50k,
    # which stay in the cache)
    bounds = np.flatnonzero(np.r_[True, ids[1:] != ids[:-1]])
    sq = np.empty((len(cand), len(GP)))
    g2 = np.einsum("ij,ij->i", GP, GP)
    p2 = np.einsum("ij,ij->i", p, p)
    m2G = np.ascontiguousarray(-2.0 * GP.T)
    per_chunk = max(1, int(5e4 // max(len(GP) * len(p) / len(cand), 1)))
    for c0 in range(0, len(cand), per_chunk):
        c1 = min(c0 + per_chunk, len(cand))
        lo_, hi_ = bounds[c0], (bounds[c1] if c1 < len(cand) else len(p))
        d2 = np.einsum("ij,jk->ik", p[lo_:hi_], m2G)  # not BLAS: its threads wake slowly
        d2 += p2[lo_:hi_, None]
        sq[c0:c1] = np.minimum.reduceat(d2, bounds[c0:c1] - lo_, axis=0)
    sq += g2
    sq = np.maximum(sq, 0.0)
    seed3 = surface.points(surface.domain.wrap(lines.uv(cand, np.zeros(len(cand))), clip=False))
    # which candidate seeds lie on which other candidate line (it would be
    # drawn twice): a seed on a line lies within half a coarse step of one of
    # its samples; there the line is sampled finely over a coarse step either
    # side and the seed's distance to those segments measured
    from scipy.spatial import cKDTree

    tol = FIELD_DUPLICATE_RTOL * size
    fine = 2e-3 * size
    row_of = np.full(lines.m, -1)
    row_of[cand] = np.arange(len(cand))
    pairs = cKDTree(seed3).sparse_distance_matrix(
        cKDTree(p), 0.5 * coarse + tol, output_type="ndarray"
    )
    j, near = pairs["i"].astype(int), pairs["j"].astype(int)
    other = ids[near] != np.asarray(cand)[j]
    j, near = j[other], near[other]
    k = ids[near]
    offsets = np.linspace(-coarse, coarse, int(np.ceil(2 * coarse / fine)) + 1)
    t = np.clip(
        t_of[near][:, None] + offsets, -lines.ends[1, k][:, None], lines.ends[0, k][:, None]
    )
    uv = lines.domain.wrap(lines.uv(np.repeat(k, len(offsets)), t.ravel()), clip=False)
    q = surface.point(uv[:, 0], uv[:, 1]).reshape(len(k), len(offsets), 3)
    qa, ab = q[:, :-1], np.diff(q, axis=1)
    rel = seed3[j][:, None] - qa
    with np.errstate(invalid="ignore", divide="ignore"):
        tt = np.einsum("ijk,ijk->ij", rel, ab) / np.einsum("ijk,ijk->ij", ab, ab)
    tt = np.fmin(np.fmax(tt, 0.0), 1.0)[..., None]  # NaN (a point twice) -> 0
    dist = np.sqrt((((rel - tt * ab) ** 2).sum(axis=2)).min(axis=1))
    on_line = np.zeros((len(cand), len(cand)), bool)
    hit = dist <= tol
    on_line[j[hit], row_of[k[hit]]] = True
    best = np.full(len(GP), np.inf)
    usable = np.ones(len(cand), bool)
    picked: list[int] = []
    while len(picked) < n and usable.any():
        energy = np.einsum("ij,j->i", np.minimum(best, sq), weight)  # (not BLAS)
        energy = np.round(energy / max(float(energy[usable].max()), 1e-300), 9)
        row = int(np.flatnonzero(usable)[np.argmin(energy[usable])])
        picked.append(cand[row])
        best = np.minimum(best, sq[row])
        usable[row] = False
        usable[on_line[:, row] | on_line[row]] = False  # the same line again
    return sorted(picked)


def field_line_batches(
    surface: Any,
    field: Any,
    n1: int,
    n2: int,
    stop: float | None = None,
    family: str = "curvature",
    spacing: str = "complete",
) -> list[CurveBatch]:
    """Batches of ``n1`` lines of the branch that runs like the ``u1 = const``
    lines at the centre of the domain and ``n2`` of the other (see the module
    docstring for ``spacing``).

    Where the lines are integrated, ``n1`` and ``n2`` are budgeted before any
    work (``lgraph._budget.check_field_lines``: at most
    ``MAX_FIELD_LINES``, ``MAX_EVEN_FIELD_LINES`` with ``spacing="even"``);
    parameter lines that are the field's lines are not integrated, so they
    only have the limit of every family, ``MAX_CURVES``."""
    if spacing not in SPACINGS:
        choices = ", ".join(map(repr, SPACINGS))
        raise ValueError(f"spacing must be one of {choices}, got {spacing!r}")
    if n1 + n2 <= 0:
        return []

    d = surface.domain
    if _parameter_lines_are_field_lines(surface, field):
        return parameter_line_batches(surface, d.lines(0, n1), d.lines(1, n2), family, family)
    owner = (
        "LinesOfCurvature" if field is principal_field
        else "AsymptoticLines" if field is asymptotic_field
        else "field_line_batches"
    )  # fmt: skip
    check_field_lines(owner, n1, n2, spacing)
    stop = field.stop if stop is None else stop
    lean = lean_oriented(field)
    singular = umbilics(surface) if field is principal_field else np.empty((0, 2))
    c = _center_seed(surface, field, stop)
    D, _, G = field(surface, np.array([c]))
    # the lines through the centre place seeds only: a loose tolerance and
    # long steps will do (each seed's line is traced exactly)
    both = trace(
        surface,
        field,
        [c, c],
        D[0],
        stop=stop,
        rtol=1e-4,
        max_step=0.2,
        singular=singular,
        lean=lean,
    )
    # the branch running like the u1 = const lines (along x2) at the centre
    x1, x2 = surface.derivatives(c[0], c[1])
    e = D[0, :, :1] * x1 + D[0, :, 1:] * x2
    a = 0 if abs(e[0] @ x2) >= abs(e[1] @ x2) else 1
    if spacing == "even":
        from ._even import even_batches

        return even_batches(surface, field, both, a, n1, n2, stop, family, singular, lean)
    grid = _grid(surface, field, stop)
    G, _, weight = grid
    # candidate seeds of both families, traced together: many along the
    # transversal (regular spacing where the lines cross it) and a coarse
    # grid over the patch (the parts they miss)
    coarse = np.flatnonzero(weight > 0)[:: max(len(G) // 25, 1)]
    seeds, dirs, fam = [], [], []
    for which, n in ((a, n1), (1 - a, n2)):
        if n <= 0:
            continue
        transversal = 1 - which  # the line of the other branch through the centre
        s_f, d_f = np.array([c]), D[0, which][None]
        if both.ends[0, transversal] + both.ends[1, transversal] > 0:
            s_t, tangent = _spread(both, transversal, 2 * n + 1)
            s_f = np.concatenate([s_f, s_t])
            d_f = np.concatenate([d_f, _crossing(field, surface, s_t, tangent)])
        s_f = np.concatenate([s_f, G[coarse]])
        d_f = np.concatenate([d_f, field(surface, G[coarse])[0][:, which]])
        keep = _stable(surface, field, s_f, d_f)
        seeds.append(s_f[keep])
        dirs.append(d_f[keep])
        fam.append(np.full(int(keep.sum()), n))
    lines = trace(
        surface,
        field,
        np.concatenate(seeds),
        np.concatenate(dirs),
        stop=stop,
        singular=singular,
        lean=lean,
    )
    out, start = [], 0
    for f in fam:
        cand = np.arange(start, start + len(f))
        start += len(f)
        b = lines.batch(family, _select(surface, lines, cand, int(f[0]) if len(f) else 0, grid))
        if b is not None:
            out.append(b)
    return out


def numeric_lines_of_curvature(surface: Any, n1: int, n2: int, spacing: str = "complete") -> list:
    """Lines of curvature of any surface, integrated from the principal
    direction field (:mod:`lgraph.families.fieldlines`).

    ``n1`` lines of the family that runs like the ``u1 = const`` lines at the
    centre of the domain, ``n2`` of the other.  By default every line is
    complete: it runs until the patch boundary, a pole, an umbilic, or until it
    closes.  ``spacing="even"`` trims lines where they come close to another
    (evenly spaced streamlines).  Where the parameter lines are lines of
    curvature (``g12 = L12 = 0``, the paper's Proposition 4.1) they are drawn.

    >>> import lgraph as lg
    >>> b = numeric_lines_of_curvature(lg.Torus(3, 1), 2, 0)
    >>> bool(b[0].closed.all())
    True
    """
    return field_line_batches(surface, principal_field, n1, n2, family="curvature", spacing=spacing)
