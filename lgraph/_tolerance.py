"""Every numeric tolerance of lgraph, in one place.

Values are relative unless their name says otherwise.  Change them here, never
inline in the algorithms.
"""

from __future__ import annotations

#: Default chord tolerance of adaptive sampling, as a fraction of the
#: diagonal of the figure's projected bounding box (1e-4 of an A4 diagonal is
#: about 0.05 pt).
CHORD_TOLERANCE = 1e-4

#: Smallest chord tolerance accepted (1e-9 of the diagonal: far below a
#: printer's resolution, far above double precision).
MIN_CHORD_TOLERANCE = 1e-9

#: Samples per curve before adaptive refinement starts.
INITIAL_SAMPLES = 33

#: Maximum number of refinement passes.
MAX_REFINE_PASSES = 18

#: A chord is split into at most this many parts in one refinement pass.
MAX_SPLIT = 64

#: Bisection stops when the parameter bracket is this small relative to the
#: curve's parameter span (four orders of magnitude above double precision;
#: far below anything visible, and 10^10 times finer than a fixed 0.01 step).
BISECTION_RTOL = 1e-12

#: Hard cap on bisection steps.
BISECTION_MAX_STEPS = 64

#: Most sub-intervals per step when locating visibility flips (K-section).
SECTIONS = 32

#: Fixed cost of one K-section step, in units of one grouped quadric test of
#: one point (measured: a step costs about as much as 2000 such tests).
STEP_COST = 2000.0

#: A surface's transition function (``Surface.visibility_margins``, of order 1)
#: this close to zero at a flip's visible end counts as zero there: the end
#: lies on the transition itself (a curve ending on a rim), so its sign is
#: rounding noise.
TRANSITION_ZERO = 1e-13

#: A ray hit closer than this (relative to the surface's size) to the ray's
#: origin is the origin's own surface, not an occluder.
SELF_HIT_RTOL = 1e-9

#: A point this close to another quadric (relative to the quadric's size; in
#: residual of its equation relative to the equation's terms) lies on it: the
#: tie rule for coincident and touching surfaces.
COINCIDENT_RTOL = 1e-9

#: Relative step (of the parameter span) of the fourth-order central
#: differences for first derivatives (errors near 1e-12).
FD_STEP_1 = 1e-3

#: Relative step of the fourth-order central differences for second
#: derivatives (rounding and truncation errors both near 1e-10).
FD_STEP_2 = 2e-3

#: A point whose normal ``x_1 x x_2`` is shorter than this times
#: ``size^2 / (span_1 span_2)`` (the surface's typical ``|x_1| |x_2|``) is a
#: singular point of the parametrization (a cuspidal edge, a pinch point, an
#: edge or pole that collapses to a point): its normal is undefined there, and
#: the one computed is rounding or finite-difference noise (near ``1e-12``).
SINGULAR_NORMAL_RTOL = 1e-9

#: A flip of the unit normal between two grid nodes is a singular curve of
#: the parametrization (a cuspidal edge) where ``|x_1 x x_2|`` at the refined
#: crossing is below this fraction of its value at the nodes (a regular
#: surface that turns by more than 90 degrees within a grid cell has no zero).
SINGULAR_EDGE_RTOL = 1e-4

#: A singular curve whose image spans less than this fraction of the
#: surface's size is an edge collapsed to a point (drawn as nothing).
SINGULAR_COLLAPSED_RTOL = 1e-9

#: Largest number of curves a single family may request.
MAX_CURVES = 100_000

#: Largest number of sample points of one curve batch (and of the first
#: sampling of a whole scene), checked before each refinement pass: about
#: 400 MB of samples, far beyond any figure (a gallery figure has < 200 000).
MAX_POINTS = 4_000_000

#: The refined sample count predicted from the first samples' chord
#: deviations (``lgraph.render.prediction.predict_points``) is refused before
#: any ray test when it exceeds ``MAX_POINTS`` this many times: on every
#: gallery figure the prediction was 0.91 to 1.54 times the refined count
#: (the most without hidden lines, whose far sides are not refined), so a
#: render that fits the budget is not refused by it; the exact check before
#: each refinement pass stays the backstop.
POINTS_PREDICTION_MARGIN = 4.0

#: Most (ray, patch box) pairs the ray tests of a render are predicted to
#: meet on numeric surfaces (``lgraph.render.prediction``): the samples'
#: (a probe of ``RAY_PROBE`` first samples times the predicted sample
#: count), the visibility flips' (each located by K-section) and, with
#: hidden lines, the sheets counted in front of hidden samples; refused
#: before the work: 36 to 140 us a box measured, so one to five minutes of
#: work; the costliest gallery figures are predicted at most 18 600 (the
#: Klein bottle; the Roman surface 14 700).  The probe runs only above
#: ``MAX_RAY_BOXES / 97`` predicted samples a numeric surface (half that
#: when every hidden sample's sheets are counted).
MAX_RAY_BOXES = 2_000_000
RAY_PROBE = 256

