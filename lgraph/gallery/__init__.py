"""The figure gallery: ``lgraph gallery OUTDIR`` and the helpers gallery scripts use.

A gallery script (``gallery/<stem>.py``) is a short module that defines

* ``CAPTION: str`` -- what is shown, the surface's equation, the parameters;
* ``build()`` returning ``(scene, projector)``, or ``(scene, projector, render_kwargs)``
  (e.g. ``{"hidden_lines": True}``), or a list of such tuples, one per panel;
* ``if __name__ == "__main__": run_script_main(__file__, build)``, which writes
  ``<stem>.pdf`` and ``<stem>.png`` into the current folder;
* optionally ``ANIMATION``, a dict of :func:`lgraph.orbit` and
  :func:`lgraph.animate` keywords (``frames``, ``elevation``, ``distance``,
  ``fps``, ``width``, ``hidden_lines``): the figure (its first panel) also
  turns about the z axis in ``<stem>.gif``, which is then its thumbnail.

Multi-panel figures become one drawing: the panels are scaled to a common
height and laid out left to right (:func:`render_figure`), so every figure is
exactly one ``<stem>.pdf`` and one ``<stem>.png``.

:func:`build_gallery` renders every script in parallel worker processes and
writes ``OUTDIR/<stem>.pdf``, ``OUTDIR/<stem>.png``, ``OUTDIR/src/<stem>.py``
and ``OUTDIR/index.html``.

>>> import lgraph as lg
>>> scene = lg.Scene()
>>> _ = scene.add(lg.Sphere(1), lg.ParameterLines(3, 4))
>>> p = lg.ParallelProjector(direction=(1, 0, 0))
>>> one = render_figure((scene, p))
>>> two = render_figure([(scene, p), (scene, p, {"hidden_lines": True})])
>>> w1 = one.bounds()[2] - one.bounds()[0]
>>> w2 = two.bounds()[2] - two.bounds()[0]
>>> w2 > 2 * w1
True
"""

from __future__ import annotations

import ast
import importlib.util
import os
import re
import shutil
import sys
import time
import traceback
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any, TextIO

import attrs
import numpy as np

from ..output._atomic import Terminated, signals_as_exception, stop_pool, worker_setup
from .page import figure_title, write_index

__all__ = [
    "build_gallery",
    "default_gallery_dir",
    "discover_scripts",
    "render_figure",
    "run_script_main",
    "script_caption",
    "script_animation",
    "figure_title",
]

#: Gap between panels, as a fraction of the common panel height.
PANEL_GAP = 0.12

#: Longer side of a one-panel figure's page in pt; n panels get n times as much
#: width (up to 3 panels), so each panel keeps its size.
PAGE_EXTENT = 500.0

#: Resolution of the gallery PNGs.
PNG_DPI = 150


# -- scripts ------------------------------------------------------------------
def default_gallery_dir() -> Path:
    """The repository's ``gallery/`` folder, next to the ``lgraph`` package.

    Raises FileNotFoundError with a clear message when lgraph is installed
    without its gallery scripts (a non-editable install).
    """
    import lgraph

    here = Path(lgraph.__file__).resolve().parent.parent / "gallery"
    if not here.is_dir():
        raise FileNotFoundError(
            f"lgraph gallery: no gallery scripts at {str(here)!r}; the gallery ships with "
            "the source tree, not with an installed wheel (install lgraph from a checkout "
            "with `pip install -e .`, or run from the repository root)"
        )
    return here


def _natural_key(stem: str) -> tuple[int, list[Any]]:
    # paper figures first (in the paper's order), then the extras by name
    parts = [int(p) if p.isdigit() else p for p in re.split(r"(\d+)", stem)]
    return (0 if stem.startswith("fig_") else 1, parts)


def discover_scripts(source_dir: str | os.PathLike[str] | None = None) -> list[Path]:
    """Gallery scripts in ``source_dir`` (default :func:`default_gallery_dir`):
    every ``*.py`` not starting with ``_``, paper figures first."""
    folder = Path(source_dir) if source_dir is not None else default_gallery_dir()
    if not folder.is_dir():
        raise FileNotFoundError(f"lgraph gallery: folder {str(folder)!r} does not exist")
    scripts = [p for p in folder.glob("*.py") if not p.name.startswith("_")]
    return sorted(scripts, key=lambda p: _natural_key(p.stem))


def script_caption(path: str | os.PathLike[str]) -> str:
    """The script's ``CAPTION`` read from its source (without running it);
    empty if it is not a plain string literal."""
    try:
        tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    except (OSError, SyntaxError, ValueError):
        return ""
    for node in tree.body:
        targets = []
        if isinstance(node, ast.Assign):
            targets, value = node.targets, node.value
        elif isinstance(node, ast.AnnAssign) and node.value is not None:
            targets, value = [node.target], node.value
        if any(isinstance(t, ast.Name) and t.id == "CAPTION" for t in targets):
            try:
                v = ast.literal_eval(value)
            except ValueError:
                return ""
            return v if isinstance(v, str) else ""
    return ""


