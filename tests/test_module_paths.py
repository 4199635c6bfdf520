"""Moving code between modules keeps every import path that worked (issue 12).

``lgraph``'s lazy table names the module of each public name; the modules
split for issue 12 keep the paths that plugins, backends and tests import
from, and stay under about 500 lines each.
"""

from __future__ import annotations

import importlib
import io
from pathlib import Path

import pytest

import lgraph

PACKAGE = Path(lgraph.__file__).resolve().parent


@pytest.mark.parametrize("name", sorted(lgraph._EXPORTS))
def test_every_lazy_export_resolves_in_its_module(name: str) -> None:
    module = importlib.import_module(lgraph._EXPORTS[name], "lgraph")
    assert getattr(lgraph, name) is getattr(module, name)


@pytest.mark.parametrize("name", ["Label", "Point", "Arrow", "Parallelogram", "Page"])
def test_moved_classes_are_imported_from_their_new_home(name: str) -> None:
    """The lazy table names the module that defines them (importing it costs
    only that module)."""
    assert getattr(lgraph, name).__module__ == "lgraph" + lgraph._EXPORTS[name]


#: (old module, name) -> the public object it must still be
OLD_PATHS = [
    ("lgraph.drawing", "Drawing"),
    ("lgraph.drawing", "Stroke"),
    ("lgraph.drawing", "PlacedLabel"),
    ("lgraph.drawing", "Page"),
    ("lgraph.drawing", "Style"),
    ("lgraph.drawing", "HIDDEN_STYLE"),
    ("lgraph.objects", "Label"),
    ("lgraph.objects", "Point"),
    ("lgraph.objects", "Arrow"),
    ("lgraph.objects", "Parallelogram"),
    # issue #30: the modules that became packages keep their public names
    ("lgraph.scene", "Scene"),
    ("lgraph.scene", "Node"),
    ("lgraph.scene", "Group"),
    ("lgraph.animation", "animate"),
    ("lgraph.notebook", "interact"),
    ("lgraph.projectors", "orbit"),
    ("lgraph.surfaces", "Surface"),
    ("lgraph.surfaces.quadrics", "Ellipsoid"),
    ("lgraph.surfaces.quadrics", "HyperboloidOneSheet"),
    ("lgraph.surfaces.hyperboloids", "EllipticCone"),
    ("lgraph.surfaces.classical", "MonkeySaddle"),
    ("lgraph.surfaces.classical", "Torus"),
    ("lgraph.surfaces.quartic", "Torus"),
    ("lgraph.surfaces.onesided", "KleinBottle"),
    ("lgraph.surfaces.revolution", "SurfaceOfRevolution"),
    ("lgraph.surfaces.profiles", "Profile"),
    ("lgraph.surfaces.ruled", "RuledSurface"),
    ("lgraph.surfaces.parametric", "ParametricSurface"),
    ("lgraph.surfaces.implicit", "ImplicitSurface"),
    ("lgraph.surfaces.algebraic", "AlgebraicSurface"),
    ("lgraph.scenefile", "load_scene_file"),
    ("lgraph.scenefile", "SceneFileError"),
]


@pytest.mark.parametrize(("module", "name"), OLD_PATHS)
def test_old_import_paths_give_the_public_objects(module: str, name: str) -> None:
    assert getattr(importlib.import_module(module), name) is getattr(lgraph, name)


def test_every_old_module_path_is_its_new_module() -> None:
    """Issue #30 moved modules into folders; each old path imports the new module
    itself (so ``isinstance``, monkeypatching and plugins' imports agree)."""
    from lgraph._moved import MOVED

    assert len(MOVED) > 50
    for old, new in MOVED.items():
        assert importlib.import_module(old) is importlib.import_module(new), old
        assert not (PACKAGE.parent / (old.replace(".", "/") + ".py")).exists(), old


