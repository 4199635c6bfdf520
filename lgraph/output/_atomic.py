"""Files written atomically, and work that a SIGTERM or SIGHUP stops cleanly.

A file is written to a temporary file beside the target
(:func:`temporary_beside`: ``.<start of the name>.XXXXXXXX.part``, short
whatever the target's name) and moved into place only when complete
(:func:`publish`); on any error or stop signal it is removed and nothing is
left behind.  Used by :meth:`lgraph.Drawing.save`, the animation writers and
the command line.

Stop signals (:func:`signals_as_exception`): while long work runs in the
main thread, a SIGTERM or SIGHUP raises :class:`Terminated` there, as Ctrl-C
raises ``KeyboardInterrupt``, so that the code under way cleans up on its
way out (temporary files removed, worker processes stopped).  Then the
signal takes its usual course: the previous handler is called, or the
default action ends the process (its status says "killed by SIGTERM", as
before); the command line instead prints ``lgraph <command>: terminated by
SIGTERM`` and exits with 128 + the signal number.  A second signal while
cleaning up takes its usual course at once.  Worker processes of a local
pool are ended (:func:`stop_pool`), and end by themselves when their parent
was killed outright (:func:`worker_setup`).  Foreign code (plugins) that
calls ``sys.exit()`` raises an error instead (:func:`no_exit`).

Paths (:func:`lexical`): ``..`` is resolved as text (``os.path.normpath``):
``a/b/../../x.pdf`` is ``x.pdf``, and writing it creates no folder ``a/b``.
This is the path as written, the same whether or not its folders exist yet;
the price is that ``link/../x.pdf`` is ``./x.pdf`` even when ``link`` is a
symbolic link to a folder elsewhere (where the operating system would put
it beside that folder).

>>> import pathlib, tempfile
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> tmp = temporary_beside(folder / "x.txt", "save")
>>> _ = pathlib.Path(tmp).write_text("done")
>>> publish(tmp, folder / "x.txt").read_text(), sorted(p.name for p in folder.iterdir())
('done', ['x.txt'])
>>> str(lexical("a/b/../../x.pdf")), str(lexical("a/./b/../x.pdf"))
('x.pdf', 'a/x.pdf')
"""

from __future__ import annotations

import errno
import functools
import os
import signal
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

__all__ = [
    "temporary_beside",
    "publish",
    "lexical",
    "check_name",
    "name_max",
    "removed_on_signals",
    "signals_as_exception",
    "Terminated",
    "STOP_SIGNALS",
    "stop_pool",
    "worker_setup",
    "no_exit",
    "exit_message",
]

#: the signals that :func:`signals_as_exception` turns into :class:`Terminated`
STOP_SIGNALS: tuple[int, ...] = tuple(
    getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n)
)

#: bytes of the target's name kept at the start of a temporary name
_TMP_NAME_START = 24


# -- paths ---------------------------------------------------------------------------
def lexical(path: str | os.PathLike[str]) -> Path:
    """``path`` with ``.`` and ``..`` resolved as text (``os.path.normpath``;
    see the module's docstring for symbolic links)."""
    text = os.fspath(path)
    return Path(os.path.normpath(text)) if text else Path(".")


def name_max(folder: str | os.PathLike[str]) -> int:
    """The longest file name, in bytes, that ``folder``'s file system takes
    (``PC_NAME_MAX``; 255 when it cannot say)."""
    try:
        n = os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        return 255
    return int(n) if n and n > 0 else 255


def check_name(path: str | os.PathLike[str], owner: str) -> Path:
    """``path`` (made :func:`lexical`), or ``OSError(ENAMETOOLONG)`` naming it
    when its file name is longer than its folder's file system allows."""
    path = lexical(path)
    parent = path.parent
    n = len(os.fsencode(path.name))
    limit = name_max(parent if parent.is_dir() else ".")
    if n > limit:
        raise OSError(
            errno.ENAMETOOLONG,
            f"{owner}: file name too long ({n} bytes; the file system allows {limit})",
            str(path),
        )
    return path


def _name_start(name: str, limit: int) -> str:
    """The first characters of ``name`` that fit in ``limit`` bytes."""
    out = name[:limit]
    while len(os.fsencode(out)) > limit:
        out = out[:-1]
    return out


