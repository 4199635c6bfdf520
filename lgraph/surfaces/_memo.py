"""View-independent results kept per surface object, computed once for every view.

Surfaces are immutable (frozen attrs classes), so what a surface computes from
its own definition alone -- its bounding box, the bounding-volume hierarchy of
its patches, the normals on the grid of its numeric contour -- never goes
stale.  :func:`per_surface` keeps such results keyed by the surface object's
identity: an entry goes when its surface is garbage-collected, and at most
:data:`MAX_SURFACES` surfaces are remembered (the oldest is dropped first), so
the memory held is bounded (about 2 MB a surface with a numeric contour).
No derivation: bookkeeping only.

>>> import lgraph as lg
>>> s = lg.Sphere(1)
>>> calls = []
>>> per_surface(s, "demo", lambda: calls.append(1) or 42), per_surface(s, "demo", lambda: 0)
(42, 42)
>>> len(calls)
1
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Hashable
from typing import Any, TypeVar

__all__ = ["per_surface", "clear", "MAX_SURFACES"]

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


def clear() -> None:
    """Forget every surface's results."""
    _MEMO.clear()
