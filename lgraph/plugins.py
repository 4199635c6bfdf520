"""Registries of surfaces, line families and output backends, and plugin discovery.

lgraph's own classes and those of installed plugins are found the same way:
by name.  A plugin is a separately installed distribution that declares entry
points in one of three groups::

    [project.entry-points."lgraph.surfaces"]
    cyclide = "lgraph_cyclide:DupinCyclide"      # a Surface subclass

    [project.entry-points."lgraph.families"]
    diagonal_lines = "lgraph_cyclide:DiagonalLines"   # a Family subclass

    [project.entry-points."lgraph.backends"]
    hpgl = "lgraph_hpgl:write_hpgl"               # writer(drawing, path, **options)

Discovery is lazy: ``import lgraph`` scans nothing; the first lookup of a
kind (:func:`get_surface`, :func:`get_family`, a file suffix that
``Drawing.save`` does not know, ``lgraph plugins``) reads the entry-point
metadata of that group, and a plugin's module is imported only when one of
its names is used.  A plugin that fails to import (an exception, or
``sys.exit()``) or is not callable becomes a stand-in: the failure is reported
once (:class:`PluginWarning`); using it raises :class:`PluginError` with the
original traceback, as does a factory calling ``sys.exit()``.  It never
breaks lgraph or other plugins.  Two plugins claiming the same name, or a plugin
claiming a built-in name, are reported with a warning that names both
distributions; the first one found (``sys.path`` order) or the built-in wins.

>>> get_surface("ellipsoid").__name__
'Ellipsoid'
>>> get_family("parameter_lines").__name__
'ParameterLines'
>>> get_surface("ellipsiod")
Traceback (most recent call last):
...
KeyError: "unknown surface 'ellipsiod'; known: ..."
"""

from __future__ import annotations

import re
import threading
import traceback
import warnings
from collections.abc import Callable, Iterable
from typing import Any

from .output._atomic import no_exit

__all__ = [
    "GROUPS",
    "PluginError",
    "PluginWarning",
    "PluginInfo",
    "get_surface",
    "surface_names",
    "register_surface",
    "get_family",
    "family_names",
    "load_backends",
    "installed_plugins",
    "describe_plugins",
    "snake_case",
]

#: entry-point group of each kind of plugin
GROUPS: dict[str, str] = {
    "surface": "lgraph.surfaces",
    "family": "lgraph.families",
    "backend": "lgraph.backends",
}


class PluginError(RuntimeError):
    """Using a plugin that failed to load; the message holds its original traceback."""


class PluginWarning(UserWarning):
    """A plugin failed to load, or two plugins claim the same name."""


def snake_case(name: str) -> str:
    """``HyperboloidOneSheet`` -> ``hyperboloid_one_sheet``.

    >>> snake_case("HyperboloidOneSheet"), snake_case("Sphere"), snake_case("ABCSurface")
    ('hyperboloid_one_sheet', 'sphere', 'abc_surface')
    """
    s = re.sub(r"([A-Z]+)([A-Z][a-z])", r"\1_\2", name)
    return re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", s).lower()


class PluginInfo:
    """One entry point of one installed plugin, and what became of it.

    ``status`` is ``"not loaded"`` until first use, then ``"ok"`` or
    ``"failed: <error>"``; entries that lost a name clash are ``"ignored: ..."``.
    """

    def __init__(self, kind: str, entry_point: Any) -> None:
        self.kind = kind
        self.entry_point = entry_point
        self.name: str = entry_point.name
        self.value: str = entry_point.value
        dist = getattr(entry_point, "dist", None)
        self.distribution: str = _dist_name(dist)
        self.version: str = str(getattr(dist, "version", None) or "?")
        self.status = "not loaded"
        self.error: BaseException | None = None
        self.traceback: str | None = None
        self._obj: Any = None
        self._lock = threading.Lock()

    @property
    def origin(self) -> str:
        """``distribution version (module:attr)`` for messages."""
        return f"{self.distribution} {self.version} ({self.value})"

    @property
    def who(self) -> str:
        """``surface plugin 'name' from <origin>`` for messages."""
        return f"{self.kind} plugin {self.name!r} from {self.origin}"

    def load(self) -> Any:
        """Import the plugin object once; on failure return a stand-in (and warn once)."""
        with self._lock:
            if self.status == "not loaded":
                try:
                    obj = self.entry_point.load()
                    if not callable(obj):
                        kind = f"{type(obj).__name__} {obj!r:.40}"
                        raise TypeError(f"{self.value!r} is not a class or function ({kind})")
                    if not isinstance(obj, type) and self.kind != "backend":  # a factory
                        obj = no_exit(obj, f"lgraph: {self.who}", PluginError)
                    self._obj, self.status = obj, "ok"
                except (Exception, SystemExit) as exc:  # noqa: BLE001 - a plugin may raise anything
                    self.error, self.status = exc, f"failed: {type(exc).__name__}: {exc}"
                    self.traceback = "".join(traceback.format_exception(exc))
                    self._obj = _BrokenPlugin(self)
                    warnings.warn(
                        f"lgraph: {self.kind} plugin {self.name!r} from {self.origin} failed to "
                        f"load ({type(exc).__name__}: {exc}); using it will raise the error",
                        PluginWarning,
                        stacklevel=3,
                    )
            return self._obj

    def __repr__(self) -> str:
        return f"PluginInfo({self.kind} {self.name!r} from {self.origin}: {self.status})"


