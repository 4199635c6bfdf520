"""Animations and many frames: :func:`lgraph.animate` renders a scene from many views.

Frames go straight to a streaming writer (``lgraph.animation.writers``): an
animated GIF, APNG or WebP, a multi-page PDF, or a folder of numbered
PNG/SVG/PDF frames, chosen by the path's suffix.  Every frame shows the same
window of the projection plane (the union, over all views, of the scene's
projected extent), so the figure keeps its place and scale.

The geometry that does not depend on the view (lines of curvature,
geodesics, ...) is computed once per process (:mod:`lgraph.families.cache`);
only the contour, the sampling and the visibility are redone per frame.
Consecutive views are rendered together, :data:`BATCH_FRAMES` at a time
(:func:`lgraph.render.render_views`: each stage of the pipeline runs once
for all of them), wherever they run, so the frames are the same wherever
they are rendered.

Frames run in this process, in a local process pool (the default for many
frames that take long), or on any :class:`concurrent.futures.Executor` --
including a Dask cluster's ``client.get_executor()``, to which the scene is
scattered once per worker.

>>> import os, tempfile
>>> import lgraph as lg
>>> from PIL import Image
>>> scene = lg.Scene()
>>> _ = scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(6, 8))
>>> with tempfile.TemporaryDirectory() as tmp:
...     path = lg.animate(scene, lg.orbit(elevation=25, frames=4), os.path.join(tmp, "t.gif"),
...                       width=120, progress=False)
...     im = Image.open(path)
...     im.n_frames, im.size[0]
(4, 120)
"""

from __future__ import annotations

import concurrent.futures as cf
import io
import os
import pickle
import time
import uuid
import warnings
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from .._budget import frame_list
from ..output._atomic import signals_as_exception, stop_pool, worker_setup
from ..output.drawing import Drawing, Stroke
from ..output.page import Page
from ..render import render_views
from ..render.prediction import RayBudgetError
from ..render.sampling import PointBudgetError
from ..scene.projectors import Projector
from .progress import ExecutorError, Progress, checked, in_order
from .window import PIXEL_TOLERANCE, frame_window, pixel_chord
from .writers import GifWriter, writer_for

__all__ = [
    "animate",
    "ExecutorError",
    "frame_window",
    "pixel_chord",
    "PARALLEL_MIN_FRAMES",
    "POOL_MIN_SECONDS",
    "BATCH_FRAMES",
    "MAX_WIDTH",
    "PIXEL_TOLERANCE",
]

#: With ``executor=None``, at least this many frames may run in a local process pool.
PARALLEL_MIN_FRAMES = 24

#: With ``executor=None`` and ``workers=None``, a pool of ``k`` processes
#: starts only when it would save more than this many seconds over the
#: frames left after the first two batches (:data:`BATCH_FRAMES`): their
#: time here ``R`` (at the second batch's pace) times ``1 - 1/k``, less the
#: geometry each worker computes again (a frame's time in the first batch
#: less its time in the second).  A pool's start and the
#: scene sent to each worker cost about this much.
POOL_MIN_SECONDS = 1.0

#: Views rendered together (:func:`lgraph.render.render_views`): frames
#: ``0 .. BATCH_FRAMES - 1``, then the next ``BATCH_FRAMES``, and so on.
#: Their samples are held at once; a batch of views that would exceed the
#: render's point budget is rendered view by view.
BATCH_FRAMES = 12

#: Largest frame width in pixels.
MAX_WIDTH = 8000


