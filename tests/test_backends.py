"""Tests of the PDF, PNG and SVG backends, Drawing.save atomicity and dash_polyline."""

from __future__ import annotations

import os
import shutil
import subprocess
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import lgraph.output.backends as backends
from lgraph.output.drawing import Drawing, Page, Stroke, Style, dash_polyline

SVG_NS = "{http://www.w3.org/2000/svg}"
FORMATS = ("pdf", "png", "svg")


# -- helpers ----------------------------------------------------------------
def stroke(points: Sequence[Sequence[float]], **kw: object) -> Stroke:
    xy = np.asarray(points, dtype=float)
    return Stroke(xy=xy, xyz=np.zeros((len(xy), 3)), **kw)  # type: ignore[arg-type]


def drawing(*strokes: Stroke, background: object = (1.0, 1.0, 1.0)) -> Drawing:
    """A 100 x 50 pt page where projection coordinates equal page points.

    The first two strokes span the bounding box [0, 100] x [0, 50].
    """
    frame = (
        stroke([[0, 40], [100, 40]], style=Style(width=2.0), family="u1"),
        stroke([[50, 0], [50, 50]], style=Style(width=2.0), family="u2"),
    )
    return Drawing(
        strokes=frame + strokes,
        page=Page(margin=0, extent=100),
        background=background,  # type: ignore[arg-type]
    )


def dashed_drawing() -> Drawing:
    return drawing(stroke([[0, 10], [100, 10]], style=Style(width=2.0, dash=(10.0, 10.0))))


def listing(folder: Path) -> list[str]:
    return sorted(os.listdir(folder))


def gray(path: Path) -> np.ndarray:
    with Image.open(path) as im:
        return np.asarray(im.convert("L"), dtype=float)


def _dash_polyline_reference(points: np.ndarray, pattern: Sequence[float]) -> list[np.ndarray]:
    """The original loop implementation of dash_polyline."""
    pts = np.asarray(points, float)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    total = arc[-1]
    period = float(sum(pattern))
    starts, ends = [], []
    base = 0.0
    while base < total:
        pos = base
        for k in range(0, len(pattern), 2):
            on0, on1 = pos, min(pos + pattern[k], total)
            if on0 < total:
                starts.append(on0)
                ends.append(on1)
            pos += pattern[k] + pattern[k + 1]
        base += period
    dashes = []
    for a, b in zip(starts, ends):
        inner = (arc > a) & (arc < b)
        t = np.concatenate([[a], arc[inner], [b]])
        x = np.interp(t, arc, pts[:, 0])
        y = np.interp(t, arc, pts[:, 1])
        dashes.append(np.column_stack([x, y]))
    return dashes


# -- every format -------------------------------------------------------------
@pytest.mark.parametrize("fmt", FORMATS)
def test_save_writes_file_and_returns_path(tmp_path: Path, fmt: str) -> None:
    target = tmp_path / f"fig.{fmt}"
    assert drawing().save(target) == target
    assert target.stat().st_size > 0
    assert listing(tmp_path) == [f"fig.{fmt}"]  # no temp file left


@pytest.mark.parametrize("fmt", FORMATS)
def test_empty_drawing(tmp_path: Path, fmt: str) -> None:
    target = tmp_path / f"empty.{fmt}"
    Drawing(strokes=()).save(target)
    assert target.stat().st_size > 0


@pytest.mark.parametrize("fmt", FORMATS)
def test_unknown_option_raises_type_error_and_writes_nothing(tmp_path: Path, fmt: str) -> None:
    with pytest.raises(TypeError, match=rf"write_{fmt}: unknown option 'bogus'"):
        drawing().save(tmp_path / f"fig.{fmt}", bogus=1)
    assert listing(tmp_path) == []


def test_pdf_rejects_png_options(tmp_path: Path) -> None:
    with pytest.raises(TypeError, match="write_pdf: unknown option 'dpi'"):
        drawing().save(tmp_path / "fig.pdf", dpi=72)