def temporary_beside(path: str | os.PathLike[str], owner: str) -> str:
    """An empty temporary file in ``path``'s folder, ``.<name>.XXXXXXXX.part``
    with at most the first 24 bytes of the name (any target name that the file
    system takes has a temporary name it takes too); ``FileNotFoundError``
    naming ``owner`` when the folder does not exist, ``OSError(ENAMETOOLONG)``
    naming ``path`` when its name is too long.  ``path`` is taken
    :func:`lexical`."""
    path = check_name(path, owner)
    parent = path.parent
    if not parent.is_dir():
        raise FileNotFoundError(f"{owner}: folder {str(parent)!r} does not exist")
    # "." + start + "." + 8 random + ".part" within the file system's limit
    room = min(_TMP_NAME_START, name_max(parent) - 15)
    start = _name_start(path.name, max(0, room))
    fd, tmp = tempfile.mkstemp(prefix=f".{start}.", suffix=".part", dir=parent)
    os.close(fd)
    return tmp


def publish(tmp: str, path: str | os.PathLike[str]) -> Path:
    """Move the finished ``tmp`` to ``path`` (taken :func:`lexical`) with the
    usual file mode (``mkstemp`` makes 0600 files); returns the path written."""
    path = lexical(path)
    os.chmod(tmp, 0o666 & ~_umask())
    os.replace(tmp, path)
    return path


def _unlink(tmp: str | os.PathLike[str]) -> None:
    try:
        os.unlink(tmp)
    except OSError:
        pass


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


# -- stop signals --------------------------------------------------------------------
class Terminated(BaseException):
    """A SIGTERM or SIGHUP arrived while lgraph was at work
    (:func:`signals_as_exception`).  A ``BaseException``, like
    ``KeyboardInterrupt``: ``except Exception`` does not catch it."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum

    @property
    def signal_name(self) -> str:
        """``"SIGTERM"``, ``"SIGHUP"``, ..."""
        try:
            return signal.Signals(self.signum).name
        except ValueError:
            return f"signal {self.signum}"

    @property
    def exit_status(self) -> int:
        """The shell's status of a process the signal ended: 128 + its number."""
        return 128 + self.signum

    def __str__(self) -> str:
        return f"terminated by {self.signal_name}"


_depth = [0]  # nesting of signals_as_exception in the main thread


def _usual_course(signum: int, previous: Any, frame: Any) -> None:
    """What ``signum`` would have done without us: the ``previous`` handler
    (already restored), or the default action (which ends the process)."""
    if callable(previous):
        previous(signum, frame)
    elif previous == signal.SIG_DFL:
        os.kill(os.getpid(), signum)
        for _ in range(100):  # delivery to another thread may take a moment
            time.sleep(0.01)


@contextmanager
def signals_as_exception(*, take_default: bool = True) -> Iterator[None]:
    """While the body runs: a SIGTERM or SIGHUP raises :class:`Terminated` in
    the main thread (once; a second signal takes its usual course at once).

    Only the outermost use installs handlers (inner ones, and uses outside
    the main thread, do nothing), only for signals that are not ignored, and
    restores the previous handlers when the body ends.  If a ``Terminated``
    comes out of the body (or was swallowed inside it), the signal then
    takes its usual course: the previous handler is called, or, with
    ``take_default`` (a library call), its default action ends the process;
    without (the command line), ``Terminated`` is raised for the caller to
    exit with :attr:`Terminated.exit_status`.  Processes forked while the
    handlers are installed take the default action.
    """
    if threading.current_thread() is not threading.main_thread() or _depth[0]:
        yield
        return
    pid = os.getpid()
    previous: dict[int, Any] = {}
    state: dict[str, Any] = {"signum": None, "active": True}

    def restore() -> None:
        for sig, prev in previous.items():
            try:
                signal.signal(sig, prev)
            except (ValueError, OSError, TypeError):  # pragma: no cover
                pass
        previous.clear()

    def handler(signum: int, frame: Any) -> None:
        if os.getpid() != pid:  # a forked child (a pool's worker): the default action
            signal.signal(signum, signal.SIG_DFL)
            os.kill(os.getpid(), signum)
            return
        if state["active"] and state["signum"] is None:
            state["signum"] = signum
            raise Terminated(signum)
        prev = previous.get(signum, signal.SIG_DFL)  # a second one: at once
        restore()
        _usual_course(signum, prev, frame)

    for sig in STOP_SIGNALS:
        prev = signal.getsignal(sig)
        if prev is None or prev == signal.SIG_IGN:  # set outside Python, or ignored
            continue
        try:
            signal.signal(sig, handler)
        except (ValueError, OSError):  # pragma: no cover - no signals here
            continue
        previous[sig] = prev
    _depth[0] += 1
    caught: Terminated | None = None
    try:
        yield
    except Terminated as exc:
        caught = exc
    finally:
        _depth[0] -= 1
        state["active"] = False
        prevs = dict(previous)
        restore()
    signum = caught.signum if caught is not None else state["signum"]
    if signum is None:
        return
    prev = prevs.get(signum, signal.SIG_DFL)
    if callable(prev) or take_default:
        _usual_course(signum, prev, None)
    if caught is not None:
        raise caught
    raise Terminated(signum)


