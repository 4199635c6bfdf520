"""What the helpers of a surface of revolution need of it (:class:`Revolved`).

The contour, the ray test, the local analysis, the convex shortcut and the
transition functions (``_contour.py``, ``_hits.py``, ``_local.py``,
``_convex.py``, ``_fast.py``, ``_margins.py``) read the profile, its grid and
the frame of a :class:`~lgraph.surfaces.revolution.SurfaceOfRevolution`; they
type their argument with this protocol so that they need not import the class
that calls them (issue #30).  The members are exactly those they read, typed
as the class types them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, Protocol

import numpy as np

from .._domain import Parametrized

__all__ = ["Revolved"]


class Revolved(Parametrized, Protocol):
    """A surface of revolution as its helpers see it: a patch (:class:`Parametrized`)
    with its meridian profile ``t -> (rho, z)``, the profile's grid and the
    surface's frame."""

    @property
    def profile(self) -> Callable[[np.ndarray], Any] | str | Sequence[Sequence[float]]:
        """The profile ``t -> (rho, z)`` (typed as given; it holds a callable)."""
        ...

    @property
    def t_range(self) -> tuple[float, float] | None: ...

    @property
    def angle_range(self) -> tuple[float, float]: ...

    @property
    def frame(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...

    @property
    def poles(self) -> tuple[bool, bool]: ...

    @property
    def profile_closed(self) -> bool: ...

    @property
    def _grid(self) -> dict:
        """The profile on the grid of ``t`` (``t``, ``rho``, ``z``, ``drho``, ``dz``)
        and what the helpers keep with it per surface."""
        ...

    def rz(self, t: Any) -> tuple[np.ndarray, np.ndarray]: ...

    def drz(self, t: Any) -> tuple[np.ndarray, np.ndarray]: ...

    def ddrz(self, t: Any) -> tuple[np.ndarray, np.ndarray]: ...

    def _at_pole(self, t: np.ndarray) -> np.ndarray: ...

    def _roots_in_t(self, func: Callable[[np.ndarray], np.ndarray]) -> np.ndarray: ...