@pytest.mark.parametrize("fmt", ["pdf", "svg"])
@pytest.mark.parametrize("precision", [-1, 7, 2.5, True, "3"])
def test_bad_precision(tmp_path: Path, fmt: str, precision: object) -> None:
    with pytest.raises(ValueError, match="precision must be an integer"):
        drawing().save(tmp_path / f"fig.{fmt}", precision=precision)
    assert listing(tmp_path) == []


# -- PDF ----------------------------------------------------------------------
def test_pdf_content_uncompressed(tmp_path: Path) -> None:
    red = Style(color=(1.0, 0.0, 0.0), width=1.5)
    d = drawing(stroke([[10, 10], [20, 20], [30, 10]], style=red))
    target = d.save(tmp_path / "fig.pdf", compress=False, title="My figure")
    data = target.read_bytes()
    assert data.startswith(b"%PDF-")
    assert b"/MediaBox [ 0 0 100 50 ]" in data
    assert b"1 J 1 j" in data  # round caps and joins
    # integer coordinates in 1/1000 pt under a scaling matrix; widths scaled to match
    assert b"0.001 0 0 0.001 0 0 cm" in data
    assert b"1 0 0 RG" in data and b"1500 w" in data
    assert b"10000 10000 m\n20000 20000 l\n30000 10000 l\nS" in data
    assert b"(My figure)" in data and b"(lgraph)" in data
    # Width and colour are set only when they change: the two frame strokes share them.
    assert data.count(b" RG") == 2 and data.count(b"2000 w") == 1


@pytest.mark.parametrize(
    ("precision", "unit", "path"),
    [(0, None, b"10 10 m\n20 21 l\nS"), (1, b"0.1 0 0 0.1 0 0 cm", b"100 100 m\n200 206 l\nS")],
)
def test_pdf_precision_sets_the_integer_unit(
    tmp_path: Path, precision: int, unit: bytes | None, path: bytes
) -> None:
    d = drawing(stroke([[10, 10], [20, 20.6]], style=Style(width=2.0, dash=(3.0, 1.0))))
    data = d.save(tmp_path / "fig.pdf", compress=False, precision=precision).read_bytes()
    assert path in data
    if unit is None:
        assert b" cm" not in data.split(b"stream")[1].replace(b"1 0 0 1 0 0 cm", b"")
        assert b"[3 1] 0 d" in data and b"2 w" in data
    else:
        assert unit in data and b"[30 10] 0 d" in data and b"20 w" in data


def test_pdf_compressed_is_smaller(tmp_path: Path) -> None:
    t = np.linspace(0, 2 * np.pi, 2000)
    d = drawing(stroke(np.column_stack([50 + 20 * np.cos(t), 25 + 20 * np.sin(t)])))
    small = d.save(tmp_path / "c.pdf").stat().st_size
    big = d.save(tmp_path / "u.pdf", compress=False).stat().st_size
    assert small < big / 2


@pytest.mark.parametrize("level", [True, 1, 9])
def test_pdf_compression_levels(tmp_path: Path, level: object) -> None:
    data = dashed_drawing().save(tmp_path / "fig.pdf", compress=level).read_bytes()
    assert b"/FlateDecode" in data and b"ASCII85Decode" not in data
    assert b"[10000 10000] 0 d" not in data  # the content stream is compressed


@pytest.mark.parametrize("compress", [-1, 10, 2.0, "yes", None])
def test_pdf_bad_compress(tmp_path: Path, compress: object) -> None:
    with pytest.raises(ValueError, match="compress must be True, False or a zlib level"):
        drawing().save(tmp_path / "fig.pdf", compress=compress)
    assert listing(tmp_path) == []


def test_pdf_dash_operator(tmp_path: Path) -> None:
    data = dashed_drawing().save(tmp_path / "fig.pdf", compress=False).read_bytes()
    assert b"[10000 10000] 0 d" in data  # in units of 1/1000 pt
    solid_after = drawing(
        stroke([[0, 10], [100, 10]], style=Style(width=2.0, dash=(3.0, 1.0))),
        stroke([[0, 20], [100, 20]], style=Style(width=2.0)),
    )
    data = solid_after.save(tmp_path / "fig2.pdf", compress=False).read_bytes()
    assert b"[3000 1000] 0 d" in data and b"[] 0 d" in data


