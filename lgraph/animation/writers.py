"""Writers that stream animation frames into one file or a folder, atomically.

Each writer takes frames one at a time (``add``: a pillow image or PNG bytes
for raster formats) and keeps only what the format needs to finish the file,
never all the decoded frames (the GIF writer keeps the last grey one):

* :class:`GifWriter` -- animated GIF; every colour frame is quantized to its
  own 256-colour palette by pillow (fast octree), a grey (``"L"``) frame
  keeps its grey levels exactly, and only the box where it differs from the
  grey frame before is encoded (the rest stays on screen); each is spliced
  in as it comes (pillow's own ``save_all`` holds every frame until the end);
* :class:`ApngWriter` -- animated PNG: pillow's PNG encoding of each frame,
  its ``IDAT`` data re-chunked as the APNG ``fdAT`` frames;
* :class:`WebpWriter` -- animated WebP through pillow (libwebp assembles the
  file at the end, so the frames are held, PNG-compressed, until then);
* :class:`PdfPagesWriter` -- a multi-page PDF, one frame a page (reportlab);
* :class:`FolderWriter` -- numbered files ``frame_0000.png`` ... in a folder.

A file is written to a temporary name beside the target and renamed when
complete (:meth:`FrameWriter.close`); :meth:`FrameWriter.abort` (called on
any error or interrupt) removes it, so no half-written file is left.  Paths
are taken as written, ``..`` resolved lexically (``lgraph.output._atomic.lexical``).

>>> import io, tempfile, os
>>> from PIL import Image
>>> frames = []
>>> for k in range(3):
...     buf = io.BytesIO()
...     Image.new("RGB", (8, 6), (k * 100, 0, 0)).save(buf, "PNG")
...     frames.append(buf.getvalue())
>>> with tempfile.TemporaryDirectory() as tmp:
...     w = GifWriter(os.path.join(tmp, "a.gif"), n_frames=3, fps=10)
...     for f in frames:
...         w.add(f)
...     path = w.close()
...     im = Image.open(path)
...     im.n_frames, im.size, im.info["duration"], sorted(os.listdir(tmp))
(3, (8, 6), 100, ['a.gif'])
"""

from __future__ import annotations

import io
import os
import struct
import zlib
from pathlib import Path
from typing import Any

from ..output._atomic import check_name, lexical, publish, temporary_beside

__all__ = [
    "FrameWriter",
    "GifWriter",
    "ApngWriter",
    "WebpWriter",
    "PdfPagesWriter",
    "FolderWriter",
    "writer_for",
    "ANIMATION_SUFFIXES",
    "FRAME_FORMATS",
]

#: suffix -> writer class for one-file animations
ANIMATION_SUFFIXES = (".gif", ".png", ".apng", ".webp", ".pdf")
#: formats of the numbered frames in a folder
FRAME_FORMATS = ("png", "svg", "pdf")


class FrameWriter:
    """Base class: a temporary file beside ``path``, renamed by :meth:`close`.

    ``kind`` says what :meth:`add` takes: ``"png"`` (PNG bytes) or
    ``"drawing"`` (a :class:`~lgraph.Drawing`).
    """

    kind = "png"

    def __init__(self, path: str | os.PathLike[str], n_frames: int, fps: float) -> None:
        self.path = lexical(path)
        self.n_frames = n_frames
        self.fps = fps
        self.count = 0
        self._tmp = temporary_beside(self.path, "animate")
        self._file = open(self._tmp, "w+b")  # noqa: SIM115 - closed by close() or abort()

    def add(self, frame: Any) -> None:
        self._add(frame)
        self.count += 1

    def _add(self, frame: Any) -> None:  # pragma: no cover - abstract
        raise NotImplementedError

    def _finish(self) -> None:
        """Write what follows the last frame."""

    def close(self) -> Path:
        """Finish the file and move it into place; returns its path."""
        if self.count != self.n_frames:
            self.abort()
            raise RuntimeError(
                f"animate: {self.count} frames were written, {self.n_frames} expected"
            )
        try:
            self._finish()
            self._file.close()
            publish(self._tmp, self.path)
        except BaseException:
            self.abort()
            raise
        return self.path

    def abort(self) -> None:
        """Remove the temporary file (nothing is left behind)."""
        try:
            self._file.close()
        except Exception:  # noqa: BLE001 - closing a broken file: nothing to save
            pass
        try:
            os.unlink(self._tmp)
        except OSError:
            pass