#: Curves that oscillate faster than their ``INITIAL_SAMPLES`` resolve
#: (aliased) refine to far more samples than their first chords predict:
#: ``predict_points`` samples ``ALIAS_PROBE_CURVES`` curves of every family
#: of every batch (evenly spread; exact ellipses never alias) at
#: ``ALIAS_STEP`` times the density of the first samples; a curve whose
#: predicted need grows more than ``ALIAS_GROWTH`` times there is aliased
#: (a resolved curve's need stays put: within 1.14 times on the gallery),
#: and is sampled ``ALIAS_STEP`` times denser again, ``ALIAS_LEVELS``
#: levels in all (8193 samples a curve), at most ``ALIAS_MAX_POINTS``
#: points a level.
ALIAS_PROBE_CURVES = 4
ALIAS_STEP = 4
ALIAS_GROWTH = 1.5
ALIAS_LEVELS = 4
ALIAS_MAX_POINTS = 131_072

#: Rays tested together against a numeric surface (bounds the working memory).
HIT_CHUNK_RAYS = 2048

#: Most (ray, patch box) candidates of one chunk of rays against a numeric
#: surface (about 100 per ray; a torus covered four times needs ~40): more
#: means the surface winds over itself too often; refused, not computed.
HIT_MAX_CANDIDATES = 200_000

#: Grid samples per curve used to find where a curve leaves its drawn patch
#: (a patch excursion shorter than 1/384 of the parameter range may be missed).
CLIP_SAMPLES = 385

#: Bisection steps locating a patch boundary on a curve (near machine precision).
CLIP_BISECTIONS = 60

# -- ruled surfaces (lgraph.surfaces.ruled) ----------------------------------
#: grazing rays from contour points: roots closer than this (times the size)
#: to the origin are the origin's own tangency, not an occluder
RULED_CONTOUR_SELF_RTOL = 1e-6
#: ray-ruling scan: cells per radian of turning and per patch diameter of edge length
RULED_CELLS_PER_UNIT = 8
RULED_MIN_CELLS = 64
RULED_MAX_CELLS = 4096
#: samples used to measure a directrix (turning, lengths, bounds)
RULED_PRE_SAMPLES = 2049
#: root refinement stops at this relative bracket width
RULED_XTOL = 4e-16
#: matrix entries per chunk when scanning rays (memory bound)
RULED_CHUNK = 1 << 21
#: a ruled surface is developable when det(y', z, z') is below this (relative)
RULED_DEVELOPABLE_RTOL = 1e-7

# -- numeric line fields (lgraph.families.fieldlines) ---------------------------------
#: local error allowed per integration step, relative to the parameter spans
#: (lines of curvature: positions to ~1e-8 of the patch) ...
FIELD_RTOL = 1e-8
#: ... and for asymptotic lines, whose tangent is what is seen (II(t) = 0): the
#: interpolant's tangent then satisfies it to ~1e-7 relative
ASYMPTOTIC_RTOL = 5e-12
#: first and largest step, relative to the surface's size
FIELD_FIRST_STEP = 1e-2
FIELD_MAX_STEP = 5e-2
#: a line whose step must shrink below this (relative to the size) to stay
#: valid has reached a singular point (umbilic, pole, edge of the field) and stops
FIELD_MIN_STEP = 1e-7
#: longest half line (each way from its seed), in sizes
FIELD_MAX_LENGTH = 3.0
#: most integration steps of one family (all lines together): bounds the work
FIELD_MAX_ITERATIONS = 20_000
#: a line stops where the principal field's anisotropy (k2 - k1) / (|k1| + |k2|)
#: falls below this (an umbilic) ...
UMBILIC_STOP = 2e-3
#: ... and an asymptotic line where -K / (H^2 + |K|) does (a parabolic line)
PARABOLIC_STOP = 1e-2
#: a line of curvature ends where it passes this close to an umbilic (scaled
#: parameters): beyond it, lines near the one through the umbilic part ways
FIELD_SINGULAR_RTOL = 2e-4
#: a line closes when it passes this close to its seed (scaled parameters)
FIELD_CLOSE_RTOL = 1e-5
#: a new line retraces a drawn one when its seed lies this close to it (of the size)
FIELD_DUPLICATE_RTOL = 1e-5
#: the parameter lines are the field's lines when g12 and L12 (lines of
#: curvature) or L11 and L22 (asymptotic lines) vanish to this, relative
PARAMETER_LINES_RTOL = 1e-7