# -- one frame --------------------------------------------------------------------
@attrs.frozen(eq=False)
class _Job:
    """Everything a worker needs to render any frame (sent once per worker)."""

    scene: Any
    window: tuple[float, float, float, float]
    page: Page
    size: tuple[int, int]
    kind: str  # "png", "svg", "pdf" (the frame file's bytes) or "drawing"
    render_options: dict
    gray: bool = False  # grey raster frames may come as "L" images (GIF frames)

    def __reduce__(self) -> tuple:
        # the fields with cloudpickle when installed (scenes may hold lambdas);
        # unpickling goes through _load, which counts it
        return (_load, (_dumps(attrs.astuple(self, recurse=False)),))

    def render(self, views: list[Projector], portable: bool = False) -> list[Any]:
        """Frames for a batch of ``views``, rendered together: pillow images
        (raster kinds; PNG bytes, fast to encode, when ``portable``, i.e. sent
        back from another process), the frame files' bytes (SVG, PDF) or slim
        drawings (PDF pages)."""
        try:
            drawings = render_views(self.scene, views, **self.render_options)
        except (PointBudgetError, RayBudgetError):
            if len(views) == 1:
                raise
            # the batch exceeds the point (or ray-test) budget that one view may keep to
            drawings = [render_views(self.scene, [v], **self.render_options)[0] for v in views]
        return [self._frame(d, portable) for d in drawings]

    def _frame(self, d: Drawing, portable: bool) -> Any:
        d = Drawing(
            strokes=d.strokes,
            page=self.page,
            background=d.background,
            labels=d.labels,
            window=self.window,
        )
        if self.kind == "drawing":  # only what a page needs: no xyz, uv, surface
            slim = tuple(
                Stroke(
                    s.xy,
                    np.empty((0, 3)),
                    visible=s.visible,
                    family=s.family,
                    style=s.style,
                    occlusion=s.occlusion,
                )
                for s in d.strokes
            )
            return attrs.evolve(d, strokes=slim)
        if self.kind == "png":
            from ..output.backends.png import render_image

            im, _ = render_image(d, size=self.size, gray=self.gray)
            if not portable:
                return im
            buf = io.BytesIO()
            im.save(buf, "PNG", compress_level=1)
            return buf.getvalue()
        from ..notebook.display import to_bytes

        return to_bytes(d, self.kind)


# Worker side: the job installed by the pool initializer, or remembered by token.
_INSTALLED: dict[str, Any] = {}
#: How many times this process has unpickled a job (tests check "once per worker").
JOB_LOADS = [0]


def _load(data: bytes) -> _Job:
    JOB_LOADS[0] += 1
    return _Job(*pickle.loads(data))


def _install(data: bytes) -> None:
    worker_setup()  # stop signals: the default action; ends when the parent is gone
    _INSTALLED["job"] = pickle.loads(data)


def _render_installed(views: list[Projector]) -> list[Any]:
    return _INSTALLED["job"].render(views, True)


def _batches(views: list[Projector]) -> list[list[Projector]]:
    """The views in batches of :data:`BATCH_FRAMES` (the last may be shorter)."""
    return [views[i : i + BATCH_FRAMES] for i in range(0, len(views), BATCH_FRAMES)]


def _flat(batches: Iterator[list[Any]]) -> Iterator[Any]:
    """The frames of the batches, in order; closing it closes ``batches``
    (which cancels the batches not yet started)."""
    try:
        for frames in batches:
            yield from frames
    finally:
        close = getattr(batches, "close", None)
        if close is not None:
            close()


def _render_chunk(token: str, data: bytes, views: list[Projector]) -> list[Any]:
    job = _INSTALLED.get(token)
    if job is None:
        _INSTALLED.clear()  # one scene at a time per worker
        job = _INSTALLED[token] = pickle.loads(data)
    return job.render(views, True)


def _render_scattered(job: _Job, views: list[Projector]) -> list[Any]:
    return job.render(views, True)


def _dumps(obj: Any) -> bytes:
    """Pickle ``obj`` (with cloudpickle when installed: scenes may hold lambdas)."""
    try:
        import cloudpickle
    except ImportError:
        return pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    return cloudpickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)


# -- scheduling ----------------------------------------------------------------------
def _is_dask(executor: Any) -> bool:
    return type(executor).__module__.startswith("distributed") and hasattr(executor, "_client")