def test_pdf_background(tmp_path: Path) -> None:
    blue = drawing(background=(0.0, 0.0, 1.0))
    data = blue.save(tmp_path / "b.pdf", compress=False).read_bytes()
    assert b"0 0 1 rg 0 0 100 50 re f" in data
    for bg in (None, (1.0, 1.0, 1.0)):
        data = drawing(background=bg).save(tmp_path / "w.pdf", compress=False).read_bytes()
        assert b" re f" not in data


class _StubDrawing:
    """The minimal drawing interface backends use; its points may hold NaN breaks."""

    background = (1.0, 1.0, 1.0)

    def __init__(self, *points: np.ndarray) -> None:
        self.strokes = [stroke(p) for p in points]

    def page_size(self) -> tuple[float, float]:
        return (100.0, 50.0)

    def page_strokes(self):  # type: ignore[no-untyped-def]
        for s in self.strokes:
            yield s.xy, s


def test_nonfinite_points_split_the_stroke(tmp_path: Path) -> None:
    from lgraph.output.backends.pdf import write_pdf
    from lgraph.output.backends.png import write_png
    from lgraph.output.backends.svg import write_svg

    d = _StubDrawing(np.array([[10, 10], [20, 10], [np.nan, 0], [30, 10], [40, 10], [50, 10]]))
    write_pdf(d, tmp_path / "fig.pdf", compress=False)
    data = (tmp_path / "fig.pdf").read_bytes()
    assert b"nan" not in data and b"inf" not in data
    assert b"10000 10000 m\n20000 10000 l\nS" in data
    assert b"30000 10000 m\n40000 10000 l\n50000 10000 l\nS" in data
    write_svg(d, tmp_path / "fig.svg")
    lines = list(ET.parse(tmp_path / "fig.svg").getroot().iter(SVG_NS + "polyline"))
    assert [len(p.get("points").split()) for p in lines] == [2, 3]
    write_png(d, tmp_path / "fig.png", dpi=72)
    img = gray(tmp_path / "fig.png")
    assert img[40, 15] < 200 and img[40, 45] < 200 and img[40, 25] > 250


@pytest.mark.skipif(shutil.which("pdftoppm") is None, reason="pdftoppm (poppler) not installed")
@pytest.mark.parametrize("compress", [True, False, 1])
def test_pdf_renders_with_pdftoppm(tmp_path: Path, compress: bool) -> None:
    target = dashed_drawing().save(tmp_path / "fig.pdf", compress=compress)
    subprocess.run(
        ["pdftoppm", "-png", "-r", "72", "-singlefile", str(target), str(tmp_path / "out")],
        check=True,
        capture_output=True,
    )
    img = gray(tmp_path / "out.png")
    assert img.shape == (50, 100)
    # Horizontal line at y = 40 pt is row 10 from the top (not flipped).
    assert img[10, 20] < 100 and img[40, 15] > 200 and img[25, 20] > 200
    # Vertical line at x = 50.
    assert img[30, 50] < 100
    # Dashed line at y = 10 pt (row 40): dark in a dash, light in a gap.
    assert img[40, 5] < 100 and img[40, 15] > 200


# -- PNG ----------------------------------------------------------------------
def test_png_size_pixels_and_orientation(tmp_path: Path) -> None:
    target = drawing().save(tmp_path / "fig.png", dpi=72)
    with Image.open(target) as im:
        assert im.size == (100, 50) and im.mode == "RGB"
        assert im.info["dpi"] == pytest.approx((72, 72), abs=0.05)
    img = gray(target)
    assert (img[9:11, 5:45] < 100).all()  # line at y = 40 pt is near the top
    assert (img[39:41, 5:45] > 250).all()  # nothing near the bottom
    assert (img[0:3, :] > 250).all() or (img[0:3, :45] > 250).all()
    assert (img[15:35, 20] > 250).all()  # white away from lines
    assert (img[20:30, 49:51] < 100).all()  # vertical line at x = 50