#: Pen plotters (lgraph.output.plotter): an end of a stroke lying within the merge
#: tolerance of another stroke over at least this many tolerances is trimmed as
#: a duplicate (a whole stroke lying so is always removed; stretches inside a
#: stroke never are: they are crossings or tangencies, and removing them would
#: split the stroke).
DUPLICATE_MIN_END = 2.0

# -- budgets of other operations (checked by lgraph._budget) -----------------
#: Longest geodesic, in multiples of its surface's size (bounding-box diagonal).
MAX_GEODESIC_TURNS = 1000
#: Largest seed grid (per parameter) of intersection curves.
MAX_INTERSECTION_GRID = 1000
#: Most marching steps of one intersection curve (the step's lower limit).
MAX_MARCH_STEPS = 200_000
#: Most frames of an animation or orbit.
MAX_FRAMES = 100_000

# -- budgets of line families (checked by lgraph._budget) ----------------------
#: Most levels of one level-line family (``LevelLines(n=...)`` or the length
#: of its ``values``; a figure has a few dozen).
MAX_LEVELS = 1000
#: Largest tracing grid (nodes per parameter) of ``LevelLines`` and
#: ``ParabolicLines``: marching squares hold about 250 bytes per node, so
#: ``1025`` needs about 270 MB (``4097`` would need 4 GB).
MAX_LEVEL_GRID = 1025
#: Most grid cells one level-line family marches: levels times
#: ``(grid - 1)^2`` (about 15 s; 1000 levels on the default grid of 193 fit).
MAX_LEVEL_CELLS = 40_000_000
#: Grid nodes of a level-line family's function evaluated at once (rows of
#: the grid in chunks: the working memory of the function stays bounded).
LEVEL_CHUNK_NODES = 65_536
#: Most numerically integrated lines per family (``n1``, ``n2``) of
#: ``LinesOfCurvature`` and ``AsymptoticLines`` (complete lines, the
#: default spacing: about 10 s for 500 + 500; closed forms and parameter
#: lines allow ``MAX_CURVES``).
MAX_FIELD_LINES = 500
#: ... with ``spacing="even"`` (its cost grows faster than the square of the
#: count: about 15 s for 100 + 100).
MAX_EVEN_FIELD_LINES = 100

# -- animation frames (lgraph.animation.window) -----------------------------------
#: ``render_options={"tolerance": "pixel"}``: raster frames are sampled so that
#: every chord stays within this many output pixels of its curve (instead of
#: the render's default, ``CHORD_TOLERANCE`` of the figure's diagonal: 0.06 px
#: in a 480 px frame).
PIXEL_TOLERANCE = 0.25

#: The most characters of one label's text, checked before anything reads it
#: (a label is a few words or a formula; a megabyte kept mathtext busy for 20 s
#: and then ran out of memory).
MAX_LABEL_LENGTH = 1000

#: The deepest nesting of groups in a label's text: braces ``{...}`` (not
#: ``\{``), ``\left...\right`` and the optional argument of ``\sqrt[...]``.
#: mathtext recurses about 45 Python frames per level (``\hat{``, ``\sqrt{``,
#: ``\frac{``), so 10 levels need about 520 of Python's default 1000 and leave
#: room for the caller; a RecursionError that still happens (unbraced chains
#: of accents) becomes a ValueError too.
MAX_LABEL_DEPTH = 10

# -- implicit and algebraic surfaces (lgraph.surfaces.implicit, algebraic) ------
#: Curves F = G = 0 (contours, sections): a traced point is on the curve when
#: both residuals, as distances |F|/|grad F| and |G|/|grad G|, are below this
#: (relative to the clip box's diagonal).
IMPLICIT_TRACE_TOL = 1e-12
#: ... traced with steps of this fraction of the clip box's diagonal, halved
#: down to ``IMPLICIT_MIN_STEP`` (then the curve ends: a singular point).
IMPLICIT_STEP = 1 / 160
IMPLICIT_MIN_STEP = 1e-6
#: Finite-difference step of the numeric gradient (fourth order) of an
#: ImplicitSurface, relative to the clip box's diagonal (10 times it for the Hessian).
IMPLICIT_FD_STEP = 1e-4
#: Samples of F along a ray's interval (the ray test of a general F), and the
#: most bisection rounds with a Lipschitz bound.
IMPLICIT_RAY_SAMPLES = 96
IMPLICIT_LIPSCHITZ_ROUNDS = 48
#: Most halvings in the Bernstein root count of a ray's polynomial.
BERNSTEIN_MAX_DEPTH = 40
#: An origin where |F| is below this fraction of F's terms in absolute value
#: lies on the algebraic surface (rounding error of evaluating F).
ON_SURFACE_RTOL = 1e-12
#: Singular points: halvings of the clip box, and the most boxes on one level.
SINGULAR_LEVELS = 11
SINGULAR_MAX_BOXES = 20_000
