"""Scene files: a TOML description of a scene, rendered by ``lgraph render``.

Nothing in a scene file is ever evaluated as Python: surfaces and families
are looked up by registry name (:mod:`lgraph.plugins`), surfaces and curves
of your own are written as formulas in lgraph's own expression language
(:mod:`lgraph.formula`, :doc:`/scene_files`), a string where a number is
expected is such a formula of the file's constants (``"2*pi"``), and every
value is checked before anything is built.  The whole
file is validated before :func:`~lgraph.load_scene_file` returns, so a partially
valid file renders nothing.  Every problem of a file is reported at once:
:class:`SceneFileError` has one line per problem naming the file, the line
and the key::

    scene.toml:9: object[0].params.a: unknown name 'w'; ... at column 3 of 'w'
    scene.toml:14: save.dpi: unknown option 'dpi' for .pdf output; allowed: ...

The format::

    [projector]                  # parallel: direction = [x, y, z] or azimuth/elevation
    kind = "central"             # central: eye (+ target) or azimuth/elevation/distance
    eye = [9, -7, 6]
    target = [0, 0, 0]

    [page]                       # optional: width/height/margin in pt, or preset = "a4"
    preset = "a4"
    landscape = true

    [render]                     # optional: keyword arguments of Scene.render
    hidden_lines = true
    tolerance = 1e-4
    hidden_style = { color = "#808080", width = 0.3, dash = [2, 1.5] }  # or per family:
                                 # hidden_style = { contour = {...}, default = {...} }
    max_occlusion = 1            # draw hidden parts behind one sheet only

    [save]                       # optional: options of the backend chosen by the output
    title = "Ellipsoid"          # suffix (.pdf: compress, precision, title; .png: dpi,
                                 # size, supersample; .svg: precision, layers; plugins: their own)
    width = "8.5cm"              # physical size of the figure (any format): pt, mm, cm, in;
                                 # and/or height = "6cm" (both: fit inside, aspect kept)

    [constants]                  # optional: names for the formulas and numbers below
    R = 1.3                      # a number, or a formula of the constants above it
    top = "2*R"

    [[object]]                   # one table per surface
    surface = "ellipsoid"
    params = { a = 3, b = 2, c = "R" }
    families = [{ name = "lines_of_curvature", n1 = 14, n2 = 18 }, "contour"]
    transform = [{ translate = [0, 0, 0] }, { rotate = { axis = "z", degrees = 30 } },
                 { scale = 2 }]  # applied in the order listed
    style = { color = "#000000", width = 0.5 }   # or per family: style.contour = {...}
    contour = true               # draw the contour (default true)
    hides = true                 # hide what lies behind (default true)
    intersections = true         # draw where it cuts other surfaces (default true)

    [[object]]                   # a surface of formulas: x, y, z of u and v
    surface = "parametric"       # (or "revolution": rho, z of t; t; axis; angle)
    x = "(7.5 + v*cos(u/2)) * cos(u)"
    y = "(7.5 + v*cos(u/2)) * sin(u)"
    z = "v*sin(u/2)"
    u = [0, "2*pi"]              # the parameter ranges
    v = [-0.6, 0.6]              # also periodic = [true, false] ("twisted" too), poles = ...
    families = [{ name = "parameter_lines", n1 = 24, n2 = 4 }]

    [[curve]]                    # a free curve: x, y, z of t; t; closed, style, transform
    x = "7.5*cos(t)"
    y = "7.5*sin(t)"
    z = "0"
    t = [0, "2*pi"]
    closed = true

    [[labels]]                   # text at a 3-D point, hidden like the lines
    text = '$\\mathbf{p} = (0, 0, 2c)$'   # $...$ is TeX; in '...' a backslash is itself
    at = [0, 0, "top"]           # the top of the ellipsoid as transformed above
    anchor = "sw"                # center, n, ne, e, se, s, sw, w, nw (TikZ's meaning)
    offset = [2, 2]              # pt; also size (pt), color, always

    [[points]]                   # a dot at a 3-D point: at, size (pt), color, always
    at = [0, 0, "top"]

    [[group]]                    # a sub-scene: its members move with its transform,
    transform = [{ translate = [0, -5, 0] }]  # and take its style unless they set one
    style = { color = "#0033cc" }
    [[group.object]]             # members: object, labels, points and group tables
    surface = "sphere"           # (groups nest to any depth)
    params = { r = 1 }

Every table and key:

==============  ========================================================================
table           keys
==============  ========================================================================
``projector``   ``kind`` (``"parallel"`` or ``"central"``, required); parallel:
                ``direction`` (3 numbers, toward the viewer) or ``azimuth`` and
                ``elevation`` (degrees), ``up`` (with ``direction``); central: ``eye``
                and ``target`` (3 numbers each) or ``azimuth``, ``elevation`` and
                ``distance``, ``up`` (with ``eye``).  Required.
``page``        ``preset`` (``"a4"``, ``"a5"``, ``"letter"``) with ``landscape`` and
                ``margin``; or ``width`` and ``height`` (pt, both), ``margin``,
                ``extent``.  Optional: the default crops the page to the figure.
``render``      ``hidden_lines`` (bool), ``tolerance`` (1e-9 to 0.1 of the figure's
                diagonal), ``hidden_style`` (a style table, or one per family name
                with ``default`` for the rest), ``max_occlusion`` (hidden parts
                behind more sheets are not drawn), ``intersections`` (bool,
                default true: draw where surfaces cut each other).  Optional.
``save``        ``width``, ``height`` (a physical size such as ``"8.5cm"``, any format)
                and the options of the output's backend (see
                :func:`lgraph.output.backends.backend_options`).  Optional.
``constants``   names and their values: numbers or formulas of the constants above
                (the formulas' variables ``u v t x y z``, the functions, ``pi`` and
                ``e`` are no names).  Optional.
``[[object]]``  ``surface`` (a registry name, ``lgraph plugins`` lists them, required),
                ``params`` (the surface's parameters by name: numbers or arrays of
                numbers), ``families`` (names, or tables with ``name`` and the
                family's parameters; default the surface's own, ``["parameter_lines"]``
                for most, none for an ``arrow``: its outline), ``transform``
                (an array of ``{ translate = [x, y, z] }``, ``{ rotate = { axis =
                "x" | "y" | "z" | [x, y, z], degrees = d } }``, ``{ scale = s | [sx,
                sy, sz] }``), ``style`` (a style table, or one per family name with
                ``default`` for the rest), ``contour``, ``hides`` and
                ``intersections`` (bools).  ``surface = "parametric"``: instead
                of ``params`` the formulas ``x``, ``y``, ``z`` of ``u, v``, the
                ranges ``u`` and ``v``, ``periodic``, ``poles``;
                ``surface = "revolution"``: ``rho`` and ``z`` of ``t``, the range
                ``t``, ``axis``, ``angle`` (a range).  ``level_lines`` takes a
                ``function`` formula of ``x, y, z`` (of ``u, v`` with ``argument =
                "uv"``).
``[[curve]]``   ``x``, ``y``, ``z`` (formulas of ``t``) and ``t`` (a range, required),
                ``closed``, ``style``, ``transform``.
``[[labels]]``  ``text`` and ``at`` (required), ``offset``, ``anchor``, ``size``,
                ``color``, ``always``.
``[[points]]``  ``at`` (required), ``size``, ``color``, ``always``.
``[[group]]``   ``transform``, ``style`` and members: ``object``, ``curve``,
                ``labels``, ``points`` and ``group`` tables (nested to any depth).
style table     ``color`` (``"#rrggbb"``, a name or 3 numbers in [0, 1]), ``width``
                (pt), ``dash`` (an array of on/off lengths in pt).
==============  ========================================================================

TOML is read with :mod:`!tomllib` (Python >= 3.11); on Python 3.10 with the
``tomli`` package (a dependency of lgraph there).  The file is UTF-8, with or
without a byte-order mark.

>>> import tempfile, os
>>> text = '''
... [projector]
... kind = "parallel"
... azimuth = 30
... elevation = 20
... [[object]]
... surface = "sphere"
... params = { r = 1 }
... families = [{ name = "parameter_lines", n1 = 4, n2 = 8 }]
... '''
>>> with tempfile.TemporaryDirectory() as tmp:
...     path = os.path.join(tmp, "s.toml")
...     with open(path, "w") as f:
...         _ = f.write(text)
...     scene, projector, options = load_scene_file(path)
>>> len(scene), type(projector).__name__, options
(1, 'ParallelProjector', {'render': {}, 'save': {}})
"""

