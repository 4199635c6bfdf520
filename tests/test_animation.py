"""lg.orbit and lg.animate: views, formats, frame sizes, atomic writes, executors."""

from __future__ import annotations

import concurrent.futures as cf
import io
import math
import re
import sys

import numpy as np
import pytest
from PIL import Image

import lgraph as lg
from lgraph.animation import frames as animation
from lgraph.animation.progress import Progress
from lgraph.cli import main as cli_main
from lgraph.render import render_views


@pytest.fixture(scope="module")
def scene() -> lg.Scene:
    s = lg.Scene()
    s.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(5, 6))
    return s


VIEWS = lg.orbit(elevation=25, frames=5)
WIDTH = 96


def _frames(path) -> list[np.ndarray]:
    im = Image.open(path)
    out = []
    for k in range(getattr(im, "n_frames", 1)):
        im.seek(k)
        out.append(np.asarray(im.convert("RGB"), dtype=int))
    return out


def _reference(scene, views, width=WIDTH, hidden_lines=False, **options) -> list[np.ndarray]:
    """Each frame rendered on its own: the scene, the common window, write_png
    (the curves sampled to a quarter pixel, animate's default for raster frames)."""
    window = animation.frame_window(scene, views)
    m = 0.03 * width
    h = max(16, round((width - 2 * m) * (window[3] - window[1]) / (window[2] - window[0]) + 2 * m))
    page = lg.Page(width=float(width), height=float(h), margin=m)
    if "tolerance" not in options:
        options["chord"] = animation.pixel_chord(page, window)
    out = []
    for v in views:
        (d,) = render_views(scene, [v], hidden_lines=hidden_lines, **options)
        d = lg.Drawing(d.strokes, page=page, window=window, labels=d.labels)
        buf = io.BytesIO()
        d.save(buf, format="png", size=(width, h))
        out.append(np.asarray(Image.open(io.BytesIO(buf.getvalue())).convert("RGB"), dtype=int))
    return out


# -- orbit ----------------------------------------------------------------------------
def test_orbit_parallel_views_turn_about_z_at_constant_elevation():
    views = lg.orbit(elevation=30, frames=8, azimuth=10)
    assert len(views) == 8
    d = np.array([v.frame[2] for v in views])
    np.testing.assert_allclose(d[:, 2], math.sin(math.radians(30)), atol=1e-12)
    az = np.degrees(np.arctan2(d[:, 1], d[:, 0]))
    np.testing.assert_allclose(np.diff(np.unwrap(np.radians(az))), math.radians(45), atol=1e-12)
    assert az[0] == pytest.approx(10)


def test_orbit_central_views_keep_their_distance():
    views = lg.orbit(elevation=-20, frames=6, distance=12, target=(1, 2, 3))
    for v in views:
        assert isinstance(v, lg.CentralProjector)
        assert np.linalg.norm(v.eye - (1, 2, 3)) == pytest.approx(12)
        assert (v.eye[2] - 3) / 12 == pytest.approx(-math.sin(math.radians(20)))
    with pytest.raises(ValueError, match="distance must be a positive"):
        lg.orbit(frames=2, distance=-1)
    with pytest.raises(ValueError, match="turn must be a finite"):
        lg.orbit(turn=float("nan"))


# -- formats ----------------------------------------------------------------------------
def test_gif_has_every_frame_at_the_requested_size(scene, tmp_path):
    path = lg.animate(scene, VIEWS, tmp_path / "t.gif", width=WIDTH, fps=10, progress=False)
    im = Image.open(path)
    assert im.n_frames == len(VIEWS)
    assert im.info["duration"] == 100 and im.info["loop"] == 0
    got, want = _frames(path), _reference(scene, VIEWS)
    assert got[0].shape == want[0].shape and got[0].shape[1] == WIDTH
    for g, w in zip(got, want):
        # a palette of up to 256 colours: small differences in anti-aliased grey
        assert np.abs(g - w).mean() < 1.0 and np.abs(g - w).max() < 40
    assert not np.array_equal(got[0], got[1])  # the frames differ: it turns
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.gif"]


