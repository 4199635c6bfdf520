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

import importlib
from typing import Any

#: public name -> the module that defines it; imported on first use (PEP 562), so
#: ``import lgraph`` costs only this table and a script pays for what it uses
_EXPORTS: dict[str, str] = {
    "principal_curvatures": ".curvature",
    "principal_directions": ".curvature",
    "Curve": ".curves",
    "CurveBatch": ".curves",
    "CurveOnSurface": ".curves",
    "HIDDEN_STYLE": ".style",
    "HiddenStyles": ".style",
    "Drawing": ".drawing",
    "Page": ".page",
    "PlacedLabel": ".drawing",
    "Stroke": ".drawing",
    "Style": ".style",
    "Contour": ".families",
    "Family": ".families",
    "LinesOfCurvature": ".families",
    "ParameterLines": ".families",
    "Umbilics": ".families",
    "Transform": ".geometry.transforms",
    "rotate": ".geometry.transforms",
    "scale": ".geometry.transforms",
    "translate": ".geometry.transforms",
    "LevelLines": ".families.level",
    "Label": ".objects.marks",
    "Point": ".objects.marks",
    "ParabolicLines": ".families.parabolic",
    "CentralProjector": ".projectors",
    "ParallelProjector": ".projectors",
    "Projector": ".projectors",
    "Group": ".scene",
    "Node": ".scene",
    "Scene": ".scene",
    "SceneFileError": ".scenefile",
    "SceneFileWarning": ".scenefile",
    "load_scene_file": ".scenefile",
    "SelfIntersection": ".families.self_intersection",
    "Arrow": ".objects.shapes",
    "AsymptoticLines": ".families.asymptotic",
    "Geodesic": ".families.geodesic",
    "IntersectionCurve": ".families.intersection",
    "Parallelogram": ".objects.shapes",
    "geodesic": ".families.geodesic",
    "intersection_curves": ".families.intersection",
    "ConfocalQuadric": ".surfaces",
    "Domain": ".surfaces",
    "Ellipsoid": ".surfaces",
    "EllipticCone": ".surfaces",
    "EllipticCylinder": ".surfaces",
    "EllipticParaboloid": ".surfaces",
    "GeneralCone": ".surfaces",
    "GeneralCylinder": ".surfaces",
    "HyperbolicCylinder": ".surfaces",
    "HyperbolicParaboloid": ".surfaces",
    "HyperboloidOneSheet": ".surfaces",
    "HyperboloidTwoSheets": ".surfaces",
    "ParabolicCylinder": ".surfaces",
    "Pseudosphere": ".surfaces",
    "Quadric": ".surfaces",
    "RuledSurface": ".surfaces",
    "Sphere": ".surfaces",
    "Surface": ".surfaces",
    "SurfaceOfRevolution": ".surfaces",
    "TangentSurface": ".surfaces",
    "TripleOrthogonalSystem": ".surfaces",
    "Catenoid": ".surfaces.classical",
    "DupinCyclide": ".surfaces.quartic",
    "Enneper": ".surfaces.classical",
    "Helicoid": ".surfaces.classical",
    "MonkeySaddle": ".surfaces.classical",
    "ParametricSurface": ".surfaces.parametric",
    "MoebiusStrip": ".surfaces.onesided",
    "KleinBottle": ".surfaces.onesided",
    "BoySurface": ".surfaces.onesided",
    "RomanSurface": ".surfaces.onesided",
    "CrossCap": ".surfaces.onesided",
    "Torus": ".surfaces.quartic",
    "Profile": ".surfaces.profiles",
    "named_profile": ".surfaces.profiles",
    "profile_from_points": ".surfaces.profiles",
    "orbit": ".projectors",
    "animate": ".animation",
    "interact": ".notebook",
}


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'lgraph' has no attribute {name!r}")
    value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))


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
    "HiddenStyles",
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
__all__ += ["load_scene_file", "SceneFileError", "SceneFileWarning"]
__all__ += ["Label", "Point", "PlacedLabel", "Group"]
__all__ += ["SurfaceOfRevolution", "Pseudosphere"]
__all__ += ["Profile", "named_profile", "profile_from_points"]
__all__ += ["LevelLines", "ParabolicLines", "SelfIntersection"]
__all__ += ["orbit", "animate", "interact"]
__all__ += ["MoebiusStrip", "KleinBottle", "BoySurface", "RomanSurface", "CrossCap"]

# algebraic and implicit surfaces (issue #29)
_EXPORTS |= {
    "ImplicitSurface": ".surfaces.implicit",
    "AlgebraicSurface": ".surfaces.algebraic",
    "CayleyCubic": ".surfaces.algebraic",
    "ClebschCubic": ".surfaces.algebraic",
    "GoursatSurface": ".surfaces.algebraic",
    "KummerSurface": ".surfaces.algebraic",
    "RomanSteiner": ".surfaces.algebraic",
    "Singularities": ".families.singular",
}
__all__ += ["ImplicitSurface", "AlgebraicSurface", "CayleyCubic", "ClebschCubic"]
__all__ += ["GoursatSurface", "KummerSurface", "RomanSteiner", "Singularities"]