from __future__ import annotations

import os
import re
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ._errors import _Invalid
from ._locate import _key_text, _Locator  # noqa: F401 - _Locator: used by tests
from ._members import _OBJECT  # noqa: F401 - the format's keys
from ._output import SceneFileWarning
from ._schema import _TOP, parse_scene  # noqa: F401 - the format's keys
from ._values import _STYLE  # noqa: F401 - the format's keys

__all__ = ["load_scene_file", "parse_scene", "SceneFileError", "SceneFileWarning"]

#: the largest scene file read (bytes), checked before reading it
MAX_SCENE_FILE_BYTES = 1_000_000


class SceneFileError(Exception):
    """A scene file that cannot be rendered; the message has one line per
    problem, ``file:line: key: what is wrong``.  ``path``, ``line`` and
    ``key`` are those of the first problem; ``errors`` lists every problem as
    ``(line, key, message)``."""

    def __init__(
        self,
        message: str,
        *,
        path: str = "",
        line: int | None = None,
        key: str = "",
        errors: list[tuple[int | None, str, str]] | None = None,
    ):
        super().__init__(message)
        self.path = path
        self.line = line
        self.key = key
        self.errors = errors if errors is not None else [(line, key, message)]


# -- entry point -----------------------------------------------------------------------
def _toml() -> Any:
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10: the tomli package, if installed
        try:
            import tomli as tomllib  # type: ignore[no-redef]
        except ModuleNotFoundError:
            raise SceneFileError(
                "reading scene files needs Python >= 3.11 or the 'tomli' package"
            ) from None
    return tomllib


