"""The render pipeline: sampling, visibility and exact transitions.

1. every node's families give curve batches (in the node's local frame);
2. the initial samples are tested against every surface in the scene
   (vectorized, with a projected bounding-box cull; :mod:`lgraph.render.occlusion`),
   and samples are added on both sides of contour crossings that they miss
   (exact ellipses on their own ellipsoid, in closed form);
3. all curves are sampled adaptively until each chord deviates from the true
   projected curve by at most ``tolerance`` times the figure's diagonal
   (:mod:`lgraph.render.sampling`) -- except, without hidden lines, chords on the
   far side of their own ellipsoid -- and the new samples are tested;
4. where the projected net (the exact outlines of the ellipsoids, the
   contours and boundaries of the other hiding surfaces) crosses one chord
   twice or more, a sample is tested between every two crossings
   (:mod:`lgraph.render.crossings`): a hidden piece shorter than a chord is
   not missed;
5. where visibility flips between two samples, the flip is located to near
   machine precision on the curve parameter (:mod:`lgraph.render.flips`);
6. with hidden lines, every hidden sample counts the surface sheets in
   front of it, and where the count changes along a curve the change is
   located like a flip (:mod:`lgraph.render.depth`);
7. runs of equal visibility and depth become strokes, hidden ones styled by
   the ``hidden_style`` rule (``lgraph.render.strokes``);
8. labels and point marks are placed and hidden like the lines
   (:mod:`lgraph.render.marks`).

A scene of one ellipsoid drawn by exact ellipses (its parameter lines and
contour, nothing else) takes steps 2 to 6 in closed form instead, without a
ray test (``lgraph/render/lone.py``): the same strokes at a fraction of the
fixed cost.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from .. import _tolerance as tol
from .._validate import as_number, positive_finite
from ..geometry.transforms import Transform
from ..output.drawing import Drawing, Stroke
from ..output.page import Page, _page
from ..scene.projectors import CentralProjector, ParallelProjector, Projector
from ..scene.style import OUTLINE, HiddenStyle, Style, hidden_style_rule
from .crossings import seed_net_crossings
from .depth import occlusion_depth
from .flips import locate_flips, seed_crossings
from .intersections import intersection_batches, meeting_pairs
from .lone import lone_ellipsoid, lone_visibility
from .occlusion import NotBatchable, Occlusion
from .prediction import RayMeter, Work, later_work, predict_points, probe_ray_tests
from .sampling import Samples, check_points, refine
from .strokes import run_strokes
from .twins import twin_groups
from .views import Views

if TYPE_CHECKING:
    from ._protocols import NodeT, Renderable, RenderNode

__all__ = ["render", "render_views", "local_projector"]


def local_projector(projector: Projector, transform: Transform) -> Projector:
    """The projector expressed in the local frame of a node with ``transform``.

    Only its view geometry (rays, view vectors, contour) is meaningful.
    """
    if transform.is_identity:
        return projector
    inv = transform.inverse()
    if isinstance(projector, CentralProjector):
        up = inv.apply_vector(projector.up)
        return CentralProjector(
            eye=inv.apply(projector.eye),
            target=inv.apply(projector.target),
            up=up if np.any(up) else (0, 0, 1),
        )
    d = inv.apply_vector(projector.frame[2])
    up = inv.apply_vector(projector.frame[1])
    return ParallelProjector(direction=d, up=up)


def _classify(s: Samples, vis: Occlusion, rows: np.ndarray | None = None) -> None:
    """Test the fresh samples (or those of ``rows``) against the scene, in one call."""
    f = np.flatnonzero(s.fresh) if rows is None else rows
    if not len(f):
        return
    cause = np.empty(len(f), dtype=np.int64)
    owner, kind = s.owners(f)
    # np.take: rows gathered several times faster than by fancy indexing
    xyz, xy = np.take(s.xyz, f, axis=0), np.take(s.xy, f, axis=0)
    s.hidden[f] = vis.hidden(xyz, xy, owner, kind, cause, view=s.view[s.cid[f]])
    s.cause[f] = cause
    s.fresh[f] = False


def _self_hidden(s: Samples, vis: Occlusion) -> np.ndarray | None:
    """Samples hidden by their own closed quadric (on its far side).

    When hidden lines are not drawn, a chord between two of them is not
    refined.  A visible piece inside such a chord would have to cross the
    contour twice within it; for exact ellipses (parameter lines of
    ellipsoids) :func:`~lgraph.render.flips.seed_crossings` has put samples at
    both crossings already; other curves could, in principle, hide such a
    near-tangency shorter than the chord.  Chords hidden by *other* surfaces
    are refined as usual, so that visible pieces peeking out between hidden
    samples keep being found.
    """
    if not vis.nq:
        return None
    q = s.cause
    return (q >= 0) & (vis.q_node[np.maximum(q, 0)] == s.owner[s.cid])


def _undrawn(nodes: tuple, first: np.ndarray, ni: int) -> Any:
    """Node ``ni`` less what an earlier node holding the same surface in the
    same place (a surface added twice; ``first`` from :func:`twin_groups`)
    already draws: its contour and boundary, and families equal to that
    node's.  Coincident copies are drawn once, with the first copy's style."""
    node = nodes[ni]
    if first[ni] < 0 or first[ni] == ni:
        return node
    earlier = nodes[int(first[ni])]
    families = tuple(f for f in node.families if f not in earlier.families)
    return attrs.evolve(node, families=families, contour=node.contour and not earlier.contour)


def render(
    scene: Renderable[NodeT],
    projector: Projector,
    *,
    hidden_lines: bool = False,
    tolerance: float = tol.CHORD_TOLERANCE,
    page: Page | tuple[float, float] | None = None,
    hidden_style: HiddenStyle | None = None,
    intersections: bool = True,
) -> Drawing:
    """Render ``scene`` as seen by ``projector`` (see :meth:`lgraph.Scene.render`)."""
    if not isinstance(projector, Projector):
        raise TypeError(
            "Scene.render: projector must be a ParallelProjector or CentralProjector, "
            f"got {type(projector).__name__}"
        )
    options = _checked_options(hidden_lines, tolerance, page, hidden_style, intersections)
    return _render(scene, Views([projector]), *options)[0]


def render_views(
    scene: Renderable[NodeT],
    projectors: Sequence[Projector],
    *,
    hidden_lines: bool = False,
    tolerance: float = tol.CHORD_TOLERANCE,
    page: Page | tuple[float, float] | None = None,
    hidden_style: HiddenStyle | None = None,
    chord: float | None = None,
    intersections: bool = True,
) -> list[Drawing]:
    """Render ``scene`` from every projector in one pass (the frames of an
    animation): one drawing per projector, the drawing :func:`render` gives
    for it (options as there).

    ``chord``, a length in the projection plane, replaces ``tolerance``: every
    chord within that distance of its curve in every view (within 1e-9 and
    0.1 of the view's figure diagonal, the limits of ``tolerance``).  Frames
    that share one window and scale use it to sample to a fixed fraction of
    a pixel whatever the size of the figure in each view.

    The curves of all views are sampled, tested and split together
    (:mod:`lgraph.render.views`), so the fixed cost of each pipeline stage is
    paid once for all of them.  Each view is sampled, tested and split with
    its own projector and tolerance as when rendered alone; a flip located
    by K-section may end within its bracket width (``BISECTION_RTOL`` of the
    curve's span) elsewhere.  Memory grows with the number of views: the
    budget ``MAX_POINTS`` counts the samples of all views.

    >>> import lgraph as lg
    >>> scene = lg.Scene()
    >>> _ = scene.add(lg.Sphere(1), lg.ParameterLines(4, 6))
    >>> views = lg.orbit(elevation=30, frames=3)
    >>> [len(d.strokes) for d in render_views(scene, views)]
    [11, 11, 11]
    """
    projectors = list(projectors)
    for k, p in enumerate(projectors):
        if not isinstance(p, Projector):
            raise TypeError(
                f"render_views: projectors[{k}] must be a ParallelProjector or "
                f"CentralProjector, got {type(p).__name__}"
            )
    if not projectors:
        return []
    options = _checked_options(hidden_lines, tolerance, page, hidden_style, intersections)
    if chord is not None:
        options = (*options, positive_finite("render_views", "chord", chord))
    try:
        return _render(scene, Views(projectors), *options)
    except NotBatchable:  # e.g. an eye inside a sphere's box in some views only
        return [_render(scene, Views([p]), *options)[0] for p in projectors]


def _checked_options(
    hidden_lines: object,
    tolerance: object,
    page: object,
    hidden_style: object,
    intersections: object = True,
) -> tuple[bool, float, Page | None, Callable[[str, int], Style | None], bool]:
    """The render options, checked (errors name the bad one)."""
    tolerance = as_number(tolerance)
    if not (
        isinstance(tolerance, (int, float))
        and not isinstance(tolerance, bool)
        and math.isfinite(tolerance)
        and tol.MIN_CHORD_TOLERANCE <= tolerance <= 0.1
    ):
        raise ValueError(
            f"Scene.render: tolerance must be a number in [{tol.MIN_CHORD_TOLERANCE:g}, 0.1] "
            f"(a fraction of the figure's diagonal), got {tolerance!r}"
        )
    for name, flag in (("hidden_lines", hidden_lines), ("intersections", intersections)):
        if not isinstance(flag, (bool, np.bool_)):
            raise TypeError(f"Scene.render: {name} must be True or False, got {flag!r}")
    rule = hidden_style_rule(hidden_style)
    page = _checked_page(page)
    return bool(hidden_lines), tolerance, page, rule, bool(intersections)


def _render(
    scene: Renderable[NodeT],
    views: Views,
    hidden_lines: bool,
    tolerance: float,
    page: Page | None,
    rule: Callable[[str, int], Style | None],
    intersections: bool,
    chord: float | None = None,
) -> list[Drawing]:
    """The pipeline (module docstring) for every view at once; chords within
    ``tolerance`` of each view's figure diagonal, or within ``chord``."""
    nodes = scene.nodes
    first = twin_groups(nodes)
    drawn = [_undrawn(nodes, first, ni) for ni in range(len(nodes))]
    per_node = [
        scene.view_batches(node, [local_projector(p, node.transform) for p in views.projectors])
        for node in drawn
    ]
    # the curves where two surfaces meet, drawn on one of them, lie on both
    partner: dict[int, int] = {}  # id of such a batch -> the other node
    meeting = meeting_pairs(nodes, first)
    drawn_meetings = [
        (a, b)
        for a, b in meeting
        if intersections and nodes[a].intersections and nodes[b].intersections
    ]
    for ni, extra in intersection_batches(nodes, drawn_meetings).items():
        per_node[ni] = [[*in_view, *(b for b, _ in extra)] for in_view in per_node[ni]]
        partner.update((id(b), other) for b, other in extra)
    batches = [
        (ni, b, nodes[ni].transform, k)
        for k in range(views.k)
        for ni, in_views in enumerate(per_node)
        for b in in_views[k]
        if len(b)
    ]
    check_points(tol.INITIAL_SAMPLES * sum(len(b[1]) for b in batches))
    if not batches:
        return [
            _with_marks(scene, [], nodes, p, hidden_lines, rule, page) for p in views.projectors
        ]
    s = Samples(batches, views)
    behind = views.behind(s.xyz, s.view[s.cid])
    if behind.any():
        node = s.parts[s.part[s.cid[np.argmax(behind)]]].node
        raise ValueError(
            f"CentralProjector: part of node {node} ({nodes[node].item!r}) lies at or "
            "behind the eye; move the eye farther away"
        )
    # column by column: numpy reduces an (n, 2) array along an axis slowly
    x, y = s.xy[:, 0], s.xy[:, 1]
    finite = np.isfinite(x) & np.isfinite(y)
    if not finite.all():
        batch, node, _, _ = s.parts[s.part[s.cid[np.argmin(finite)]]]
        raise ValueError(
            f"render: node {node} ({nodes[node].item!r}) produced non-finite points "
            f"in family {batch.family!r}"
        )
    diag = [0.0] * views.k  # of each view's figure (a view without curves: 0)
    for k, rows in views.groups(s.view[s.cid]):
        xk, yk = x[rows], y[rows]
        diag[k] = math.hypot(xk.max() - xk.min(), yk.max() - yk.min())
    if chord is None:
        abs_tol = [tolerance * (d if d > 0 else 1.0) for d in diag]
    else:
        abs_tol = [
            chord if d <= 0 else min(max(chord, tol.MIN_CHORD_TOLERANCE * d), 0.1 * d) for d in diag
        ]
    chord_tol = abs_tol[0] if views.k == 1 else np.array(abs_tol)[s.view]
    # budgets predicted: a sampling, or ray tests, far over the budget are
    # refused before the ray tests (:mod:`lgraph.render.prediction`)
    predicted = predict_points(s, chord_tol)
    lone = lone_ellipsoid(nodes, s)
    if lone is not None:  # one ellipsoid: visibility in closed form (render/lone.py)
        vis, depth = None, lone_visibility(s, nodes[lone], chord_tol, hidden_lines)
    else:
        vis, depth = _visibility(
            s, nodes, views, partner, meeting, drawn_meetings, predicted, abs_tol, diag,
            hidden_lines,
        )  # fmt: skip
    strokes = run_strokes(s, nodes, hidden_lines, rule, [1e-12 * d for d in diag], depth)
    _warn_unused_styles(s, nodes)
    return [
        _with_marks(scene, strokes[k], nodes, p, hidden_lines, rule, page, vis, k)
        for k, p in enumerate(views.projectors)
    ]


def _visibility(
    s: Samples,
    nodes: tuple[RenderNode, ...],
    views: Views,
    partner: dict[int, int],
    meeting: list[tuple[int, int]],
    drawn_meetings: list[tuple[int, int]],
    predicted: int,
    abs_tol: list[float],
    diag: list[float],
    hidden_lines: bool,
) -> tuple[Occlusion, np.ndarray]:
    """The general pipeline's visibility stages (module docstring): every
    sample tested, chords refined, the net's crossings seeded, flips
    located; the scene's occlusion test and every sample's occlusion depth."""
    chord_tol = abs_tol[0] if views.k == 1 else np.array(abs_tol)[s.view]
    shared = _shared_owners(s, partner, len(nodes))
    vis = Occlusion(nodes, views, shared)
    # with hidden lines, a hiding surface asked one by one that draws no
    # contour leaves a gap in the net, and so do surfaces that may meet
    # without their intersection drawn: then every hidden sample's sheets
    # are counted
    every = any(not nodes[j].contour for j in vis.twins)
    every |= any(nodes[a].hides and nodes[b].hides for a, b in set(meeting) - set(drawn_meetings))
    meter = RayMeter(nodes)  # the patch boxes a ray meets on numeric surfaces

    def later(rows: np.ndarray | None = None, **kw: Any) -> Callable[[], list[Work]]:
        """The later stages' ray tests predicted (counting sheets, locating
        flips), computed only when a check needs them."""
        return lambda: later_work(s, vis, nodes, hidden_lines, every, tested=rows, **kw)

    def probed(rows: np.ndarray) -> list[Work]:
        return later(rows, samples=predicted)()

    probe_ray_tests(s, vis, meter, predicted, _classify, probed, hidden_lines and every)
    meter.run(_classify, s, vis)
    first: list[Work] = []  # the flips between the first samples, kept for later

    def at_first() -> list[Work]:
        first[:] = later(samples=predicted)()
        return first

    meter.check(predicted, "predicted", at_first, s)
    seed_crossings(s, vis)
    settled = None if hidden_lines else _self_hidden(s, vis)
    refine(s, chord_tol, settled)
    flips = [w for w in first if w.kind == "flips"]  # before the refined samples' ray tests:

    def at_refined() -> list[Work]:
        return [*later(np.flatnonzero(~s.fresh), samples=len(s.t))(), *flips]

    meter.check(int(s.fresh.sum()), "refined", at_refined, s)
    _classify(s, vis)
    # a short piece between two samples: chords crossed twice by the net, or
    # passed closer than the two polylines' tolerances
    if seed_net_crossings(s, vis, 2 * np.asarray(abs_tol)):
        _classify(s, vis)
    meter.check(0, "", later(exact=True), s)  # the flips counted, before they are located
    locate_flips(s, vis)
    # hidden runs split where the number of sheets in front changes
    if hidden_lines:
        return vis, occlusion_depth(s, vis, every, diag)
    return vis, s.hidden.astype(np.int64)


def _shared_owners(s: Samples, partner: dict[int, int], n: int) -> list[tuple[int, int]]:
    """Give the curves that lie on two nodes (``partner``: id of their batch
    -> the other node) the owner ``n + k`` of pair ``k`` (see
    :class:`~lgraph.render.occlusion.Occlusion`); returns the pairs."""
    pairs: dict[tuple[int, int], int] = {}
    for part in s.parts:
        other = partner.get(id(part.batch))
        if other is None:
            continue
        k = pairs.setdefault((part.node, other), len(pairs))
        s.owner[part.first : part.first + len(part.batch)] = n + k
    return list(pairs)


def _with_marks(
    scene: Renderable[NodeT],
    strokes: list[Stroke],
    nodes: tuple[RenderNode, ...],
    projector: Projector,
    hidden_lines: bool,
    rule: Callable[[str, int], Style | None],
    page: Page | tuple[float, float] | None,
    vis: Occlusion | None = None,
    view: int = 0,
) -> Drawing:
    """The drawing, with the scene's labels and point marks placed
    (:mod:`lgraph.render.marks`; ``vis`` tests points in view ``view``)."""
    labels, points = scene.labels, scene.points
    placed: list = []
    if labels or points:
        from .marks import place_marks

        if vis is None:
            vis, view = Occlusion(nodes, projector), 0
        halo = getattr(scene, "halo", False)
        placed, dots = place_marks(labels, points, projector, vis, hidden_lines, rule, view, halo)
        strokes = strokes + dots
    return Drawing(strokes=strokes, page=page, labels=placed)


def _checked_page(page: object) -> Page | None:
    """``page`` as a Page (or None), checked before any rendering."""
    if page is None or isinstance(page, Page):
        return page

    try:
        return _page(page)
    except (TypeError, ValueError) as e:
        raise ValueError(
            f"Scene.render: page must be a Page, (width, height) in pt or None, got {page!r} ({e})"
        ) from None


def _warn_unused_styles(s: Samples, nodes: tuple[RenderNode, ...]) -> None:
    """Warn about keys of a node's style dict that name no family it draws
    (a typo such as ``"kontour"`` would otherwise pass silently)."""
    drawn: dict[int, set[str]] = {}
    for batch, node, _, _ in s.parts:
        names = batch.curve_family
        got = {batch.family} if names is None else set(names)
        if "contour" in got:
            got.add(getattr(batch.surface, "outline_family", "contour"))
        drawn.setdefault(node, set()).update(got)
    for k, node in enumerate(nodes):
        if isinstance(node.style, dict):
            unused = sorted(set(node.style) - drawn.get(k, set()) - {"default", *OUTLINE})
            if unused:
                warnings.warn(
                    f"Scene.render: node {k} ({node.item!r}) has styles for {unused}, which it "
                    f"does not draw; it draws {sorted(drawn.get(k, set()))}",
                    stacklevel=5,
                )