def test_png_default_dpi_and_size_options(tmp_path: Path) -> None:
    d = drawing()
    with Image.open(d.save(tmp_path / "a.png")) as im:
        assert im.size == (208, 104)  # 150 dpi default
    with Image.open(d.save(tmp_path / "b.png", size=400)) as im:
        assert im.size == (400, 200)
        assert im.info["dpi"] == pytest.approx((288, 288), abs=0.05)
    target = d.save(tmp_path / "c.png", size=(300, 300))
    with Image.open(target) as im:
        assert im.size == (300, 300)
    img = gray(target)
    # Page 100 x 50 fitted at 3 px/pt and centred vertically: y = 40 pt -> row 75 + 30.
    assert img[105, 60] < 100 and img[20, 60] > 250


def test_png_line_width_scales_with_dpi(tmp_path: Path) -> None:
    d = drawing()
    thin = gray(d.save(tmp_path / "a.png", dpi=72))
    thick = gray(d.save(tmp_path / "b.png", dpi=288))
    dark_thin = (thin[:, 20] < 128).sum()
    dark_thick = (thick[:, 80] < 128).sum()
    assert 1 <= dark_thin <= 3
    assert 6 <= dark_thick <= 10  # 2 pt at 4 px/pt = 8 px


def test_png_antialiased(tmp_path: Path) -> None:
    d = drawing(stroke([[0, 0], [100, 37]], style=Style(width=1.0)))
    img = gray(d.save(tmp_path / "a.png", dpi=72))
    levels = np.unique(img)
    assert ((levels > 20) & (levels < 235)).sum() > 5  # intermediate greys
    img1 = gray(d.save(tmp_path / "b.png", dpi=72, supersample=1))
    assert np.unique(img1).size <= 3


def test_png_dashes_have_gaps(tmp_path: Path) -> None:
    img = gray(dashed_drawing().save(tmp_path / "fig.png", dpi=72))
    row = img[39:42, :].min(axis=0)
    dark = row < 100
    assert dark[2:8].all() and not dark[13:17].any() and dark[22:28].all()
    transitions = np.count_nonzero(np.diff(dark[1:48].astype(int)))
    assert transitions >= 4


def test_png_round_joins_and_caps(tmp_path: Path) -> None:
    # A sharp V with a thick line: a round join fills the outer corner.
    d = drawing(stroke([[20, 10], [30, 30], [40, 10]], style=Style(width=6.0)))
    img = gray(d.save(tmp_path / "fig.png", dpi=72))
    # Apex at (30, 30) pt = pixel row 20; the round join reaches up ~3 px above it.
    assert img[18, 30] < 128
    # Round cap at (20, 10) pt = row 40: the cap covers a little below the end point.
    assert img[42, 20] < 200


def test_png_transparent_background(tmp_path: Path) -> None:
    target = drawing(background=None).save(tmp_path / "fig.png", dpi=72)
    with Image.open(target) as im:
        assert im.mode == "RGBA"
        alpha = np.asarray(im)[:, :, 3]
    assert alpha[25, 20] == 0 and alpha[10, 20] > 200


