"""Surface classes."""

from ._base import CONTOUR, OFF, ON, Domain, Surface
from .confocal import ConfocalQuadric, TripleOrthogonalSystem
from .cylinders import EllipticCylinder, HyperbolicCylinder, ParabolicCylinder
from .hyperboloids import EllipticCone, HyperboloidOneSheet, HyperboloidTwoSheets
from .paraboloids import EllipticParaboloid, HyperbolicParaboloid
from .quadrics import Ellipsoid, Quadric, Sphere
from .revolution import Pseudosphere, SurfaceOfRevolution
from .ruled import GeneralCone, GeneralCylinder, RuledSurface, TangentSurface

__all__ = ["CONTOUR", "OFF", "ON", "Domain", "Surface", "Quadric", "Ellipsoid", "Sphere"]
__all__ += [
    "HyperboloidOneSheet",
    "HyperboloidTwoSheets",
    "EllipticCone",
    "EllipticParaboloid",
    "HyperbolicParaboloid",
    "EllipticCylinder",
    "HyperbolicCylinder",
    "ParabolicCylinder",
    "ConfocalQuadric",
    "TripleOrthogonalSystem",
]
__all__ += ["RuledSurface", "GeneralCylinder", "GeneralCone", "TangentSurface"]
__all__ += ["SurfaceOfRevolution", "Pseudosphere"]
