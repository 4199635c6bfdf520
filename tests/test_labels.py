"""Labels, point marks, groups and physical sizes, each checked independently:
projections by the projector itself, hiding by a ray cast written here, PDF
page sizes read from the file, PNG ink counted in pixels, glyph outlines
compared with the glyphs set alone."""

from __future__ import annotations

import re
import subprocess
import sys
import xml.etree.ElementTree as ET
import zlib

import numpy as np
import pytest
from PIL import Image

import lgraph as lg
from lgraph.output._text import MOVETO, segments, text_shape

PROJECTORS = [
    lg.ParallelProjector(direction=(1.0, -0.6, 0.5)),
    lg.CentralProjector(eye=(7.0, -4.0, 3.5), target=(0.0, 0.0, 0.0)),
]


def _sphere_hides(points: np.ndarray, projector, centre, r) -> tuple[np.ndarray, np.ndarray]:
    """Brute force: does the ray from each point toward the viewer meet the sphere?

    Returns (hidden, margin): margin is how far the ray passes from grazing.
    """
    if isinstance(projector, lg.CentralProjector):
        w = projector.eye - points
        smax = np.linalg.norm(w, axis=1)
        v = w / smax[:, None]
    else:
        v = np.broadcast_to(projector.frame[2], points.shape)
        smax = np.full(len(points), np.inf)
    o = points - centre
    b = np.einsum("ij,ij->i", o, v)
    c = np.einsum("ij,ij->i", o, o) - r * r
    disc = b * b - c
    sq = np.sqrt(np.maximum(disc, 0))
    s1, s2 = -b - sq, -b + sq
    hit = (disc >= 0) & (((s1 > 1e-9) & (s1 < smax)) | ((s2 > 1e-9) & (s2 < smax)))
    return hit, np.abs(disc)


# -- placement and hiding ------------------------------------------------------------
@pytest.mark.parametrize("projector", PROJECTORS, ids=["parallel", "central"])
def test_label_xy_is_the_projected_anchor(projector):
    scene = lg.Scene()
    scene.add(lg.Label("P", at=(0.3, -0.2, 0.9), always=True))
    T = lg.translate(0.5, 1.0, -0.25) @ lg.rotate("z", 30)
    scene.add(lg.Label("Q", at=(1.0, 0.0, 0.0), always=True), transform=T)
    d = scene.render(projector)
    assert [lab.text for lab in d.labels] == ["P", "Q"]
    np.testing.assert_allclose(d.labels[0].xy, projector.project(np.array([0.3, -0.2, 0.9])))
    np.testing.assert_allclose(d.labels[1].xy, projector.project(T.apply([1.0, 0.0, 0.0])))
    np.testing.assert_allclose(d.labels[1].xyz, T.apply([1.0, 0.0, 0.0]))


@pytest.mark.parametrize("projector", PROJECTORS, ids=["parallel", "central"])
def test_labels_and_points_hidden_by_a_sphere_as_a_ray_cast_says(projector):
    rng = np.random.default_rng(13)
    centre, r = np.array([0.2, -0.1, 0.3]), 1.3
    pts = rng.uniform(-2.2, 2.2, size=(300, 3)) + centre
    pts = pts[np.linalg.norm(pts - centre, axis=1) > r + 1e-3]  # outside the sphere
    hidden, margin = _sphere_hides(pts, projector, centre, r)
    sure = margin > 1e-6  # not grazing the sphere's outline
    assert hidden[sure].sum() > 20 and (~hidden[sure]).sum() > 20
    scene = lg.Scene()
    scene.add(lg.Sphere(r), lg.ParameterLines(2, 3), transform=lg.translate(*centre))
    for i, p in enumerate(pts):
        scene.add(lg.Label(f"L{i}", at=p))
        scene.add(lg.Point(p))
    d = scene.render(projector)
    shown = {int(lab.text[1:]) for lab in d.labels}
    expect = set(np.flatnonzero(~hidden & sure).tolist())
    assert expect <= shown
    assert not (shown & set(np.flatnonzero(hidden & sure).tolist()))
    dots = [s for s in d.strokes if s.family == "point"]
    assert len(dots) == len(d.labels)
    got = np.array([s.xyz[0] for s in dots])
    np.testing.assert_allclose(got, pts[sorted(shown)])
    # with hidden lines: every label comes back, the hidden ones marked and greyed
    dh = scene.render(projector, hidden_lines=True)
    assert len(dh.labels) == len(pts)
    vis = np.array([lab.visible for lab in dh.labels])
    assert np.array_equal(vis[sure], ~hidden[sure])
    grey = lg.HIDDEN_STYLE.color
    assert all(lab.style.color == grey for lab in dh.labels if not lab.visible)
    assert all(lab.style.color == (0.0, 0.0, 0.0) for lab in dh.labels if lab.visible)


