"""Numeric defaults of :class:`~lgraph.surfaces._base.Surface`: contour and ray hits.

Both need nothing but ``point`` (and ``derivatives``, which has a
finite-difference default), so any parametrized surface can be drawn with
hidden lines removed.  This module is the entry point (``Surface.contour``
and ``Surface.hits`` import from it, and so do the numeric line families);
the work is done in

* :mod:`._zero_set`: zero sets ``fun(u1, u2) = 0`` by marching squares on a
  parameter grid, crossings refined on their grid edges;
* :mod:`._numeric_contour`: :func:`contour`, the zero set of the view cosine
  ``N . w / |w|``, as splines projected back onto it by Newton's method;
* :mod:`._numeric_boxes`: the bounding-volume hierarchy of the surface's
  patches (cached per surface);
* :mod:`._numeric_hits`: :func:`hits`, Newton's method on
  ``x(u1, u2) = o + s v`` in the candidate patches, subdividing where it fails.

>>> import numpy as np
>>> import lgraph as lg
>>> e = lg.Ellipsoid(3, 2, 1)
>>> s = lg.ParametricSurface(e.point, (-np.pi / 2, np.pi / 2), (0, 2 * np.pi),
...                          periodic=(False, True), poles=(True, False))
>>> o = np.array([[0.0, 0.0, -5.0], [5.0, 5.0, 5.0]])
>>> hits(s, o, np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]), np.array([np.inf, np.inf])).tolist()
[True, False]
"""

from __future__ import annotations

from ._numeric_boxes import _hierarchy
from ._numeric_contour import (
    _unwrap,
    contour,
    project_to_contour,
    project_to_zero,
    view_cosine,
    zero_set_batch,
)
from ._numeric_hits import hits
from ._zero_set import _edge_roots, zero_set

__all__ = ["contour", "hits", "view_cosine", "project_to_contour", "zero_set", "zero_set_batch"]
__all__ += ["project_to_zero"]
# private names that lgraph.families.self_intersection and the tests import from here
__all__ += ["_hierarchy", "_unwrap", "_edge_roots"]