def test_png_colored_background(tmp_path: Path) -> None:
    target = drawing(background=(0.0, 0.0, 1.0)).save(tmp_path / "fig.png", dpi=72)
    with Image.open(target) as im:
        assert im.getpixel((20, 25)) == (0, 0, 255)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"dpi": 0}, "dpi must be a positive finite number"),
        ({"dpi": -10}, "dpi must be a positive finite number"),
        ({"dpi": float("nan")}, "dpi must be a positive finite number"),
        ({"dpi": float("inf")}, "dpi must be a positive finite number"),
        ({"dpi": "high"}, "dpi must be a positive finite number"),
        ({"dpi": 1e6}, "limit is 20000 px per side"),
        ({"size": 0}, "size must be a positive integer"),
        ({"size": 30000}, "exceeds the limit of 20000 px"),
        ({"size": (100, 0)}, r"size\[1\] must be a positive integer"),
        ({"size": (100.5, 10)}, r"size\[0\] must be a positive integer"),
        ({"size": (1, 2, 3)}, "size must be an int"),
        ({"supersample": 0}, "supersample must be an integer in 1..8"),
        ({"supersample": 2.0}, "supersample must be an integer in 1..8"),
    ],
)
def test_png_validation(tmp_path: Path, options: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        drawing().save(tmp_path / "fig.png", **options)
    assert listing(tmp_path) == []


# -- SVG ----------------------------------------------------------------------
def test_svg_structure(tmp_path: Path) -> None:
    red = Style(color=(1.0, 0.0, 0.0), width=1.5)
    d = drawing(
        stroke([[10, 10], [20, 20], [30, 10]], style=red, family='a<b&"c'),
        stroke([[0, 0], [1, 1]], visible=False),
    )
    root = ET.parse(d.save(tmp_path / "fig.svg", layers=None)).getroot()
    assert root.tag == SVG_NS + "svg"
    assert root.get("width") == "35.2778mm" and root.get("height") == "17.6389mm"
    assert root.get("viewBox") == "0 0 100 50"
    lines = root.findall(SVG_NS + "polyline")
    assert len(lines) == 4
    # Hidden strokes come first (drawing order).
    assert lines[0].get("data-visible") == "false"
    assert [len(p.get("points").split()) for p in lines] == [2, 2, 2, 3]
    v = lines[3]
    assert v.get("fill") == "none" and v.get("stroke") == "#ff0000"
    assert v.get("stroke-width") == "1.5"
    assert v.get("stroke-linecap") == "round" and v.get("stroke-linejoin") == "round"
    assert v.get("stroke-dasharray") is None
    assert v.get("data-family") == 'a<b&"c' and v.get("data-visible") == "true"
    # y flipped: (10, 10) pt -> (10, 40) in SVG user units.
    assert v.get("points") == "10.000,40.000 20.000,30.000 30.000,40.000"
    assert lines[1].get("points") == "0.000,10.000 100.000,10.000"


def test_svg_dasharray_precision_and_background(tmp_path: Path) -> None:
    target = dashed_drawing().save(tmp_path / "fig.svg", precision=1)
    root = ET.parse(target).getroot()
    lines = list(root.iter(SVG_NS + "polyline"))
    assert root.findall(SVG_NS + "g")[-1].get("stroke-dasharray") == "10 10"
    assert lines[-1].get("points") == "0.0,40.0 100.0,40.0"
    assert root.find(SVG_NS + "rect") is None  # white background is the paper
    target = drawing(background=(0.0, 0.0, 1.0)).save(tmp_path / "b.svg")
    rect = ET.parse(target).getroot().find(SVG_NS + "rect")
    assert rect is not None and rect.get("fill") == "#0000ff"


def test_svg_many_points(tmp_path: Path) -> None:
    t = np.linspace(0, 2 * np.pi, 5001)
    d = drawing(stroke(np.column_stack([50 + 20 * np.cos(t), 25 + 20 * np.sin(t)])))
    lines = list(ET.parse(d.save(tmp_path / "fig.svg")).getroot().iter(SVG_NS + "polyline"))
    pts = np.array([p.split(",") for p in lines[-1].get("points").split()], dtype=float)
    assert pts.shape == (5001, 2)
    assert np.allclose(pts[:, 0], 50 + 20 * np.cos(t), atol=6e-4)
    assert np.allclose(pts[:, 1], 50 - (25 + 20 * np.sin(t)), atol=6e-4)


# -- atomicity and errors ---------------------------------------------------
def _failing_writer(drawing: Drawing, path: Path, **options: object) -> None:
    with open(path, "w") as f:
        f.write("half a file")
    raise RuntimeError("disk on fire")


def test_failing_registered_writer_leaves_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(backends._BACKENDS, ".boom", _failing_writer)
    with pytest.raises(RuntimeError, match="disk on fire"):
        drawing().save(tmp_path / "fig.boom")
    assert listing(tmp_path) == []


def test_register_backend(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(backends, "_BACKENDS", dict(backends._BACKENDS))
    backends.register_backend("BOOM", _failing_writer)
    assert ".boom" in backends.backend_suffixes()
    with pytest.raises(ValueError, match="already registered"):
        backends.register_backend(".boom", _failing_writer)
    with pytest.raises(RuntimeError):
        drawing().save(tmp_path / "fig.BOOM")
    assert listing(tmp_path) == []


@pytest.mark.parametrize("fmt", FORMATS)
def test_real_writer_failing_midway_leaves_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fmt: str
) -> None:
    original = Drawing.page_points

    def broken(self: Drawing):  # type: ignore[no-untyped-def]
        original(self)  # the writer is under way: every backend draws from page_points
        raise RuntimeError("midway")

    monkeypatch.setattr(Drawing, "page_points", broken)
    with pytest.raises(RuntimeError, match="midway"):
        drawing().save(tmp_path / f"fig.{fmt}")
    assert listing(tmp_path) == []


@pytest.mark.parametrize("fmt", FORMATS)
def test_failed_save_keeps_existing_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fmt: str
) -> None:
    target = tmp_path / f"fig.{fmt}"
    target.write_bytes(b"old content")
    monkeypatch.setitem(backends._BACKENDS, f".{fmt}", _failing_writer)
    with pytest.raises(RuntimeError):
        drawing().save(target)
    assert target.read_bytes() == b"old content"
    assert listing(tmp_path) == [f"fig.{fmt}"]


