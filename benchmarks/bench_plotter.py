"""Pen-up travel and path counts of every gallery figure: lgraph's ``for_plotter``
against vpype's ``linemerge linesort`` (and ``linesort --two-opt``) on the same SVG.

Run on demand (needs vpype: ``pip install vpype``)::

    python benchmarks/bench_plotter.py [--only NAME ...]

Both sides are measured by vpype itself: the figure is saved as a layered SVG
200 mm wide (one layer per family), then

* vpype: ``read fig.svg linemerge linesort`` (vpype's defaults: merge tolerance
  0.05 mm, greedy nearest-neighbour sort with path reversal), and the same with
  ``linesort --two-opt``;
* lgraph: ``drawing.for_plotter(merge="0.05mm", width="200mm")`` saved the same way, then
  ``read clean.svg``;

and the pen-up length is the sum over layers of vpype's ``pen_up_length``.
Times are wall-clock seconds of one run in this process.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

PX_PER_MM = 96 / 25.4


def measure(doc) -> tuple[float, int]:  # noqa: ANN001
    """Pen-up length (mm) and path count of a vpype document."""
    travel = sum(layer.pen_up_length()[0] for layer in doc.layers.values())
    return travel / PX_PER_MM, sum(len(layer) for layer in doc.layers.values())


def main() -> int:
    import vpype_cli

    from lgraph.gallery import discover_scripts, render_figure

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", default=None)
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for script in discover_scripts():
            name = script.stem
            if args.only and not any(o in name for o in args.only):
                continue
            import importlib.util

            spec = importlib.util.spec_from_file_location(name, script)
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            drawing = render_figure(module.build())
            raw = Path(tmp) / f"{name}.svg"
            drawing.save(raw, width="200mm")
            t = time.perf_counter()
            clean = drawing.for_plotter(merge="0.05mm", width="200mm")
            t_lgraph = time.perf_counter() - t
            clean_svg = Path(tmp) / f"{name}-clean.svg"
            clean.save(clean_svg, width="200mm")
            before = measure(vpype_cli.execute(f"read {raw}"))
            t = time.perf_counter()
            vp = measure(vpype_cli.execute(f"read {raw} linemerge linesort"))
            t_vpype = time.perf_counter() - t
            vp2 = measure(vpype_cli.execute(f"read {raw} linemerge linesort --two-opt"))
            ours = measure(vpype_cli.execute(f"read {clean_svg}"))
            rows.append((name, before, vp, vp2, ours, t_lgraph, t_vpype))
            print(
                f"{name}: paths {before[1]} -> vpype {vp[1]} / lgraph {ours[1]}; pen-up mm "
                f"{before[0]:.0f} -> vpype {vp[0]:.0f} (2-opt {vp2[0]:.0f}) / lgraph {ours[0]:.0f}"
                f"  [{t_lgraph:.2f} s / {t_vpype:.2f} s]",
                flush=True,
            )
    print()
    print("| figure | paths | vpype paths | lgraph paths | pen-up mm | vpype | vpype 2-opt "
          "| lgraph | lgraph / vpype |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|---|")
    for name, before, vp, vp2, ours, _, _ in rows:
        ratio = ours[0] / vp[0] if vp[0] else float("nan")
        print(f"| {name} | {before[1]} | {vp[1]} | {ours[1]} | {before[0]:.0f} | {vp[0]:.0f} "
              f"| {vp2[0]:.0f} | {ours[0]:.0f} | {ratio:.2f} |")  # fmt: skip
    worse = [r[0] for r in rows if r[4][0] > r[2][0] * (1 + 1e-9)]
    print(f"\nlgraph's travel exceeds vpype's on: {worse or 'none'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
