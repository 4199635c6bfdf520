"""Command line: ``lgraph demo | render | animate | gallery | plugins``.

Input errors (a bad scene file, option, output path, ...) are found before
any rendering where they can be; they exit with status 2 and one message
``lgraph <command>: error: ...`` on stderr, no traceback (``--debug`` shows
it; it is accepted before or after the command).  An unexpected failure
exits with status 1, also without a traceback unless ``--debug``.

A SIGTERM or SIGHUP stops ``render``, ``animate`` and ``demo`` cleanly, as
Ctrl-C does (``lgraph.output._atomic.signals_as_exception``): no temporary file is
left, the old file at the target is kept, worker processes are stopped, and
the command prints ``lgraph <command>: terminated by SIGTERM`` and exits with
128 + the signal's number (143; Ctrl-C: 130).  Plugin code that calls
``sys.exit()`` is an error naming the plugin (status 2), not an exit.

Output paths are taken as written, ``..`` resolved lexically
(``os.path.normpath``): ``-o a/b/../../x.pdf`` writes ``x.pdf`` and creates
no folder ``a/b``, even where ``a`` is a symbolic link.  A file name longer
than the file system takes is refused before any work.

``lgraph render scene.toml -o fig.pdf -o fig.png`` renders once and saves to
every output.  A ``[save]`` option that only some of the outputs' backends
take is then a warning, ``lgraph render: warning: scene.toml:12: save.title:
not an option of the .png backend; ignored for fig.png``, and is left out for
those outputs; one that none of them takes is an error.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

__all__ = ["main", "demo_scene", "build_parser"]


class InputError(Exception):
    """A problem with what the user gave (exit status 2)."""


class Failure(Exception):
    """A command that could not finish, for a reason it can say (exit status 1)."""


def demo_scene():  # noqa: ANN201
    """The figure of ``lgraph demo``: the paper's Figure 7.2, the lines of
    curvature of a triaxial ellipsoid (as ``gallery/fig_7_2_ellipsoid.py``)."""
    import lgraph as lg

    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(14, 18))
    return scene.render(lg.CentralProjector.from_angles(35, 25, 16))


def _output_folder(folder: Path) -> Path:
    """Create ``folder`` (taken lexically: only the folders it needs) if
    missing; refuse one that is a file or not writable."""
    from .output._atomic import lexical

    folder = lexical(folder)
    if folder.exists() and not folder.is_dir():
        raise InputError(f"{str(folder)!r} is not a folder")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise InputError(f"cannot create the folder {str(folder)!r}: {e.strerror or e}") from None
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"the folder {str(folder)!r} is not writable")
    return folder


def _check_name(out: Path, given: Path) -> None:
    """Refuse an output whose file name is longer than the file system takes
    (``given``: ``out`` as written, for the message)."""
    from .output._atomic import check_name

    try:
        check_name(out, "output")
    except OSError as e:
        why = str(e.strerror or e).removeprefix("output: ")
        raise InputError(f"output {str(given)!r}: {why}") from None


def check_output(path: str | os.PathLike[str]) -> Path:
    """Check an output file before any work: a known suffix (a backend for
    it), a name the file system takes, not a folder, its folder existing
    (created if missing) and writable.  The path is taken lexically
    (``..`` resolved as text).  Raises :class:`InputError`."""
    from .output._atomic import lexical
    from .output.backends import get_backend
    from .plugins import PluginError

    given, out = Path(path), lexical(path)
    try:
        get_backend(out.suffix)
    except (ValueError, PluginError) as e:
        raise InputError(str(e).splitlines()[0].replace("Drawing.save: ", "")) from None
    _check_name(out, given)
    if out.is_dir():
        raise InputError(f"output {str(given)!r} is a folder; give a file name")
    _output_folder(out.parent if str(out.parent) else Path("."))
    return out


def _demo(args: argparse.Namespace) -> int:
    out = _output_folder(Path(args.outdir))
    drawing = demo_scene()
    for suffix in (".pdf", ".png"):
        path = drawing.save(out / f"lgraph-demo{suffix}")
        print(f"wrote {path.resolve()}")
    return 0


def _same_file(a: Path, b: Path) -> bool:
    """Whether ``a`` and ``b`` name one file (an existing one by identity, as
    ``os.path.samefile``; otherwise by resolved path)."""
    try:
        if a.exists() and b.exists():
            return os.path.samefile(a, b)
        a, b = a.resolve(), b.resolve()
    except (OSError, RuntimeError):  # unreadable, or a symbolic link loop
        a, b = a.absolute(), b.absolute()
    return os.path.normcase(a) == os.path.normcase(b)


def _refuse_scene_file(out: Path, scene: str | os.PathLike[str], given: Path | None = None) -> None:
    """Refuse to write over the scene file being read (``given``: ``out`` as
    written, for the message)."""
    if _same_file(out, Path(scene)):
        shown = str(given if given is not None else out)
        raise InputError(f"output {shown!r} is the scene file itself; give another output file")


def check_outputs(
    scene: str | os.PathLike[str], outputs: Sequence[str | os.PathLike[str]]
) -> list[Path]:
    """Check the outputs of one rendering before any work: none is the scene
    file, none is given twice, and each passes :func:`check_output`.
    Raises :class:`InputError`."""
    from .output._atomic import lexical

    given = [Path(o) for o in outputs]  # for messages: as written
    outs = [lexical(o) for o in outputs]
    for i, out in enumerate(outs):
        _refuse_scene_file(out, scene, given[i])
        for k, earlier in enumerate(outs[:i]):
            if _same_file(out, earlier):
                shown, first = str(given[i]), str(given[k])
                also = f" (also as {first!r})" if first != shown else ""
                raise InputError(f"output {shown!r} is given twice{also}; give each once")
    return [check_output(g) for g in given]


def _load_scene(scene: str, outputs: list[Path], command: str) -> tuple[Any, Any, dict[str, Any]]:
    """``load_scene_file`` for ``outputs``; an ignored ``[save]`` option is
    printed as ``lgraph <command>: warning: ...`` on stderr."""
    from .scenefile import SceneFileError, SceneFileWarning, load_scene_file

    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", SceneFileWarning)
            loaded = load_scene_file(scene, output=outputs)
    except SceneFileError as e:
        raise InputError(str(e)) from None
    for w in caught:
        if issubclass(w.category, SceneFileWarning):
            print(f"lgraph {command}: warning: {w.message}", file=sys.stderr)
        else:  # not ours: as if not caught
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
    return loaded


def _render(args: argparse.Namespace) -> int:
    outs = check_outputs(args.scene, args.output or [Path(args.scene).with_suffix(".pdf")])
    for name in ("width", "height"):  # physical sizes: checked before rendering
        if getattr(args, name, None) is not None:
            from .output.units import length_pt

            try:
                length_pt(getattr(args, name), name)
            except ValueError as e:
                raise InputError(f"--{name}: {e}") from None
    scene, projector, options = _load_scene(args.scene, outs, "render")
    drawing = scene.render(projector, **options.get("render", {}))  # once for every output
    plotted: dict[Any, Any] = {}  # --plotter: the cleaned drawing, by figure width
    for out, save_options in zip(outs, options["save"], strict=True):
        save = dict(save_options)
        for name in ("width", "height"):  # the command line wins over the scene file
            if getattr(args, name, None) is not None:
                save[name] = args.__dict__[name]
        figure = drawing
        if args.plotter:  # tolerances on the page as saved
            width = save.get("width")
            if width not in plotted:
                plotted[width] = drawing.for_plotter(width=width)
            figure = plotted[width]
        path = figure.save(out, **save)
        print(f"wrote {Path(path).resolve()}")
    return 0


def _animate(args: argparse.Namespace) -> int:
    from .animation.frames import ExecutorError, animate
    from .animation.writers import ANIMATION_SUFFIXES
    from .output._atomic import lexical
    from .scene.projectors import CentralProjector, orbit
    from .scenefile import SceneFileError, load_scene_file

    given = Path(args.output or Path(args.scene).with_suffix(".gif"))
    out = lexical(given)
    suffix = out.suffix.lower()
    if suffix and suffix not in ANIMATION_SUFFIXES:  # checked before any work
        raise InputError(
            f"unknown suffix {out.suffix!r} for an animation; use .gif, .png/.apng (APNG), "
            ".webp, .pdf (a page per frame) or a folder name without suffix (numbered frames)"
        )
    if suffix:
        _refuse_scene_file(out, args.scene, given)
        _check_name(out, given)
    _output_folder(out if not suffix else (out.parent if str(out.parent) else Path(".")))
    client_class = None
    if args.scheduler:
        try:
            from distributed import Client as client_class
        except ImportError:
            raise InputError(
                "--scheduler needs dask.distributed; install it with pip install 'lgraph[cluster]'"
            ) from None
    try:
        scene, projector, options = load_scene_file(args.scene)
    except SceneFileError as e:
        raise InputError(str(e)) from None
    distance, target = args.distance, (0.0, 0.0, 0.0)
    if isinstance(projector, CentralProjector):  # keep the scene file's eye distance
        target = tuple(projector.target.tolist())
        if distance is None:
            distance = projector.distance
    views = orbit(args.elevation, args.frames, distance, azimuth=args.azimuth, target=target)
    render = dict(options.get("render", {}))
    hidden = bool(render.pop("hidden_lines", False)) or args.hidden_lines
    kw = dict(fps=args.fps, hidden_lines=hidden, width=args.width, render_options=render)
    try:
        if client_class is not None:
            with client_class(args.scheduler, timeout=args.timeout) as client:
                path = animate(scene, views, out, executor=client.get_executor(), **kw)
        else:
            path = animate(scene, views, out, workers=args.workers, **kw)
    except ExecutorError as e:
        raise Failure(str(e).removeprefix("animate: ")) from e
    print(f"wrote {Path(path).resolve()}")
    return 0


def _gallery(args: argparse.Namespace) -> int:
    from .gallery import build_gallery

    return build_gallery(args.outdir, jobs=args.jobs, only=args.only)


def _plugins(args: argparse.Namespace) -> int:
    from .plugins import describe_plugins

    print(describe_plugins())
    return 0


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer >= 1, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected an integer >= 1, got {value}")
    return value


def _suffixes() -> str:
    try:
        from .output.backends import backend_suffixes

        return ", ".join(backend_suffixes())
    except Exception:  # noqa: BLE001 - help must print whatever a plugin does
        return ".pdf, .png, .svg"


def _add_debug(parser: argparse.ArgumentParser, default: Any) -> None:
    parser.add_argument(
        "--debug",
        action="store_true",
        default=default,
        help="show the Python traceback of an error",
    )


def build_parser() -> argparse.ArgumentParser:
    from . import __version__

    p = argparse.ArgumentParser(
        prog="lgraph",
        description="Print-quality line graphics of mathematical surfaces "
        "with exact hidden-line removal.",
    )
    p.add_argument("--version", action="version", version=f"lgraph {__version__}")
    _add_debug(p, default=False)
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    d = sub.add_parser("demo", help="write lgraph-demo.pdf and lgraph-demo.png")
    d.add_argument(
        "outdir", nargs="?", default=".", help="folder to write into (created if missing)"
    )
    d.set_defaults(func=_demo, stoppable=True)
    r = sub.add_parser("render", help="render a TOML scene file")
    r.add_argument("scene", help="scene file (.toml)")
    r.add_argument(
        "-o",
        "--output",
        action="append",
        metavar="OUTPUT",
        help=f"output file, by suffix: {_suffixes()}; repeat for several (rendered once, "
        "saved to each); default: the scene's name with .pdf",
    )
    r.add_argument("--width", help="figure width, e.g. 8.5cm, 85mm, 3.3in, 240pt")
    r.add_argument("--height", help="figure height (with --width: fit inside, aspect kept)")
    r.add_argument(
        "--plotter",
        action="store_true",
        help="clean for a pen plotter: merge paths, drop duplicates and fragments, "
        "sort for short pen-up travel (Drawing.for_plotter)",
    )
    r.set_defaults(func=_render, stoppable=True)
    a = sub.add_parser(
        "animate",
        help="render a TOML scene file turning about the z axis (GIF, APNG, WebP, PDF, frames)",
    )
    a.add_argument("scene", help="scene file (.toml)")
    a.add_argument(
        "-o",
        "--output",
        help="output: .gif, .png (APNG), .webp, .pdf (a page per frame) or a folder for "
        "numbered PNG frames; default: scene name .gif",
    )
    a.add_argument("--frames", type=_positive_int, default=36, help="number of frames (default 36)")
    a.add_argument("--elevation", type=float, default=25.0, help="degrees (default 25)")
    a.add_argument("--azimuth", type=float, default=0.0, help="of the first frame (default 0)")
    a.add_argument(
        "--distance",
        type=float,
        default=None,
        help="central projection from this distance (default: the scene file's, else parallel)",
    )
    a.add_argument("--fps", type=float, default=12.0, help="frames per second (default 12)")
    a.add_argument(
        "--width", type=_positive_int, default=480, help="frame width in px (default 480)"
    )
    a.add_argument("--hidden-lines", action="store_true", help="draw hidden parts dashed")
    a.add_argument(
        "--workers",
        type=_positive_int,
        default=None,
        help="local worker processes (default: automatic)",
    )
    a.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="render on a Dask cluster (tcp://host:8786; needs lgraph[cluster])",
    )
    a.add_argument(
        "--timeout", type=float, default=30.0, help="seconds to reach the scheduler (default 30)"
    )
    a.set_defaults(func=_animate, stoppable=True)
    g = sub.add_parser("gallery", help="build every gallery figure (PDF + PNG) and index.html")
    g.add_argument("outdir", help="output folder (created if missing)")
    g.add_argument("-j", "--jobs", type=_positive_int, default=None, help="worker processes")
    g.add_argument(
        "--only", nargs="*", default=None, help="only figures whose name contains one of these"
    )
    g.set_defaults(func=_gallery, stoppable=True)
    pl = sub.add_parser(
        "plugins", help="list the surfaces, line families and backends, and installed plugins"
    )
    pl.set_defaults(func=_plugins)
    for command in (d, r, a, g, pl):  # --debug also after the command
        _add_debug(command, default=argparse.SUPPRESS)  # keeps the value given before it
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 1 failure, 2 bad
    input, 128 + n stopped by signal n: 130 Ctrl-C, 143 SIGTERM)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    from contextlib import nullcontext

    from .output._atomic import Terminated, signals_as_exception
    from .plugins import PluginError

    prefix = f"lgraph {args.command}: error:"
    # render, animate, demo, gallery: a SIGTERM or SIGHUP stops them cleanly
    stoppable = getattr(args, "stoppable", False)
    try:
        with signals_as_exception(take_default=False) if stoppable else nullcontext():
            try:
                return int(args.func(args) or 0)
            except SystemExit as e:  # from plugin code: an error naming the plugin
                error = _plugin_exit(e)
                if error is None:
                    raise
                raise error from e
    except KeyboardInterrupt:
        print(f"lgraph {args.command}: interrupted", file=sys.stderr)
        return 130
    except Terminated as e:
        print(f"lgraph {args.command}: {e}", file=sys.stderr)
        return e.exit_status
    except (InputError, ValueError, TypeError, PluginError, OSError, NotImplementedError) as e:
        if args.debug:
            raise
        text = str(e) or type(e).__name__
        if isinstance(e, PluginError):  # its first line (the rest: the plugin's traceback)
            text = text.splitlines()[0].removeprefix("lgraph: ").removesuffix("; original error:")
            if e.__cause__ is not None and not isinstance(e.__cause__, SystemExit):
                text += f" ({_short(e.__cause__)})"
        if isinstance(e, OSError) and not isinstance(e, FileNotFoundError) and e.filename:
            text = f"{e.strerror or e}: {e.filename}"
        print(f"{prefix} {text}", file=sys.stderr)
        return 2
    except Failure as e:
        if args.debug:
            raise
        print(f"{prefix} {e}", file=sys.stderr)
        return 1
    except Exception as e:  # noqa: BLE001 - no traceback for the user without --debug
        if args.debug:
            raise
        print(
            f"{prefix} unexpected {type(e).__name__}: {e} (run with --debug for details)",
            file=sys.stderr,
        )
        return 1


def _plugin_exit(exc: SystemExit) -> Exception | None:
    """A ``PluginError`` naming the plugin whose code raised ``exc`` (the
    innermost frame of its traceback in a loaded plugin's module), or None:
    a plugin must not end lgraph."""
    from .output._atomic import exit_message
    from .plugins import PluginError, installed_plugins

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        infos = [i for i in installed_plugins(load=False) if i.status == "ok"]
    found = None
    tb = exc.__traceback__
    while tb is not None:
        module = str(tb.tb_frame.f_globals.get("__name__", ""))
        code = tb.tb_frame.f_code
        outer = str(getattr(code, "co_qualname", code.co_name)).split(".")[0]  # Ball.__init__
        mine = [i for i in infos if (module + ".").startswith(i.value.partition(":")[0] + ".")]
        if mine:  # the entry point named in the frame first (a module may hold several)
            exact = [i for i in mine if i.value.rpartition(":")[2].split(".")[0] == outer]
            found = (exact or mine)[0]
        tb = tb.tb_next
    return None if found is None else PluginError(exit_message(f"lgraph: {found.who}", exc))


def _short(exc: BaseException) -> str:
    """``ModuleNotFoundError: No module named 'x'``, ``SystemExit: 3``: one line."""
    text = str(exc).splitlines()[0] if str(exc) else ""
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