def script_animation(path: str | os.PathLike[str]) -> dict[str, Any] | None:
    """The script's ``ANIMATION`` dict read from its source (without running
    it); None if it has none or it is not a plain literal."""
    try:
        tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    except (OSError, SyntaxError, ValueError):
        return None
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
            isinstance(t, ast.Name) and t.id == "ANIMATION" for t in node.targets
        ):
            try:
                value = ast.literal_eval(node.value)
            except ValueError:
                return None
            return value if isinstance(value, dict) else None
    return None


_ORBIT_KEYS = ("frames", "elevation", "distance", "azimuth")


def _animate(result: Any, spec: dict[str, Any], path: Path) -> Path:
    """Write the turntable of a script's first panel (``ANIMATION = {...}``)."""
    from ..animation.frames import animate
    from ..scene.projectors import orbit

    scene, _, kwargs = _panels(result)[0]
    views = orbit(**{k: spec[k] for k in _ORBIT_KEYS if k in spec})
    options = {k: v for k, v in spec.items() if k not in _ORBIT_KEYS}
    options.setdefault("hidden_lines", kwargs.get("hidden_lines", False))
    return animate(scene, views, path, progress=False, workers=1, **options)


def _load_module(path: Path) -> Any:
    folder = str(path.parent)
    if folder not in sys.path:  # scripts may share private helpers (_common.py)
        sys.path.insert(0, folder)
    name = f"lgraph_gallery_{path.stem}"
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:  # pragma: no cover - .py files always load
        raise ImportError(f"cannot load gallery script {str(path)!r}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


# -- rendering ------------------------------------------------------------------
def _panels(result: Any) -> list[tuple[Any, Any, dict[str, Any]]]:
    """Normalize what ``build()`` returns to a list of (scene, projector, kwargs)."""
    if isinstance(result, tuple):
        result = [result]
    if not isinstance(result, list) or not result:
        raise TypeError(
            "gallery: build() must return (scene, projector[, render_kwargs]) or a non-empty "
            f"list of them, got {type(result).__name__}"
        )
    out = []
    for i, panel in enumerate(result):
        if not isinstance(panel, tuple) or len(panel) not in (2, 3):
            raise TypeError(
                f"gallery: panel {i} must be (scene, projector) or (scene, projector, "
                f"render_kwargs), got {panel!r:.80}"
            )
        kwargs = dict(panel[2]) if len(panel) == 3 else {}
        out.append((panel[0], panel[1], kwargs))
    return out


def render_figure(result: Any, tolerance: float | None = None) -> Any:
    """Render what a gallery ``build()`` returns into one :class:`~lgraph.Drawing`.

    Several panels are scaled to the height of the tallest one and placed left
    to right with a small gap.  ``tolerance`` (if given) overrides the chord
    tolerance of panels that do not set their own.
    """
    from ..output.drawing import Drawing
    from ..output.page import Page

    drawings = []
    for scene, projector, kwargs in _panels(result):
        if tolerance is not None:
            kwargs.setdefault("tolerance", tolerance)
        drawings.append(scene.render(projector, **kwargs))
    if len(drawings) == 1:
        return drawings[0]
    boxes = [d.bounds() for d in drawings]
    height = max(max(b[3] - b[1], 1e-300) for b in boxes)
    strokes = []
    labels = []
    x = 0.0
    for d, (x0, y0, x1, y1) in zip(drawings, boxes):
        h = max(y1 - y0, 1e-300)
        k = height / h
        shift = np.array([x - k * x0, -k * (y0 + y1) / 2])
        strokes.extend(attrs.evolve(s, xy=s.xy * k + shift, curve=None) for s in d.strokes)
        labels.extend(attrs.evolve(lab, xy=lab.xy * k + shift) for lab in d.labels)
        x += k * (x1 - x0) + PANEL_GAP * height
    page = Page(extent=PAGE_EXTENT * min(len(drawings), 3))
    return Drawing(strokes=strokes, page=page, background=drawings[0].background, labels=labels)


def _save(drawing: Any, folder: Path, stem: str) -> list[Path]:
    return [
        drawing.save(folder / f"{stem}.pdf"),
        drawing.save(folder / f"{stem}.png", dpi=PNG_DPI),
    ]


def run_script_main(file: str, build: Callable[[], Any]) -> list[Path]:
    """The ``__main__`` block of a gallery script: render ``build()`` and write
    ``<stem>.pdf`` and ``<stem>.png`` into the current folder (and
    ``<stem>.gif`` when the script defines ``ANIMATION``)."""
    stem = Path(file).stem
    t0 = time.perf_counter()
    result = build()
    paths = _save(render_figure(result), Path("."), stem)
    spec = script_animation(file)
    if spec:
        paths.append(_animate(result, spec, Path(f"{stem}.gif")))
    for p in paths:
        print(f"wrote {p.resolve()}")
    print(f"{stem}: {time.perf_counter() - t0:.1f} s")
    return paths


def _build_one(path: str, outdir: str, tolerance: float | None) -> dict[str, Any]:
    """Worker: import, build, render and save one figure; never raises."""
    t0 = time.perf_counter()
    stem = Path(path).stem
    info: dict[str, Any] = {"stem": stem, "caption": None, "error": None}
    try:
        module = _load_module(Path(path))
        caption = getattr(module, "CAPTION", None)
        info["caption"] = caption if isinstance(caption, str) else None
        if not callable(getattr(module, "build", None)):
            raise AttributeError(f"gallery script {stem} defines no build() function")
        result = module.build()
        drawing = render_figure(result, tolerance)
        if not drawing.strokes:
            raise ValueError(f"gallery script {stem} drew nothing (no strokes)")
        _save(drawing, Path(outdir), stem)
        info["strokes"] = len(drawing.strokes)
        spec = getattr(module, "ANIMATION", None)
        if spec:
            _animate(result, dict(spec), Path(outdir) / f"{stem}.gif")
            info["animation"] = True
    except (KeyboardInterrupt, Terminated):  # a stop of the whole gallery
        raise
    except BaseException:  # noqa: BLE001 - report everything, keep going
        info["error"] = traceback.format_exc()
    info["seconds"] = time.perf_counter() - t0
    return info


# -- the page -----------------------------------------------------------------
def _build_in_pool(
    scripts: Sequence[Path],
    outdir: str,
    tolerance: float | None,
    jobs: int,
    report: Callable[[dict[str, Any]], None],
) -> None:
    """Build the figures in ``jobs`` worker processes, reporting each as it
    ends; on a stop (Ctrl-C, a stop signal) the workers are ended at once."""
    pool = ProcessPoolExecutor(max_workers=jobs, initializer=worker_setup)
    try:
        futures = {pool.submit(_build_one, str(p), outdir, tolerance): p for p in scripts}
        for fut in as_completed(futures):
            p = futures[fut]
            try:
                info = fut.result()
            except (KeyboardInterrupt, Terminated):
                raise
            except BaseException:  # noqa: BLE001 - a worker died (e.g. killed)
                info = {
                    "stem": p.stem,
                    "caption": None,
                    "seconds": 0.0,
                    "error": traceback.format_exc(),
                }
            report(info)
    except BaseException:
        stop_pool(pool)
        raise
    pool.shutdown()


def build_gallery(
    outdir: str | os.PathLike[str],
    jobs: int | None = None,
    only: Sequence[str] | None = None,
    *,
    source_dir: str | os.PathLike[str] | None = None,
    tolerance: float | None = None,
    stream: TextIO | None = None,
) -> int:
    """Build every gallery figure into ``outdir``; return the exit status.

    Parameters
    ----------
    outdir : path
        Output folder (created if missing).
    jobs : int, optional
        Worker processes (default ``os.cpu_count()``); ``1`` builds in this process.
    only : list of str, optional
        Build only scripts whose name contains one of these strings.
    source_dir : path, optional
        Folder of gallery scripts (default: the repository's ``gallery/``).
    tolerance : float, optional
        Override the chord tolerance (e.g. ``1e-3`` for quick drafts).
    stream : text file, optional
        Where progress goes (default ``sys.stdout``).

    Returns
    -------
    int
        0 when every figure was built, 1 when any failed (each failure is
        reported with its traceback; the other figures are still built),
        2 when there was nothing to build.
    """
    out = stream if stream is not None else sys.stdout
    scripts = discover_scripts(source_dir)
    if only:
        scripts = [p for p in scripts if any(s in p.stem for s in only)]
    if not scripts:
        print("lgraph gallery: no gallery scripts match", file=out)
        return 2
    outdir = Path(outdir)
    (outdir / "src").mkdir(parents=True, exist_ok=True)
    for p in scripts:
        shutil.copyfile(p, outdir / "src" / p.name)
    n = len(scripts)
    jobs = max(1, min(jobs or os.cpu_count() or 1, n))
    print(f"lgraph gallery: building {n} figures into {outdir} with {jobs} worker(s)", file=out)
    out.flush()

    results: dict[str, dict[str, Any]] = {}
    t0 = time.perf_counter()

    def report(info: dict[str, Any]) -> None:
        results[info["stem"]] = info
        status = "FAILED" if info["error"] else f"{info['seconds']:.1f} s"
        print(f"[{len(results)}/{n}] {info['stem']}  {status}", file=out)
        if info["error"]:
            print(info["error"].rstrip(), file=out)
        out.flush()

    # a SIGTERM or SIGHUP stops the gallery (not only the figure under way):
    # the figure's file is not half written, the workers are ended
    with signals_as_exception():
        if jobs == 1:
            for p in scripts:
                report(_build_one(str(p), str(outdir), tolerance))
        else:
            _build_in_pool(scripts, str(outdir), tolerance, jobs, report)

    items = []
    for p in scripts:
        info = results[p.stem]
        if info.get("caption") is None:
            info["caption"] = script_caption(p)
        items.append(info)
    index = write_index(outdir, items)
    failed = [i["stem"] for i in items if i["error"]]
    took = time.perf_counter() - t0
    print(f"wrote {index} ({n - len(failed)}/{n} figures, {took:.1f} s)", file=out)
    if failed:
        print(f"lgraph gallery: {len(failed)} failed: {', '.join(failed)}", file=out)
        return 1
    return 0
