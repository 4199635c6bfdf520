"""SurfaceOfRevolution: closed-form lines of curvature, contour and ray hits,
each checked independently (Rodrigues' formula with finite-difference normals,
the view condition from the analytic derivatives and brute-force sign scans,
a dense ray march against the implicit inside test of each profile)."""

from __future__ import annotations

import numpy as np
import pytest
from bruteforce import sign_changes

import lgraph as lg
from lgraph._own import CONTOUR, ON
from lgraph.surfaces.revolution._contour import contour_residual

EGG = lg.SurfaceOfRevolution(lg.named_profile("egg"), (0, np.pi))
VASE = lg.SurfaceOfRevolution(lg.named_profile("vase"), (0, 3.0))
TORUS = lg.SurfaceOfRevolution(
    lg.named_profile("circle", center=(2.0, 0.0), radius=0.7), (0, 2 * np.pi)
)
TILTED = lg.SurfaceOfRevolution(lg.named_profile("egg"), (0, np.pi), axis=(1, 2, 2))
HALF = lg.SurfaceOfRevolution(lg.named_profile("vase"), (0, 3.0), angle_range=(0.3, 3.5))
# a profile without analytic derivatives (finite differences)
PLAIN = lg.SurfaceOfRevolution(lambda t: (1.2 + 0.3 * np.cos(2 * t), t), (-1.5, 1.5))
SURFACES = {
    "egg": EGG,
    "vase": VASE,
    "torus": TORUS,
    "tilted": TILTED,
    "half": HALF,
    "plain": PLAIN,
}
PROJECTORS = {
    "par": lg.ParallelProjector(direction=(1, -1.3, 0.7)),
    "side": lg.ParallelProjector(direction=(1, 0.5, 0)),  # perpendicular to the z axis
    "cen": lg.CentralProjector(eye=(7, -6, 4)),
    "low": lg.CentralProjector(eye=(2.5, 1.0, -1.0)),  # close, below
}


def _eval(batch, n=257):
    idx = np.repeat(np.arange(len(batch)), n)
    t = np.concatenate([np.linspace(a, b, n) for a, b in zip(batch.t0, batch.t1)])
    xyz, uv = batch.evaluate(idx, t)
    return idx, xyz, uv


def _fd_normal(s, u1, u2, h=1e-6):
    """Unit normal from central differences of point() alone."""
    x1 = (s.point(u1 + h, u2) - s.point(u1 - h, u2)) / (2 * h)
    x2 = (s.point(u1, u2 + h) - s.point(u1, u2 - h)) / (2 * h)
    n = np.cross(x1, x2)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


# -- construction ----------------------------------------------------------------
@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: lg.SurfaceOfRevolution(lambda t: (t - 1, t), (0, 2)), "rho >= 0"),
        (
            lambda: lg.SurfaceOfRevolution(
                lambda t: (np.where(t < 0, np.nan, t) ** 0.5, t), (-1, 1)
            ),
            "finite",
        ),
        (lambda: lg.SurfaceOfRevolution(lambda t: (1 + 0 * t, t), (1, 1)), "t_range"),
        (lambda: lg.SurfaceOfRevolution(lambda t: (1 + 0 * t, t), (0, 1), axis=(0, 0, 0)), "axis"),
        (lambda: lg.SurfaceOfRevolution(lambda t: (0 * t, t), (0, 1)), "leave the axis"),
        (lambda: lg.SurfaceOfRevolution(3, (0, 1)), "callable, a profile name"),
        (lambda: lg.SurfaceOfRevolution("spiral"), "name must be one of"),
        (lambda: lg.SurfaceOfRevolution(lambda t: (t, t)), "t_range is required"),
        (lambda: lg.named_profile("egg", a="x"), "finite number"),
        (lambda: lg.profile_from_points([[1, 0], [-1, 1], [1, 2], [1, 3]]), "rho must be >= 0"),
    ],
)
def test_bad_input_is_a_clear_error(make, message):
    with pytest.raises((ValueError, TypeError), match=message):
        make()


def test_poles_found_automatically():
    assert EGG.poles == (True, True) and EGG.domain.poles == ((True, True), (False, False))
    assert lg.SurfaceOfRevolution("vase", (0, 3)).domain.poles[0] == (False, False)
    half_egg = lg.SurfaceOfRevolution("egg", (0, 2.0))
    assert half_egg.domain.poles[0] == (True, False)
    assert sum(len(x) for x in half_egg.boundary()) == 1  # the rim, not the pole
    assert VASE.poles == (False, False)
    assert lg.Pseudosphere().poles == (False, False)
    b = EGG.boundary()
    assert b == [] or sum(len(x) for x in b) == 0
    assert sum(len(x) for x in VASE.boundary()) == 2
    assert sum(len(x) for x in HALF.boundary()) == 4


