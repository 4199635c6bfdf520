"""The structure of a scene file: its top-level tables, members and groups.

:func:`parse_scene` checks the top-level tables and builds the scene from its
members (``[[object]]``, ``[[labels]]``, ``[[points]]``, ``[[group]]``,
groups nested to any depth), collecting every problem; the tables themselves
are read in ``_members.py`` (objects, labels, points) and ``_output.py``
(projector, page, render, save).  No formula of docs/mathematics.rst.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ._errors import Key, _Collect, _Invalid
from ._formulas import curve, read_constants
from ._members import _label, _object, _point
from ._output import _page, _projector, _render, _save
from ._values import _only, _required, _styles, _table, _transform, constants_of

_TOP = (
    "projector",
    "constants",
    "object",
    "curve",
    "labels",
    "points",
    "group",
    "page",
    "render",
    "save",
)


_MEMBERS = ("object", "curve", "labels", "points", "group")


def parse_scene(
    data: Mapping[str, Any], suffix: str | Sequence[str] = ".pdf"
) -> tuple[Any, Any, dict[str, Any]]:
    """Build ``(scene, projector, options)`` from parsed TOML ``data``.

    ``suffix`` is that of the output file (or those of several): ``[save]``
    keys are checked against the options of its backend (an option that only
    some of several backends take is kept for those).  ``[constants]`` are
    read first: every formula and number of the file may use them.  Raises ``_Invalid`` (with the
    offending key, and every further problem in ``more``) when anything is
    wrong; nothing is rendered here.
    """

    check = _Collect()
    check(_only, (), data, _TOP)
    constants = {}
    if "constants" in data:
        constants = check(read_constants, ("constants",), data["constants"], default={})
    with constants_of(constants):
        return _parse(data, suffix, check)


def _parse(
    data: Mapping[str, Any], suffix: str | Sequence[str], check: _Collect
) -> tuple[Any, Any, dict[str, Any]]:
    projector = check(lambda: _projector(("projector",), _required((), data, "projector")))
    if not any(k in data for k in _MEMBERS):
        check(_required, (), data, "object")
    scene = _members((), data, check)
    render: dict[str, Any] = {}
    if "render" in data:
        render = check(
            lambda: _render(("render",), _table(("render",), data["render"])), default={}
        )
    if "page" in data:
        page = check(lambda: _page(("page",), _table(("page",), data["page"])))
        if page is not None:
            render["page"] = page
    if projector is not None:
        for k, node in enumerate(scene):
            check(_in_front, ("projector",), projector, node, k)
    save: dict[str, Any] = {}
    if "save" in data:
        save = check(lambda: _save(("save",), _table(("save",), data["save"]), suffix), default={})
    check.raise_all()
    return scene, projector, {"render": render, "save": save}


def _array_of_tables(key: Key, v: Any, name: str) -> list[dict[str, Any]]:
    if not isinstance(v, list) or not v:
        raise _Invalid(key, f"expected one or more [[{name}]] tables")
    return [_table(key + (k,), t) for k, t in enumerate(v)]


def _members(key: Key, table: Mapping[str, Any], check: _Collect | None = None) -> Any:
    """A scene of the ``object``, ``labels``, ``points`` and ``group`` tables in
    ``table``; with ``check``, every problem is recorded there and the members
    that are fine are built (otherwise the first problem is raised)."""
    import lgraph as lg

    own = check is None
    check = _Collect() if check is None else check
    scene = lg.Scene()
    objects = (
        check(_array_of_tables, key + ("object",), table["object"], "object", default=[])
        if "object" in table
        else []
    )
    for k, obj in enumerate(objects):
        ok = key + ("object", k)
        built = check(_object, ok, obj, check)
        if built is None:
            continue
        item, families, kw = built
        check(_add, ok, scene, item, kw, families)
    if "curve" in table:
        tables = check(_array_of_tables, key + ("curve",), table["curve"], "curve", default=[])
        for k, t in enumerate(tables):
            built = check(curve, key + ("curve", k), t)
            if built is not None:
                check(_add, key + ("curve", k), scene, built[0], built[1])
    for name, build in (("labels", _label), ("points", _point)):
        if name in table:
            tables = check(_array_of_tables, key + (name,), table[name], name, default=[])
            for k, t in enumerate(tables):
                member = check(build, key + (name, k), t)
                if member is not None:
                    scene.add(member)
    if "group" in table:
        groups = check(_array_of_tables, key + ("group",), table["group"], "group", default=[])
        for k, g in enumerate(groups):
            check(_group, key + ("group", k), g, scene, check)
    if own:
        check.raise_all()
    return scene


def _add(key: Key, scene: Any, item: Any, kw: dict[str, Any], families: Any = ()) -> None:
    try:
        scene.add(item, *families, **kw)
    except (TypeError, ValueError) as exc:
        raise _Invalid(key, str(exc)) from None


def _group(gk: Key, g: dict[str, Any], scene: Any, check: _Collect) -> None:
    _only(gk, g, ("transform", "style") + _MEMBERS)
    if not any(m in g for m in _MEMBERS):
        raise _Invalid(gk, "a group needs members: object, curve, labels, points or group tables")
    kw: dict[str, Any] = {}
    if "transform" in g:
        kw["transform"] = _transform(gk + ("transform",), g["transform"])
    if "style" in g:
        kw["style"] = _styles(gk + ("style",), g["style"])
    scene.add(_members(gk, g, check), **kw)


def _in_front(key: Key, projector: Any, node: Any, k: int) -> None:
    """A central projector's eye must see every object in front of it: checked
    on a 17 x 17 grid of each surface before any rendering (the renderer
    checks every sample again)."""
    import numpy as np

    import lgraph as lg

    surface = node.surface
    if not isinstance(projector, lg.CentralProjector) or surface is None:
        return
    if not getattr(surface, "parametric", True):  # an implicit surface: points of F = 0
        x = node.transform.apply(surface.sample_points())
    else:
        d = surface.domain
        g = [np.linspace(*d.range(i), 17) for i in (0, 1)]
        u1, u2 = np.meshgrid(*g, indexing="ij")
        with np.errstate(all="ignore"):
            x = node.transform.apply(np.asarray(surface.point(u1, u2), float).reshape(-1, 3))
    x = x[np.isfinite(x).all(axis=1)]
    if len(x) and (projector.depth(x) <= 0).any():
        raise _Invalid(
            key + ("eye",),
            f"object[{k}] ({surface!r}) lies partly at or behind the eye "
            f"{projector.eye.tolist()}; move the eye farther away",
        )
