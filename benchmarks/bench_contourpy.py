"""Our marching squares (``surfaces._zero_set.zero_set``) vs contourpy (issue 12).

Run:  python benchmarks/bench_contourpy.py [--repeat 7] [--grid 193]

Numeric contours and level lines are the zero sets of a function on a
parameter grid (``lgraph.surfaces.parametric._zero_set.zero_set``: marching squares,
each crossing refined on its grid edge to machine precision by
``_edge_roots``, crossings joined into curves, across periodic seams too).
The contourpy pipeline does the same with ``contourpy.contour_generator``
for the topology: the same grid values (a periodic axis gets one more,
wrapped, row so that its seam is contoured), each point that contourpy
interpolates on a grid edge is located on its edge (one of its coordinates
is a grid value exactly) and refined there by the same ``_edge_roots``.
Stitching the pieces that contourpy leaves open at periodic seams is not
done here: its time is therefore a lower bound.

Reported per case: the medians of the whole zero set's time for both, and of
its parts that are the same for both (the function on the grid and the
refinement of the crossings), so that the marching itself can be compared;
the largest distance between the refined crossings of the two (parameter
units); and how many curves each returns, closed and open.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from typing import Any

import numpy as np


def cases() -> list[tuple[str, Any, Any]]:
    import lgraph as lg
    from lgraph.surfaces.parametric._contour import view_cosine

    torus = lg.Torus(2.0, 0.7)
    generic = lg.ParametricSurface(
        torus.point, (0, 2 * np.pi), (0, 2 * np.pi), periodic=(True, True)
    )
    view = lg.ParallelProjector(direction=(1, -1, 0.7))
    enneper = lg.Enneper()
    central = lg.CentralProjector(eye=(6, -5, 4))

    def contour(surface: Any, projector: Any) -> Any:
        return lambda u1, u2: view_cosine(surface, projector, u1, u2)

    def level(surface: Any, value: float) -> Any:
        return lambda u1, u2: surface.point(u1, u2)[..., 2] - value

    return [
        ("torus contour (periodic u1, u2)", generic, contour(generic, view)),
        ("Enneper contour, central view", enneper, contour(enneper, central)),
        ("torus level z = 0.3 (periodic)", generic, level(generic, 0.3)),
        ("Enneper level z = 0.2", enneper, level(enneper, 0.2)),
    ]


def grid_values(surface: Any, fun: Any, grid: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    from lgraph.surfaces.parametric._zero_set import _grid_axis

    a1, a2 = _grid_axis(surface, 0, grid), _grid_axis(surface, 1, grid)
    U1, U2 = np.meshgrid(a1, a2, indexing="ij")
    F = fun(U1, U2)
    return a1, a2, np.where(np.isfinite(F), F, 0.0)


def contourpy_zero_set(
    surface: Any, fun: Any, grid: int
) -> tuple[list[np.ndarray], np.ndarray, dict[str, float]]:
    """(lines as contourpy returns them, the refined crossings, times of the parts)."""
    import contourpy

    from lgraph.surfaces.parametric._zero_set import _edge_roots

    d = surface.domain
    t0 = time.perf_counter()
    a1, a2, F = grid_values(surface, fun, grid)
    t1 = time.perf_counter()
    x, y = a1, a2
    if d.periodic[0]:
        x, F = np.append(a1, a1[0] + d.span(0)), np.vstack([F, F[:1]])
    if d.periodic[1]:
        y, F = np.append(a2, a2[0] + d.span(1)), np.hstack([F, F[:, :1]])
    gen = contourpy.contour_generator(x, y, F.T, line_type="Separate")
    lines = gen.lines(0.0)
    if not lines:
        return [], np.empty((0, 2)), {}
    pts = np.concatenate(lines)
    # each point lies on a grid edge: one coordinate is a grid value (up to the
    # rounding of contourpy's interpolation); take the nearer grid line
    jy = np.clip(np.searchsorted(y, pts[:, 1]), 1, len(y) - 1)
    jy -= (pts[:, 1] - y[jy - 1]) < (y[jy] - pts[:, 1])
    ix = np.clip(np.searchsorted(x, pts[:, 0]), 1, len(x) - 1)
    ix -= (pts[:, 0] - x[ix - 1]) < (x[ix] - pts[:, 0])
    dy = np.abs(pts[:, 1] - y[jy]) / (y[1] - y[0])
    dx = np.abs(pts[:, 0] - x[ix]) / (x[1] - x[0])
    on_row = dy <= dx  # edge along u1 at u2 = y[jy]
    node = (dx < 1e-9) & (dy < 1e-9)  # a grid node where f = 0 exactly: its own crossing
    at_node = np.column_stack([x[ix[node]], y[jy[node]]])
    ix = np.where(on_row, np.searchsorted(x, pts[:, 0]), ix)
    jy = np.where(on_row, jy, np.searchsorted(y, pts[:, 1]))
    i0 = np.where(on_row, np.clip(ix - 1, 0, len(x) - 2), ix)
    j0 = np.where(on_row, jy, np.clip(jy - 1, 0, len(y) - 2))
    i1 = np.where(on_row, i0 + 1, i0)
    j1 = np.where(on_row, j0, j0 + 1)
    pa, pb = np.column_stack([x[i0], y[j0]]), np.column_stack([x[i1], y[j1]])

    def fun_p(p: np.ndarray) -> np.ndarray:
        return fun(p[:, 0], p[:, 1])

    t2 = time.perf_counter()
    refined = _edge_roots(fun_p, pa, pb, F[i0, j0], F[i1, j1])
    refined[node] = at_node
    t3 = time.perf_counter()
    return lines, refined, {"grid": t1 - t0, "marching": t2 - t1, "refine": t3 - t2}


def _wrapped(surface: Any, p: np.ndarray) -> np.ndarray:
    d = surface.domain
    p = p.copy()
    for i in (0, 1):
        if d.periodic[i]:
            lo = d.range(i)[0]
            p[:, i] = lo + np.mod(p[:, i] - lo, d.span(i))
    return p


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--grid", type=int, default=193)
    args = parser.parse_args(argv)
    from scipy.spatial import cKDTree

    from lgraph.surfaces.parametric._zero_set import zero_set

    print(f"grid {args.grid} x {args.grid}, medians of {args.repeat} alternating runs\n")
    print(
        "| case | lgraph zero_set | contourpy pipeline (no seam stitching) | of both: grid values"
        " + refinement | lgraph marching | contourpy marching | largest crossing difference"
        " | curves lgraph (closed) | lines contourpy (closed) |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for name, surface, fun in cases():
        times: dict[str, list[float]] = {"ours": [], "cp": [], "grid": [], "refine": []}
        ours: Any = None
        lines: Any = None
        refined: Any = None
        for _ in range(args.repeat):  # alternate, so that load changes hit both
            t0 = time.perf_counter()
            ours = zero_set(surface, fun, args.grid)
            t1 = time.perf_counter()
            lines, refined, parts = contourpy_zero_set(surface, fun, args.grid)
            t2 = time.perf_counter()
            times["ours"].append(t1 - t0)
            times["cp"].append(t2 - t1)
            times["grid"].append(parts["grid"])
            times["refine"].append(parts["refine"])
        med = {k: statistics.median(v) for k, v in times.items()}
        same = med["grid"] + med["refine"]
        mine = _wrapped(surface, np.concatenate([p for p, _ in ours]))
        cp_pts = _wrapped(surface, refined)
        dist_a = cKDTree(cp_pts).query(mine)[0].max()
        dist_b = cKDTree(mine).query(cp_pts)[0].max()
        n_closed = sum(c for _, c in ours)
        cp_closed = sum(bool(np.array_equal(ln[0], ln[-1])) for ln in lines)
        print(
            f"| {name} | {med['ours'] * 1e3:.1f} ms | {med['cp'] * 1e3:.1f} ms | "
            f"{same * 1e3:.1f} ms | {(med['ours'] - same) * 1e3:.1f} ms | "
            f"{(med['cp'] - same) * 1e3:.1f} ms | {max(dist_a, dist_b):.1e} | "
            f"{len(ours)} ({n_closed}) | {len(lines)} ({cp_closed}) |"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
