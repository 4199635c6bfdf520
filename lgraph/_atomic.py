"""Files written atomically: a temporary file beside the target, moved into
place only when complete; on any error, or a SIGTERM/SIGHUP while writing,
it is removed and nothing is left behind.  Used by :meth:`lgraph.Drawing.save`
and the animation writers.

>>> import pathlib, tempfile
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> tmp = temporary_beside(folder / "x.txt", "save")
>>> _ = pathlib.Path(tmp).write_text("done")
>>> publish(tmp, folder / "x.txt").read_text(), sorted(p.name for p in folder.iterdir())
('done', ['x.txt'])
"""

from __future__ import annotations

import os
import signal
import tempfile
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

__all__ = ["temporary_beside", "publish", "removed_on_signals"]


def temporary_beside(path: str | os.PathLike[str], owner: str) -> str:
    """An empty temporary file in ``path``'s folder (``.name.XXXX.part``);
    ``FileNotFoundError`` naming ``owner`` when the folder does not exist."""
    path = Path(path)
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise FileNotFoundError(f"{owner}: folder {str(parent)!r} does not exist")
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=parent)
    os.close(fd)
    return tmp


def publish(tmp: str, path: str | os.PathLike[str]) -> Path:
    """Move the finished ``tmp`` to ``path`` with the usual file mode
    (``mkstemp`` makes 0600 files)."""
    os.chmod(tmp, 0o666 & ~_umask())
    os.replace(tmp, path)
    return Path(path)


@contextmanager
def removed_on_signals(tmp: str) -> Iterator[None]:
    """While writing ``tmp``: a SIGTERM or SIGHUP first removes it, then takes
    its usual course (the previous handler, or the default action, which ends
    the process).  Only in the main thread (where signal handlers live)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    signums = [getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n)]
    previous: dict[int, Any] = {}

    def handler(signum: int, frame: Any) -> None:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        prev = previous.get(signum, signal.SIG_DFL)
        signal.signal(signum, prev)
        if callable(prev):
            prev(signum, frame)
        elif prev != signal.SIG_IGN:
            os.kill(os.getpid(), signum)  # the default action, now that tmp is gone

    try:
        for sig in signums:
            previous[sig] = signal.signal(sig, handler)
    except (ValueError, OSError):  # pragma: no cover - signals unavailable here
        pass
    try:
        yield
    finally:
        for sig, prev in previous.items():
            signal.signal(sig, prev if prev is not None else signal.SIG_DFL)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
