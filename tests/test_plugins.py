"""Plugin discovery: built-in registries, simulated entry points (good, broken,
duplicate plugins) and, when installed, the real example plugins."""

from __future__ import annotations

import importlib.metadata as md
import subprocess
import sys
import textwrap
import warnings
from types import SimpleNamespace

import attrs
import numpy as np
import pytest

import lgraph as lg
from lgraph import plugins
from lgraph.families import FAMILIES
from lgraph.output.backends import get_backend
from lgraph.plugins import PluginError, PluginWarning

GOOD = '''\
import attrs
import lgraph as lg

@attrs.frozen
class Ball(lg.Sphere):
    """A sphere under another name."""

class Rings(lg.ParameterLines):
    pass

def write_fake(drawing, path, **options):
    with open(path, "w") as f:
        f.write(f"fake {len(drawing.strokes)} {sorted(options)}")
'''

BROKEN = """\
import lgraph_nonexistent_dependency_for_tests  # noqa: F401  (fails here)

Thing = None
"""


class FakeEntryPoint:
    """An importlib.metadata.EntryPoint with the distribution it came from."""

    def __init__(self, name: str, value: str, group: str, dist: str, version: str = "1.0"):
        self._ep = md.EntryPoint(name, value, group)
        self.name, self.value, self.group = name, value, group
        self.dist = SimpleNamespace(name=dist, version=version)

    def load(self):
        return self._ep.load()


@pytest.fixture
def fake_plugins(tmp_path, monkeypatch):
    """Install plugin modules on sys.path and serve their entry points."""
    (tmp_path / "lgraph_test_good.py").write_text(GOOD)
    (tmp_path / "lgraph_test_broken.py").write_text(BROKEN)
    monkeypatch.syspath_prepend(str(tmp_path))
    eps: list[FakeEntryPoint] = []

    def entry_points(**kw):
        return [e for e in eps if e.group == kw.get("group")]

    monkeypatch.setattr(md, "entry_points", entry_points)
    plugins._reset()
    yield eps
    plugins._reset()
    for mod in ("lgraph_test_good", "lgraph_test_broken"):
        sys.modules.pop(mod, None)


def add(eps, kind, name, value, dist="good-plugin", version="1.0"):
    eps.append(FakeEntryPoint(name, value, plugins.GROUPS[kind], dist, version))