def test_grey_gif_frames_are_exact_and_colour_ones_close(scene, tmp_path):
    # black on white: frames drawn in one grey channel, the GIF keeps every level
    got, want = _frames(lg.animate(scene, VIEWS, tmp_path / "g.gif", width=WIDTH,
                                   progress=False)), _reference(scene, VIEWS)  # fmt: skip
    assert all(np.array_equal(g, w) for g, w in zip(got, want))
    # red hidden lines in some frames only (a graph seen from above hides
    # nothing): colour and grey frames mixed
    scene = lg.Scene()
    scene.add(lg.HyperbolicParaboloid(1, 1), lg.ParameterLines(5, 5))
    red = lg.Style(color="red", dash=(2, 1.5))
    views = [lg.ParallelProjector(direction=(0, 0, 1)), *lg.orbit(elevation=10, frames=3)[:2]]
    opts = {"hidden_style": red}
    path = lg.animate(scene, views, tmp_path / "c.gif", width=WIDTH, hidden_lines=True,
                      render_options=opts, progress=False)  # fmt: skip
    got = _frames(path)
    for g, w in zip(got, _reference(scene, views, hidden_lines=True, hidden_style=red)):
        assert np.abs(g - w).mean() < 1.0 and np.abs(g - w).max() < 40
    reds = [((f[..., 0] - f[..., 2]) > 60).sum() for f in got]
    assert reds[0] == 0 and reds[1] > 0 and reds[2] > 0


@pytest.mark.parametrize("name", ["t.png", "t.apng", "t.webp"])
def test_apng_and_webp_are_lossless(scene, tmp_path, name):
    path = lg.animate(scene, VIEWS, tmp_path / name, width=WIDTH, fps=8, progress=False)
    got, want = _frames(path), _reference(scene, VIEWS)
    assert len(got) == len(VIEWS)
    for g, w in zip(got, want):
        assert np.array_equal(g, w)
    if name != "t.webp":
        assert Image.open(path).info["duration"] == pytest.approx(125)


def test_pdf_has_one_page_per_frame(scene, tmp_path):
    path = lg.animate(scene, VIEWS, tmp_path / "t.pdf", width=200, progress=False)
    data = path.read_bytes()
    assert data.startswith(b"%PDF-")
    assert len(re.findall(rb"/Type /Page\b", data)) == len(VIEWS)
    boxes = set(re.findall(rb"/MediaBox \[([^\]]*)\]", data))
    assert len(boxes) == 1  # every page the same size
    w = float(boxes.pop().split()[2])
    assert w == pytest.approx(200)


@pytest.mark.parametrize("fmt", ["png", "svg", "pdf"])
def test_folder_of_numbered_frames(scene, tmp_path, fmt):
    out = lg.animate(scene, VIEWS, tmp_path / "frames", width=WIDTH, frame_format=fmt,
                     progress=False)  # fmt: skip
    names = sorted(p.name for p in out.iterdir())
    assert names == [f"frame_{k:04d}.{fmt}" for k in range(len(VIEWS))]
    if fmt == "png":
        want = _reference(scene, VIEWS)
        for k, p in enumerate(sorted(out.iterdir())):
            assert np.array_equal(np.asarray(Image.open(p).convert("RGB"), dtype=int), want[k])


def test_the_figure_keeps_its_scale_and_stays_inside(scene, tmp_path):
    views = lg.orbit(elevation=10, frames=12, distance=14)
    frames = _frames(lg.animate(scene, views, tmp_path / "t.png", width=120, progress=False))
    heights = []
    for f in frames:
        ink = np.argwhere(f.min(axis=2) < 160)
        assert len(ink)
        (r0, c0), (r1, c1) = ink.min(axis=0), ink.max(axis=0)
        assert r0 > 0 and c0 > 0 and r1 < f.shape[0] - 1 and c1 < f.shape[1] - 1
        heights.append(r1 - r0)
    # the ellipsoid's height in the picture hardly changes as it turns
    assert max(heights) - min(heights) <= 0.12 * max(heights)


