"""Budgets and robustness: costly inputs are refused before the work (with a
ValueError naming the parameter and the limit), degenerate surfaces are
reported, coincident surfaces and scenes far from the origin draw correctly.

The refused cases run in a child process whose peak resident memory must
stay under 1 GB: a refusal that first allocated gigabytes fails there."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import warnings
from pathlib import Path

import numpy as np
import pytest

import lgraph as lg

ROOT = Path(__file__).resolve().parents[1]


def _run_capped(code: str, limit_mb: int = 1024) -> subprocess.CompletedProcess:
    """Run ``code`` in a child Python; it must stay under ``limit_mb`` MB of
    resident memory (the child's own high-water mark at its end; the address
    space is capped at twice that as a guard against a runaway allocation).

    Not ``getrusage``'s ``ru_maxrss``: on Linux a child started by
    fork/vfork + exec inherits the parent's peak there, so a pytest worker
    that once held 1.4 GB made every child "use" 1.4 GB.  ``VmHWM`` in
    ``/proc/self/status`` belongs to the child's own address space."""
    prog = textwrap.dedent(
        f"""
        import atexit, resource, sys
        cap = {2 * limit_mb} << 20
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
        sys.path.insert(0, {str(ROOT)!r})
        def peak():
            try:
                with open("/proc/self/status") as fh:
                    kb = next(int(l.split()[1]) for l in fh if l.startswith("VmHWM:"))
            except (OSError, StopIteration):  # not Linux: the inherited peak is an upper bound
                kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
                if sys.platform == "darwin":  # bytes there
                    kb /= 1024
            mb = kb / 1024
            print("PEAK-MB", mb, "OK" if mb < {limit_mb} else "TOO-MUCH")
        atexit.register(peak)
        """
    ) + textwrap.dedent(code)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    r = subprocess.run(
        [sys.executable, "-c", prog], capture_output=True, text=True, timeout=120, env=env
    )
    assert "OK" in r.stdout.split("PEAK-MB")[-1], r.stdout[-500:] + r.stderr[-2000:]
    return r


def _torus_winding(k: int) -> lg.ParametricSurface:
    def f(u, v):
        u, v = np.broadcast_arrays(u, v)
        r = 2 + np.cos(v)
        return np.stack([r * np.cos(k * u), r * np.sin(k * u), np.sin(v)], -1)

    return lg.ParametricSurface(f, (0, 2 * np.pi), (0, 2 * np.pi))


REFUSED = {
    "constant surface": (
        "import numpy as np, lgraph as lg\n"
        "s = lg.ParametricSurface(lambda u, v: np.zeros(np.broadcast(u, v).shape + (3,)),"
        " (0, 1), (0, 1))\n",
        "all its points are equal",
    ),
    "half collapsed": (
        "import numpy as np, lgraph as lg\n"
        "def f(u, v):\n"
        "    u, v = np.broadcast_arrays(u, v)\n"
        "    r = np.maximum(u - 0.5, 0)\n"
        "    return np.stack([r * np.cos(v), r * np.sin(v), r * r], -1)\n"
        "s = lg.ParametricSurface(f, (0, 1), (0, 6.28))\n",
        "not regular",
    ),
    "sixteen windings": (
        "import numpy as np, lgraph as lg\n"
        "def f(u, v):\n"
        "    u, v = np.broadcast_arrays(u, v)\n"
        "    r = 2 + np.cos(v)\n"
        "    return np.stack([r * np.cos(16 * u), r * np.sin(16 * u), np.sin(v)], -1)\n"
        "s = lg.ParametricSurface(f, (0, 6.283185307179586), (0, 6.283185307179586))\n",
        "winds over itself",
    ),
}


@pytest.mark.parametrize("name", sorted(REFUSED))
def test_degenerate_and_overwound_surfaces_are_refused_within_1gb(name: str) -> None:
    setup, message = REFUSED[name]
    r = _run_capped(
        setup
        + textwrap.dedent(
            """
            sc = lg.Scene(); sc.add(s)
            try:
                sc.render(lg.ParallelProjector(direction=(1, 2, 3)))
            except ValueError as e:
                print("REFUSED", e)
            """
        )
    )
    assert r.returncode == 0, r.stderr[-2000:]
    assert "REFUSED ParametricSurface:" in r.stdout and message in r.stdout


def test_tiny_tolerance_is_refused_at_once() -> None:
    sc = lg.Scene()
    sc.add(lg.Sphere(1))
    for bad in (1e-14, 1e-300, 0.0, -1.0, float("nan"), True):
        with pytest.raises(ValueError, match="tolerance must be a number in"):
            sc.render(lg.ParallelProjector(direction=(1, 2, 3)), tolerance=bad)
    # numpy scalars are numbers
    d = sc.render(lg.ParallelProjector(direction=(1, 2, 3)), tolerance=np.float64(1e-3))
    assert d.n_points > 0


