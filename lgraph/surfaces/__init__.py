"""Surface classes."""

from ._base import CONTOUR, OFF, ON, Domain, Surface
from .quadrics.confocal import ConfocalQuadric, TripleOrthogonalSystem
from .quadrics.cylinders import EllipticCylinder, HyperbolicCylinder, ParabolicCylinder
from .quadrics.hyperboloids import EllipticCone, HyperboloidOneSheet, HyperboloidTwoSheets
from .quadrics.paraboloids import EllipticParaboloid, HyperbolicParaboloid
from .quadrics.quadric import Ellipsoid, Quadric, Sphere
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
