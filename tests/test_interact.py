"""lg.interact: the widget's sliders re-render the view (no browser needed)."""

from __future__ import annotations

import io
import sys

import numpy as np
import pytest
from PIL import Image

import lgraph as lg
from lgraph.families import cache as family_cache


def _scene() -> lg.Scene:
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(4, 5))
    return scene


def _png(drawing: lg.Drawing, width: int) -> np.ndarray:
    pw, ph = drawing.page_size()
    buf = io.BytesIO()
    drawing.save(buf, format="png", size=(width, round(width * ph / pw)))
    return np.asarray(Image.open(io.BytesIO(buf.getvalue())))


def test_sliders_rerender_from_the_cache():
    pytest.importorskip("ipywidgets", reason="ipywidgets is not installed (lgraph[jupyter])")
    scene = _scene()
    family_cache.clear()
    view = lg.interact(scene, azimuth=10, elevation=20, width=200)
    assert [s.description for s in (view.azimuth, view.elevation)] == ["azimuth", "elevation"]
    assert view.distance is None
    first = view.image.value
    want = scene.render(lg.ParallelProjector.from_angles(10, 20))
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(first))), _png(want, 200))
    view.azimuth.value = 100  # what the browser does when the slider moves
    second = view.image.value
    assert second != first
    want = scene.render(lg.ParallelProjector.from_angles(100, 20))
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(second))), _png(want, 200))
    view.elevation.value = -40
    np.testing.assert_allclose(view.projector().frame[2][2], np.sin(np.radians(-40)))
    info = family_cache.info()
    assert info["misses"] == 1 and info["hits"] >= 2  # lines of curvature computed once
    assert "application/vnd.jupyter.widget-view+json" in view._repr_mimebundle_()


def test_distance_slider_gives_central_projection():
    pytest.importorskip("ipywidgets", reason="ipywidgets is not installed (lgraph[jupyter])")
    view = lg.interact(_scene(), distance=16, width=120)
    p = view.projector()
    assert isinstance(p, lg.CentralProjector) and p.distance == pytest.approx(16)
    view.distance.value = 30
    assert view.projector().distance == pytest.approx(30)
    assert view.drawing.strokes
    with pytest.raises(ValueError, match="distance must be a positive"):
        lg.interact(_scene(), distance=0)


def test_without_ipywidgets_is_a_clear_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "ipywidgets", None)
    with pytest.raises(ImportError, match="lgraph\\[jupyter\\]"):
        lg.interact(_scene())


def test_import_lgraph_imports_no_optional_dependency():
    import subprocess

    code = (
        "import sys, lgraph; bad = [m for m in ('matplotlib', 'dask', 'distributed', "
        "'ipywidgets', 'IPython', 'cloudpickle') if m in sys.modules]; print(bad)"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "[]"
