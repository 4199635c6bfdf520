"""Scene-file tables read by cattrs vs our hand-written checks (issue 12).

Run:  python benchmarks/bench_scenefile_cattrs.py [--repeat 7] [--n 2000]

A prototype reads the ``[[labels]]``, ``[[points]]`` and ``[page]`` tables
with ``cattrs`` (attrs spec classes, ``forbid_extra_keys``,
``detailed_validation``, strict hooks so that a string or a bool is never
taken for a number), and turns cattrs' exception groups into our
``(key, message)`` problems, which the scene file's locator then places on a
line.  Compared with ``lgraph.scenefile``: the messages for the same bad
tables, how many problems each reports, the time to read ``n`` labels and
points, and the lines of code each needs.  Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import inspect
import statistics
import sys
import time
from typing import Any

import attrs

# -- the cattrs prototype -----------------------------------------------------------------
STRICT = {float: "a number", int: "an integer", bool: "true or false", str: "a string"}


def converter() -> Any:
    import math

    import cattrs

    from lgraph.scenefile._locate import _show

    conv = cattrs.Converter(forbid_extra_keys=True, detailed_validation=True)

    def strict(tp: type) -> Any:
        def hook(v: Any, _: Any) -> Any:
            ok = isinstance(v, tp) and not (tp in (int, float) and isinstance(v, bool))
            if tp is float and isinstance(v, int) and not isinstance(v, bool):
                ok, v = True, float(v)
            if not ok:
                raise ValueError(f"expected {STRICT[tp]}, got {_show(v)}")
            if tp is float and not math.isfinite(v):
                raise ValueError(f"expected a finite number, got {v!r}")
            return v

        return hook

    for tp in STRICT:
        conv.register_structure_hook(tp, strict(tp))

    def color(v: Any, _: Any) -> Any:
        if isinstance(v, str):
            return v
        if isinstance(v, list) and len(v) == 3:
            return tuple(conv.structure(x, float) for x in v)
        raise ValueError(f"expected a colour '#rrggbb', a name or [r, g, b], got {_show(v)}")

    conv.register_structure_hook(Color, color)
    return conv


class Color:  # marker type: a colour string or [r, g, b]
    pass


@attrs.define
class LabelSpec:
    text: str
    at: tuple[float, float, float]
    offset: tuple[float, float] = (0.0, 0.0)
    anchor: str = "center"
    size: float = 10.0
    color: Color | None = None
    always: bool = False


@attrs.define
class PointSpec:
    at: tuple[float, float, float]
    size: float = 3.0
    color: Color | None = None
    always: bool = False


@attrs.define
class PageSpec:
    width: float | None = None
    height: float | None = None
    margin: float = 18.0
    extent: float = 500.0


def problems(exc: BaseException, key: tuple) -> list[tuple[tuple, str]]:
    """cattrs' exception group -> our ``(key, message)`` problems."""
    from cattrs.errors import (
        AttributeValidationNote,
        ClassValidationError,
        ForbiddenExtraKeysError,
        IterableValidationError,
    )

    out: list[tuple[tuple, str]] = []
    if isinstance(exc, ForbiddenExtraKeysError):
        return [(key + (k,), f"unknown key {k!r}") for k in sorted(exc.extra_fields)]
    if isinstance(exc, (ClassValidationError, IterableValidationError)):
        with_notes, without = exc.group_exceptions()
        for sub, note in with_notes:
            step = note.name if isinstance(note, AttributeValidationNote) else note.index
            if isinstance(sub, KeyError):
                out.append((key, f"missing required key {step!r}"))
            else:
                out += problems(sub, key + (step,))
        for sub in without:
            out += problems(sub, key)
        return out
    return [(key, str(exc))]


def read_cattrs(conv: Any, data: dict, out: list) -> list:
    """Build Label and Point objects of ``data``; problems go to ``out``."""
    import lgraph as lg

    built = []
    for name, spec in (("labels", LabelSpec), ("points", PointSpec)):
        for k, t in enumerate(data.get(name, [])):
            key = (name, k)
            try:
                s = conv.structure(t, spec)
            except Exception as exc:
                out += problems(exc, key)
                continue
            try:
                if spec is LabelSpec:
                    kw = attrs.asdict(s)
                    built.append(lg.Label(kw.pop("text"), **kw))
                else:
                    style = None if s.color is None else lg.Style(color=s.color)
                    built.append(lg.Point(s.at, size=s.size, style=style, always=s.always))
            except (ValueError, TypeError) as exc:
                out.append((key, str(exc)))
    if "page" in data:
        try:
            s = conv.structure(data["page"], PageSpec)
            built.append(lg.Page(**attrs.asdict(s)))
        except Exception as exc:
            out += problems(exc, ("page",))
    return built