def _max_workers(executor: Any) -> int:
    n = getattr(executor, "_max_workers", None)
    if _is_dask(executor):
        try:
            n = sum(executor._client.nthreads().values())
        except Exception:  # noqa: BLE001 - a cluster that cannot say: assume a few
            n = 4
    return max(1, int(n or os.cpu_count() or 1))


def _local_pool(job: _Job, workers: int, pools: list) -> Any:
    """A process pool of ``workers`` with ``job`` installed (appended to
    ``pools``), or None when the scene cannot be pickled (with a warning)."""
    try:
        data = _dumps(job)
    except Exception as e:  # noqa: BLE001 - e.g. a lambda without cloudpickle
        warnings.warn(
            f"animate: the scene cannot be sent to worker processes ({e}); rendering "
            "the frames in this process (pip install cloudpickle to send lambdas)",
            RuntimeWarning,
            stacklevel=4,
        )
        return None
    pool = cf.ProcessPoolExecutor(workers, initializer=_install, initargs=(data,))
    pools.append(pool)
    return pool


def _pooled(
    job: _Job, batches: list[list[Projector]], workers: int, pools: list, first: int = 0
) -> Iterator:
    """Frames of ``batches`` rendered in a local pool of ``workers`` processes
    (here when the scene cannot be sent); ``first``: the first frame's index."""
    pool = _local_pool(job, workers, pools)
    if pool is None:
        return _flat(job.render(b) for b in batches)
    results = in_order(lambda b: pool.submit(_render_installed, b), batches, 2 * workers)
    return _flat(checked(results, batches, job.kind, pool, first))


def _adaptive(job: _Job, batches: list[list[Projector]], workers: int, pools: list) -> Iterator:
    """The default for many frames: the first two batches here (the first
    fills the geometry cache), then the rest in a pool of ``workers``
    processes only if that saves more than :data:`POOL_MIN_SECONDS`.  The
    frames are the same either way."""
    t0 = time.perf_counter()
    yield from job.render(batches[0])
    t1 = time.perf_counter()
    if len(batches) < 2:
        return
    yield from job.render(batches[1])
    t2 = time.perf_counter()
    rest = batches[2:]
    # per frame: the first batch's (with the geometry) and the second's
    first, later = (t1 - t0) / len(batches[0]), (t2 - t1) / len(batches[1])
    n_rest = sum(len(b) for b in rest)
    saved = later * n_rest * (1 - 1 / workers) - max(0.0, first - later)
    if rest and saved > POOL_MIN_SECONDS:
        yield from _pooled(job, rest, workers, pools, len(batches[0]) + len(batches[1]))
    else:
        yield from _flat(job.render(b) for b in rest)


def _frames(
    job: _Job, views: list[Projector], executor: Any, workers: int | None, pools: list
) -> Iterator[Any]:
    """The rendered frames in order (batches of :data:`BATCH_FRAMES` views
    rendered together wherever they run); local pools started are appended
    to ``pools`` (for the caller to shut down)."""
    n = len(views)
    batches = _batches(views)
    if executor is None:
        if workers is None:
            k = min(os.cpu_count() or 1, 8)
            if n >= max(PARALLEL_MIN_FRAMES, 3) and k > 1:
                return _adaptive(job, batches, k, pools)
            workers = 1
        workers = max(1, min(int(workers), len(batches)))
        if workers > 1:
            return _pooled(job, batches, workers, pools)
        return _flat(job.render(b) for b in batches)
    if not isinstance(executor, cf.Executor):
        raise TypeError(
            "animate: executor must be a concurrent.futures.Executor (a process or thread "
            f"pool, a Dask client's get_executor()) or None, got {type(executor).__name__}"
        )
    k = _max_workers(executor)
    if isinstance(executor, cf.ThreadPoolExecutor):  # shares this process's scene
        results = in_order(lambda b: executor.submit(job.render, b), batches, 2 * k)
        return _flat(checked(results, batches, job.kind, executor))
    if _is_dask(executor):  # the job goes to every worker once
        scattered = executor._client.scatter(job, broadcast=True, hash=False)
        submit = executor.submit
        results = in_order(lambda b: submit(_render_scattered, scattered, b), batches, 2 * k)
        return _flat(checked(results, batches, job.kind, executor))
    # any other executor: batches of frames, each with the pickled job; a worker
    # unpickles a job once and keeps it for the following batches
    try:
        data = _dumps(job)
    except Exception as e:  # noqa: BLE001 - e.g. a lambda without cloudpickle
        raise TypeError(
            f"animate: the scene cannot be sent to the executor's workers ({e}); install "
            "cloudpickle, or use a ThreadPoolExecutor or executor=None"
        ) from e
    token = uuid.uuid4().hex
    results = in_order(lambda b: executor.submit(_render_chunk, token, data, b), batches, 2 * k)
    return _flat(checked(results, batches, job.kind, executor))