def _dist_name(dist: Any) -> str:
    name = getattr(dist, "name", None)
    if name is None and dist is not None:
        try:
            name = dist.metadata["Name"]
        except Exception:  # noqa: BLE001
            pass
    return str(name or "(unknown distribution)")


class _BrokenPlugin:
    """Stand-in for a plugin that failed to import: raises its error when used."""

    def __init__(self, info: PluginInfo) -> None:
        self._info = info
        self.__name__ = info.value.rpartition(":")[2] or info.name

    def _raise(self) -> Any:
        info = self._info
        error = PluginError(f"lgraph: {info.who} failed to load; original error:\n{info.traceback}")
        raise error from info.error

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self._raise()

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):  # introspection (inspect.signature, attrs.has, ...)
            raise AttributeError(name)
        return self._raise()

    def __repr__(self) -> str:
        return f"<broken lgraph plugin {self._info.name!r} from {self._info.origin}>"


# -- discovery ------------------------------------------------------------------
_lock = threading.RLock()
#: kind -> name -> PluginInfo (the winner of each name)
_plugins: dict[str, dict[str, PluginInfo]] = {}
#: kind -> entries that lost a name clash (kept for describe_plugins)
_ignored: dict[str, list[PluginInfo]] = {}


def _entry_points(group: str) -> Iterable[Any]:
    import importlib.metadata as md

    try:
        return list(md.entry_points(group=group))
    except Exception as exc:  # noqa: BLE001 - broken metadata must not break lgraph
        warnings.warn(
            f"lgraph: could not read entry points of {group!r}: {exc}", PluginWarning, stacklevel=3
        )
        return []


def _discover(kind: str, builtin_names: Callable[[], Iterable[str]]) -> dict[str, PluginInfo]:
    """Scan the entry points of ``kind`` once; later calls return the cached table."""
    with _lock:
        if kind in _plugins:
            return _plugins[kind]
        table: dict[str, PluginInfo] = {}
        ignored: list[PluginInfo] = []
        builtins = set(builtin_names())
        seen: set[tuple[str, str, str]] = set()
        for ep in _entry_points(GROUPS[kind]):
            info = PluginInfo(kind, ep)
            key = (info.name, info.value, info.distribution)
            if key in seen:  # the same distribution found twice on sys.path
                continue
            seen.add(key)
            name = _normalize(kind, info.name)
            if name in builtins:
                info.status = "ignored: clashes with lgraph's built-in"
                ignored.append(info)
                warnings.warn(
                    f"lgraph: {kind} plugin {info.name!r} from {info.origin} clashes with "
                    f"lgraph's built-in {kind} of that name; the built-in is kept",
                    PluginWarning,
                    stacklevel=4,
                )
            elif name in table:
                first = table[name]
                info.status = f"ignored: name taken by {first.distribution}"
                ignored.append(info)
                warnings.warn(
                    f"lgraph: two plugins define the {kind} {info.name!r}: {first.origin} and "
                    f"{info.origin}; using the one from {first.distribution}",
                    PluginWarning,
                    stacklevel=4,
                )
            else:
                table[name] = info
        _plugins[kind] = table
        _ignored[kind] = ignored
        return table