def test_always_draws_a_hidden_label():
    scene = lg.Scene()
    scene.add(lg.Sphere(1.0), lg.ParameterLines(2, 3))
    scene.add(lg.Label("behind", at=(-2.0, 0, 0)))
    scene.add(lg.Label("always", at=(-2.0, 0, 0), always=True))
    d = scene.render(lg.ParallelProjector(direction=(1, 0, 0)))
    assert [(lab.text, lab.visible) for lab in d.labels] == [("always", True)]


def test_labels_never_change_the_strokes():
    p = PROJECTORS[1]
    a, b = lg.Scene(), lg.Scene()
    for s in (a, b):
        s.add(lg.Ellipsoid(2, 1.5, 1), lg.LinesOfCurvature(4, 4))
    b.add(lg.Label("$\\kappa_1$", at=(2, 0, 0), anchor="sw"))
    da, db = a.render(p), b.render(p)
    assert len(da.strokes) == len(db.strokes)
    for s, t in zip(da.strokes, db.strokes):
        assert np.array_equal(s.xy, t.xy) and s.family == t.family


def test_arrow_label_sits_beyond_the_tip():
    p = PROJECTORS[0]
    tail, tip = np.array([0.0, 0, 0]), np.array([0.0, 1.0, 1.0])
    scene = lg.Scene()
    scene.add(lg.Arrow(tail, tip, label="$N$"), lg.Contour(), contour=False)
    d = scene.render(p)
    (lab,) = d.labels
    np.testing.assert_allclose(lab.xy, p.project(tip))
    box = d.label_boxes()[0]
    centre = (box[:2] + box[2:]) / 2
    scale, offset, _, _ = d._layout()
    tip_page = lab.xy * scale + offset
    direction = p.project(tip) - p.project(tail)
    # the text lies on the side the arrow points to, not over the arrow
    assert (centre - tip_page) @ direction > 0


# -- groups --------------------------------------------------------------------------
def _twins():
    T1 = lg.translate(1.0, -2.0, 0.5) @ lg.rotate((1, 1, 0), 25)
    T2 = lg.rotate("z", 40) @ lg.scale(1.2, 1.0, 0.8)
    T3 = lg.translate(0.0, 0.0, 2.5)
    blue = lg.Style(color="#0033cc", width=0.7)
    red = lg.Style(color="#cc0000")
    inner = lg.Scene()
    inner.add(lg.Ellipsoid(1.0, 0.7, 0.5), lg.ParameterLines(3, 5), transform=T3)
    inner.add(lg.Sphere(0.4), lg.ParameterLines(2, 4), style=red)
    inner.add(lg.Label("$x_1$", at=(0.4, 0, 0)), transform=T3)
    inner.add(lg.Point((0.0, 0.0, 0.4)))
    middle = lg.Scene()
    middle.add(inner, transform=T2, style=blue)
    middle.add(lg.Torus(2.0, 0.3), lg.ParameterLines(4, 3))
    outer = lg.Scene()
    outer.add(middle, transform=T1)
    outer.add(middle, transform=lg.translate(-4, 0, 0))
    flat = lg.Scene()
    for T in (T1, lg.translate(-4, 0, 0)):
        flat.add(lg.Ellipsoid(1.0, 0.7, 0.5), lg.ParameterLines(3, 5), transform=T @ T2 @ T3,
                 style=blue)  # fmt: skip
        flat.add(lg.Sphere(0.4), lg.ParameterLines(2, 4), style=red, transform=T @ T2)
        flat.add(lg.Label("$x_1$", at=(0.4, 0, 0), color=blue.color), transform=T @ T2 @ T3)
        flat.add(lg.Point((0.0, 0.0, 0.4), style=blue), transform=T @ T2)
        flat.add(lg.Torus(2.0, 0.3), lg.ParameterLines(4, 3), transform=T)
    return outer, flat, (T1, T2, T3)