def test_hidden_lines(scene, tmp_path):
    a = _frames(lg.animate(scene, VIEWS[:2], tmp_path / "a.png", width=WIDTH, progress=False))
    b = _frames(lg.animate(scene, VIEWS[:2], tmp_path / "b.png", width=WIDTH, progress=False,
                           hidden_lines=True))  # fmt: skip
    assert (b[0].min(axis=2) < 250).sum() > (a[0].min(axis=2) < 250).sum()
    assert np.array_equal(b[0], _reference(scene, VIEWS[:2], hidden_lines=True)[0])


def _max_sagitta(xy: np.ndarray, r: float) -> float:
    """Largest gap between the chords through ``xy`` (points on a circle of
    radius ``r`` about the origin) and the circle: r (1 - cos(angle / 2))."""
    a = np.unwrap(np.arctan2(xy[:, 1], xy[:, 0]))
    return float((r * (1 - np.cos(np.abs(np.diff(a)) / 2))).max())


@pytest.mark.parametrize("width", [120, 480])
def test_pixel_sampling_keeps_chords_within_a_quarter_pixel(tmp_path, monkeypatch, width):
    # the unit circle seen from above (three ways up): its projection is the
    # unit circle exactly, so each chord's distance from the curve is known
    scene = lg.Scene()
    scene.add(lg.Curve(lambda t: np.stack([np.cos(t), np.sin(t), 0 * t], -1), 0, 2 * np.pi))
    views = [lg.ParallelProjector(direction=(0, 0, 1), up=(np.cos(a), np.sin(a), 0))
             for a in (0.0, 0.7, 2.0)]  # fmt: skip
    seen = []
    render = lg.Scene.render

    def spy(scene, views, **kw):  # frames are rendered in batches of views
        drawings = render_views(scene, views, **kw)
        seen.extend(((kw.get("tolerance"), kw.get("chord")), d) for d in drawings)
        return drawings

    monkeypatch.setattr(animation, "render_views", spy)
    opts = {"tolerance": "pixel"}
    path = lg.animate(scene, views, tmp_path / "t.gif", width=width, progress=False,
                      workers=1, render_options=opts)  # fmt: skip
    h = Image.open(path).size[1]
    window = animation.frame_window(scene, views)
    margin = 0.03 * width
    page = lg.Page(width=float(width), height=float(h), margin=margin)
    px = min((width - 2 * margin) / (window[2] - window[0]),
             (h - 2 * margin) / (window[3] - window[1]))  # fmt: skip
    want = (None, animation.pixel_chord(page, window))
    assert [t for t, _ in seen] == [want] * 3
    assert want[1] * px == pytest.approx(0.25, rel=1e-12)  # a quarter pixel, in every view
    for view, (_, d) in zip(views, seen):
        (c,) = [s.xy for s in d.strokes]
        assert np.allclose(np.hypot(*c.T), 1.0, atol=1e-12)
        sag = _max_sagitta(c, 1.0) * px  # in output pixels
        assert sag <= animation.PIXEL_TOLERANCE
        # the default: 1e-4 of the figure's diagonal (2 sqrt 2), finer and more points
        (c0,) = [s.xy for s in render(scene, view).strokes]
        assert _max_sagitta(c0, 1.0) <= 1e-4 * 2 * math.sqrt(2) < sag / px
        assert len(c0) > len(c)
    # raster frames are sampled to the pixel by default; a number sets every frame's
    seen.clear()
    lg.animate(scene, views, tmp_path / "d.gif", width=width, progress=False, workers=1)
    assert [t for t, _ in seen] == [want] * 3
    seen.clear()
    lg.animate(scene, views, tmp_path / "n.gif", width=width, progress=False, workers=1,
               render_options={"tolerance": 1e-4})  # fmt: skip
    assert [t for t, _ in seen] == [(1e-4, None)] * 3
    # vector frames keep the render's default
    seen.clear()
    lg.animate(scene, views, tmp_path / "t.pdf", progress=False, workers=1, render_options=opts)
    assert [t for t, _ in seen] == [(None, None)] * 3
    with pytest.raises(ValueError, match='must be a number or "pixel"'):
        lg.animate(scene, views, tmp_path / "u.gif", progress=False,
                   render_options={"tolerance": "pixels"})  # fmt: skip
    assert not (tmp_path / "u.gif").exists()