def test_matches_the_torus_class_and_its_curvatures():
    t = lg.Torus(2.0, 0.7)
    u, v = np.meshgrid(np.linspace(0, 6, 9), np.linspace(0.1, 6, 7), indexing="ij")
    # SoR (u1 = profile angle, u2 = turn) against Torus (u1 = turn, u2 = tube angle)
    assert np.allclose(TORUS.point(v, u), t.point(u, v), atol=1e-14)
    k_sor = np.sort(np.abs(np.stack(TORUS.principal_curvatures(v, u))), axis=0)
    k_tor = np.sort(np.abs(np.stack(t.principal_curvatures(u, v))), axis=0)
    assert np.allclose(k_sor, k_tor, atol=1e-9)


def test_pseudosphere_has_constant_negative_curvature():
    s = lg.Pseudosphere(1.5)
    t, phi = np.meshgrid(np.linspace(0.2, 2.8, 9), np.linspace(0, 6, 5))
    k1, k2 = s.principal_curvatures(t, phi)
    assert np.allclose(k1 * k2, -1 / 1.5**2, atol=1e-9)


def test_finite_difference_profile_derivatives():
    t = np.linspace(-1.4, 1.4, 11)
    dr, dz = PLAIN.drz(t)
    ddr, ddz = PLAIN.ddrz(t)
    assert np.allclose(dr, -0.6 * np.sin(2 * t), atol=1e-10) and np.allclose(dz, 1, atol=1e-10)
    assert np.allclose(ddr, -1.2 * np.cos(2 * t), atol=1e-7) and np.allclose(ddz, 0, atol=1e-7)


# -- lines of curvature ----------------------------------------------------------------
@pytest.mark.parametrize("name", ["egg", "tilted", "vase", "plain"])
def test_lines_of_curvature_are_meridians_and_parallels(name):
    s = SURFACES[name]
    e1, e2, a = s.frame
    (batch,) = lg.LinesOfCurvature(5, 7).batches(s, None)
    idx, xyz, uv = _eval(batch)
    h = xyz @ a
    r = np.linalg.norm(xyz - h[:, None] * a, axis=1)
    ang = np.arctan2(xyz @ e2, xyz @ e1)
    n_par = 0
    for k in range(len(batch)):
        sel = idx == k
        if np.ptp(uv[sel, 0]) == 0:  # a parallel: one height, one radius
            n_par += 1
            assert np.ptp(h[sel]) < 1e-12 and np.ptp(r[sel]) < 1e-12
        else:  # a meridian: one angle (where off the axis)
            ok = sel & (r > 1e-6)
            d = np.angle(np.exp(1j * (ang[ok] - ang[ok][0])))
            assert np.abs(d).max() < 1e-12
    assert n_par == 5
    # Rodrigues: along a line of curvature dN is parallel to dx (normals by finite differences)
    inner = (uv[:, 0] > s.t_range[0] + 0.05) & (uv[:, 0] < s.t_range[1] - 0.05)
    for k in range(len(batch)):
        sel = np.nonzero((idx == k) & inner)[0][::16]
        p = uv[sel]
        along = 0 if np.ptp(uv[idx == k, 0]) > 0 else 1
        h_ = 5e-4
        dp = np.zeros_like(p)
        dp[:, along] = h_
        dn = _fd_normal(s, *(p + dp).T) - _fd_normal(s, *(p - dp).T)
        dx = s.points(p + dp) - s.points(p - dp)
        cross = np.linalg.norm(np.cross(dn, dx), axis=1)
        # |dN x dx| / |dx|^2: the normal's turn off the principal direction
        # per unit length (principal curvatures here are of order 1)
        assert np.all(cross / np.einsum("ij,ij->i", dx, dx) < 1e-5)