def test_sampling_budget_is_checked_before_a_split_pass() -> None:
    r = _run_capped(
        """
        import lgraph as lg
        sc = lg.Scene(); sc.add(lg.Sphere(1), lg.ParameterLines(3000, 3000))
        try:
            sc.render(lg.ParallelProjector(direction=(1, 2, 3)), tolerance=1e-9)
        except ValueError as e:
            print("REFUSED", e)
        """
    )
    assert r.returncode == 0, r.stderr[-2000:]
    assert "REFUSED Scene.render:" in r.stdout and "the limit is 4000000" in r.stdout


def test_a_surface_winding_twice_still_draws() -> None:
    """Two windings of a torus draw the same outline as one (the budget does
    not refuse ordinary overlaps)."""
    p = lg.ParallelProjector(direction=(1, 2, 3))
    lengths = []
    for k in (1, 2):
        sc = lg.Scene()
        sc.add(_torus_winding(k), lg.ParameterLines(1, 1))
        d = sc.render(p, tolerance=1e-3)
        c = [s for s in d.strokes if s.family == "contour"]
        lengths.append(sum(np.hypot(*np.diff(s.xy, axis=0).T).sum() for s in c))
    # the k = 2 surface has its contour twice, on top of each other
    assert lengths[1] == pytest.approx(2 * lengths[0], rel=2e-3)


def test_geodesic_and_intersection_budgets() -> None:
    T, S = lg.Torus(3, 1), lg.Sphere(1)
    with pytest.raises(ValueError, match="geodesic: length 1e\\+06 exceeds the limit"):
        lg.geodesic(T, (0, 0), (1, 0), 1e6)
    sc = lg.Scene()
    sc.add(T, lg.Geodesic((0, 0), (1, 0), length=1e7))
    with pytest.raises(ValueError, match="Geodesic: length .* exceeds the limit"):
        sc.render(lg.ParallelProjector(direction=(1, 2, 3)))
    with pytest.raises(ValueError, match="intersection_curves: step 1e-09 needs more than"):
        lg.intersection_curves(S, T, step=1e-9)
    with pytest.raises(ValueError, match="intersection_curves: grid must be an integer"):
        lg.intersection_curves(S, T, grid=100000)
    for bad in (0, -1, float("inf")):
        with pytest.raises(ValueError, match="intersection_curves: step must be a positive"):
            lg.intersection_curves(S, T, step=bad)
    with pytest.raises(ValueError, match="the two surfaces are the same"):
        lg.intersection_curves(S, lg.Sphere(1))
    with pytest.raises(TypeError, match="intersection_curves: other must be a Surface"):
        lg.intersection_curves(S, "sphere")
    with pytest.raises(ValueError, match="geodesic: direction must be non-zero"):
        lg.geodesic(T, (0, 0), (0, 0), 1.0)


def _png_drawing(style: lg.Style) -> lg.Drawing:
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(4, 8), style=style)
    return sc.render(lg.ParallelProjector(direction=(1, 2, 3)), tolerance=1e-3)


def test_png_dash_shorter_than_a_pixel_is_drawn_solid(tmp_path: Path) -> None:
    from PIL import Image

    d = _png_drawing(lg.Style(dash=(1e-6, 1e-6)))
    with pytest.warns(UserWarning, match="shorter than a pixel"):
        d.save(tmp_path / "dash.png")
    solid = _png_drawing(lg.Style())
    solid.save(tmp_path / "solid.png")
    a = np.asarray(Image.open(tmp_path / "dash.png"))
    b = np.asarray(Image.open(tmp_path / "solid.png"))
    assert np.array_equal(a, b)


def test_png_stroke_wider_than_the_image_fills_it(tmp_path: Path) -> None:
    from PIL import Image

    d = _png_drawing(lg.Style(width=1e6, color="red"))
    with pytest.warns(UserWarning, match="covers the whole image"):
        d.save(tmp_path / "wide.png")
    img = np.asarray(Image.open(tmp_path / "wide.png"))
    assert (img[..., 0] == 255).all() and (img[..., 1] == 0).all()  # CSS red
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _png_drawing(lg.Style(width=1e300)).save(tmp_path / "huge.pdf")  # vector: as given


def test_dash_polyline_refuses_absurd_dash_counts() -> None:
    from lgraph.output.dashes import dash_polyline

    with pytest.raises(ValueError, match="dash_polyline: pattern .* the limit is"):
        dash_polyline(np.array([[0.0, 0.0], [1e3, 0.0]]), (1e-6, 1e-6))


