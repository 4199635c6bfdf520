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

from . import _moved

_moved.install()  # the module paths from before the folders (issue #30) keep working

#: public name -> the module that defines it; imported on first use (PEP 562), so
#: ``import lgraph`` costs only this table and a script pays for what it uses
_EXPORTS: dict[str, str] = {
    "principal_curvatures": ".curvature",
    "principal_directions": ".curvature",
    "Curve": ".curves",
    "CurveBatch": ".curves",
    "CurveOnSurface": ".curves",
    "HIDDEN_STYLE": ".scene.style",
    "HiddenStyles": ".scene.style",
    "Drawing": ".output.drawing",
    "Page": ".output.page",
    "PlacedLabel": ".output.drawing",
    "Stroke": ".output.drawing",
    "Style": ".scene.style",
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
    "Label": ".scene.objects.marks",
    "Point": ".scene.objects.marks",
    "ParabolicLines": ".families.parabolic",
    "CentralProjector": ".scene.projectors",
    "ParallelProjector": ".scene.projectors",
    "Projector": ".scene.projectors",
    "Group": ".scene.graph",
    "Node": ".scene.graph",
    "Scene": ".scene.graph",
    "SceneFileError": ".scenefile",
    "SceneFileWarning": ".scenefile",
    "load_scene_file": ".scenefile",
    "SelfIntersection": ".families.self_intersection",
    "Arrow": ".scene.objects.shapes",
    "AsymptoticLines": ".families.asymptotic",
    "Geodesic": ".families.geodesic",
    "IntersectionCurve": ".families.intersection",
    "Parallelogram": ".scene.objects.shapes",
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
    "DupinCyclide": ".surfaces.classical.quartic",
    "Enneper": ".surfaces.classical",
    "Helicoid": ".surfaces.classical",
    "MonkeySaddle": ".surfaces.classical",
    "ParametricSurface": ".surfaces.parametric",
    "MoebiusStrip": ".surfaces.classical.onesided",
    "KleinBottle": ".surfaces.classical.onesided",
    "BoySurface": ".surfaces.classical.onesided",
    "RomanSurface": ".surfaces.classical.onesided",
    "CrossCap": ".surfaces.classical.onesided",
    "Torus": ".surfaces.classical.quartic",
    "Profile": ".surfaces.revolution.profiles",
    "named_profile": ".surfaces.revolution.profiles",
    "profile_from_points": ".surfaces.revolution.profiles",
    "orbit": ".scene.projectors",
    "animate": ".animation.frames",
    "interact": ".notebook.sliders",
}


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        if f"{__name__}.{name}" in _moved.MOVED:  # lg.backends, lg.drawing: old modules
            return importlib.import_module(f"{__name__}.{name}")
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
    "AlgebraicSurface": ".surfaces.implicit.algebraic",
    "CayleyCubic": ".surfaces.implicit.algebraic",
    "ClebschCubic": ".surfaces.implicit.algebraic",
    "GoursatSurface": ".surfaces.implicit.algebraic",
    "KummerSurface": ".surfaces.implicit.algebraic",
    "RomanSteiner": ".surfaces.implicit.algebraic",
    "Singularities": ".families.singular",
}
__all__ += ["ImplicitSurface", "AlgebraicSurface", "CayleyCubic", "ClebschCubic"]
__all__ += ["GoursatSurface", "KummerSurface", "RomanSteiner", "Singularities"]