# -- contour --------------------------------------------------------------------------
@pytest.mark.parametrize("pname", list(PROJECTORS))
@pytest.mark.parametrize("name", list(SURFACES))
def test_contour_points_have_normal_perpendicular_to_view(name, pname):
    s, p = SURFACES[name], PROJECTORS[pname]
    batches = s.contour(p)
    pts = []
    for b in batches:
        _, xyz, uv = _eval(b, 401)
        n = s.normal(uv[:, 0], uv[:, 1])
        w = (
            p.eye - xyz
            if isinstance(p, lg.CentralProjector)
            else np.broadcast_to(p.frame[2], xyz.shape)
        )
        w = w / np.linalg.norm(w, axis=1, keepdims=True)
        ok = np.linalg.norm(np.cross(*s.derivatives(uv[:, 0], uv[:, 1])), axis=1) > 1e-9
        assert np.abs(np.einsum("ij,ij->i", n, w)[ok]).max() < 1e-10
        assert np.abs(contour_residual(s, p, uv)[ok]).max() < 1e-10
        assert np.allclose(s.points(uv), xyz)
        lo, hi = s.angle_range
        mid = (lo + hi) / 2
        assert np.all(np.abs(np.angle(np.exp(1j * (uv[:, 1] - mid)))) <= (hi - lo) / 2 + 1e-9)
        pts.append(xyz)
    # completeness: every sign change of N.w along a grid of parallels lies on a curve
    t = np.linspace(*s.t_range, 41)[1:-1]
    phi = np.linspace(*s.angle_range, 2001)
    T, P = np.meshgrid(t, phi, indexing="ij")
    n = _fd_normal(s, T, P)
    x = s.point(T, P)
    w = p.eye - x if isinstance(p, lg.CentralProjector) else np.broadcast_to(p.frame[2], x.shape)
    f = np.einsum("...i,...i", n, w)
    i, j = np.nonzero(np.sign(f[:, 1:]) * np.sign(f[:, :-1]) < 0)
    if len(i):
        assert pts, "sign changes of N.w but no contour"
        allpts = np.concatenate(pts)
        cross = 0.5 * (x[i, j] + x[i, j + 1])
        dist = np.linalg.norm(cross[:, None, :] - allpts[None, ::3, :], axis=2).min(axis=1)
        assert dist.max() < 0.02 * s.size


def test_contour_viewed_along_the_axis_is_parallels():
    (b,) = EGG.contour(lg.ParallelProjector(direction=(0, 0, 1)))
    _, xyz, uv = _eval(b)
    # the widest parallel of the egg: z' ... rho' = 0
    dr, _ = EGG.drz(uv[:, 0])
    assert len(b) == 1 and np.abs(dr).max() < 1e-12


def test_contour_closes_through_its_folds():
    (b,) = TORUS.contour(PROJECTORS["cen"])
    assert b.closed.all()
    for k in range(len(b)):
        t = np.linspace(b.t0[k], b.t1[k], 257)
        xyz, _ = b.evaluate(np.full(len(t), k), t)
        assert np.linalg.norm(xyz[0] - xyz[-1]) < 1e-12
        steps = np.linalg.norm(np.diff(xyz, axis=0), axis=1)
        assert steps.max() < 10 * np.median(steps)  # smooth through the folds, no jumps


# -- hits -----------------------------------------------------------------------------
def _inside(name, p):
    """Implicit inside test of each test surface (written from its profile formula)."""
    s = SURFACES[name]
    a = s.frame[2]
    h = p @ a
    r = np.linalg.norm(p - h[..., None] * a, axis=-1)
    if name in ("egg", "tilted"):
        # z = -1.4 cos t, rho = sin t (1 + 0.18 cos t)
        c = np.clip(-h / 1.4, -1, 1)
        return np.where(np.abs(h) < 1.4, r - np.sqrt(1 - c * c) * (1 + 0.18 * c), 1.0)
    if name == "torus":
        return (r - 2.0) ** 2 + h**2 - 0.49
    if name == "plain":
        return np.where(np.abs(h) <= 1.5, r - 1.2 - 0.3 * np.cos(2 * h), np.nan)
    raise KeyError(name)


def _march(name, o, v, smax, start=0.0, n=20000):
    """Brute force: sign changes of the inside test along the ray (NaN: off the patch).

    ``margin``: the smallest ``|g|`` at a turning point of ``g`` along the ray (a
    near-tangency, where the march itself is unreliable)."""
    lam = start + (np.minimum(smax, 12.0) - start)[:, None] * np.linspace(0, 1, n)[None, :]
    g = _inside(name, o[:, None, :] + lam[..., None] * v[:, None, :])
    return sign_changes(g)