# -- GIF --------------------------------------------------------------------------
def _skip_blocks(data: bytes, pos: int) -> int:
    """Position after the data sub-blocks starting at ``pos`` (and their terminator)."""
    while data[pos]:
        pos += data[pos] + 1
    return pos + 1


def as_image(frame: Any) -> Any:
    """A raster frame as a pillow image (RGB, RGBA or grey ``"L"``): from an
    image or PNG bytes."""
    from PIL import Image

    if isinstance(frame, (bytes, bytearray)):
        frame = Image.open(io.BytesIO(frame))
        frame.load()
    return frame


def _png_bytes(im: Any) -> bytes:
    buf = io.BytesIO()
    im.save(buf, "PNG")
    return buf.getvalue()


_DESCENDING_GREYS = bytes(c for g in range(255, -1, -1) for c in (g, g, g))


def _changed_box(previous: Any, im: Any) -> tuple[int, int, int, int] | None:
    """The box of the pixels where the grey frame ``im`` differs from the grey
    frame ``previous`` (one pixel when none does); None for the whole frame."""
    from PIL import ImageChops

    if previous is None or previous.size != im.size:
        return None
    box = ImageChops.difference(previous, im).getbbox()
    return box if box is not None else (0, 0, 1, 1)


def _gif_frame(
    frame: Any, box: tuple[int, int, int, int] | None = None
) -> tuple[tuple[int, int], bytes, bytes]:
    """Encode one frame (a grey one only within ``box``, if given) as GIF with
    pillow; return the frame's size, the image descriptor with a local colour
    table, and the LZW image data.  Rows are stored in order, not interlaced:
    a progressive first pass is of no use in an animation, and the frames
    encode a little faster and smaller."""
    from PIL import Image, ImageChops

    im = as_image(frame)
    buf = io.BytesIO()
    if im.mode == "L":
        # grey frames: the 256 grey levels are the palette, no search needed.
        # Stored in descending order (index 255 - g for grey g): readers such as
        # pillow take a GIF whose first palette is the ascending grey ramp for a
        # greyscale image and then turn later colour frames grey.
        part = im if box is None or box == (0, 0, *im.size) else im.crop(box)
        pal = ImageChops.invert(part)  # 255 - g
        pal.putpalette(_DESCENDING_GREYS)  # "L" -> "P" in place
        pal.save(buf, "GIF", optimize=False, interlace=False)
    else:
        box = None
        im = im.convert("RGB")
        pal = im.quantize(colors=256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)
        pal.save(buf, "GIF", interlace=False)
    data = buf.getvalue()
    flags = data[10]
    pos = 13
    table, bits = b"", 0
    if flags & 0x80:  # global colour table: becomes the frame's local one
        size = 3 << ((flags & 7) + 1)
        table, bits = data[pos : pos + size], flags & 7
        pos += size
    while data[pos] == 0x21:  # extensions: skipped (we write our own control block)
        pos = _skip_blocks(data, pos + 2)
    if data[pos] != 0x2C:  # pragma: no cover - pillow always writes an image
        raise ValueError("animate: pillow wrote a GIF without an image descriptor")
    desc = bytearray(data[pos : pos + 10])
    if box is not None:  # the part's place in the frame
        desc[1:5] = struct.pack("<HH", box[0], box[1])
    pos += 10
    if desc[9] & 0x80:  # a local table already
        size = 3 << ((desc[9] & 7) + 1)
        desc_table = data[pos : pos + size]
        pos += size
    else:
        desc[9] = (desc[9] & 0x40) | 0x80 | bits
        desc_table = table
    start = pos
    pos = _skip_blocks(data, pos + 1)  # LZW minimum code size, then the blocks
    return im.size, bytes(desc) + desc_table, data[start:pos]