# -- errors and interruptions ---------------------------------------------------------------
def test_a_failing_frame_leaves_no_file(scene, tmp_path):
    views = [*VIEWS[:2], lg.CentralProjector(eye=(0.1, 0, 0))]  # the eye inside the ellipsoid
    for name in ("t.gif", "t.png", "t.webp", "t.pdf"):
        with pytest.raises(ValueError, match="behind the eye"):
            lg.animate(scene, views, tmp_path / name, width=WIDTH, progress=False)
    assert list(tmp_path.iterdir()) == []


def test_an_interrupt_leaves_no_half_written_file(scene, tmp_path, monkeypatch):
    real = animation._Job.render
    count = []

    def render(self, views):  # a batch of 2 views a call: the 2nd call is interrupted
        count.append(1)
        if len(count) == 2:
            raise KeyboardInterrupt
        return real(self, views)

    monkeypatch.setattr(animation, "BATCH_FRAMES", 2)
    monkeypatch.setattr(animation._Job, "render", render)
    with pytest.raises(KeyboardInterrupt):
        lg.animate(scene, VIEWS, tmp_path / "t.gif", width=WIDTH, progress=False, workers=1)
    assert list(tmp_path.iterdir()) == []
    count.clear()
    with pytest.raises(KeyboardInterrupt):
        lg.animate(scene, VIEWS, tmp_path / "f", width=WIDTH, progress=False, workers=1)
    # the complete frames stay, nothing half-written
    assert sorted(p.name for p in (tmp_path / "f").iterdir()) == [
        "frame_0000.png",
        "frame_0001.png",
    ]


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"fps": 0}, "fps must be a number in"),
        ({"width": 8}, "width must be an integer from 16"),
        ({"workers": 0}, "workers must be a positive integer"),
        ({"loop": -1}, "loop must be an integer"),
        ({"frame_format": "jpg"}, "frame_format must be one of png, svg, pdf"),
    ],
)
def test_bad_arguments_are_clear(scene, tmp_path, kwargs, message):
    with pytest.raises(ValueError, match=message):
        lg.animate(scene, VIEWS, tmp_path / "out", progress=False, **kwargs)


def test_bad_paths_scenes_views_and_executors(scene, tmp_path):
    with pytest.raises(ValueError, match="unknown suffix '.mp4'"):
        lg.animate(scene, VIEWS, tmp_path / "t.mp4", progress=False)
    with pytest.raises(FileNotFoundError, match="does not exist"):
        lg.animate(scene, VIEWS, tmp_path / "no" / "t.gif", progress=False)
    with pytest.raises(ValueError, match="views is empty"):
        lg.animate(scene, [], tmp_path / "t.gif", progress=False)
    with pytest.raises(TypeError, match=r"views\[1\] must be a Projector"):
        lg.animate(scene, [VIEWS[0], "side"], tmp_path / "t.gif", progress=False)
    with pytest.raises(TypeError, match="scene must be a Scene"):
        lg.animate(lg.Sphere(1), VIEWS, tmp_path / "t.gif", progress=False)
    with pytest.raises(TypeError, match="concurrent.futures.Executor"):
        lg.animate(scene, VIEWS, tmp_path / "t.gif", progress=False, executor=4)
    assert list(tmp_path.iterdir()) == []


