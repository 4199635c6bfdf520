"""View-independent results kept per surface object, computed once for every view.

Surfaces are immutable (frozen attrs classes), so what a surface computes from
its own definition alone -- its bounding box, the bounding-volume hierarchy of
its patches, the normals on the grid of its numeric contour -- never goes
stale.  :func:`per_surface` keeps such results keyed by the surface object's
identity: an entry goes when its surface is garbage-collected, and at most
:data:`MAX_SURFACES` surfaces are remembered (the oldest is dropped first), so
the memory held is bounded (about 2 MB a surface with a numeric contour).
:func:`per_value` keeps results that equal surfaces share (lgraph's own
hashable classes: equal fields, equal results), so that the equal spheres of
many nodes share one evaluation kernel.  No derivation: bookkeeping only.

>>> import lgraph as lg
>>> s = lg.Sphere(1)
>>> calls = []
>>> per_surface(s, "demo", lambda: calls.append(1) or 42), per_surface(s, "demo", lambda: 0)
(42, 42)
>>> len(calls)
1
"""

from __future__ import annotations

import threading
import weakref
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any, TypeVar

__all__ = ["per_surface", "per_value", "by_value", "clear", "MAX_SURFACES"]

T = TypeVar("T")

#: most surfaces whose results are kept at once
MAX_SURFACES = 64

# id(surface) -> (a callable returning the surface while it lives, its results)
_MEMO: dict[int, tuple[Callable[[], Any], dict[Hashable, Any]]] = {}


def _forget(sid: int, ref: Any, memo: dict = _MEMO) -> None:
    # bound to the dict itself: it may run while the interpreter shuts down
    entry = memo.get(sid)
    if entry is not None and entry[0] is ref:
        del memo[sid]


def per_surface(surface: Any, key: Hashable, compute: Callable[[], T]) -> T:
    """``compute()`` the first time ``key`` is asked of this surface object;
    the same result afterwards."""
    sid = id(surface)
    entry = _MEMO.get(sid)
    if entry is None or entry[0]() is not surface:
        if len(_MEMO) >= MAX_SURFACES:
            del _MEMO[next(iter(_MEMO))]
        try:
            ref: Callable[[], Any] = weakref.ref(surface, lambda r, s=sid, f=_forget: f(s, r))
        except TypeError:  # not weak-referenceable: held until pushed out
            ref = (lambda s: lambda: s)(surface)
        entry = _MEMO[sid] = (ref, {})
    table = entry[1]
    if key not in table:
        table[key] = compute()
    return table[key]


# a surface (by value) -> its results; strong references, the least recently
# used surface dropped first
_BY_VALUE: OrderedDict[Any, dict[Hashable, Any]] = OrderedDict()
_lock = threading.Lock()


def by_value(surface: Any) -> bool:
    """Whether :func:`per_value` keeps ``surface``'s results by value (a
    hashable surface of lgraph's own)."""
    if not type(surface).__module__.startswith("lgraph."):
        return False
    try:
        hash(surface)
    except TypeError:
        return False
    return True


def per_value(surface: Any, key: Hashable, compute: Callable[[], T]) -> T:
    """``compute()`` the first time ``key`` is asked of any surface equal to
    this one, for lgraph's own hashable surfaces (frozen attrs classes: equal
    fields give equal results); :func:`per_surface` for any other.  The
    result must not depend on which of the equal surfaces computed it.

    >>> import lgraph as lg
    >>> per_value(lg.Sphere(2), "demo", lambda: []) is per_value(lg.Sphere(2), "demo", list)
    True
    """
    if not by_value(surface):
        return per_surface(surface, key, compute)
    with _lock:
        table = _BY_VALUE.get(surface)
        if table is not None and key in table:
            _BY_VALUE.move_to_end(surface)
            return table[key]
    value = compute()
    with _lock:
        table = _BY_VALUE.get(surface)
        if table is None:
            while len(_BY_VALUE) >= MAX_SURFACES:
                _BY_VALUE.popitem(last=False)
            table = _BY_VALUE[surface] = {}
        return table.setdefault(key, value)


def clear() -> None:
    """Forget every surface's results."""
    _MEMO.clear()
    with _lock:
        _BY_VALUE.clear()
