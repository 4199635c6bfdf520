"""Command line: ``lgraph demo | render | gallery | plugins``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

__all__ = ["main", "demo_scene"]


def demo_scene():  # noqa: ANN201
    """The figure of ``lgraph demo``: the paper's Figure 7.2, the lines of
    curvature of a triaxial ellipsoid (as ``gallery/fig_7_2_ellipsoid.py``)."""
    import lgraph as lg

    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(14, 18))
    return scene.render(lg.CentralProjector.from_angles(35, 25, 16))


def _demo(args: argparse.Namespace) -> int:
    out = Path(args.outdir)
    drawing = demo_scene()
    for suffix in (".pdf", ".png"):
        path = drawing.save(out / f"lgraph-demo{suffix}")
        print(f"wrote {path.resolve()}")
    return 0


def _render(args: argparse.Namespace) -> int:
    from .scenefile import SceneFileError, load_scene_file

    try:
        scene, projector, options = load_scene_file(args.scene)
    except SceneFileError as e:
        print(f"lgraph render: {e}", file=sys.stderr)
        return 2
    drawing = scene.render(projector, **options.get("render", {}))
    out = args.output or str(Path(args.scene).with_suffix(".pdf"))
    save = dict(options.get("save", {}))
    for name in ("width", "height"):  # the command line wins over the scene file
        if getattr(args, name, None) is not None:
            save[name] = args.__dict__[name]
    if args.plotter:  # tolerances on the page as saved
        drawing = drawing.for_plotter(width=save.get("width"))
    path = drawing.save(out, **save)
    print(f"wrote {Path(path).resolve()}")
    return 0


def _gallery(args: argparse.Namespace) -> int:
    from .gallery import build_gallery

    return build_gallery(args.outdir, jobs=args.jobs, only=args.only)


def _plugins(args: argparse.Namespace) -> int:
    from .plugins import describe_plugins

    print(describe_plugins())
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="lgraph",
        description="Print-quality line graphics of mathematical surfaces "
        "with exact hidden-line removal.",
    )
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    d = sub.add_parser("demo", help="write lgraph-demo.pdf and lgraph-demo.png")
    d.add_argument("outdir", nargs="?", default=".", help="folder to write into (default: .)")
    d.set_defaults(func=_demo)
    r = sub.add_parser("render", help="render a TOML scene file")
    r.add_argument("scene", help="scene file (.toml)")
    r.add_argument(
        "-o", "--output", help="output file (.pdf, .png, .svg); default: scene name .pdf"
    )
    r.add_argument("--width", help="figure width, e.g. 8.5cm, 85mm, 3.3in, 240pt")
    r.add_argument("--height", help="figure height (with --width: fit inside, aspect kept)")
    r.add_argument(
        "--plotter",
        action="store_true",
        help="clean for a pen plotter: merge paths, drop duplicates and fragments, "
        "sort for short pen-up travel (Drawing.for_plotter)",
    )
    r.set_defaults(func=_render)
    g = sub.add_parser("gallery", help="build every gallery figure (PDF + PNG) and index.html")
    g.add_argument("outdir", help="output folder (created if missing)")
    g.add_argument("-j", "--jobs", type=int, default=None, help="worker processes")
    g.add_argument(
        "--only", nargs="*", default=None, help="only figures whose name contains one of these"
    )
    g.set_defaults(func=_gallery)
    pl = sub.add_parser("plugins", help="list installed plugins")
    pl.set_defaults(func=_plugins)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    from .plugins import PluginError

    try:
        return int(args.func(args) or 0)
    except (ValueError, TypeError, OSError, NotImplementedError, PluginError) as e:
        print(f"lgraph {args.command}: error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
