"""Intersection curves drawn by default (issue #24): on both surfaces,
hidden like every curve, and switched off per render or per node."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg

CENTRE = np.array([2.5, 1.0, 1.0])


def _two(**add):
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.5), lg.ParameterLines(4, 6), **add)
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 6), transform=lg.translate(*CENTRE))
    return scene


def _ellipsoid(x):
    return (x[:, 0] / 3) ** 2 + (x[:, 1] / 2) ** 2 + (x[:, 2] / 1.5) ** 2 - 1


def _sphere(x):
    return np.linalg.norm(x - CENTRE, axis=1) - 1


VIEW = lg.CentralProjector(eye=(9, -7, 6), target=(0, 0, 0))


def test_the_readme_pair_draws_its_intersection_on_both_surfaces():
    dr = _two().render(VIEW, hidden_lines=True)
    cut = [s for s in dr.strokes if s.family == "intersection"]
    assert cut, "the ellipsoid and the sphere cut each other"
    x = np.concatenate([s.xyz for s in cut])
    # distances to both surfaces (|F| / |grad F| for the ellipsoid)
    grad = np.column_stack([2 * x[:, 0] / 9, 2 * x[:, 1] / 4, 2 * x[:, 2] / 2.25])
    assert np.max(np.abs(_ellipsoid(x)) / np.linalg.norm(grad, axis=1)) < 1e-9
    assert np.max(np.abs(_sphere(x))) < 1e-9
    # one closed curve: the strokes' lengths add up to its whole length, and
    # a visible and a hidden part (seen from the eye, it goes round the sphere)
    assert {s.visible for s in cut} == {True, False}


def _ray_hidden(p, eye):
    """Brute force: does the segment from ``p`` to the eye meet the
    ellipsoid or the sphere away from ``p`` (analytic roots)?"""
    d = eye - p
    out = np.zeros(len(p), dtype=bool)
    for A, c in ((np.diag([1 / 9, 1 / 4, 1 / 2.25]), np.zeros(3)), (np.eye(3), CENTRE)):
        o = p - c
        qa = np.einsum("ij,jk,ik->i", d, A, d)
        qb = 2 * np.einsum("ij,jk,ik->i", o, A, d)
        qc = np.einsum("ij,jk,ik->i", o, A, o) - 1
        disc = qb * qb - 4 * qa * qc
        r = np.sqrt(np.maximum(disc, 0))
        for s in ((-qb - r) / (2 * qa), (-qb + r) / (2 * qa)):
            out |= (disc > 0) & (s > 1e-7) & (s < 1)
    return out


def test_the_intersection_is_hidden_where_rays_meet_a_surface():
    dr = _two().render(VIEW, hidden_lines=True)
    eye = np.asarray(VIEW.eye)
    cut = [s for s in dr.strokes if s.family == "intersection"]
    ends = np.concatenate([s.xyz[[0, -1]] for s in cut])
    for s in cut:
        brute = _ray_hidden(s.xyz, eye)
        # away from the transitions (a band of 1e-3 of the scene around each end)
        far = np.min(np.linalg.norm(s.xyz[:, None] - ends[None], axis=2), axis=1) > 1e-3
        assert far.sum() > 0
        assert np.all(brute[far] == (not s.visible))


def test_intersections_can_be_turned_off():
    assert not [
        s for s in _two().render(VIEW, intersections=False).strokes if s.family == "intersection"
    ]
    assert not [
        s for s in _two(intersections=False).render(VIEW).strokes if s.family == "intersection"
    ]
    with pytest.raises(TypeError, match="intersections must be True or False"):
        _two().render(VIEW, intersections="no")
    with pytest.raises(TypeError, match="intersections must be True or False"):
        lg.Scene().add(lg.Sphere(1), intersections=1)


def test_a_surface_added_twice_does_not_meet_itself():
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 6))
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 6))
    assert not [s for s in scene.render(VIEW).strokes if s.family == "intersection"]


def test_surfaces_apart_draw_no_intersection():
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 6))
    scene.add(lg.Sphere(1), lg.ParameterLines(3, 6), transform=lg.translate(2.2, 0, 0))
    assert not [s for s in scene.render(VIEW).strokes if s.family == "intersection"]


def test_two_user_surfaces_meet_by_marching():
    # no implicit equation on either: marching on both parameter planes
    cyl = lg.ParametricSurface(
        lambda u, v: np.stack(np.broadcast_arrays(np.cos(u), np.sin(u), v), -1),
        (0, 2 * np.pi),
        (-1.5, 1.5),
        periodic=(True, False),
    )
    plane = lg.ParametricSurface(
        lambda u, v: np.stack(np.broadcast_arrays(u, v, 0.3 * u), -1), (-2, 2), (-2, 2)
    )
    scene = lg.Scene()
    scene.add(cyl, lg.ParameterLines(3, 3))
    scene.add(plane, lg.ParameterLines(3, 3))
    dr = scene.render(lg.ParallelProjector.from_angles(30, 25), hidden_lines=True)
    cut = [s for s in dr.strokes if s.family == "intersection"]
    assert cut
    x = np.concatenate([s.xyz for s in cut])
    assert np.max(np.abs(np.hypot(x[:, 0], x[:, 1]) - 1)) < 1e-9
    assert np.max(np.abs(x[:, 2] - 0.3 * x[:, 0])) < 1e-9
    # the whole ellipse x^2 + y^2 = 1, z = 0.3 x is found: its angles leave no gap
    ang = np.sort(np.arctan2(x[:, 1], x[:, 0]))
    assert np.diff(np.concatenate([ang, [ang[0] + 2 * np.pi]])).max() < 0.3


SCENE = """
[projector]
kind = "central"
eye = [9, -7, 6]

{render}

[[object]]
surface = "ellipsoid"
params = {{ a = 3, b = 2, c = 1.5 }}
{flag}

[[object]]
surface = "sphere"
params = {{ r = 1 }}
transform = [{{ translate = [2.5, 1, 1] }}]
"""


@pytest.mark.parametrize(
    ("render", "flag", "drawn"),
    [
        ("", "", True),
        ("[render]\nintersections = false", "", False),
        ("", "intersections = false", False),
    ],
)
def test_scene_files_say_intersections(tmp_path, render, flag, drawn):
    from lgraph.scenefile import load_scene_file

    path = tmp_path / "two.toml"
    path.write_text(SCENE.format(render=render, flag=flag), encoding="utf-8")
    scene, projector, options = load_scene_file(path)
    d = scene.render(projector, **options.get("render", {}))
    assert any(s.family == "intersection" for s in d.strokes) == drawn


def test_a_scene_file_flag_must_be_a_boolean(tmp_path):
    from lgraph.scenefile import SceneFileError, load_scene_file

    path = tmp_path / "two.toml"
    path.write_text(SCENE.format(render="[render]\nintersections = 1", flag=""), encoding="utf-8")
    with pytest.raises(SceneFileError, match=r"two.toml:7: render.intersections: expected true"):
        load_scene_file(path)