def test_nested_scene_renders_like_its_flat_twin():
    outer, flat, _ = _twins()
    p = PROJECTORS[1]
    a, b = outer.render(p), flat.render(p)
    assert len(outer) == len(flat) == 6
    assert len(a.strokes) == len(b.strokes) > 20
    key = lambda s: (s.family, round(float(s.xy[0, 0]), 9), round(float(s.xy[0, 1]), 9))  # noqa: E731
    for s, t in zip(sorted(a.strokes, key=key), sorted(b.strokes, key=key)):
        assert s.family == t.family and s.style == t.style and s.visible == t.visible
        np.testing.assert_allclose(s.xy, t.xy, atol=1e-12)
    assert [lab.text for lab in a.labels] == [lab.text for lab in b.labels]
    for la, lb in zip(a.labels, b.labels):
        np.testing.assert_allclose(la.xy, lb.xy, atol=1e-12)
        assert la.style == lb.style


def test_labels_in_groups_follow_the_composed_transform():
    outer, _, (T1, T2, T3) = _twins()
    labels = outer.labels
    np.testing.assert_allclose(labels[0].at, (T1 @ T2 @ T3).apply([0.4, 0, 0]))
    # composition order: outer after inner, checked point by point
    np.testing.assert_allclose(labels[0].at, T1.apply(T2.apply(T3.apply([0.4, 0, 0]))))
    p = PROJECTORS[0]
    d = outer.render(p)
    both = np.array(
        [T.apply(T2.apply(T3.apply([0.4, 0, 0]))) for T in (T1, lg.translate(-4, 0, 0))]
    )
    on = {lab.text for lab in d.labels}
    assert on <= {"$x_1$"}
    expect = p.project(both)
    for lab in d.labels:
        assert np.min(np.linalg.norm(expect - lab.xy, axis=1)) < 1e-12


def test_group_cycles_are_refused():
    a, b = lg.Scene(), lg.Scene()
    a.add(b)
    with pytest.raises(ValueError, match="cannot contain itself"):
        b.add(a)
    with pytest.raises(ValueError, match="cannot contain itself"):
        a.add(a)


# -- physical sizes ------------------------------------------------------------------
def _pdf_page(path) -> tuple[list[float], bytes]:
    data = path.read_bytes()
    box = re.search(rb"/MediaBox \[\s*([\d.\s-]+)\]", data).group(1).split()
    stream = re.search(rb"stream\r?\n(.*?)endstream", data, re.S).group(1)
    return [float(x) for x in box], stream