def test_unknown_suffix(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"unknown file suffix '\.doc'"):
        drawing().save(tmp_path / "fig.doc")
    with pytest.raises(ValueError, match=r"unknown file suffix '\(none\)'"):
        drawing().save(tmp_path / "fig")
    assert listing(tmp_path) == []


def test_missing_folder(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="does not exist"):
        drawing().save(tmp_path / "no" / "such" / "fig.pdf")
    assert listing(tmp_path) == []


def test_large_pdf(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    t = np.linspace(0, 2 * np.pi, 10_000)
    strokes = [
        stroke(np.column_stack([np.cos(t) * r, np.sin(t) * r])) for r in rng.uniform(1, 10, size=20)
    ]
    d = Drawing(strokes=strokes)
    assert d.n_points == 200_000
    target = d.save(tmp_path / "big.pdf")
    data = target.read_bytes()
    assert data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF")


# -- dash_polyline ------------------------------------------------------------
@pytest.mark.parametrize("seed", range(8))
def test_dash_polyline_matches_reference(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 60))
    pts = np.cumsum(rng.normal(size=(n, 2)), axis=0)
    if seed % 2:
        pts[3:5] = pts[2]  # repeated points
    k = int(rng.integers(1, 4))
    pattern = tuple(rng.uniform(0.1, 2.0, size=2 * k))
    got = dash_polyline(pts, pattern)
    want = _dash_polyline_reference(pts, pattern)
    assert len(got) == len(want)
    for g, w in zip(got, want):
        assert g.shape == w.shape
        np.testing.assert_allclose(g, w, atol=1e-9)


def test_dash_polyline_edge_cases() -> None:
    assert dash_polyline(np.zeros((0, 2)), (1, 1)) == []
    assert dash_polyline(np.zeros((1, 2)), (1, 1)) == []
    assert dash_polyline(np.zeros((3, 2)), (1, 1)) == []  # zero length
    # Last dash clipped at the end.
    dashes = dash_polyline(np.array([[0.0, 0.0], [3.0, 0.0]]), (2, 0.5))
    assert [d[:, 0].tolist() for d in dashes] == [[0.0, 2.0], [2.5, 3.0]]
    # Corners inside a dash are kept.
    (d,) = dash_polyline(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]), (5, 1))
    assert d.tolist() == [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]


def test_pdf_falls_back_to_decimals_past_the_integer_limit(tmp_path: Path) -> None:
    """At 6 decimals a 3000 pt page would need integers past 2^31 (the limit of
    PDF readers): the writer then formats decimals, with no scaling matrix."""
    d = Drawing(
        strokes=(stroke([[0, 0], [1, 1]]),), page=Page(3000, 3000, 10)
    )  # fmt: skip
    data = d.save(tmp_path / "big.pdf", compress=False, precision=6).read_bytes()
    assert b"10.000000 10.000000 m\n2990.000000 2990.000000 l\nS" in data
    assert b"0.000001 0 0 0.000001 0 0 cm" not in data and b"0.5 w" in data
    small = d.save(tmp_path / "small.pdf", compress=False, precision=5).read_bytes()
    assert b"0.00001 0 0 0.00001 0 0 cm" in small and b"1000000 1000000 m" in small
