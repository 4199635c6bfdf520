"""Surface classes."""

from ._base import CONTOUR, OFF, ON, Domain, Surface
from .quadrics import Ellipsoid, Quadric, Sphere

__all__ = ["CONTOUR", "OFF", "ON", "Domain", "Surface", "Quadric", "Ellipsoid", "Sphere"]