class GifWriter(FrameWriter):
    """Animated GIF, streamed: header, then one frame at a time.

    Delays are whole hundredths of a second (``round(100 / fps)``, at least 2,
    as browsers slow shorter delays down); ``loop=0`` repeats for ever.
    """

    def __init__(self, path: Any, n_frames: int, fps: float, loop: int = 0) -> None:
        super().__init__(path, n_frames, fps)
        self.loop = loop
        self.delay = max(2, round(100 / fps))
        self.size: tuple[int, int] | None = None
        self.previous: Any = None  # the last frame, if grey

    def _add(self, frame: Any) -> None:
        im = as_image(frame)
        grey = im.mode == "L"
        size, desc, image = _gif_frame(im, _changed_box(self.previous, im) if grey else None)
        self.previous = im if grey else None
        f = self._file
        if self.size is None:
            self.size = size
            f.write(b"GIF89a" + struct.pack("<HHBBB", size[0], size[1], 0, 0, 0))
            f.write(b"\x21\xff\x0bNETSCAPE2.0\x03\x01" + struct.pack("<H", self.loop) + b"\x00")
        elif size != self.size:
            raise ValueError(f"animate: frame {self.count} is {size} px, the first {self.size}")
        # graphic control: disposal 1 (keep), the delay, no transparency
        f.write(b"\x21\xf9\x04\x04" + struct.pack("<H", self.delay) + b"\x00\x00")
        f.write(desc)
        f.write(image)

    def _finish(self) -> None:
        self._file.write(b"\x3b")


# -- APNG -------------------------------------------------------------------------
def _png_chunks(data: bytes) -> list[tuple[bytes, bytes]]:
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("animate: a frame is not PNG data")
    out, pos = [], 8
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos : pos + 4])
        out.append((data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + n]))
        pos += 12 + n
    return out


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


