"""Figure objects that are not surfaces of study.

* ``marks.py`` -- :class:`~lgraph.Label` (text at a 3-D
  point) and :class:`~lgraph.Point` (a dot there), hidden like the lines;
* ``shapes.py`` -- :class:`~lgraph.Parallelogram` (a planar
  patch, e.g. a tangent plane) and :class:`~lgraph.Arrow` (shaft and head),
  surfaces with exact ray tests and contours.

All are added with ``scene.add``; every name is importable from here and
from ``lgraph``.
"""

from .marks import ANCHORS, Label, Point
from .shapes import Arrow, Parallelogram

__all__ = ["Label", "Point", "ANCHORS", "Arrow", "Parallelogram"]