def _outline_lengths(scene: lg.Scene, projector: lg.Projector) -> list[float]:
    d = scene.render(projector)
    return [
        float(np.hypot(*np.diff(s.xy, axis=0).T).sum()) for s in d.strokes if s.family == "contour"
    ]


@pytest.mark.parametrize("direction", [(1, 2, 3), (0, 0, 1), (1, 0, 0), (-2, 1, 0.5)])
def test_the_same_sphere_twice_draws_its_outline_whole(direction) -> None:
    """Coincident spheres: the outline is drawn once, one closed stroke as
    long as the projected great circle (2 pi r), never fragments cut by
    round-off."""
    sc = lg.Scene()
    sc.add(lg.Sphere(1.5))
    sc.add(lg.Sphere(1.5))
    lengths = _outline_lengths(sc, lg.ParallelProjector(direction=direction))
    # a polyline within the chord tolerance (1e-4 of the diagonal) of the circle
    assert lengths == pytest.approx([3 * np.pi], rel=2e-4)


def _wavy_torus() -> lg.ParametricSurface:
    def f(u, v):
        u, v = np.broadcast_arrays(u, v)
        r = 2 + np.cos(v)
        return np.stack([r * np.cos(u), r * np.sin(u), np.sin(v) + 0.3 * np.cos(2 * u)], -1)

    return lg.ParametricSurface(f, (0, 2 * np.pi), (0, 2 * np.pi), periodic=True)


WAVY = _wavy_torus()  # one object added twice (a ParametricSurface has no implicit equation)

COINCIDENT = {
    "parametric, the same object": lambda: WAVY,
    "sphere": lambda: lg.Sphere(1),
    "paraboloid patch": lambda: lg.EllipticParaboloid(1, 1),
    "hyperboloid patch": lambda: lg.HyperboloidOneSheet(1, 1, 1),
    "torus": lambda: lg.Torus(3, 1),
}


def _lengths(d) -> dict[str, float]:
    out: dict[str, float] = {}
    for s in d.strokes:
        out[s.family] = out.get(s.family, 0.0) + float(np.hypot(*np.diff(s.xy, axis=0).T).sum())
    return out


@pytest.mark.parametrize("name", sorted(COINCIDENT))
def test_a_surface_added_twice_draws_once_what_it_draws_once(name) -> None:
    """A surface added twice in the same place draws, family by family, what
    it draws once (the copy's outline and equal families are not drawn
    again), and the copy hides nothing of it (the tie rule)."""
    p = lg.ParallelProjector(direction=(1, 2, 3))
    one, two = lg.Scene(), lg.Scene()
    one.add(COINCIDENT[name]())
    for _ in range(2):
        two.add(COINCIDENT[name]())
    a, b = one.render(p), two.render(p)
    assert len(b.strokes) == len(a.strokes)
    la, lb = _lengths(a), _lengths(b)
    assert la.keys() == lb.keys()
    # numeric surfaces locate their flips by Newton's method (to ~1e-7)
    rel = 1e-6 if name.startswith("parametric") else 1e-9
    for family in la:
        assert lb[family] == pytest.approx(la[family], rel=rel), family


def test_coincident_spheres_hide_what_one_hides() -> None:
    """Two copies of a sphere with different parameter lines: each copy's
    lines are hidden exactly as on a single sphere (the outline drawn once)."""
    p = lg.ParallelProjector(direction=(1, -2, 1.5))
    first, second, two = lg.Scene(), lg.Scene(), lg.Scene()
    first.add(lg.Sphere(1), lg.ParameterLines(5, 9))
    second.add(lg.Sphere(1), lg.ParameterLines(3, 4), contour=False)
    two.add(lg.Sphere(1), lg.ParameterLines(5, 9))
    two.add(lg.Sphere(1), lg.ParameterLines(3, 4))
    la, lc, lb = (sum(_lengths(sc.render(p)).values()) for sc in (first, second, two))
    # polylines within the chord tolerance (1e-4 of the diagonal): lengths to ~1e-6
    assert lb == pytest.approx(la + lc, rel=1e-5)


def _two_spheres(o: float) -> lg.Scene:
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(6, 12), transform=lg.translate(o, o, o))
    sc.add(
        lg.Ellipsoid(1, 0.7, 0.5),
        lg.LinesOfCurvature(5, 7),
        transform=lg.translate(o + 1.2, o + 0.3, o),
    )
    return sc


