"""Bookkeeping of a long run of frames (:func:`lgraph.animate`): a one-line
progress bar on a terminal, and the results that come back from an executor,
checked before a writer takes them (:func:`checked`: lists of frames, as
many as asked; an executor that lost them raises :class:`ExecutorError`).
No derivation: bookkeeping only.

>>> from PIL import Image
>>> is_frame(Image.new("L", (4, 4)), "png"), is_frame("garbage", "png")
(True, False)
"""

from __future__ import annotations

import concurrent.futures as cf
import sys
import time
from collections import deque
from collections.abc import Iterator, Sequence
from typing import Any, TextIO

__all__ = ["Progress", "ExecutorError", "in_order", "checked", "is_frame", "FRAME_KINDS"]


class Progress:
    """A one-line progress bar on a terminal; silent otherwise."""

    def __init__(self, total: int, enabled: bool, stream: TextIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        isatty = getattr(self.stream, "isatty", None)
        self.on = bool(enabled) and callable(isatty) and bool(isatty())
        self.total, self.done, self.t0 = total, 0, time.perf_counter()

    def update(self) -> None:
        self.done += 1
        if not self.on:
            return
        took = time.perf_counter() - self.t0
        left = took / self.done * (self.total - self.done)
        n = round(30 * self.done / self.total)
        self.stream.write(
            f"\ranimate [{'#' * n}{'.' * (30 - n)}] {self.done}/{self.total} frames, "
            f"{took:.1f} s, {left:.1f} s left "
        )
        self.stream.flush()

    def close(self) -> None:
        if self.on:
            self.stream.write("\n")
            self.stream.flush()


# -- the results of an executor ----------------------------------------------------
class ExecutorError(RuntimeError):
    """The executor could not render the frames: its workers were lost (a Dask
    cluster that lost its workers or its scheduler, a process pool whose
    workers died) or it cancelled them.  Nothing is written."""


#: what a frame of each kind of job is, for messages
FRAME_KINDS = {
    "png": "a pillow image or PNG bytes",
    "svg": "the bytes of an SVG file",
    "pdf": "the bytes of a PDF file",
    "drawing": "a Drawing",
}


def is_frame(frame: Any, kind: str) -> bool:
    """Whether ``frame`` is what a job of ``kind`` (:data:`FRAME_KINDS`) renders."""
    if kind == "drawing":
        from ..output.drawing import Drawing

        return isinstance(frame, Drawing)
    if isinstance(frame, (bytes, bytearray)):
        start = bytes(frame[:8])
        if kind == "png":
            return start == b"\x89PNG\r\n\x1a\n"
        return start.startswith(b"%PDF") if kind == "pdf" else b"<" in start
    if kind == "png":
        from PIL import Image

        return isinstance(frame, Image.Image)
    return False


def what(obj: Any) -> str:
    """``a str ('abc')``: the type and the start of the value, for messages.

    >>> what(None), what(42)
    ('a NoneType (None)', 'an int (42)')
    """
    name, text = type(obj).__name__, repr(obj)
    text = text if len(text) <= 40 else text[:37] + "..."
    return f"{'an' if name[:1].lower() in 'aeiou' else 'a'} {name} ({text})"


def _lost(executor: Any, frames: str, exc: BaseException) -> ExecutorError:
    """The error for results that ``executor`` lost (``frames``: which ones)."""
    client = getattr(executor, "_client", None)
    if type(executor).__module__.startswith("distributed") and client is not None:
        status = getattr(client, "status", "?")
        where = getattr(getattr(client, "scheduler", None), "address", None) or "?"
        return ExecutorError(
            f"animate: the Dask cluster lost its workers while rendering {frames} (a worker "
            f"died or was restarted, or the cluster was shut down; scheduler {where}, client "
            f"{status}); the scene sent to the workers is lost with them, nothing was written"
        )
    if isinstance(exc, cf.BrokenExecutor):
        return ExecutorError(
            f"animate: the executor's workers died while rendering {frames} (killed, or out "
            f"of memory?): {exc}; nothing was written"
        )
    return ExecutorError(
        f"animate: the executor cancelled {frames} (was it shut down?); nothing was written"
    )


def in_order(submit: Any, items: Sequence[Any], window: int) -> Iterator[Any]:
    """Submit ``items`` keeping at most ``window`` pending; yield results in
    order.  Closing it cancels the pending ones."""
    pending: deque = deque()
    it = iter(items)
    try:
        for item in it:
            fut = submit(item)
            if not callable(getattr(fut, "result", None)):
                raise TypeError(
                    f"animate: the executor's submit() returned {what(fut)}, not a future"
                )
            pending.append(fut)
            if len(pending) >= window:
                yield pending.popleft().result()
        while pending:
            yield pending.popleft().result()
    finally:
        for fut in pending:
            fut.cancel()


def checked(
    results: Iterator[Any], batches: Sequence[list], kind: str, executor: Any, first: int = 0
) -> Iterator[list[Any]]:
    """The ``results`` of ``batches`` from ``executor`` (:func:`in_order`), each
    checked to be a list of as many frames of ``kind`` (``first``: the index of
    the first frame); lost ones raise :class:`ExecutorError`.  Closing it
    closes ``results``."""
    index = first
    try:
        for batch in batches:
            frames = f"frames {index} to {index + len(batch) - 1}"
            try:
                result = next(results)
            except StopIteration:
                return
            except (cf.CancelledError, cf.BrokenExecutor) as e:
                raise _lost(executor, frames, e) from e
            if not isinstance(result, (list, tuple)):
                raise TypeError(
                    f"animate: the executor returned {what(result)} for {frames}, not a list "
                    "of frames"
                )
            if len(result) != len(batch):
                raise TypeError(
                    f"animate: the executor returned {len(result)} frames for {frames}, "
                    f"{len(batch)} expected"
                )
            for k, frame in enumerate(result):
                if not is_frame(frame, kind):
                    raise TypeError(
                        f"animate: the executor returned {what(frame)} for frame {index + k}, "
                        f"not a frame ({FRAME_KINDS.get(kind, kind)})"
                    )
            yield list(result)
            index += len(batch)
    finally:
        close = getattr(results, "close", None)
        if close is not None:
            close()
