"""Surface classes: every kind, by its subpackage.

The base class and the quadrics, ruled surfaces and surfaces of revolution
are imported with the package; the parametric, classical and implicit
surfaces when first asked for (``from lgraph.surfaces import Torus``), since
their modules import the line families, which import this package.
"""

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

#: the surfaces imported when first used: name -> its module (below this package)
_LAZY = {
    "ParametricSurface": ".parametric",
    "MonkeySaddle": ".classical",
    "Enneper": ".classical",
    "Catenoid": ".classical",
    "Helicoid": ".classical",
    "Torus": ".classical.quartic",
    "DupinCyclide": ".classical.quartic",
    "MoebiusStrip": ".classical.onesided",
    "KleinBottle": ".classical.onesided",
    "BoySurface": ".classical.onesided",
    "RomanSurface": ".classical.onesided",
    "CrossCap": ".classical.onesided",
    "ImplicitSurface": ".implicit",
    "AlgebraicSurface": ".implicit.algebraic",
    "ClebschCubic": ".implicit.algebraic",
    "CayleyCubic": ".implicit.algebraic",
    "KummerSurface": ".implicit.algebraic",
    "GoursatSurface": ".implicit.algebraic",
    "RomanSteiner": ".implicit.algebraic",
}
__all__ += list(_LAZY)


def __getattr__(name: str) -> object:
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
