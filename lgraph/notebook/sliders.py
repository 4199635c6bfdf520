"""An interactive view for Jupyter: sliders for azimuth, elevation and distance.

``lg.interact(scene)`` returns an ipywidgets box (optional dependency,
``pip install 'lgraph[jupyter]'``) with the picture and its sliders; moving
a slider re-renders the scene from the new view.  The view-independent
geometry comes from the cache (:mod:`lgraph.families.cache`), so only the
contour and the visibility are recomputed.  lgraph imports ipywidgets only
when :func:`interact` is called.
"""

from __future__ import annotations

from typing import Any

__all__ = ["interact", "InteractiveView"]


def _widgets() -> Any:
    try:
        import ipywidgets
    except ImportError:
        raise ImportError(
            "lg.interact needs ipywidgets, which is not installed; install it with "
            "pip install 'lgraph[jupyter]' (or pip install ipywidgets)"
        ) from None
    return ipywidgets


class InteractiveView:
    """The state behind :func:`interact`: sliders, the image and the render.

    Attributes
    ----------
    widget : ipywidgets.VBox
        What a notebook cell displays (sliders above the picture).
    azimuth, elevation, distance : ipywidgets.FloatSlider
        The sliders (``distance`` is None for parallel projection).
    image : ipywidgets.Image
        The picture (PNG bytes in ``image.value``).
    drawing : Drawing
        The last rendered drawing.
    """

    def __init__(
        self,
        scene: Any,
        *,
        azimuth: float,
        elevation: float,
        distance: float | None,
        hidden_lines: bool,
        width: int,
    ) -> None:
        w = _widgets()
        self.scene = scene
        self.hidden_lines = hidden_lines
        self.width = width
        slider = dict(continuous_update=False, readout_format=".0f")
        self.azimuth = w.FloatSlider(
            value=azimuth, min=-180.0, max=180.0, step=5.0, description="azimuth", **slider
        )
        self.elevation = w.FloatSlider(
            value=elevation, min=-90.0, max=90.0, step=5.0, description="elevation", **slider
        )
        self.distance = None
        sliders = [self.azimuth, self.elevation]
        if distance is not None:
            self.distance = w.FloatSlider(
                value=distance,
                min=distance / 4,
                max=distance * 4,
                step=distance / 40,
                description="distance",
                continuous_update=False,
                readout_format=".1f",
            )
            sliders.append(self.distance)
        self.image = w.Image(format="png")
        self.widget = w.VBox([w.HBox(sliders), self.image])
        for s in sliders:
            s.observe(self._changed, names="value")
        self.update()

    def projector(self) -> Any:
        """The projector for the sliders' current values."""
        from ..scene.projectors import CentralProjector, ParallelProjector

        az, el = float(self.azimuth.value), float(self.elevation.value)
        if self.distance is None:
            return ParallelProjector.from_angles(az, el)
        return CentralProjector.from_angles(az, el, float(self.distance.value))

    def update(self) -> None:
        """Render the current view into the image."""
        d = self.scene.render(self.projector(), hidden_lines=self.hidden_lines)
        self.drawing = d
        self.image.value = _png(d, self.width)

    def _changed(self, _change: Any) -> None:
        self.update()

    def _repr_mimebundle_(self, **kwargs: Any) -> Any:
        return self.widget._repr_mimebundle_(**kwargs)


def _png(drawing: Any, width: int) -> bytes:
    from .display import to_bytes

    pw, ph = drawing.page_size()
    return to_bytes(drawing, "png", size=(width, max(1, round(width * ph / pw))))


def interact(
    scene: Any,
    *,
    azimuth: float = -60.0,
    elevation: float = 30.0,
    distance: float | None = None,
    hidden_lines: bool = False,
    width: int = 480,
) -> InteractiveView:
    """Show ``scene`` with azimuth/elevation (and distance) sliders in Jupyter.

    Parameters
    ----------
    scene : Scene
        What to draw.
    azimuth, elevation : float
        The first view, in degrees (as ``ParallelProjector.from_angles``).
    distance : float, optional
        Central projection from this distance, with a distance slider; None
        (default) gives parallel projection.
    hidden_lines : bool
        Draw hidden parts dashed.
    width : int
        Picture width in pixels.

    Returns
    -------
    InteractiveView
        Displays itself as the widget; ``.widget`` is the ipywidgets box.
    """
    from ..scene.graph import Scene

    if not isinstance(scene, Scene):
        raise TypeError(f"interact: scene must be a Scene, got {type(scene).__name__}")
    if isinstance(width, bool) or not isinstance(width, int) or not 16 <= width <= 4000:
        raise ValueError(f"interact: width must be an integer from 16 to 4000 px, got {width!r}")
    if distance is not None and not (
        isinstance(distance, (int, float)) and not isinstance(distance, bool) and distance > 0
    ):
        raise ValueError(f"interact: distance must be a positive number or None, got {distance!r}")
    return InteractiveView(
        scene,
        azimuth=azimuth,
        elevation=elevation,
        distance=distance,
        hidden_lines=hidden_lines,
        width=width,
    )