def test_width_in_cm_gives_the_page_width_and_keeps_line_widths(tmp_path):
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.ParameterLines(4, 6))
    scene.add(lg.Label("$P$", at=(3, 0, 0), anchor="w"))
    d = scene.render(PROJECTORS[0])
    plain = d.save(tmp_path / "plain.pdf", compress=False)
    sized = d.save(tmp_path / "sized.pdf", width="8.5cm", compress=False)
    box0, s0 = _pdf_page(plain)
    box1, s1 = _pdf_page(sized)
    assert box1[2] - box1[0] == pytest.approx(8.5 / 2.54 * 72, abs=1e-3)  # 240.945 pt
    assert round(box1[2] - box1[0]) == 241
    assert abs((box0[2] - box0[0]) - 241) > 50  # the plain page is another size
    widths = lambda s: sorted(set(re.findall(rb"\n([\d.]+) w\n", s)))  # noqa: E731
    assert widths(s0) == widths(s1) and widths(s0)
    cm = lambda s: re.findall(rb"[\d.]+ 0 0 [\d.]+ 0 0 cm", s)  # noqa: E731
    assert cm(s0) == cm(s1)
    # height, both, other units; PNG pixels follow the page
    assert d.sized(height="60mm").page_size()[1] == pytest.approx(60 / 25.4 * 72)
    w, h = d.sized(width="3in", height="1in").page_size()
    assert w <= 216 + 1e-6 and h <= 72 + 1e-6 and max(w / 216, h / 72) == pytest.approx(1)
    png = d.save(tmp_path / "a.png", width="8.5cm", dpi=72)
    assert Image.open(png).size[0] == 241
    with pytest.raises(ValueError, match="parsecs"):
        d.save(tmp_path / "b.pdf", width="8.5 parsecs")
    assert not (tmp_path / "b.pdf").exists()


def test_sized_page_without_labels_is_exact():
    s = lg.Stroke(xy=np.array([[0.0, 0.0], [3.0, 1.0]]), xyz=np.zeros((2, 3)))
    d = lg.Drawing(strokes=(s,))
    w, h = d.sized(width="10cm").page_size()
    assert w == pytest.approx(10 / 2.54 * 72, rel=1e-12)
    # no margin: the ink (points plus half the 0.5 pt line width each side) spans the page
    assert (h - 0.5) == pytest.approx((w - 0.5) / 3, rel=1e-12)


# -- ink where the text is -----------------------------------------------------------
def test_png_of_labels_has_ink_in_their_boxes_only(tmp_path):
    scene = lg.Scene()
    scene.add(lg.Label("$\\kappa_n N$", at=(0, 0, 0), anchor="sw", size=14))
    scene.add(lg.Label("plain P", at=(1.0, 0.5, 0), anchor="ne", color="#cc0000"))
    d = scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    dpi = 144
    img = np.asarray(Image.open(d.save(tmp_path / "l.png", dpi=dpi)).convert("L"))
    ink = img < 200
    _, ph = d.page_size()
    k = dpi / 72
    inside = np.zeros_like(ink)
    for x0, y0, x1, y1 in d.label_boxes():
        c0, c1 = int(np.floor(x0 * k)) - 1, int(np.ceil(x1 * k)) + 1
        r0, r1 = int(np.floor((ph - y1) * k)) - 1, int(np.ceil((ph - y0) * k)) + 1
        box = ink[r0:r1, c0:c1]
        assert box.mean() > 0.08  # real glyphs, not a speck
        inside[r0:r1, c0:c1] = True
    assert ink.sum() > 100
    assert not (ink & ~inside).any()


def test_svg_has_one_group_per_label_and_pdf_fills_glyphs(tmp_path):
    scene = lg.Scene()
    scene.add(lg.Sphere(1), lg.ParameterLines(2, 4))
    scene.add(lg.Label("$x_1$", at=(0, 0, 1.5)))
    scene.add(lg.Label("N", at=(0, 0, -1.5)))
    d = scene.render(lg.ParallelProjector(direction=(1, 0.3, 0.2)))
    root = ET.parse(d.save(tmp_path / "a.svg")).getroot()
    groups = [g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "label"]
    assert [g.get("data-text") for g in groups] == ["$x_1$", "N"]
    # all in one layer of their own, after the strokes' layers (plotter tools)
    layers = root.findall("{http://www.w3.org/2000/svg}g")
    assert layers[-1].get("{http://www.inkscape.org/namespaces/inkscape}label") == "4 labels"
    assert list(layers[-1]) == groups
    assert all(g.find("{http://www.w3.org/2000/svg}path") is not None for g in groups)
    _, stream = _pdf_page(d.save(tmp_path / "a.pdf", compress=False))
    assert stream.count(b"\nf") == 2 and b" c\n" in stream


