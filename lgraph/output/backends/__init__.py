"""Output backends, chosen by file suffix and imported only when first used.

A backend is a callable ``write(drawing, path, **options)`` that writes the
whole file at ``path`` (``Drawing.save`` makes the write atomic).

>>> get_backend(".svg").__name__
'write_svg'
>>> get_backend(".doc")
Traceback (most recent call last):
...
ValueError: Drawing.save: unknown file suffix '.doc'; known: ...
"""

from __future__ import annotations

import importlib
from typing import Any

__all__ = ["get_backend", "register_backend", "backend_suffixes", "backend_options"]

from .._backend_table import BACKENDS as _BACKENDS
from .._backend_table import Writer


def register_backend(suffix: str, writer: str | Writer, *, replace: bool = False) -> None:
    """Register ``writer`` for files ending in ``suffix`` (e.g. ``".hpgl"``)."""
    suffix = suffix.lower() if suffix.startswith(".") else "." + suffix.lower()
    if suffix in _BACKENDS and not replace:
        raise ValueError(f"register_backend: a backend for {suffix!r} is already registered")
    _BACKENDS[suffix] = writer


def backend_suffixes() -> list[str]:
    """All suffixes with a backend, built-in and registered."""
    _load_plugins()
    return sorted(_BACKENDS)


def _load_plugins() -> None:
    try:
        from ...plugins import load_backends
    except ImportError:  # pragma: no cover - plugins module always present
        return
    load_backends()


def get_backend(suffix: str) -> Writer:
    """The writer for ``suffix``; raises ValueError for an unknown one."""
    key = suffix.lower()
    if key not in _BACKENDS:
        _load_plugins()
    if key not in _BACKENDS:
        known = ", ".join(sorted(_BACKENDS))
        shown = suffix if suffix else "(none)"
        raise ValueError(f"Drawing.save: unknown file suffix {shown!r}; known: {known}")
    entry: Any = _BACKENDS[key]
    if isinstance(entry, str):
        module, _, name = entry.partition(":")
        entry = getattr(importlib.import_module(module), name)
        _BACKENDS[key] = entry
    return entry


def backend_options(suffix: str) -> dict[str, Any]:
    """The options the writer for ``suffix`` accepts, with their defaults.

    A writer declares its options as keyword parameters after ``drawing,
    path`` (their defaults tell the expected type), or, when it takes
    ``**options``, in an attribute ``lgraph_options`` (a dict name ->
    default).  Scene files check their ``[save]`` keys against this before
    rendering, and pass them on unchanged.  Loads the writer (a plugin's on
    first use); raises ValueError for an unknown suffix.

    >>> backend_options(".svg")
    {'precision': 3, 'layers': 'family', 'curves': 'polyline', 'text': 'outlines'}
    >>> sorted(backend_options(".png"))
    ['dpi', 'size', 'supersample']
    """
    import inspect

    writer: Any = get_backend(suffix)
    load = getattr(writer, "load_writer", None)
    if load is not None:  # a plugin backend not imported yet
        writer = load()
    declared = getattr(writer, "lgraph_options", None)
    if isinstance(declared, dict):
        return dict(declared)
    try:
        params = list(inspect.signature(writer).parameters.values())[2:]
    except (TypeError, ValueError):
        return {}
    kinds = (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    return {
        p.name: None if p.default is inspect.Parameter.empty else p.default
        for p in params
        if p.kind in kinds
    }
