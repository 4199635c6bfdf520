"""A one-line progress bar for long runs (:func:`lgraph.animate`), on a
terminal only.  No derivation: bookkeeping only."""

from __future__ import annotations

import sys
import time
from typing import TextIO

__all__ = ["Progress"]


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