# -- mathematics ---------------------------------------------------------------------
def _subpaths(shape) -> list[np.ndarray]:
    kind, end = segments(shape.codes)
    starts = np.flatnonzero(kind == MOVETO)
    bounds = [end[starts[i]] for i in range(len(starts))] + [len(shape.codes)]
    return [shape.vertices[bounds[i] : bounds[i + 1]] for i in range(len(starts))]


def test_kappa_n_is_a_kappa_and_a_lowered_smaller_n():
    both = _subpaths(text_shape("$\\kappa_n$", 10.0))
    kappa = _subpaths(text_shape("$\\kappa$", 10.0))
    n = _subpaths(text_shape("$n$", 10.0))
    k_letter = _subpaths(text_shape("$k$", 10.0))
    assert len(both) == len(kappa) + len(n)
    # the first glyph is exactly the kappa set alone (and not a latin k)
    for a, b in zip(both, kappa):
        np.testing.assert_allclose(a, b, atol=1e-9)
    k_all, kappa_all = np.concatenate(k_letter), np.concatenate(kappa)
    assert k_all.shape != kappa_all.shape or not np.allclose(k_all, kappa_all)
    # the rest is the n, scaled by f < 1 and moved: fit x' = f x + t
    sub = np.concatenate(both[len(kappa) :])
    alone = np.concatenate(n)
    A = np.column_stack([alone.ravel(), np.tile([1.0, 0.0], len(alone)),
                         np.tile([0.0, 1.0], len(alone))])  # fmt: skip
    (f, tx, ty), *_ = np.linalg.lstsq(A, sub.ravel(), rcond=None)
    np.testing.assert_allclose(A @ [f, tx, ty], sub.ravel(), atol=1e-6)
    assert 0.5 < f < 0.85  # a subscript size
    assert ty < -0.5  # lowered below the baseline (pt)
    assert tx > np.concatenate(kappa)[:, 0].max() - 1.0  # after the kappa


@pytest.mark.parametrize(
    "tex",
    [
        "$\\alpha \\beta \\gamma \\omega \\Gamma \\Omega$",
        "$x_1 u^2 \\kappa_{n}$",
        "$\\mathbf{x}_1 \\times \\mathbf{x}_2$",
        "$\\mathrm{d}s \\cdot x' \\partial \\nabla$",
        "$\\frac{\\partial x}{\\partial u_1}$",
    ],
)
def test_supported_tex(tex):
    lab = lg.Label(tex, at=(0, 0, 0))
    x0, y0, x1, y1 = text_shape(lab.text, lab.size).box
    assert x1 > x0 and y1 > y0


# -- bad input -----------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"text": ""}, "text must not be empty"),
        ({"text": "$x_1"}, "unbalanced \\$"),
        ({"at": (0, float("nan"), 0)}, "at must be three finite numbers"),
        ({"at": (0, float("inf"), 0)}, "at must be three finite numbers"),
        ({"size": -2}, "size must be a positive"),
        ({"anchor": "north"}, "anchor must be one of center, n, ne"),
        ({"offset": (1,)}, "offset must be two finite numbers"),
        ({"anchor": "auto"}, "needs a direction"),
    ],
)
def test_bad_labels_are_refused_at_creation(kwargs, message):
    args = {"text": "P", "at": (0, 0, 0), **kwargs}
    with pytest.raises(ValueError, match=message) as info:
        lg.Label(args.pop("text"), **args)
    if kwargs.get("text"):
        assert repr(kwargs["text"]) in str(info.value)  # names the label