def _normalize(kind: str, name: str) -> str:
    if kind == "backend":
        name = name.lower()
        return name if name.startswith(".") else "." + name
    return name


def _reset() -> None:
    """Forget discovered plugins and what they registered (for tests)."""
    from . import families
    from .output._backend_table import BACKENDS as _BACKENDS

    with _lock:
        for info in _plugins.get("family", {}).values():
            if families.FAMILIES.get(info.name) is not None and info.status != "not loaded":
                families.FAMILIES.pop(info.name, None)
        for suffix, info in _plugins.get("backend", {}).items():
            if isinstance(_BACKENDS.get(suffix), _LazyBackend) or info.status != "not loaded":
                _BACKENDS.pop(suffix, None)
        _plugins.clear()
        _ignored.clear()
        _registered_surfaces.clear()


# -- surfaces --------------------------------------------------------------------
#: surfaces registered at run time with :func:`register_surface`
_registered_surfaces: dict[str, type] = {}


def _builtin_surfaces() -> dict[str, type]:
    """Every concrete Surface class ``lgraph`` exports, by snake_case name.

    Built at each call from ``lgraph.__all__``, so classes added to lgraph
    appear without being listed here.
    """
    import attrs

    import lgraph

    from .surfaces._base import Surface

    out: dict[str, type] = {}
    for export in getattr(lgraph, "__all__", ()):
        obj = getattr(lgraph, export, None)
        if isinstance(obj, type) and issubclass(obj, Surface) and attrs.has(obj):
            out[snake_case(obj.__name__)] = obj
    return out


def _surface_table() -> dict[str, Any]:
    return {**_builtin_surfaces(), **_registered_surfaces}


def register_surface(name: str, cls: type, *, replace: bool = False) -> None:
    """Register a surface class under ``name`` at run time (no entry point needed)."""
    if name in _surface_table() and not replace:
        raise ValueError(f"register_surface: a surface named {name!r} is already registered")
    _registered_surfaces[name] = cls


def surface_names() -> list[str]:
    """Names of all surfaces: built-in, registered and from plugins."""
    table = _surface_table()
    return sorted(set(table) | set(_discover("surface", table.keys)))


def get_surface(name: str) -> Any:
    """The surface class called ``name`` (a stand-in if its plugin is broken).

    Raises
    ------
    KeyError
        For an unknown name; the message lists the known ones.
    """
    table = _surface_table()
    if name in table:
        return table[name]
    plugins = _discover("surface", table.keys)
    if name in plugins:
        return plugins[name].load()
    raise KeyError(f"unknown surface {name!r}; known: {', '.join(surface_names())}")


# -- families --------------------------------------------------------------------
def _builtin_families() -> dict[str, Any]:
    from .families import (  # noqa: F401  (importing the modules registers their families)
        FAMILIES,
        asymptotic,
        geodesic,
        intersection,
        level,
        parabolic,
        self_intersection,  # noqa: F401
        singular,  # noqa: F401
    )

    return FAMILIES


def family_names() -> list[str]:
    """Names of all line families: built-in, registered and from plugins."""
    fams = _builtin_families()
    return sorted(set(fams) | set(_discover("family", lambda: list(fams))))


def get_family(name: str) -> Any:
    """The family class called ``name``; a plugin's class is registered in
    ``lgraph.families.FAMILIES`` when first loaded.

    Raises
    ------
    KeyError
        For an unknown name; the message lists the known ones.
    """
    from .families import register_family

    fams = _builtin_families()
    if name in fams:
        return fams[name]
    plugins = _discover("family", lambda: list(fams))
    if name in plugins:
        obj = plugins[name].load()
        register_family(name, obj, replace=True)
        return obj
    raise KeyError(f"unknown line family {name!r}; known: {', '.join(family_names())}")


# -- backends --------------------------------------------------------------------
class _LazyBackend:
    """Registered for a plugin suffix: imports the plugin on first write."""

    def __init__(self, suffix: str, info: PluginInfo) -> None:
        self.suffix = suffix
        self.info = info
        self.__name__ = info.value.rpartition(":")[2] or info.name

    def load_writer(self) -> Any:
        """Import the plugin's writer (and register it in place of this stub)."""
        from .output._backend_table import BACKENDS as _BACKENDS

        writer = self.info.load()
        if not isinstance(writer, _BrokenPlugin) and _BACKENDS.get(self.suffix) is self:
            _BACKENDS[self.suffix] = writer
        return writer

    def __call__(self, drawing: Any, path: Any, **options: Any) -> Any:
        return self.load_writer()(drawing, path, **options)

    def __repr__(self) -> str:
        return f"<lgraph backend {self.suffix} from {self.info.origin}, loaded on first use>"


