"""The unbounded quadrics, drawn on bounded patches: every class in one import.

Hyperboloids of one and two sheets, the elliptic cone, the elliptic and
hyperbolic paraboloids and the three quadric cylinders, each in its normal
form (axis z, centred at the origin) with a default extent changeable by
keyword.  Only the drawn patch hides anything; contours and lines of
curvature are cut to it exactly.  The ray test and the contour conic come
from :class:`~lgraph.surfaces.quadrics.Quadric`.  The classes live in
:mod:`~lgraph.surfaces.hyperboloids`, :mod:`~lgraph.surfaces.paraboloids`
and :mod:`~lgraph.surfaces.cylinders`, on the shared base of
:mod:`lgraph.surfaces._patch_quadric`; this module gathers them.
"""

from ._patch_quadric import _PatchQuadric  # noqa: F401 - the base, for confocal quadrics
from .cylinders import EllipticCylinder, HyperbolicCylinder, ParabolicCylinder
from .hyperboloids import EllipticCone, HyperboloidOneSheet, HyperboloidTwoSheets
from .paraboloids import EllipticParaboloid, HyperbolicParaboloid

__all__ = [
    "HyperboloidOneSheet",
    "HyperboloidTwoSheets",
    "EllipticCone",
    "EllipticParaboloid",
    "HyperbolicParaboloid",
    "EllipticCylinder",
    "HyperbolicCylinder",
    "ParabolicCylinder",
]