def test_bad_label_in_a_scene_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 0\nelevation = 0\n'
        '[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
        '[[labels]]\ntext = "$\\\\input{x}$"\nat = [0, 0, 1]\n'
    )
    # TeX that reaches files is refused at load (mathtext's unknown commands are
    # not: they may be the document's macros, for TikZ; tests/test_figures_tex.py)
    with pytest.raises(lg.SceneFileError, match=r"s.toml:8: labels\[0\]: .*\\input"):
        lg.load_scene_file(path)
    path.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 0\nelevation = 0\n'
        '[save]\nwidth = "8.5 parsecs"\n[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
    )
    with pytest.raises(lg.SceneFileError, match=r"save.width: .*parsecs"):
        lg.load_scene_file(path)


# -- without matplotlib --------------------------------------------------------------
def test_plain_labels_need_no_matplotlib(tmp_path):
    code = f"""
import sys
sys.modules["matplotlib"] = None  # as if not installed
import lgraph as lg
scene = lg.Scene()
scene.add(lg.Sphere(1), lg.ParameterLines(2, 3))
scene.add(lg.Label("P plain", at=(0, 0, 1.3)))
d = scene.render(lg.ParallelProjector(direction=(1, 0, 0.3)))
for suffix in (".pdf", ".svg", ".png"):
    d.save(r"{tmp_path}" + "/a" + suffix)
scene.add(lg.Label("$x$", at=(0, 0, 1.3)))
d = scene.render(lg.ParallelProjector(direction=(1, 0, 0.3)))
try:
    d.save(r"{tmp_path}" + "/b.pdf")
except ImportError as e:
    print("ImportError", e)
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "lgraph[labels]" in r.stdout
    img = np.asarray(Image.open(tmp_path / "a.png").convert("L"))
    assert (img < 128).sum() > 0
    assert b"Times-Roman" in (tmp_path / "a.pdf").read_bytes()


def test_import_lgraph_does_not_import_matplotlib():
    code = (
        "import sys, lgraph as lg\n"
        "s = lg.Scene(); s.add(lg.Sphere(1)); s.add(lg.Label('P', at=(0, 0, 2)))\n"
        "s.render(lg.ParallelProjector(direction=(1, 0, 0)))\n"
        "print('matplotlib' in sys.modules)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "False"


def test_pdf_stream_is_deflated_by_default(tmp_path):
    scene = lg.Scene()
    scene.add(lg.Label("$x$", at=(0, 0, 0)))
    d = scene.render(lg.ParallelProjector(direction=(0, 0, 1)))
    data = d.save(tmp_path / "a.pdf").read_bytes()
    stream = re.search(rb"stream\r?\n(.*?)endstream", data, re.S).group(1)
    assert b" c\n" in zlib.decompress(stream)


def test_cli_width_option(tmp_path):
    from lgraph.cli import main

    scene = tmp_path / "s.toml"
    scene.write_text(
        '[projector]\nkind = "parallel"\nazimuth = 30\nelevation = 20\n'
        '[[object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
        '[[labels]]\ntext = "$N$"\nat = [0, 0, 1.3]\n'
        "[[group]]\ntransform = [{ translate = [0, 3, 0] }]\n"
        '[[group.object]]\nsurface = "sphere"\nparams = { r = 1 }\n'
        "[[group.points]]\nat = [0, 0, 1.2]\n"
    )
    out = tmp_path / "s.pdf"
    assert main(["render", str(scene), "-o", str(out), "--width", "85mm"]) == 0
    box, _ = _pdf_page(out)
    assert box[2] - box[0] == pytest.approx(85 / 25.4 * 72, abs=1e-3)
    loaded, projector, _ = lg.load_scene_file(scene)
    assert len(loaded) == 2 and len(loaded.labels) == 1 and len(loaded.points) == 1
    np.testing.assert_allclose(loaded.points[0].at, [0, 3, 1.2])