def load_backends() -> None:
    """Register plugin backends (``lgraph.backends`` entry points) by suffix.

    Called by :func:`lgraph.output.backends.get_backend` for a suffix it does not
    know; scans the entry points once and imports nothing until a plugin
    backend is first used.
    """
    from .output._backend_table import BACKENDS as _BACKENDS

    with _lock:
        first = "backend" not in _plugins
        builtins = list(_BACKENDS)
        table = _discover("backend", lambda: builtins)
        if first:
            for suffix, info in table.items():
                _BACKENDS.setdefault(suffix, _LazyBackend(suffix, info))


# -- listing ---------------------------------------------------------------------
def installed_plugins(load: bool = True) -> list[PluginInfo]:
    """Every plugin entry point of the three groups (``load=True`` imports them
    to report their status)."""
    surfaces = _surface_table()
    fams = _builtin_families()
    load_backends()
    tables = {
        "surface": _discover("surface", surfaces.keys),
        "family": _discover("family", lambda: list(fams)),
        "backend": _plugins["backend"],
    }
    out: list[PluginInfo] = []
    for kind, table in tables.items():
        for name, info in table.items():
            if load and kind == "family":
                get_family(name)  # loads and registers it
            elif load:
                info.load()
            out.append(info)
        out.extend(_ignored.get(kind, []))
    return out


def describe_plugins() -> str:
    """What ``lgraph plugins`` prints: a table of the installed plugins (name,
    kind, distribution, version, status), the names of every surface, line
    family and backend (built-in, registered and from plugins; wrapped
    lines such as ``surfaces (26): arrow, catenoid, ...``) and, last, a
    count of the built-ins.

    >>> text = describe_plugins()
    >>> all(f"{kind} (" in text for kind in ("surfaces", "families", "backends"))
    True
    >>> text.splitlines()[-1]
    'built-in: ... surfaces, ... line families, ... backends'
    """
    from .output._backend_table import BACKENDS as _BACKENDS

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PluginWarning)  # the status column says it
        infos = installed_plugins(load=True)
        names = {
            "surfaces": surface_names(),
            "families": family_names(),
            "backends": sorted(_BACKENDS),
        }
    n_surf = len(_builtin_surfaces())
    n_fam = len([k for k, v in _builtin_families().items() if not _from_plugin("family", k)])
    n_back = len([k for k in _BACKENDS if not _from_plugin("backend", k)])
    footer = f"built-in: {n_surf} surfaces, {n_fam} line families, {n_back} backends"
    listed = [_name_list(f"{kind} ({len(found)}):", found) for kind, found in names.items()]
    if not infos:
        groups = ", ".join(GROUPS.values())
        return "\n".join([f"no plugins installed (entry-point groups {groups})", *listed, footer])
    rows = [("NAME", "KIND", "DISTRIBUTION", "VERSION", "STATUS")]
    for i in infos:
        status = i.status.splitlines()[0] if i.status else ""
        rows.append((i.name, i.kind, i.distribution, i.version, status))
    widths = [max(len(r[c]) for r in rows) for c in range(4)]
    lines = ["  ".join(r[c].ljust(widths[c]) for c in range(4)) + "  " + r[4] for r in rows]
    return "\n".join([*lines, "", *listed, footer])


def _name_list(title: str, names: list[str], width: int = 79) -> str:
    """``title`` and the comma-separated ``names``, wrapped at ``width`` with
    an indent of 4 (a name is never split).

    >>> print(_name_list("backends (3):", [".pdf", ".png", ".svg"]))
    backends (3): .pdf, .png, .svg
    """
    import textwrap

    return textwrap.fill(
        ", ".join(names) or "(none)",
        width=width,
        initial_indent=f"{title} ",
        subsequent_indent="    ",
        break_long_words=False,
        break_on_hyphens=False,
    )


def _from_plugin(kind: str, name: str) -> bool:
    return name in _plugins.get(kind, {})