class ApngWriter(FrameWriter):
    """Animated PNG (APNG), streamed; every frame must have the first one's
    size and colour type.  The delay is ``1/fps`` s exactly (a fraction)."""

    def __init__(self, path: Any, n_frames: int, fps: float, loop: int = 0) -> None:
        super().__init__(path, n_frames, fps)
        self.loop = loop
        self.ihdr: bytes | None = None
        self.seq = 0
        num, den = float(1 / fps).as_integer_ratio()
        while den > 65535 or num > 65535:  # 16-bit fields: a close fraction
            num, den = max(1, num >> 1), den >> 1
        self.delay = (num, den)

    def _add(self, frame: Any) -> None:
        chunks = _png_chunks(_png_bytes(as_image(frame)))
        ihdr = next(body for kind, body in chunks if kind == b"IHDR")
        f = self._file
        if self.ihdr is None:
            self.ihdr = ihdr
            f.write(b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", ihdr))
            f.write(_chunk(b"acTL", struct.pack(">II", self.n_frames, self.loop)))
        elif ihdr != self.ihdr:
            raise ValueError(f"animate: frame {self.count} differs in size or colour type")
        w, h = struct.unpack(">II", ihdr[:8])
        fctl = struct.pack(">IIIIIHHBB", self.seq, w, h, 0, 0, *self.delay, 0, 0)
        f.write(_chunk(b"fcTL", fctl))
        self.seq += 1
        for kind, body in chunks:
            if kind != b"IDAT":
                continue
            if self.count == 0:  # the default image is the first frame
                f.write(_chunk(b"IDAT", body))
            else:
                f.write(_chunk(b"fdAT", struct.pack(">I", self.seq) + body))
                self.seq += 1

    def _finish(self) -> None:
        self._file.write(_chunk(b"IEND", b""))


# -- WebP -------------------------------------------------------------------------
class WebpWriter(FrameWriter):
    """Animated WebP (lossless) through pillow, assembled at :meth:`close`."""

    def __init__(self, path: Any, n_frames: int, fps: float, loop: int = 0) -> None:
        super().__init__(path, n_frames, fps)
        self.loop = loop
        self.frames: list[bytes] = []

    def _add(self, frame: Any) -> None:
        buf = io.BytesIO()  # held until the end: compressed, quickly
        as_image(frame).save(buf, "PNG", compress_level=1)
        self.frames.append(buf.getvalue())

    def _finish(self) -> None:
        from PIL import Image

        ims = [Image.open(io.BytesIO(b)) for b in self.frames]
        ims[0].save(
            self._file,
            "WEBP",
            save_all=True,
            append_images=ims[1:],
            duration=round(1000 / self.fps),
            loop=self.loop,
            lossless=True,
        )
        self.frames.clear()


# -- PDF --------------------------------------------------------------------------
class PdfPagesWriter(FrameWriter):
    """A multi-page PDF, one frame a page (for beamer slides: ``\\animategraphics``
    or ``\\includegraphics[page=k]``)."""

    kind = "drawing"

    def __init__(self, path: Any, n_frames: int, fps: float, precision: int = 3) -> None:
        super().__init__(path, n_frames, fps)
        self.precision = precision
        self.canvas: Any = None

    def _add(self, drawing: Any) -> None:
        from ..output.backends.pdf import _DEFAULT_LEVEL, draw_page, new_canvas

        size = drawing.page_size()
        if self.canvas is None:
            self.canvas = new_canvas(self._file, size, _DEFAULT_LEVEL, "lgraph animation")
        self.canvas.setPageSize(size)
        draw_page(self.canvas, drawing, self.precision)
        self.canvas.showPage()

    def _finish(self) -> None:
        self.canvas.save()


# -- a folder of frames ---------------------------------------------------------------
class FolderWriter:
    """Numbered frames ``frame_0000.<fmt>`` in a folder (created if missing).

    Frames come as the bytes of their file (or a pillow image, saved as PNG);
    each is written atomically (a
    temporary name, then a rename), so an interrupted run leaves only
    complete frames.
    """

    kind = "bytes"

    def __init__(self, folder: Any, n_frames: int, fmt: str) -> None:
        self.folder = lexical(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.fmt = fmt
        self.n_frames = n_frames
        self.count = 0
        self.digits = max(4, len(str(n_frames - 1)))

    def frame_path(self, k: int) -> Path:
        return self.folder / f"frame_{k:0{self.digits}d}.{self.fmt}"

    def add(self, data: Any) -> None:
        if not isinstance(data, (bytes, bytearray)):
            data = _png_bytes(data)
        path = self.frame_path(self.count)
        tmp = temporary_beside(path, "animate")
        try:
            Path(tmp).write_bytes(data)
            publish(tmp, path)
        except BaseException:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            raise
        self.count += 1

    def close(self) -> Path:
        return self.folder

    def abort(self) -> None:
        """Complete frames stay; a partly written one was never renamed."""


def writer_for(
    path: str | os.PathLike[str], n_frames: int, fps: float, frame_format: str, loop: int
) -> Any:
    """The writer for ``path``: by suffix, or a folder of frames when it has none
    (or is an existing folder)."""
    p = lexical(path)
    suffix = p.suffix.lower()
    if suffix:  # a name the file system takes, before anything else looks at it
        check_name(p, "animate")
    if p.is_dir() or not suffix:
        fmt = str(frame_format).lower().lstrip(".")
        if fmt not in FRAME_FORMATS:
            raise ValueError(
                f"animate: frame_format must be one of {', '.join(FRAME_FORMATS)}, "
                f"got {frame_format!r}"
            )
        return FolderWriter(p, n_frames, fmt)
    if suffix == ".gif":
        return GifWriter(p, n_frames, fps, loop)
    if suffix in (".png", ".apng"):
        return ApngWriter(p, n_frames, fps, loop)
    if suffix == ".webp":
        return WebpWriter(p, n_frames, fps, loop)
    if suffix == ".pdf":
        return PdfPagesWriter(p, n_frames, fps)
    raise ValueError(
        f"animate: unknown suffix {p.suffix!r}; use .gif, .png/.apng (APNG), .webp, .pdf "
        "(one frame a page) or a folder name without suffix (numbered frames)"
    )