def test_progress_bar_only_on_a_terminal():
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    tty, pipe = Tty(), io.StringIO()
    for stream in (tty, pipe):
        bar = Progress(3, True, stream)
        for _ in range(3):
            bar.update()
        bar.close()
    assert "3/3 frames" in tty.getvalue() and "\r" in tty.getvalue()
    assert pipe.getvalue() == ""
    quiet = Tty()
    bar = Progress(3, False, quiet)
    bar.update()
    assert quiet.getvalue() == ""


# -- executors --------------------------------------------------------------------------
def test_executors_give_the_frames_of_a_serial_run(scene, tmp_path, monkeypatch):
    monkeypatch.setattr(animation, "BATCH_FRAMES", 2)  # 3 batches of views to spread
    views = lg.orbit(elevation=25, frames=6, distance=15)
    serial = lg.animate(scene, views, tmp_path / "s.png", width=WIDTH, progress=False, workers=1)
    want = serial.read_bytes()
    with cf.ThreadPoolExecutor(2) as ex:
        p = lg.animate(scene, views, tmp_path / "t.png", width=WIDTH, progress=False, executor=ex)
        assert p.read_bytes() == want
    with cf.ProcessPoolExecutor(2) as ex:
        p = lg.animate(scene, views, tmp_path / "p.png", width=WIDTH, progress=False, executor=ex)
        assert p.read_bytes() == want
    p = lg.animate(scene, views, tmp_path / "w.png", width=WIDTH, progress=False, workers=2)
    assert p.read_bytes() == want


def test_the_default_starts_a_pool_only_for_long_runs(scene, tmp_path, monkeypatch):
    views = lg.orbit(elevation=25, frames=animation.PARALLEL_MIN_FRAMES)
    started = []
    local_pool = animation._local_pool

    def counting(job, workers, pools):
        started.append(workers)
        return local_pool(job, workers, pools)

    monkeypatch.setattr(animation, "_local_pool", counting)
    monkeypatch.setattr(animation.os, "cpu_count", lambda: 2)
    monkeypatch.setattr(animation, "BATCH_FRAMES", 4)  # 2 batches here, then 4 more
    serial = lg.animate(scene, views, tmp_path / "s.png", width=WIDTH, progress=False, workers=1)
    # a run whose rest is quicker here than a pool's start (any run, with this bound)
    monkeypatch.setattr(animation, "POOL_MIN_SECONDS", 1e9)
    quick = lg.animate(scene, views, tmp_path / "q.png", width=WIDTH, progress=False)
    assert started == [] and quick.read_bytes() == serial.read_bytes()
    # long runs (here: any run) go to a pool after the first two batches of frames
    monkeypatch.setattr(animation, "POOL_MIN_SECONDS", -1e9)
    pooled = lg.animate(scene, views, tmp_path / "p.png", width=WIDTH, progress=False)
    assert started == [2] and pooled.read_bytes() == serial.read_bytes()
    # fewer frames than PARALLEL_MIN_FRAMES stay here
    lg.animate(scene, views[:5], tmp_path / "f.png", width=WIDTH, progress=False)
    assert started == [2]


# -- the command line -------------------------------------------------------------------------
SCENE_FILE = """
[projector]
kind = "central"
azimuth = 35
elevation = 25
distance = 16

[[object]]
surface = "ellipsoid"
params = { a = 3, b = 2, c = 1.3 }
families = [{ name = "lines_of_curvature", n1 = 5, n2 = 6 }]
"""