@pytest.mark.parametrize("name", ["egg", "tilted", "torus", "plain"])
def test_hits_agree_with_a_dense_ray_march(name):
    s = SURFACES[name]
    rng = np.random.default_rng(3)
    o = rng.uniform(-4, 4, (400, 3))
    target = rng.uniform(-1.5, 1.5, (400, 3))
    v = target - o
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    smax = np.full(400, np.inf)
    # some rays exactly perpendicular to the axis and some along it
    v[:40] -= (v[:40] @ s.frame[2])[:, None] * s.frame[2]
    v[:40] /= np.linalg.norm(v[:40], axis=1, keepdims=True)
    v[40:60] = s.frame[2]
    hit = s.hits(o, v, smax)
    ref, margin = _march(name, o, v, smax)
    clear = margin > 2e-3  # the march's own resolution: skip rays that barely touch
    assert clear.sum() > 300
    assert np.array_equal(hit[clear], ref[clear])
    assert ref.sum() > 50 and (~ref).sum() > 50


@pytest.mark.parametrize("pname", ["par", "side", "cen"])
@pytest.mark.parametrize("name", ["egg", "torus", "plain"])
def test_hits_from_points_on_the_surface(name, pname):
    s, p = SURFACES[name], PROJECTORS[pname]
    rng = np.random.default_rng(5)
    t = rng.uniform(*s.t_range, 300)
    phi = rng.uniform(0, 2 * np.pi, 300)
    x = s.point(t, phi)
    v, smax = p.rays(x)
    o = x
    vn = v / np.linalg.norm(v, axis=1, keepdims=True)
    hit = s.hits(o, v, smax, np.full(300, ON))
    lam_max = smax * np.linalg.norm(v, axis=1)
    ref, margin = _march(name, o, vn, lam_max, start=1e-3, n=5000)
    # points whose ray leaves the surface almost tangentially are ambiguous for the march
    n = s.normal(t, phi)
    grazing = np.abs(np.einsum("ij,ij->i", n, vn)) < 0.05
    clear = (margin > 1e-2) & ~grazing
    assert clear.sum() > 150
    assert np.array_equal(hit[clear], ref[clear])


def test_contour_points_do_not_hide_themselves():
    p = PROJECTORS["cen"]
    for b in EGG.contour(p):
        _, xyz, _ = _eval(b, 101)
        v, smax = p.rays(xyz)
        o = xyz
        assert not EGG.hits(o, v, smax, np.full(len(o), CONTOUR)).any()


def test_grazing_pairs_inside_one_grid_cell_are_found():
    # a coarse grid: both roots of a nearly tangent ray fall into one cell
    s = lg.SurfaceOfRevolution(lg.named_profile("egg"), (0, np.pi), resolution=16)
    rho, z = s.rz(np.array([np.pi / 2]))
    o = np.array([[rho[0] - 1e-6, -5.0, z[0]]])  # just inside the widest parallel
    v = np.array([[0.0, 1.0, 0.0]])
    assert s.hits(o, v, np.array([np.inf]))[0]
    o2 = np.array([[rho[0] + 1e-6, -5.0, z[0]]])
    assert not s.hits(o2, v, np.array([np.inf]))[0]
    # tilted a little: F's two roots within one cell, no sign change at the nodes
    v3 = np.array([[0.0, 1.0, 1e-4]])
    o3 = np.array([[0.9 * rho[0], -5.0, z[0] - 5e-4]])
    assert s.hits(o3, v3, np.array([np.inf]))[0]


def test_renders_with_hidden_lines_consistent_with_brute_force():
    scene = lg.Scene()
    scene.add(EGG, lg.LinesOfCurvature(6, 12))
    p = PROJECTORS["cen"]
    d = scene.render(p, hidden_lines=True)
    vis = [s for s in d.strokes if s.family == "curvature"]
    assert any(s.visible for s in vis) and any(not s.visible for s in vis)
    for s in vis:
        mid = s.xyz[1:-1] if len(s.xyz) > 2 else s.xyz
        v, smax = p.rays(mid)
        ref, margin = _march("egg", mid, v, smax, start=1e-3, n=4000)
        clear = margin > 5e-3
        assert np.all(ref[clear] == (not s.visible))


# -- scene files --------------------------------------------------------------------
SCENE = """
[projector]
kind = "central"
azimuth = 30
elevation = 25
distance = 14

[[object]]
surface = "surface_of_revolution"
params = {{ profile = {profile}, angle_range = [0, 4.5] }}
families = [{{ name = "lines_of_curvature", n1 = 4, n2 = 6 }},
            {{ name = "level_lines", n = 3, direction = [1, 0, 1] }},
            {{ name = "level_lines", function = "gaussian_curvature", values = [0.2] }},
            "parabolic_lines"]

[[object]]
surface = "torus"
params = {{ R = 2, r = 0.5 }}
transform = [{{ translate = [0, 0, 4] }}]
families = ["parabolic_lines", {{ name = "level_lines", values = [0.1, 0.3] }}]
"""