@pytest.mark.parametrize("central", [False, True])
def test_a_scene_far_from_the_origin_draws_as_at_the_origin(central: bool) -> None:
    """Translating scene and eye by 1e8 changes nothing beyond 1e-6 of the
    scene size: same strokes, same total lengths, and every stroke end (where
    visibility flips) within 1e-6 of the size of an end of the other."""
    out = []
    for o in (0.0, 1e8):
        if central:
            p = lg.CentralProjector(eye=(8 + o, 5 + o, 6 + o), target=(o, o, o))
        else:
            p = lg.ParallelProjector(direction=(1, 2, 3))
        d = _two_spheres(o).render(p, hidden_lines=True)
        out.append(d.strokes)
    size = 3.0
    a, b = out
    assert len(a) == len(b)
    for visible in (True, False):
        la = [s for s in a if s.visible == visible]
        lb = [s for s in b if s.visible == visible]
        length_a = sum(np.linalg.norm(np.diff(s.xyz, axis=0), axis=1).sum() for s in la)
        length_b = sum(np.linalg.norm(np.diff(s.xyz - 1e8, axis=0), axis=1).sum() for s in lb)
        assert length_b == pytest.approx(length_a, abs=1e-6 * size)
        ea = np.concatenate([s.xyz[[0, -1]] for s in la])
        eb = np.concatenate([s.xyz[[0, -1]] - 1e8 for s in lb])
        gap = np.linalg.norm(ea[:, None] - eb[None], axis=-1)
        assert gap.min(axis=0).max() < 1e-6 * size
        assert gap.min(axis=1).max() < 1e-6 * size


def test_the_limits_page_lists_every_budget_with_its_value() -> None:
    from lgraph import _tolerance as tol
    from lgraph.output.backends import png
    from lgraph.output.dashes import MAX_DASHES

    page = (ROOT / "docs" / "limits.rst").read_text(encoding="utf-8")
    values = {
        "MIN_CHORD_TOLERANCE": f"``{tol.MIN_CHORD_TOLERANCE:.0e}``".replace("e-0", "e-"),
        "MAX_POINTS": f"``{tol.MAX_POINTS}``",
        "POINTS_PREDICTION_MARGIN": f"``{tol.POINTS_PREDICTION_MARGIN}``",
        "MAX_RAY_BOXES": f"``{tol.MAX_RAY_BOXES}``",
        "RAY_PROBE": f"``{tol.RAY_PROBE}``",
        "ALIAS_PROBE_CURVES": f"``{tol.ALIAS_PROBE_CURVES}``",
        "ALIAS_STEP": f"``{tol.ALIAS_STEP}``",
        "ALIAS_GROWTH": f"``{tol.ALIAS_GROWTH}``",
        "ALIAS_LEVELS": f"``{tol.ALIAS_LEVELS}``",
        "ALIAS_MAX_POINTS": f"``{tol.ALIAS_MAX_POINTS}``",
        "MAX_CURVES": f"``{tol.MAX_CURVES}``",
        "HIT_MAX_CANDIDATES": f"``{tol.HIT_MAX_CANDIDATES}``",
        "HIT_CHUNK_RAYS": f"``{tol.HIT_CHUNK_RAYS}``",
        "MAX_GEODESIC_TURNS": f"``{tol.MAX_GEODESIC_TURNS}``",
        "MAX_INTERSECTION_GRID": f"``{tol.MAX_INTERSECTION_GRID}``",
        "MAX_MARCH_STEPS": f"``{tol.MAX_MARCH_STEPS}``",
        "MAX_FRAMES": f"``{tol.MAX_FRAMES}``",
        "MAX_DASHES": f"``{MAX_DASHES}``",
        "MAX_SIDE": f"``{png.MAX_SIDE}``",
        "COINCIDENT_RTOL": f"{tol.COINCIDENT_RTOL:.0e}".replace("e-0", "e-"),
    }
    for name, value in values.items():
        assert f"``{name}" in page, name
        assert value in page, (name, value)


def test_frame_counts_are_budgeted_before_rendering(tmp_path, monkeypatch) -> None:
    """orbit and animate refuse more frames than MAX_FRAMES, naming the
    parameter and the limit, before anything is rendered or written."""
    import lgraph._tolerance as tol

    monkeypatch.setattr(tol, "MAX_FRAMES", 3)
    with pytest.raises(ValueError, match=r"orbit: frames must be an integer from 1 to 3"):
        lg.orbit(frames=4)
    scene = lg.Scene()
    scene.add(lg.Sphere(1))
    views = [lg.ParallelProjector.from_angles(10 * k, 20) for k in range(4)]
    with pytest.raises(ValueError, match=r"animate: frames must be an integer from 1 to 3"):
        lg.animate(scene, views, tmp_path / "turn.gif", progress=False)
    assert not list(tmp_path.iterdir())
    assert len(lg.orbit(frames=3)) == 3