def test_cli_animate(tmp_path, capsys):
    f = tmp_path / "scene.toml"
    f.write_text(SCENE_FILE, encoding="utf-8")
    out = tmp_path / "turn.gif"
    argv = ["animate", str(f), "-o", str(out), "--frames", "4", "--elevation", "25",
            "--fps", "24", "--width", "80", "--workers", "1"]  # fmt: skip
    assert cli_main(argv) == 0
    assert str(out.resolve()) in capsys.readouterr().out
    im = Image.open(out)
    assert im.n_frames == 4 and im.size[0] == 80 and im.info["duration"] == 40
    # the scene file's central projection: the eye keeps its distance
    views = lg.orbit(25, 4, 16.0)
    scene, _, _ = lg.load_scene_file(f)
    want = _reference(scene, views, width=80)
    got = _frames(out)
    assert all(np.abs(g - w).mean() < 1.0 for g, w in zip(got, want))


def test_cli_animate_errors(tmp_path, capsys):
    f = tmp_path / "scene.toml"
    f.write_text(SCENE_FILE, encoding="utf-8")
    assert cli_main(["animate", str(f), "-o", str(tmp_path / "t.avi"), "--frames", "2"]) == 2
    assert "unknown suffix '.avi'" in capsys.readouterr().err
    assert cli_main(["animate", str(tmp_path / "missing.toml")]) == 2
    with pytest.raises(SystemExit) as e:
        cli_main(["animate", "--help"])
    assert e.value.code == 0
    assert "--scheduler" in capsys.readouterr().out


def test_cli_scheduler_without_dask_is_a_clear_error(tmp_path, capsys, monkeypatch):
    f = tmp_path / "scene.toml"
    f.write_text(SCENE_FILE, encoding="utf-8")
    monkeypatch.setitem(sys.modules, "distributed", None)
    argv = ["animate", str(f), "-o", str(tmp_path / "t.gif"), "--scheduler", "tcp://x:8786"]
    assert cli_main(argv) == 2
    assert "lgraph[cluster]" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == [f]


def test_labels_travel_with_the_frames(tmp_path):
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(4, 8))
    scene.add(lg.Label("N", at=(0, 0, 1.6)))
    views = lg.orbit(elevation=20, frames=3)
    frames = _frames(lg.animate(scene, views, tmp_path / "t.png", width=WIDTH, progress=False))
    want = _reference(scene, views)
    assert all(np.array_equal(g, w) for g, w in zip(frames, want))
    # the label is drawn: the same frame without it differs
    window = animation.frame_window(scene, views)
    assert window[3] > 1.6 * np.cos(np.radians(20))  # the label's anchor is in the window
    d = scene.render(views[0])
    assert len(d.labels) == 1
    h, w = frames[0].shape[:2]
    bare = lg.Drawing(d.strokes, page=lg.Page(width=float(w), height=float(h), margin=0.03 * w),
                      window=window)  # fmt: skip
    buf = io.BytesIO()
    bare.save(buf, format="png", size=(w, h))
    no_label = np.asarray(Image.open(io.BytesIO(buf.getvalue())).convert("RGB"), dtype=int)
    assert not np.array_equal(no_label, frames[0])


def test_a_scene_that_cannot_be_pickled(scene, tmp_path, monkeypatch):
    def fail(obj):
        raise TypeError("cannot pickle 'function' object")

    monkeypatch.setattr(animation, "_dumps", fail)
    monkeypatch.setattr(animation, "BATCH_FRAMES", 1)  # 3 batches: a pool of 2 would help
    views = lg.orbit(frames=3)
    # the default pool falls back to this process, with a warning
    with pytest.warns(RuntimeWarning, match="rendering the frames in this process"):
        p = lg.animate(scene, views, tmp_path / "a.png", width=WIDTH, progress=False, workers=2)
    assert len(_frames(p)) == 3
    # a process pool given explicitly: a clear error, no file
    with cf.ProcessPoolExecutor(1) as ex, pytest.raises(TypeError, match="install cloudpickle"):
        lg.animate(scene, views, tmp_path / "b.png", width=WIDTH, progress=False, executor=ex)
    assert not (tmp_path / "b.png").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.png"]
