"""Algebraic surfaces in scene files: ``surface = "algebraic"`` with a
polynomial F, the built-ins by name, hostile polynomials refused naming the key."""

from __future__ import annotations

import time

import numpy as np
import pytest

import lgraph as lg
from lgraph.scenefile import SceneFileError, load_scene_file

HEAD = """\
[projector]
kind = "parallel"
azimuth = 30
elevation = 25

[constants]
a = 1.5
"""


def _load(tmp_path, body):
    path = tmp_path / "s.toml"
    path.write_text(HEAD + body)
    scene, _projector, _options = load_scene_file(path)
    return scene


def test_algebraic_object_is_the_polynomial(tmp_path):
    scene = _load(
        tmp_path,
        """
[[object]]
surface = "algebraic"
F = "x^2 + y^2 - z^2 - a"
radius = 2
families = ["level_lines"]
""",
    )
    (surface,) = [n.surface for n in scene.nodes]
    assert isinstance(surface, lg.AlgebraicSurface)
    assert surface.polynomial_terms() == {
        (0, 0, 0): -1.5, (0, 0, 2): -1.0, (0, 2, 0): 1.0, (2, 0, 0): 1.0
    }  # fmt: skip
    p = np.array([[1.5, 0.5, np.sqrt(1.5 + 0.25 - 1.5)]])
    assert abs(surface.implicit(np.array([[np.sqrt(1.5), 0, 0]]))[0]) < 1e-15
    assert surface.implicit(p).shape == (1,)


def test_builtins_by_name_with_singularities(tmp_path):
    scene = _load(
        tmp_path,
        """
[[object]]
surface = "kummer_surface"
params = { mu = 1.3 }
families = ["level_lines", "singularities"]
""",
    )
    nodes = scene.nodes
    assert isinstance(nodes[0].surface, lg.KummerSurface)
    assert nodes[0].surface.mu == 1.3
    assert any(isinstance(f, lg.Singularities) for f in nodes[0].families)


@pytest.mark.parametrize(
    ("body", "key", "message"),
    [
        ('F = "sin(x)"\nradius = 1', "object[0].F", "must be a polynomial"),
        ('F = "(x + y + z + 1)^100000"\nradius = 1', "object[0].F", "degree at most 12"),
        ('F = "x^2 - 1"\nradius = 1\ngrid = 1000', "object[0].grid", "grid must be"),
        ('F = "x^2 - 1"\nradius = -1', "object[0].radius", "positive"),
        ('F = "x^2 - 1"', "object[0]", "needs radius"),
        ('F = "x^2 - 1"\nbounds = [[0, 1], [0, 1]]', "object[0].bounds", "expected"),
        ('F = "__import__(1)"\nradius = 1', "object[0].F", "function|name|allowed"),
    ],
)
def test_hostile_or_wrong_polynomials_name_the_key(tmp_path, body, key, message):
    start = time.perf_counter()
    with pytest.raises(SceneFileError, match=message) as info:
        _load(tmp_path, f'\n[[object]]\nsurface = "algebraic"\n{body}\n')
    assert key in str(info.value)
    assert time.perf_counter() - start < 30  # refused before any work (a loose bound)


def test_largest_polynomial_is_cheap_to_expand(tmp_path):
    # degree 12 in all three variables: 455 terms, the most allowed
    scene = _load(
        tmp_path,
        '\n[[object]]\nsurface = "algebraic"\nF = "(x + y + z + 1)^12 - 2"\nradius = 1\n'
        "families = []\n",
    )
    nodes = scene.nodes
    assert len(nodes[0].surface.polynomial_terms()) == 455


def test_implicit_surface_by_name_points_to_algebraic(tmp_path):
    with pytest.raises(SceneFileError, match='surface = "algebraic"'):
        _load(tmp_path, '\n[[object]]\nsurface = "implicit_surface"\n')


def test_central_eye_inside_the_surface_refused(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(
        '[projector]\nkind = "central"\neye = [0.0, 0.0, 0.0]\ntarget = [1.0, 0.0, 0.0]\n'
        '\n[[object]]\nsurface = "algebraic"\nF = "x^2 + y^2 + z^2 - 1"\nradius = 2\n'
    )
    with pytest.raises(SceneFileError, match="behind the eye"):
        load_scene_file(path)


def test_animation_of_an_algebraic_surface(tmp_path):
    scene = lg.Scene()
    scene.add(lg.CayleyCubic(), lg.LevelLines(3), lg.Singularities())
    out = lg.animate(scene, lg.orbit(elevation=30, frames=2), tmp_path / "c.gif", progress=False)
    assert out.exists() and out.stat().st_size > 0
