"""Cache of view-independent geometry: what a line family returns for a node.

Lines of curvature (closed-form or integrated), asymptotic lines, geodesics,
intersection curves, umbilic marks and parameter lines do not depend on the
view.  :meth:`lgraph.Scene.batches` asks this module for them, so a scene
rendered again with another projector (a turntable, an interactive view)
computes them once; only the contour, the sampling and the visibility are
redone per view.

Safety:

* What a family draws depends only on the family and the surface (curves are
  in the node's local frame; its transform and style are applied later).  The
  key is the surface (by value for the hashable frozen surfaces of lgraph,
  so that equal spheres in different nodes share their batches; else by
  identity: the entry holds the surface, so the identity cannot pass to
  another object while the entry lives) and the family (by value for the
  frozen families of lgraph, else by identity).  A shared batch's
  ``surface`` is the first equal surface: the renderer takes each stroke's
  surface from its node.  Surfaces and families are
  immutable, so an entry can never go stale: a changed scene holds new
  surfaces or families, which miss the cache and are computed afresh.  The
  same surface in several nodes (or groups) shares its entries.
* Families that depend on the view (the contour; any family whose class sets
  ``view_dependent = True``, the default for families outside lgraph) are
  never cached.
* The cache lives in the process: it is not pickled with a scene, and each
  worker process of a parallel animation fills its own.

Data derived from a cached batch without the view (the renderer's initial
samples, uniform in each curve's parameter: ``derived``) is kept with
the batch's entry and dropped with it.

Memory: at most :data:`MAX_ENTRIES` family results are kept, least recently
used evicted first (an entry keeps its surface alive until then).  One entry
holds the curves of one family on one surface: for closed forms a few
closures and parameters, for numeric lines the integrator's dense output
(0.5 MB for the 28 lines of curvature of the gallery's monkey saddle), plus
the initial samples (33 points a curve, 1.3 kB), so the cache stays bounded
by ``MAX_ENTRIES`` times that.  :func:`clear`
empties it; :func:`set_max_entries` changes the bound (0 turns caching off).

>>> import lgraph as lg
>>> is_view_dependent(lg.LinesOfCurvature(4, 4)), is_view_dependent(lg.Contour())
(False, True)
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..scene.projectors import Projector
    from ..surfaces._base import Surface
    from . import Family

__all__ = [
    "family_batches",
    "derived",
    "is_view_dependent",
    "clear",
    "info",
    "set_max_entries",
    "MAX_ENTRIES",
]


class HoldsSurface(Protocol):
    """What the cache needs of a node: its surface (:class:`lgraph.Node`, which
    the scene graph that imports this module holds, or a stand-in)."""

    @property
    def surface(self) -> Surface | None: ...


#: Default bound on the number of cached family results (see the module docs).
MAX_ENTRIES = 64

_lock = threading.RLock()
_max_entries = MAX_ENTRIES
# LRU order over (surface key, family key) -> (surface, family, list of batches)
_entries: OrderedDict[tuple[int, Any], tuple[Any, Any, list]] = OrderedDict()
_stats = {"hits": 0, "misses": 0}
# id of a batch held by an entry -> (the batch, {key: data derived from it})
_derived: dict[int, tuple[Any, dict[Any, Any]]] = {}


def _family_key(family: Family) -> Any:
    try:
        hash(family)
    except TypeError:  # an unhashable family: its identity (the entry holds it)
        return ("id", id(family))
    return family


def _surface_key(surface: Any) -> Any:
    """A surface of lgraph's own by value when it hashes (frozen attrs
    classes: equal fields, equal curves), any other by identity."""
    if type(surface).__module__.startswith("lgraph."):
        try:
            hash(surface)
        except TypeError:
            pass
        else:
            return ("value", surface)
    return ("id", id(surface))


def is_view_dependent(family: Family) -> bool:
    """Whether ``family``'s curves change with the projector (then never cached)."""
    return bool(getattr(family, "view_dependent", True))


def family_batches(
    node: HoldsSurface, index: int, family: Family, projector: Projector | None
) -> list[CurveBatch]:
    """``family.batches(node.surface, projector)``, computed once per surface
    and family when the family does not depend on the view (``index``, the
    family's position in the node, is not part of the key).

    ``projector`` is the node's local projector; view-dependent families get
    it on every call.  The returned list must not be modified.
    """
    if _max_entries <= 0 or is_view_dependent(family):
        return family.batches(node.surface, projector)
    surface = node.surface
    with _lock:
        key = (_surface_key(surface), _family_key(family))
        found = _entries.get(key)
        if found is not None:
            _entries.move_to_end(key)
            _stats["hits"] += 1
            return found[2]
        _stats["misses"] += 1
    # computed outside the lock: other threads may render other scenes meanwhile
    result = list(family.batches(surface, projector))
    with _lock:
        # the entry holds its surface and family: their ids cannot be reused
        # while the entry lives
        old = _entries.pop(key, None)  # computed twice by two threads: keep one
        if old is not None:
            _forget(old)
        _entries[key] = (surface, family, result)
        for batch in result:
            _derived[id(batch)] = (batch, {})
        _trim(_max_entries)
    return result


def _forget(entry: tuple[Any, Any, list]) -> None:
    for batch in entry[2]:
        _derived.pop(id(batch), None)


def _trim(n: int) -> None:
    """Evict the least recently used entries beyond ``n`` (lock held)."""
    while len(_entries) > n:
        _forget(_entries.popitem(last=False)[1])


def derived(batch: CurveBatch, key: Any, compute: Callable[[], Any]) -> Any:
    """``compute()``, kept with ``batch``'s entry under ``key`` when ``batch`` is
    one this cache holds (a view-independent family's), so that it is computed
    once; computed afresh for any other batch.  ``compute`` must not depend on
    the view, and the result must not be modified.

    >>> derived(object(), "k", lambda: 42)  # not a cached batch: computed each time
    42
    """
    with _lock:
        slot = _derived.get(id(batch))
        if slot is not None and slot[0] is batch and key in slot[1]:
            return slot[1][key]
    value = compute()
    with _lock:
        slot = _derived.get(id(batch))
        if slot is not None and slot[0] is batch:
            slot[1][key] = value
    return value


def clear() -> None:
    """Empty the cache and reset its counters."""
    with _lock:
        _entries.clear()
        _derived.clear()
        _stats["hits"] = _stats["misses"] = 0


def info() -> dict[str, int]:
    """``{"entries", "max_entries", "hits", "misses"}`` of this process's cache."""
    with _lock:
        return {"entries": len(_entries), "max_entries": _max_entries, **_stats}


def set_max_entries(n: int) -> None:
    """Bound the cache to ``n`` family results (0 disables caching).

    >>> set_max_entries(-1)
    Traceback (most recent call last):
    ...
    ValueError: set_max_entries: n must be a non-negative integer, got -1
    """
    global _max_entries
    if isinstance(n, bool) or not isinstance(n, int) or n < 0:
        raise ValueError(f"set_max_entries: n must be a non-negative integer, got {n!r}")
    with _lock:
        _max_entries = n
        _trim(n)