# -- the public function --------------------------------------------------------------
def _check_views(views: Any) -> list[Projector]:
    try:  # MAX_FRAMES: len() of a sequence first; a generator read lazily, refused past it
        views = frame_list("animate", views)
    except TypeError:
        raise TypeError(
            f"animate: views must be a sequence of projectors (lg.orbit(...)), got "
            f"{type(views).__name__}"
        ) from None
    if not views:
        raise ValueError("animate: views is empty; give at least one projector")
    for k, v in enumerate(views):
        if not isinstance(v, Projector):
            raise TypeError(f"animate: views[{k}] must be a Projector, got {type(v).__name__}")
    return views


def animate(
    scene: Any,
    views: Sequence[Projector],
    path: str | os.PathLike[str],
    *,
    fps: float = 12,
    hidden_lines: bool = False,
    width: int = 480,
    executor: cf.Executor | None = None,
    workers: int | None = None,
    progress: bool = True,
    frame_format: str = "png",
    loop: int = 0,
    render_options: dict[str, Any] | None = None,
) -> Path:
    """Render ``scene`` from every projector in ``views`` into an animation at ``path``.

    Parameters
    ----------
    scene : Scene
        What to draw.
    views : sequence of Projector
        One projector per frame, e.g. ``lg.orbit(elevation=25, frames=72)``.
    path : path-like
        ``.gif`` (animated GIF), ``.png`` or ``.apng`` (animated PNG), ``.webp``
        (animated WebP, lossless), ``.pdf`` (one frame a page, for beamer
        slides), or a folder name without suffix: numbered frames
        ``frame_0000.<frame_format>``.  Files are written atomically.
    fps : float
        Frames per second (GIF delays are whole hundredths of a second).
    hidden_lines : bool
        Draw hidden parts dashed.
    width : int
        Frame width in pixels for raster output (and in pt for PDF and SVG);
        the height follows from the scene's shape.
    executor : concurrent.futures.Executor, optional
        Where frames are rendered: any executor, e.g. a
        :class:`~concurrent.futures.ProcessPoolExecutor` or a Dask
        ``client.get_executor()`` (the scene is scattered to each worker once).
        None: in this process, or in a local process pool of ``workers``
        processes.  By default (``workers=None``) a run of at least
        :data:`~lgraph.animation.frames.PARALLEL_MIN_FRAMES` frames renders its
        first two batches of :data:`~lgraph.animation.frames.BATCH_FRAMES` frames
        here and hands the rest to a pool of as many processes as CPUs (at
        most 8) only if, estimated from the times of those two, the pool
        saves more than
        :data:`~lgraph.animation.frames.POOL_MIN_SECONDS`; the frames are the same
        wherever they are rendered.
    workers : int, optional
        Size of the local pool when ``executor`` is None (1: this process;
        2 or more: a pool from the first frame on, with at most one process
        per batch of :data:`~lgraph.animation.frames.BATCH_FRAMES` frames).
    progress : bool
        Show a progress bar when standard error is a terminal.
    frame_format : {"png", "svg", "pdf"}
        Format of the frames written into a folder.
    loop : int
        Times a GIF/APNG/WebP repeats; 0 for ever.
    render_options : dict, optional
        More keywords for :meth:`Scene.render` (``tolerance``, ``hidden_style``).
        ``tolerance`` defaults to ``"pixel"`` for raster frames (GIF, APNG,
        WebP, PNG): they are sampled only as finely as their pixels show,
        every chord within ``PIXEL_TOLERANCE`` (0.25, ``lgraph/_tolerance.py``)
        pixels of its curve in every frame
        (:func:`~lgraph.animation.window.pixel_chord`; for a figure that fills a
        480 px frame, about 4.6e-4 of its diagonal, 4.6 times the render's
        default, 1e-4) -- below the third of a pixel to which the rasterizer
        rounds every point anyway.  Vector frames (PDF, SVG) keep the
        render's default; a number sets the tolerance of every frame.

    Returns
    -------
    Path
        The file or folder written.
    """
    from ..scene.graph import Scene

    if not isinstance(scene, Scene):
        raise TypeError(f"animate: scene must be a Scene, got {type(scene).__name__}")
    views = _check_views(views)
    if isinstance(fps, bool) or not (isinstance(fps, (int, float)) and 0 < fps <= 100):
        raise ValueError(f"animate: fps must be a number in (0, 100], got {fps!r}")
    if isinstance(width, bool) or not isinstance(width, int) or not 16 <= width <= MAX_WIDTH:
        raise ValueError(
            f"animate: width must be an integer from 16 to {MAX_WIDTH} px, got {width!r}"
        )
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
    ):
        raise ValueError(f"animate: workers must be a positive integer or None, got {workers!r}")
    if isinstance(loop, bool) or not isinstance(loop, int) or not 0 <= loop <= 65535:
        raise ValueError(f"animate: loop must be an integer from 0 to 65535, got {loop!r}")
    options = {"tolerance": "pixel", **(render_options or {})}
    options["hidden_lines"] = bool(hidden_lines)
    if isinstance(options.get("tolerance"), str) and options["tolerance"] != "pixel":
        raise ValueError(
            'animate: render_options["tolerance"] must be a number or "pixel", '
            f"got {options['tolerance']!r}"
        )

    window = frame_window(scene, views)
    margin = 0.03 * width
    aspect = (window[3] - window[1]) / (window[2] - window[0])
    height = max(16, round((width - 2 * margin) * aspect + 2 * margin))
    page = Page(width=float(width), height=float(height), margin=margin)
    # a SIGTERM or SIGHUP from here on stops the work cleanly (no temporary
    # file, no worker left), then takes its usual course
    with signals_as_exception():
        writer = writer_for(path, len(views), fps, frame_format, loop)
        bar = Progress(len(views), progress)
        pools: list = []
        frames = None
        try:
            kind = writer.kind
            if kind == "bytes":
                kind = writer.fmt
            if options.get("tolerance") == "pixel":
                del options["tolerance"]  # vector frames can be zoomed: the render's default
                if kind == "png":
                    options["chord"] = pixel_chord(page, window)
            gray = isinstance(writer, GifWriter)  # frames in one channel may differ in mode
            job = _Job(scene, window, page, (width, height), kind, options, gray)
            frames = _frames(job, views, executor, workers, pools)
            for frame in frames:
                writer.add(frame)
                bar.update()
            result = writer.close()
        except BaseException:
            writer.abort()
            if frames is not None and hasattr(frames, "close"):
                frames.close()  # cancels the frames not yet started
            for pool in pools:
                stop_pool(pool)  # ends its workers
            pools.clear()
            raise
        finally:
            bar.close()
            for pool in pools:
                pool.shutdown()
    return Path(result)
