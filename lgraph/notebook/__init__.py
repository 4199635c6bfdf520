"""Notebooks and other programs: inline pictures, file objects, sliders.

``display.py`` file objects, the inline reprs of drawings and scenes, the
matplotlib bridge; ``sliders.py`` :func:`~lgraph.interact`, a view with
sliders in Jupyter.
"""

from .sliders import InteractiveView, interact

__all__ = ["interact", "InteractiveView"]
