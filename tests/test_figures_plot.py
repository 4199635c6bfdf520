"""``drawing.plot(ax)`` complete (issue #27): labels as matplotlib text with
mathtext, point marks, hidden parts dashed, and a legend by family."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
plt = pytest.importorskip("matplotlib.pyplot")


@pytest.fixture(scope="module")
def drawing() -> lg.Drawing:
    sc = lg.Scene()
    sc.add(lg.Torus(2, 0.7), lg.ParameterLines(4, 8), style={"u1": lg.Style(color="tab:blue")})
    sc.add(lg.Label("$\\kappa_n = \\frac{L}{E}$", at=(0, -2.0, 0.7), always=True, size=12))
    sc.add(lg.Label("$P$", at=(2.7, 0, 0), anchor="w", offset=(2, 1), color="red"))
    sc.add(lg.Point((2.7, 0, 0), size=4, always=True))
    return sc.render(lg.ParallelProjector.from_angles(-60, 35), hidden_lines=True)


@pytest.fixture()
def ax(drawing):
    ax = drawing.plot(legend=True)
    yield ax
    plt.close("all")


def test_labels_are_text_at_their_anchors_in_their_size_and_colour(drawing, ax):
    texts = [t for t in ax.texts]
    assert [t.get_text() for t in texts] == [lab.text for lab in drawing.labels]
    for t, lab in zip(texts, drawing.labels):
        assert t.get_position() == pytest.approx(tuple(lab.xy))
        assert t.get_fontsize() == pytest.approx(lab.size)
        assert matplotlib.colors.to_rgb(t.get_color()) == pytest.approx(lab.style.color)
    ax.figure.canvas.draw()  # mathtext typesets them (an error would raise here)
    # the "w" label: its left edge is the anchor + offset + padding, in pt
    fig = ax.figure
    t, lab = texts[1], drawing.labels[1]
    box = t.get_window_extent(fig.canvas.get_renderer())
    anchor_px = ax.transData.transform(lab.xy)
    pt = fig.dpi / 72
    assert box.x0 == pytest.approx(anchor_px[0] + (2 + 0.25 * lab.size) * pt, abs=1.5)


def test_point_marks_are_round_markers_of_their_size(drawing, ax):
    [line] = [ln for ln in ax.lines if ln.get_label() == "point"]
    assert line.get_marker() == "o" and line.get_markersize() == pytest.approx(4)
    [pt] = [s for s in drawing.strokes if s.family == "point"]
    assert np.allclose(line.get_xydata(), pt.xy[:1])


def test_hidden_parts_are_dashed_below_and_the_legend_names_the_families(drawing, ax):
    from matplotlib.collections import LineCollection

    cols = [c for c in ax.collections if isinstance(c, LineCollection)]
    labels = {c.get_label() for c in cols}
    families = {s.family for s in drawing.strokes if s.family != "point"}
    assert labels >= families
    assert {f"{f} (hidden)" for f in families if f != "contour"} <= labels | {"contour (hidden)"}
    for c in cols:
        hidden = c.get_label().endswith("(hidden)")
        assert (c.get_dashes()[0][1] is not None) == hidden
        assert c.get_zorder() == (1.5 if hidden else 2.0)
    entries = [t.get_text() for t in ax.get_legend().get_texts()]
    assert len(entries) == len(set(entries))  # one entry per family and visibility
    assert {"u1", "u2", "contour", "point"} <= set(entries)


def test_a_label_with_a_halo_gets_a_knock_out_box_its_gap_wide():
    """plot(ax) cannot cut the lines (the scale of pt to data is fixed when
    matplotlib draws): a halo is a box in the axes' colour behind the text,
    padded by the gap; the box hides the lines under the label's ink."""
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(12, 24))
    sc.add(lg.Label("$\\kappa$", at=(0, 0, 0), halo=3.0, size=20, always=True))
    sc.add(lg.Label("$N$", at=(0.5, 0, 0), always=True))
    d = sc.render(lg.ParallelProjector(direction=(0, -1, 0)))
    ax = d.plot()
    try:
        halo, plain = ax.texts
        assert plain.get_bbox_patch() is None
        patch = halo.get_bbox_patch()
        assert patch is not None and patch.get_edgecolor()[3] == 0
        assert matplotlib.colors.to_rgb(patch.get_facecolor()) == pytest.approx(
            matplotlib.colors.to_rgb(ax.get_facecolor())
        )
        fig = ax.figure
        fig.canvas.draw()
        r = fig.canvas.get_renderer()
        ink, box = halo.get_window_extent(r), patch.get_window_extent(r)
        pt = fig.dpi / 72
        assert box.x0 == pytest.approx(ink.x0 - 3 * pt, abs=1.5)
        assert box.x1 == pytest.approx(ink.x1 + 3 * pt, abs=1.5)
        assert patch.get_zorder() <= halo.get_zorder()
    finally:
        plt.close("all")