def read_ours(data: dict, out: list) -> list:
    from lgraph.scenefile._errors import _Collect
    from lgraph.scenefile._members import _label, _point
    from lgraph.scenefile._output import _page

    check = _Collect()
    built = [check(_label, ("labels", k), t) for k, t in enumerate(data.get("labels", []))]
    built += [check(_point, ("points", k), t) for k, t in enumerate(data.get("points", []))]
    if "page" in data:
        built.append(check(_page, ("page",), data["page"]))
    for e in check.errors:
        out.append((e.key, e.message))
    return built


BAD = {
    "labels": [
        {"text": "P", "at": [1, "2", 3], "size": True},
        {"text": 5, "at": [0, 0, 0], "ofset": [1, 1], "colour": "red"},
        {"at": [0, 0, 0], "always": "yes"},
        {"text": "$x", "at": [0, 0, 0]},
    ],
    "points": [{"at": [0, 0], "size": "3"}],
    "page": {"width": "400", "height": 300, "margn": 1},
}


def lines_of(*funcs: Any) -> int:
    return sum(len(inspect.getsource(f).splitlines()) for f in funcs)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--n", type=int, default=2000)
    args = parser.parse_args(argv)
    from lgraph.scenefile import _members, _output, _values

    conv = converter()
    mine: list = []
    theirs: list = []
    read_ours(BAD, mine)
    read_cattrs(conv, BAD, theirs)
    print("problems found in the bad tables\n")
    print("| reader | key | message |\n|---|---|---|")
    for who, found in (("lgraph", mine), ("cattrs", theirs)):
        for key, msg in found:
            print(f"| {who} | {'.'.join(map(str, key))} | {msg} |")
    good = {
        "labels": [
            {"text": f"$P_{{{k}}}$", "at": [k, 0, 1], "offset": [2, 2], "anchor": "sw", "size": 9}
            for k in range(args.n)
        ],
        "points": [{"at": [k, 1, 0], "size": 2, "color": [0, 0, 1]} for k in range(args.n)],
        "page": {"width": 400, "height": 300, "margin": 12},
    }
    import lgraph as lg

    def direct() -> list:  # the objects alone, from clean keyword arguments
        built = [lg.Label(t["text"], **{k: v for k, v in t.items() if k != "text"})
                 for t in good["labels"]]  # fmt: skip
        built += [lg.Point(t["at"], size=t["size"], style=lg.Style(color=t["color"]))
                  for t in good["points"]]  # fmt: skip
        return built + [lg.Page(**good["page"])]

    times: dict[str, list[float]] = {"lgraph": [], "cattrs": [], "objects alone": []}
    for _ in range(args.repeat):  # alternate, so that load changes hit all three
        for who in times:
            out: list = []
            t0 = time.perf_counter()
            if who == "lgraph":
                built = read_ours(good, out)
            elif who == "cattrs":
                built = read_cattrs(conv, good, out)
            else:
                built = direct()
            times[who].append(time.perf_counter() - t0)
            assert not out and len(built) == 2 * args.n + 1, (who, out[:3])
    proto = lines_of(converter, Color, LabelSpec, PointSpec, PageSpec, problems, read_cattrs)
    ours = lines_of(_members._label, _members._point, _members._color_value, _output._page)
    ours += lines_of(_values._number, _values._string, _values._boolean, _values._only)
    print(f"\nreading {args.n} labels + {args.n} points + a page, median of {args.repeat}:\n")
    base = statistics.median(times["objects alone"])
    print("| reader | time | of which checking | lines of code (these tables) |")
    print("|---|---|---|---|")
    for who, n_lines in (("lgraph", ours), ("cattrs", proto)):
        t = statistics.median(times[who])
        print(f"| {who} | {t * 1e3:.1f} ms | {(t - base) * 1e3:.1f} ms | {n_lines} |")
    print(f"| objects alone | {base * 1e3:.1f} ms | | |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