@contextmanager
def removed_on_signals(tmp: str | os.PathLike[str]) -> Iterator[None]:
    """While writing ``tmp``: on any error, or a SIGTERM or SIGHUP
    (:func:`signals_as_exception`), ``tmp`` is removed first; the signal then
    takes its usual course (the previous handler, or the default action,
    which ends the process)."""
    with signals_as_exception():
        try:
            yield
        except BaseException:
            _unlink(tmp)
            raise


# -- worker processes ------------------------------------------------------------------
def stop_pool(pool: Any) -> None:
    """Stop a local ``ProcessPoolExecutor`` now: the work not started is
    cancelled, its worker processes are ended (work under way is dropped) and
    waited for, and so is the pool's manager thread."""
    processes = getattr(pool, "_processes", None)
    if processes is None:  # not the standard library's pool, or shut down already
        stop = getattr(pool, "terminate_workers", None)  # Python 3.14
        stop() if stop is not None else pool.shutdown(wait=False, cancel_futures=True)
        return
    processes = list(processes.values())
    manager = getattr(pool, "_executor_manager_thread", None)
    results = getattr(pool, "_result_queue", None)  # all three are None after shutdown()
    pool.shutdown(wait=False, cancel_futures=True)
    for p in processes:
        try:
            if p.is_alive():
                p.terminate()
        except (OSError, ValueError, AttributeError):  # pragma: no cover - gone already
            pass
    for p in processes:
        try:
            p.join(2)
            if p.is_alive():  # pragma: no cover - ignored SIGTERM
                p.kill()
                p.join(2)
        except (OSError, ValueError, AssertionError, AttributeError):  # pragma: no cover
            pass
    # a worker ended while sending its frames leaves half a message that the
    # manager thread would wait for for ever (this process holds the pipe's
    # other end): closing that end, the workers gone, makes it an end of file
    writer = getattr(results, "_writer", None)
    if writer is not None:
        writer.close()
    if manager is not None:
        manager.join(10)  # it finds the pool broken, cleans up and ends


def worker_setup() -> None:
    """In a worker process of a local pool (its initializer): the default
    action for the stop signals (a forked worker inherits the parent's
    handlers; the parent ends its workers itself), and a watch that ends the
    worker within a second of its parent's death (SIGKILL cannot be caught)."""
    for sig in STOP_SIGNALS:
        if callable(signal.getsignal(sig)):
            signal.signal(sig, signal.SIG_DFL)
    parent = os.getppid()
    threading.Thread(target=_watch, args=(parent,), name="lgraph-parent-watch", daemon=True).start()


def _watch(parent: int, every: float = 0.5) -> None:
    while True:
        time.sleep(every)
        if os.getppid() != parent:  # re-parented: the parent is gone
            os._exit(1)


# -- foreign code -----------------------------------------------------------------------
def no_exit(fn: Callable[..., Any], who: str, error: type[Exception] = RuntimeError) -> Any:
    """``fn`` such that a ``SystemExit`` it raises becomes ``error("<who> called
    sys.exit(...); ...")``, raised from it (foreign code must not end the process)."""

    @functools.wraps(fn)
    def call(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except SystemExit as exc:
            raise error(exit_message(who, exc)) from exc

    return call


def exit_message(who: str, exc: SystemExit) -> str:
    """``<who> called sys.exit(3); it must raise an exception instead``."""
    return f"{who} called sys.exit({exc.code!r}); it must raise an exception instead"