# -- built-ins -------------------------------------------------------------------
def test_import_lgraph_scans_no_entry_points():
    code = textwrap.dedent(
        """
        import importlib.metadata as md
        calls = []
        real = md.entry_points
        md.entry_points = lambda *a, **k: calls.append(k) or real(*a, **k)
        import lgraph, lgraph.plugins, lgraph.scenefile
        s = lgraph.Scene(); s.add(lgraph.Sphere(1))
        s.render(lgraph.ParallelProjector(direction=(1, 1, 1)))
        print(len(calls))
        """
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "0"


def test_every_exported_surface_class_is_registered_by_snake_case_name():
    exported = {
        getattr(lg, n)
        for n in lg.__all__
        if isinstance(getattr(lg, n), type)
        and issubclass(getattr(lg, n), lg.Surface)
        and attrs.has(getattr(lg, n))
    }
    assert lg.Ellipsoid in exported and lg.Sphere in exported
    for cls in exported:
        assert plugins.get_surface(plugins.snake_case(cls.__name__)) is cls
    assert plugins.get_surface("ellipsoid") is lg.Ellipsoid
    assert "surface" not in plugins.surface_names()  # abstract bases are not listed
    with pytest.raises(KeyError, match="unknown surface 'nope'; known: .*ellipsoid"):
        plugins.get_surface("nope")


def test_builtin_families_and_runtime_registration():
    for name, cls in FAMILIES.items():
        assert plugins.get_family(name) is cls
    assert plugins.get_family("lines_of_curvature") is lg.LinesOfCurvature
    with pytest.raises(KeyError, match="unknown line family 'nope'"):
        plugins.get_family("nope")

    @attrs.frozen
    class Ball2(lg.Sphere):
        pass

    try:
        plugins.register_surface("ball2", Ball2)
        assert plugins.get_surface("ball2") is Ball2
        with pytest.raises(ValueError, match="already registered"):
            plugins.register_surface("sphere", Ball2)
    finally:
        plugins._registered_surfaces.pop("ball2", None)


# -- simulated entry points -----------------------------------------------------------
def test_good_plugins_load_lazily_and_work(fake_plugins, tmp_path):
    add(fake_plugins, "surface", "ball", "lgraph_test_good:Ball")
    add(fake_plugins, "family", "rings", "lgraph_test_good:Rings")
    add(fake_plugins, "backend", "fake", "lgraph_test_good:write_fake")
    assert "ball" in plugins.surface_names() and "rings" in plugins.family_names()
    assert ".fake" in lg.backends.backend_suffixes()
    assert "lgraph_test_good" not in sys.modules  # listed, not imported
    Ball = plugins.get_surface("ball")
    Rings = plugins.get_family("rings")
    assert FAMILIES["rings"] is Rings
    scene = lg.Scene()
    scene.add(Ball(r=1), Rings(3, 4))
    d = scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    path = d.save(tmp_path / "x.fake", opt=1)
    assert path.read_text() == f"fake {len(d.strokes)} ['opt']"
    assert get_backend(".fake") is sys.modules["lgraph_test_good"].write_fake


def test_broken_plugin_warns_once_raises_its_traceback_and_breaks_nothing(fake_plugins, tmp_path):
    add(fake_plugins, "surface", "broken", "lgraph_test_broken:Thing", dist="bad-plugin")
    add(fake_plugins, "family", "broken_family", "lgraph_test_broken:Thing", dist="bad-plugin")
    add(fake_plugins, "backend", "brk", "lgraph_test_broken:Thing", dist="bad-plugin")
    add(fake_plugins, "surface", "ball", "lgraph_test_good:Ball")
    with pytest.warns(PluginWarning, match="surface plugin 'broken' from bad-plugin 1.0") as rec:
        stand_in = plugins.get_surface("broken")
    assert len(rec) == 1 and "ModuleNotFoundError" in str(rec[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a second lookup does not warn again
        assert plugins.get_surface("broken") is stand_in
        with pytest.raises(PluginError) as info:
            stand_in(1, 2, 3)
    err = info.value
    assert isinstance(err.__cause__, ModuleNotFoundError)  # chained original
    assert "lgraph_test_broken.py" in str(err) and "lgraph_nonexistent_dependency" in str(err)
    assert "Traceback (most recent call last)" in str(err)
    # the other plugin and lgraph itself still work
    assert issubclass(plugins.get_surface("ball"), lg.Sphere)
    with pytest.warns(PluginWarning, match="family plugin 'broken_family'"):
        fam = plugins.get_family("broken_family")
    with pytest.raises(PluginError, match="original error"):
        fam(3, 4)
    d = lg.Drawing(strokes=())
    with pytest.warns(PluginWarning, match="backend plugin 'brk'"):
        with pytest.raises(PluginError, match="lgraph_nonexistent_dependency"):
            d.save(tmp_path / "x.brk")
    assert not list(tmp_path.glob("x.brk*"))  # nothing half-written
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(PluginError):
            d.save(tmp_path / "x.brk")
    assert d.save(tmp_path / "x.svg").exists()


def test_duplicate_names_are_reported_naming_both_distributions(fake_plugins):
    add(fake_plugins, "surface", "ball", "lgraph_test_good:Ball", dist="first-dist", version="2.0")
    add(fake_plugins, "surface", "ball", "lgraph_test_good:Rings", dist="second-dist")
    add(fake_plugins, "surface", "ellipsoid", "lgraph_test_good:Ball", dist="third-dist")
    with pytest.warns(PluginWarning) as rec:
        names = plugins.surface_names()
    messages = [str(w.message) for w in rec]
    dup = [m for m in messages if "two plugins define the surface 'ball'" in m]
    assert len(dup) == 1 and "first-dist 2.0" in dup[0] and "second-dist 1.0" in dup[0]
    assert "using the one from first-dist" in dup[0]
    clash = [m for m in messages if "'ellipsoid'" in m]
    assert len(clash) == 1 and "third-dist" in clash[0] and "built-in is kept" in clash[0]
    assert names.count("ball") == 1
    assert plugins.get_surface("ball").__name__ == "Ball"  # the first one wins
    assert plugins.get_surface("ellipsoid") is lg.Ellipsoid


def test_describe_plugins_lists_name_kind_version_status(fake_plugins):
    add(fake_plugins, "surface", "ball", "lgraph_test_good:Ball", version="0.3")
    add(fake_plugins, "backend", "brk", "lgraph_test_broken:Thing", dist="bad-plugin")
    add(fake_plugins, "surface", "ball", "lgraph_test_good:Ball", dist="other-dist")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PluginWarning)
        text = plugins.describe_plugins()
    lines = text.splitlines()
    assert lines[0].split() == ["NAME", "KIND", "DISTRIBUTION", "VERSION", "STATUS"]
    rows = {tuple(line.split()[:4]): line for line in lines[1:-1]}
    assert rows[("ball", "surface", "good-plugin", "0.3")].rstrip().endswith("ok")
    assert "failed: ModuleNotFoundError" in rows[("brk", "backend", "bad-plugin", "1.0")]
    assert "ignored: name taken by good-plugin" in rows[("ball", "surface", "other-dist", "1.0")]
    assert lines[-1].startswith("built-in: ")
    n_surfaces = int(lines[-1].split()[1])
    assert n_surfaces == len(plugins._builtin_surfaces()) >= 2


def test_no_plugins_installed(fake_plugins):
    text = plugins.describe_plugins()
    assert text.splitlines()[0].startswith("no plugins installed")
    assert "lgraph.surfaces" in text and text.splitlines()[-1].startswith("built-in: ")


def test_broken_metadata_does_not_break_lookup(monkeypatch):
    def boom(**kw):
        raise RuntimeError("corrupt metadata")

    monkeypatch.setattr(md, "entry_points", boom)
    plugins._reset()
    try:
        with pytest.warns(PluginWarning, match="corrupt metadata"):
            assert "sphere" in plugins.surface_names()
    finally:
        plugins._reset()


# -- the real example plugins (installed by CI: .ci/plugins.sh) ------------------------
def _installed(name: str) -> bool:
    try:
        md.distribution(name)
    except md.PackageNotFoundError:
        return False
    return True


needs_cyclide = pytest.mark.skipif(
    not _installed("lgraph-cyclide"),
    reason="example plugin lgraph-cyclide not installed (pip install -e plugins/lgraph-cyclide)",
)
needs_hpgl = pytest.mark.skipif(
    not _installed("lgraph-hpgl"),
    reason="example plugin lgraph-hpgl not installed (pip install -e plugins/lgraph-hpgl)",
)


@needs_cyclide
def test_installed_cyclide_plugin_in_a_scene_file(tmp_path):
    from lgraph.scenefile import load_scene_file

    plugins._reset()
    path = tmp_path / "cyclide.toml"
    path.write_text(
        textwrap.dedent(
            """\
            [projector]
            kind = "parallel"
            azimuth = 30
            elevation = 35
            [[object]]
            surface = "cyclide"
            params = { a = 5, c = 2, mu = 3 }
            families = [{ name = "lines_of_curvature", n1 = 6, n2 = 8 },
                        { name = "diagonal_lines", n = 4 }]
            """
        )
    )
    scene, projector, _ = load_scene_file(path)
    d = scene.render(projector)
    assert {s.family for s in d.strokes} == {"contour", "curvature", "diagonal"}
    cy = plugins.get_surface("cyclide")(5, 2, 3)
    for s in d.strokes:  # every stroke lies on the cyclide
        assert np.abs(cy.implicit(s.xyz)).max() < 1e-8 * 5**4


@needs_hpgl
def test_installed_hpgl_plugin_and_lgraph_plugins_command(tmp_path):
    plugins._reset()
    d = lg.Drawing(strokes=(lg.Stroke(xy=np.array([[0.0, 0], [1, 1]]), xyz=np.zeros((2, 3))),))
    assert d.save(tmp_path / "f.hpgl").read_text().startswith("IN;")
    r = subprocess.run(
        [sys.executable, "-m", "lgraph", "plugins"], capture_output=True, text=True, timeout=60
    )
    assert r.returncode == 0 and "Traceback" not in r.stderr
    row = [line for line in r.stdout.splitlines() if line.startswith("hpgl ")]
    assert len(row) == 1 and "backend" in row[0] and "lgraph-hpgl" in row[0]
    assert row[0].rstrip().endswith("ok")


def test_lgraph_plugins_command_runs():
    r = subprocess.run(
        [sys.executable, "-m", "lgraph", "plugins"], capture_output=True, text=True, timeout=60
    )
    assert r.returncode == 0 and "Traceback" not in r.stderr
    assert r.stdout.splitlines()[-1].startswith("built-in: ")
