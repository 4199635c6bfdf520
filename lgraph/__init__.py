"""lgraph: print-quality line graphics of mathematical surfaces.

Surfaces are drawn as families of curves on them (parameter lines, lines of
curvature, the contour) with hidden parts removed exactly.

>>> import lgraph as lg
>>> scene = lg.Scene()
>>> _ = scene.add(lg.Ellipsoid(3, 2, 1.5), lg.ParameterLines(6, 12))
>>> drawing = scene.render(lg.ParallelProjector(direction=(1, -1, 0.7)))
>>> all(s.visible for s in drawing.strokes)
True
"""

from __future__ import annotations

from .curvature import principal_curvatures, principal_directions
from .curves import Curve, CurveBatch, CurveOnSurface
from .drawing import HIDDEN_STYLE, Drawing, Page, PlacedLabel, Stroke, Style
from .families import Contour, Family, LinesOfCurvature, ParameterLines, Umbilics
from .geometry.transforms import Transform, rotate, scale, translate
from .level_lines import LevelLines
from .objects import Label, Point
from .parabolic import ParabolicLines
from .projectors import CentralProjector, ParallelProjector, Projector
from .scene import Group, Node, Scene
from .scenefile import SceneFileError, load_scene_file
from .self_intersection import SelfIntersection
from .surface_curves import (
    Arrow,
    AsymptoticLines,
    Geodesic,
    IntersectionCurve,
    Parallelogram,
    geodesic,
    intersection_curves,
)
from .surfaces import (
    ConfocalQuadric,
    Domain,
    Ellipsoid,
    EllipticCone,
    EllipticCylinder,
    EllipticParaboloid,
    GeneralCone,
    GeneralCylinder,
    HyperbolicCylinder,
    HyperbolicParaboloid,
    HyperboloidOneSheet,
    HyperboloidTwoSheets,
    ParabolicCylinder,
    Pseudosphere,
    Quadric,
    RuledSurface,
    Sphere,
    Surface,
    SurfaceOfRevolution,
    TangentSurface,
    TripleOrthogonalSystem,
)
from .surfaces.parametric import (
    Catenoid,
    DupinCyclide,
    Enneper,
    Helicoid,
    MonkeySaddle,
    ParametricSurface,
    Torus,
)
from .surfaces.profiles import Profile, named_profile, profile_from_points

__version__ = "0.1.0"

__all__ = [
    "CentralProjector",
    "Contour",
    "Curve",
    "CurveBatch",
    "CurveOnSurface",
    "Domain",
    "Drawing",
    "Ellipsoid",
    "Family",
    "HIDDEN_STYLE",
    "LinesOfCurvature",
    "Node",
    "Page",
    "ParallelProjector",
    "ParameterLines",
    "Projector",
    "Quadric",
    "Scene",
    "Sphere",
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
    "Stroke",
    "Style",
    "Surface",
    "Transform",
    "Umbilics",
    "principal_curvatures",
    "principal_directions",
    "rotate",
    "scale",
    "translate",
]
__all__ += ["RuledSurface", "GeneralCylinder", "GeneralCone", "TangentSurface"]
__all__ += [
    "ParametricSurface",
    "Torus",
    "DupinCyclide",
    "MonkeySaddle",
    "Helicoid",
    "Catenoid",
    "Enneper",
    "AsymptoticLines",
    "Geodesic",
    "geodesic",
    "IntersectionCurve",
    "intersection_curves",
    "Arrow",
    "Parallelogram",
]
__all__ += ["load_scene_file", "SceneFileError"]
__all__ += ["Label", "Point", "PlacedLabel", "Group"]
__all__ += ["SurfaceOfRevolution", "Pseudosphere"]
__all__ += ["Profile", "named_profile", "profile_from_points"]
__all__ += ["LevelLines", "ParabolicLines", "SelfIntersection"]
