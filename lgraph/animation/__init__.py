"""Animation: a scene rendered from many views into one file.

``frames.py`` :func:`~lgraph.animate` (views, caches, executors, Dask),
``window.py`` the frames' common window and the pixel chord tolerance,
``writers.py`` the streaming writers (GIF, APNG, WebP, PDF, folders),
``progress.py`` the bookkeeping and progress bar of a long run.
"""

from .frames import (
    BATCH_FRAMES,
    MAX_WIDTH,
    PARALLEL_MIN_FRAMES,
    PIXEL_TOLERANCE,
    POOL_MIN_SECONDS,
    ExecutorError,
    animate,
    frame_window,
    pixel_chord,
)

__all__ = ["animate", "ExecutorError", "frame_window", "pixel_chord", "PARALLEL_MIN_FRAMES"]
__all__ += ["POOL_MIN_SECONDS", "BATCH_FRAMES", "MAX_WIDTH", "PIXEL_TOLERANCE"]