def test_an_old_path_leaves_the_new_module_its_own_spec() -> None:
    """Importing a module by its old path keeps the module's ``__spec__`` (its
    relative imports inside functions would otherwise warn, and fail where
    warnings are errors: ``__package__ != __spec__.parent``)."""
    import warnings

    for old, new in MOVED_SAMPLE:
        module = importlib.import_module(old)
        assert module.__spec__.name == new and module.__spec__.parent == module.__package__
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        import lgraph as lg

        drawing = lg.Drawing(strokes=())
        assert drawing.save(io.BytesIO(), format="svg").getvalue().startswith(b"<?xml")


MOVED_SAMPLE = [
    ("lgraph.drawing", "lgraph.output.drawing"),
    ("lgraph.backends", "lgraph.output.backends"),
]


def test_every_public_surface_class_is_in_lgraph_surfaces() -> None:
    """``from lgraph.surfaces import X`` for every surface class of ``lg``
    (the figure objects Arrow and Parallelogram live in ``lgraph.scene``), the
    same object; ``__all__`` names them all."""
    import lgraph as lg
    import lgraph.surfaces as surfaces

    objects = {"Arrow", "Parallelogram"}
    names = [
        n
        for n in dir(lg)
        if isinstance(getattr(lg, n, None), type)
        and issubclass(getattr(lg, n), surfaces.Surface)
        and n not in objects
    ]
    assert len(names) > 30
    for name in names:
        assert getattr(surfaces, name) is getattr(lg, name), name
    assert set(names) <= set(surfaces.__all__)
    with pytest.raises(AttributeError, match="no attribute 'Nonesuch'"):
        surfaces.Nonesuch  # noqa: B018


def test_the_paths_plugins_use() -> None:
    """``lgraph.surfaces.Surface``, ``lgraph.plugins``, ``lgraph.backends`` and the
    output modules the example plugins imported before issue #30."""
    old = {m: importlib.import_module(f"lgraph.{m}") for m in ["backends", "drawing", "units"]}
    from lgraph.plugins import installed_plugins
    from lgraph.surfaces import Surface

    assert Surface is lgraph.Surface and callable(installed_plugins)
    write_pdf = importlib.import_module("lgraph.backends.pdf").write_pdf
    assert old["backends"].get_backend(".pdf") is write_pdf
    assert ".svg" in old["backends"].backend_suffixes()
    assert callable(old["drawing"].dash_polyline) and old["units"].length_pt("1in") == 72
    assert lgraph.backends is importlib.import_module("lgraph.output.backends")


def test_private_paths_that_plugins_backends_and_tests_use() -> None:
    from lgraph.output.dashes import MAX_DASHES as max_dashes
    from lgraph.output.dashes import dash_polyline as dashes
    from lgraph.output.drawing import MAX_DASHES, _page, dash_polyline
    from lgraph.output.page import _page as page_converter
    from lgraph.scenefile import _OBJECT, _STYLE, _TOP, _Locator, parse_scene
    from lgraph.surfaces.quadrics._unbounded import _PatchQuadric as base

    assert dash_polyline is dashes and MAX_DASHES == max_dashes and _page is page_converter
    assert issubclass(lgraph.EllipticCone, base) and issubclass(lgraph.HyperbolicCylinder, base)
    assert "object" in _TOP and "surface" in _OBJECT and "dash" in _STYLE
    assert callable(parse_scene) and callable(_Locator)


SPLIT = [
    "output/drawing.py",
    "output/page.py",
    "output/dashes.py",
    "scene/objects/__init__.py",
    "scene/objects/marks.py",
    "scene/objects/shapes.py",
    "surfaces/quadrics/_unbounded.py",
    "surfaces/quadrics/hyperboloids.py",
    "surfaces/quadrics/paraboloids.py",
    "surfaces/quadrics/cylinders.py",
    "scenefile/__init__.py",
    "scenefile/_schema.py",
    "scenefile/_members.py",
    "scenefile/_output.py",
    "scenefile/_values.py",
]


@pytest.mark.parametrize("path", SPLIT)
def test_split_modules_are_short_and_say_what_they_are_for(path: str) -> None:
    text = (PACKAGE / path).read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 500
    assert text.lstrip("r").startswith('"""'), "a module docstring first"
