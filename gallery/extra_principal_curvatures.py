"""A labelled construction: principal directions, normal sections and their
circles of curvature at the saddle point of a hyperbolic paraboloid."""

from __future__ import annotations

import numpy as np

import lgraph as lg

A, B = 1.4, 1.0  # z = x^2/A^2 - y^2/B^2
EXT = 1.0  # the patch |x| <= A EXT, |y| <= B EXT
KAPPA1, KAPPA2 = 2 / A**2, -2 / B**2  # principal curvatures at the origin

CAPTION = (
    "Principal curvatures at the saddle point P = 0 of the hyperbolic paraboloid "
    "z = x²/1.4² − y²/1² (|x| ≤ 1.4·1.3, |y| ≤ 1.3, parameter lines). The principal "
    "directions e1, e2 are the x and y axes; the normal sections (thick) are the "
    "parabolas z = x²/1.4² and z = −y², with curvatures κ1 = 2/1.4² ≈ 1.02 and "
    "κ2 = −2; their circles of curvature have radii 1/|κi| and centres on the normal N, "
    "above P for κ1 > 0 and below for κ2 < 0. Every line and every label is hidden "
    "exactly by the saddle (a label's anchor is tested like a point of a line); hidden "
    "parts are drawn thin and dashed, hidden labels grey."
)

SADDLE = lg.HyperbolicParaboloid(A, B, extent=EXT)
_HEAD = {"head_length": 0.1, "head_radius": 0.03}


def _circle(centre: np.ndarray, radius: float, axis: np.ndarray) -> lg.Curve:
    """The circle about ``centre`` in the plane spanned by ``axis`` and z."""
    z = np.array([0.0, 0.0, 1.0])
    return lg.Curve(
        lambda t: centre + radius * (np.cos(t)[:, None] * axis + np.sin(t)[:, None] * z),
        0.0,
        2 * np.pi,
        closed=True,
    )


def build() -> tuple[lg.Scene, lg.Projector, dict]:
    scene = lg.Scene()
    scene.add(SADDLE, lg.ParameterLines(8, 8))
    thick = lg.Style(width=1.2)
    e1, e2 = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    ext = EXT
    scene.add(lg.Curve(lambda t: np.stack([A * t, 0 * t, t * t], -1), -ext, ext), style=thick)
    scene.add(lg.Curve(lambda t: np.stack([0 * t, B * t, -t * t], -1), -ext, ext), style=thick)
    thin = lg.Style(width=0.45)
    P = np.zeros(3)
    for kappa, axis, name, anchor in ((KAPPA1, e1, "1", "w"), (KAPPA2, e2, "2", "e")):
        radius = 1 / abs(kappa)
        centre = np.array([0.0, 0.0, 1 / kappa])
        scene.add(_circle(centre, radius, axis), style=thin)
        scene.add(lg.Point(centre, size=2.5))
        # a radius, from the centre to the circle at 45 degrees, with its length
        rim = centre + radius * (np.sqrt(0.5) * axis + np.sqrt(0.5) * np.sign(kappa) * (P - centre)
                                 / radius)  # fmt: skip
        scene.add(lg.Curve(lambda t, c=centre, r=rim: c + t[:, None] * (r - c), 0.0, 1.0),
                  style=lg.Style(width=0.3))  # fmt: skip
        scene.add(lg.Label(f"$1/|\\kappa_{name}|$", at=(centre + rim) / 2, anchor="s",
                           offset=(0, 1), size=9))  # fmt: skip
        scene.add(lg.Label(f"$\\kappa_{name} {'>' if kappa > 0 else '<'} 0$",
                           at=centre + radius * axis, anchor=anchor, offset=(
                               3 if anchor == "w" else -3, 0)))  # fmt: skip
    for v, name in ((0.6 * e1, "$\\mathbf{e}_1$"), (0.6 * e2, "$\\mathbf{e}_2$")):
        scene.add(lg.Arrow(P, P + v, **_HEAD, label=name), lg.Contour(), contour=False)
    scene.add(lg.Arrow(P, (0, 0, 0.45), **_HEAD, label="$N$"), lg.Contour(), contour=False)
    scene.add(lg.Point(P, size=3.0, always=True))
    scene.add(lg.Label("$P$", at=P, anchor="ne", offset=(-3, -3), always=True))
    return scene, lg.ParallelProjector.from_angles(-62, 32), {"hidden_lines": True}


if __name__ == "__main__":
    from lgraph.gallery import run_script_main

    run_script_main(__file__, build)