@pytest.mark.parametrize(
    "profile", ['"egg"', '"vase"', "[[0, 0], [1, 0.2], [1.3, 1], [0.6, 2], [0.8, 2.6]]"]
)
def test_scene_files_know_the_new_class_and_families(tmp_path, profile):
    path = tmp_path / "s.toml"
    path.write_text(SCENE.format(profile=profile), encoding="utf-8")
    scene, projector, _ = lg.load_scene_file(path)
    (node, torus) = scene.nodes
    assert isinstance(node.surface, lg.SurfaceOfRevolution)
    assert [type(f).__name__ for f in node.families] == [
        "LinesOfCurvature", "LevelLines", "LevelLines", "ParabolicLines"
    ]  # fmt: skip
    d = scene.render(projector)
    fams = {s.family for s in d.strokes}
    assert {"curvature", "level", "parabolic", "contour"} <= fams


@pytest.mark.parametrize(
    "params, message",
    [
        ('{ profile = "spiral" }', "profile"),
        ('{ profile = "egg", t_range = [1, 1] }', "t_range"),
        ("{ profile = [[1, 0], [-1, 1], [1, 2], [1, 3]] }", "rho must be >= 0"),
    ],
)
def test_scene_file_errors_for_bad_profiles(tmp_path, params, message):
    text = f"""
[projector]
kind = "parallel"
azimuth = 30
elevation = 20
[[object]]
surface = "surface_of_revolution"
params = {params}
"""
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(lg.SceneFileError, match=message):
        lg.load_scene_file(path)


def test_scene_file_level_lines_with_no_values_is_an_error(tmp_path):
    text = """
[projector]
kind = "parallel"
azimuth = 30
elevation = 20
[[object]]
surface = "torus"
params = { R = 2, r = 0.5 }
families = [{ name = "level_lines", values = [] }]
"""
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(lg.SceneFileError, match="values must be a non-empty list"):
        lg.load_scene_file(path)


# -- the catenoid reuses the surface of revolution ------------------------------------
@pytest.mark.parametrize("pname", ["par", "side", "cen"])
def test_catenoid_contour_and_hits_from_the_surface_of_revolution(pname):
    s, p = lg.Catenoid(1.0, 1.2), PROJECTORS[pname]
    batches = s.contour(p)
    assert batches and all(b.surface is s for b in batches)
    for b in batches:
        _, xyz, uv = _eval(b)
        assert np.allclose(s.points(uv), xyz, atol=1e-12)
        n = s.normal(uv[:, 0], uv[:, 1])  # the catenoid's own analytic derivatives
        w = p.view_vectors(xyz)
        w = w / np.linalg.norm(w, axis=-1, keepdims=True)
        assert np.abs(np.einsum("ij,ij->i", n, w)).max() < 1e-10
    rng = np.random.default_rng(11)
    o = rng.uniform(-3, 3, (300, 3))
    v = rng.uniform(-1.5, 1.5, (300, 3)) * [1, 1, 0.8] - o
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    hit = s.hits(o, v, np.full(300, np.inf))
    lam = 12.0 * np.linspace(0, 1, 20000)
    q = o[:, None, :] + lam[None, :, None] * v[:, None, :]
    g = np.where(
        np.abs(q[..., 2]) <= 1.2, np.hypot(q[..., 0], q[..., 1]) - np.cosh(q[..., 2]), np.nan
    )
    ref = (np.sign(g[:, 1:]) * np.sign(g[:, :-1]) < 0).any(axis=1)
    dg = np.diff(g, axis=1)
    turn = np.zeros_like(g, bool)
    turn[:, 1:-1] = dg[:, 1:] * dg[:, :-1] <= 0
    with np.errstate(invalid="ignore"):
        margin = np.nanmin(np.where(turn, np.abs(g), np.inf), axis=1)
    clear = margin > 2e-3
    assert clear.sum() > 200 and ref[clear].any() and (~ref[clear]).any()
    assert np.array_equal(hit[clear], ref[clear])
    (lc,) = lg.LinesOfCurvature(3, 4).batches(s, None)
    assert len(lc) == 7
