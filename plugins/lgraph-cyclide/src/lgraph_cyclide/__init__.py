"""lgraph-cyclide: an example lgraph plugin.

Registers, through entry points (see ``pyproject.toml``):

* the surface ``cyclide`` -> :class:`DupinCyclide` (group ``lgraph.surfaces``),
* the line family ``diagonal_lines`` -> :class:`DiagonalLines` (group ``lgraph.families``).

>>> import lgraph as lg
>>> from lgraph_cyclide import DupinCyclide
>>> scene = lg.Scene()
>>> _ = scene.add(DupinCyclide(5, 2, 3), lg.LinesOfCurvature(12, 16))
>>> d = scene.render(lg.ParallelProjector.from_angles(30, 35))
>>> sorted({s.family for s in d.strokes})
['contour', 'curvature']
"""

from __future__ import annotations

from ._cyclide import DupinCyclide
from ._diagonal import DiagonalLines

__all__ = ["DupinCyclide", "DiagonalLines"]
__version__ = "0.1.0"
