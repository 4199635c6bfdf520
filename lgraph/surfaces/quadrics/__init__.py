"""The nine quadrics and the confocal ones, with their closed forms beside them.

``quadric.py`` holds the :class:`Quadric` base (the ray test and the contour
conic), the ellipsoid and the sphere; the unbounded quadrics on bounded
patches are in ``hyperboloids.py`` (and the elliptic cone), ``paraboloids.py``
and ``cylinders.py``, on the patch base ``_unbounded.py``; ``confocal.py`` the
confocal quadrics.  Their formulas: ``_ray.py`` (the ray quadratic for many
quadrics at once), ``_conic.py`` (the contour, a plane section) and
``_curvature.py`` (the lines of curvature in closed form).
"""

from .confocal import ConfocalQuadric, TripleOrthogonalSystem
from .cylinders import EllipticCylinder, HyperbolicCylinder, ParabolicCylinder
from .hyperboloids import EllipticCone, HyperboloidOneSheet, HyperboloidTwoSheets
from .paraboloids import EllipticParaboloid, HyperbolicParaboloid
from .quadric import Ellipsoid, Quadric, Sphere

__all__ = ["Quadric", "Ellipsoid", "Sphere", "HyperboloidOneSheet", "HyperboloidTwoSheets"]
__all__ += ["EllipticCone", "EllipticParaboloid", "HyperbolicParaboloid", "EllipticCylinder"]
__all__ += ["HyperbolicCylinder", "ParabolicCylinder", "ConfocalQuadric", "TripleOrthogonalSystem"]