def _readable(text: str, limit: int) -> str:
    r"""``text`` for a message: control and other unprintable characters
    escaped (a terminal shows them, it does not obey them), cut to ``limit``
    characters.

    >>> _readable("red" + chr(27) + "[31m" + "x" * 50, 20)
    'red\\x1b[31mxxxx... (61 characters)'
    """
    if not text.isprintable():
        text = "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)
    if len(text) > limit:
        text = f"{text[: limit - 5]}... ({len(text)} characters)"
    return text


def load_scene_file(
    path: str | os.PathLike[str],
    output: str | os.PathLike[str] | Sequence[str | os.PathLike[str]] | None = None,
) -> tuple[Any, Any, dict[str, Any]]:
    """Read and validate a TOML scene file.

    ``output`` is the file the figure will be written to (default: the scene
    file with suffix ``.pdf``): its suffix chooses the backend whose options
    ``[save]`` may give.  A sequence of files is several outputs of one
    rendering: an option that none of their backends takes is an error, one
    that only some take is left out for the others with a
    ``SceneFileWarning`` (a ``UserWarning``), e.g. ``scene.toml:12:
    save.title: not an option of the .png backend; ignored for fig.png``.

    Returns
    -------
    scene : Scene
    projector : Projector
    options : dict
        ``{"render": kwargs of Scene.render (hidden_lines, tolerance, page,
        hidden_style), "save": kwargs of Drawing.save (dpi, ...)}``; for a
        sequence of outputs, ``"save"`` is a list with the kwargs of each
        output, in the order given.

    Raises
    ------
    SceneFileError
        With one line ``file:line: key: problem`` per problem found (all of
        them).  Nothing is built for a file with any problem.
    ValueError
        For an empty sequence of outputs.
    """
    from ._output import _SaveOutputs

    several = not (output is None or isinstance(output, (str, os.PathLike)))
    outputs: list[Any] = list(output) if several else [output]
    if not outputs:
        raise ValueError("load_scene_file: output: expected one or more files, got none")
    suffixes = [Path(o).suffix if o is not None else ".pdf" for o in outputs]
    tomllib = _toml()
    shown = _readable(str(path), 300)
    try:
        size = os.path.getsize(path)
        if size > MAX_SCENE_FILE_BYTES:  # before reading: tomllib takes ~3 s per MB
            raise SceneFileError(
                f"{shown}: the scene file has {size} bytes, at most {MAX_SCENE_FILE_BYTES} "
                "(MAX_SCENE_FILE_BYTES): a scene is a few tables, not data",
                path=shown,
            )
        text = Path(path).read_text(encoding="utf-8-sig")  # a BOM is fine
    except (OSError, UnicodeDecodeError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise SceneFileError(f"{shown}: cannot read the scene file: {reason}", path=shown) from None
    try:
        data = tomllib.loads(text)
    except RecursionError:
        raise SceneFileError(
            f"{shown}: invalid TOML: arrays or tables nested too deeply", path=shown
        ) from None
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc)
        m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
        line = int(m.group(1)) if m else None
        reason = re.sub(r"\s*\(at line \d+, column \d+\)", "", msg)
        near = ""
        if line is not None:
            src = text.splitlines()[line - 1].strip() if line <= len(text.splitlines()) else ""
            km = re.match(r"\[*\s*([\w.\-\"']+)", src)
            near = f"{km.group(1)}: " if km else ""
            src_short = src if len(src) <= 50 else src[:47] + "..."
            reason = f"{reason} in {src_short!r}" if src else reason
        loc = f"{shown}:{line}" if line else shown
        raise SceneFileError(
            f"{loc}: {near}invalid TOML: {reason}", path=shown, line=line, key=near.rstrip(": ")
        ) from None
    try:
        # several outputs: _save (_output.py) checks [save] against all their backends
        suffix: Any = tuple(suffixes) if several else suffixes[0]
        scene, projector, options = parse_scene(data, suffix)
    except RecursionError:
        raise SceneFileError(f"{shown}: values nested too deeply", path=shown) from None
    except _Invalid as exc:
        locator = _Locator(text)
        errors = []
        for e in [exc, *exc.more]:
            line = locator.line_of(e.key)
            key = _readable(_key_text(e.key), 80)
            errors.append((line, key, _readable(" ".join(e.message.split()), 300)))
        errors.sort(key=lambda e: (e[0] is None, e[0] or 0))
        lines = []
        for line, key, message in errors:
            loc = f"{shown}:{line}" if line else shown
            lines.append(f"{loc}: {key}: {message}" if key else f"{loc}: {message}")
        first = errors[0]
        raise SceneFileError(
            "\n".join(lines), path=shown, line=first[0], key=first[1], errors=errors
        ) from None
    if several:
        save = options.get("save")
        per = save if isinstance(save, _SaveOutputs) else _SaveOutputs([{} for _ in outputs])
        if per.ignored:
            locator = _Locator(text)
            for k, i in per.ignored:
                line = locator.line_of(k)
                loc = f"{shown}:{line}" if line else shown
                warnings.warn(
                    f"{loc}: {_key_text(k)}: not an option of the {suffixes[i].lower()} "
                    f"backend; ignored for {outputs[i]}",
                    SceneFileWarning,
                    stacklevel=2,
                )
        options = {**options, "save": per.options}
    return scene, projector, options
