"""What the unbounded quadrics share: a patch that is drawn and hides, its pieces.

:class:`_PatchQuadric` is a :class:`~lgraph.surfaces.quadrics.quadric.Quadric`
drawn only where its ``patch_margin`` is ``>= 0``: only the patch hides
anything, contours and lines of curvature are cut to it (the clipping of
:mod:`lgraph.surfaces._patch`).  :func:`_piece_lines` draws parameter lines
on every piece of a surface made of pieces (sheets, branches).  The ray test
and the contour conic are the quadric's (docs/mathematics.rst, "Quadrics:
ray test and contour").  The surfaces themselves are in
:mod:`~lgraph.surfaces.quadrics.hyperboloids`, :mod:`~lgraph.surfaces.quadrics.paraboloids`
and :mod:`~lgraph.surfaces.quadrics.cylinders`.
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from ..._validate import as_number, finite_positive
from ...curves import CurveBatch
from .._base import Domain
from .quadric import Quadric

__all__: list[str] = []


def _optional_positive(owner: str) -> Any:
    """Keyword-only field: a positive number, or None for the class default."""

    def check(inst: Any, attribute: Any, value: Any) -> None:
        if value is not None:
            finite_positive(owner)(inst, attribute, value)

    return attrs.field(default=None, kw_only=True, converter=as_number, validator=check)


def _set_default(inst: Any, name: str, value: float) -> None:
    current = getattr(inst, name)
    object.__setattr__(inst, name, float(value if current is None else current))


def _angle(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    return np.mod(np.arctan2(y, x), 2 * np.pi)


class _PatchQuadric(Quadric):
    """A quadric drawn on the patch where :meth:`patch_margin` ``>= 0``.

    Only the patch hides anything (:meth:`in_patch` is checked by ray hits),
    contour and lines of curvature are cut to it.
    """

    def in_patch(self, points: np.ndarray) -> np.ndarray:
        return np.asarray(self.patch_margin(points)) >= 0

    def patch_margin(self, points: Any) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    def boundary(self) -> list[CurveBatch]:
        """Edges of the drawn patch; per piece for surfaces made of pieces."""
        if hasattr(self, "_pieces"):
            return _piece_lines(self, 0, 0, ("boundary", "boundary"), even=False, ends=True)
        return super().boundary()


def _piece_lines(
    surface: Any, n1: int, n2: int, names: tuple[str, str], even: bool, ends: bool = False
) -> list[CurveBatch]:
    """Lines ``u1 = const`` and ``u2 = const`` on every piece of a surface.

    ``surface._pieces()`` lists ``(u1 range, u2 range, mode, fix)``: a
    sub-rectangle of the domain, how ``u2`` values are spread (``"periodic"``
    or ``"ends"``), and ``fix = (axis, sign)`` forcing the sign of the
    piece-selecting parameter (so that ``-0.0`` and rounding never jump to
    another piece), or None.  ``even``: spread the ``u2 = const`` lines evenly
    by arc length (lines of curvature of cylinders) instead of uniformly.
    ``ends``: the pieces' edges instead (``n1, n2`` unused).
    """
    from .._patch import spread

    out: list[CurveBatch] = []
    for r1, r2, mode, fix in surface._pieces():
        per = mode == "periodic"
        sub = Domain(r1, r2, periodic=(False, per))
        c1 = sub.ends(0) if ends else sub.lines(0, n1)
        if ends:
            c2 = sub.ends(1)
        elif even:
            sg = 1.0 if fix is None or fix[0] != 1 else fix[1]
            c2 = spread(
                lambda s, r=r1[0], sg=sg: surface.point(
                    r, np.copysign(np.abs(s), sg) if sg < 0 else s
                ),
                r2[0], r2[1], n2, mode,
            )  # fmt: skip
        else:
            c2 = sub.lines(1, n2)

        def make(cols: Any, fix: Any = fix) -> Any:
            def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
                p = cols(idx, t)
                if fix is not None:
                    p[:, fix[0]] = np.copysign(np.abs(p[:, fix[0]]), fix[1])
                return p

            return uv

        if len(c1):
            out.append(
                CurveBatch.from_uv(
                    surface, names[0], np.full(len(c1), r2[0]), np.full(len(c1), r2[1]),
                    make(lambda idx, t, c1=c1: np.column_stack([c1[idx], t])), closed=per,
                )
            )  # fmt: skip
        if len(c2):
            out.append(
                CurveBatch.from_uv(
                    surface, names[1], np.full(len(c2), r1[0]), np.full(len(c2), r1[1]),
                    make(lambda idx, t, c2=c2: np.column_stack([t, c2[idx]])),
                )
            )  # fmt: skip
    return out
