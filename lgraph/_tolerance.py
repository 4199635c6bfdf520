"""Every numeric tolerance of lgraph, in one place.

Values are relative unless their name says otherwise.  Change them here, never
inline in the algorithms.
"""

from __future__ import annotations

#: Default chord tolerance of adaptive sampling, as a fraction of the
#: diagonal of the figure's projected bounding box (1e-4 of an A4 diagonal is
#: about 0.05 pt).
CHORD_TOLERANCE = 1e-4

#: Samples per curve before adaptive refinement starts.
INITIAL_SAMPLES = 33

#: Maximum number of refinement passes (each may halve every segment).
MAX_REFINE_PASSES = 18

#: Bisection stops when the parameter bracket is this small relative to the
#: curve's parameter span (close to machine precision).
BISECTION_RTOL = 4e-16

#: Hard cap on bisection steps.
BISECTION_MAX_STEPS = 64

#: A ray hit closer than this (relative to the surface's size) to the ray's
#: origin is the origin's own surface, not an occluder.
SELF_HIT_RTOL = 1e-9

#: Relative step of central finite differences for first derivatives.
FD_STEP_1 = 6e-6

#: Relative step of central finite differences for second derivatives.
FD_STEP_2 = 1e-4

#: Largest number of curves a single family may request.
MAX_CURVES = 100_000

#: Largest number of points a single rendered figure may hold.
MAX_POINTS = 50_000_000
