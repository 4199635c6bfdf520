"""Faults and hostile input: stop signals, lost clusters, broken executors and
plugins, odd paths.

* a SIGTERM or SIGHUP in the middle of an animation (one process or a pool)
  leaves no temporary file and no worker process, keeps the old file at the
  target, and ends the process with the usual status;
* a Dask cluster that loses its only worker says so;
* an executor that returns garbage is named, with the frame;
* plugins that call ``sys.exit()`` or are not callable are named, and
  ``lgraph plugins`` keeps working;
* ``..`` in output paths creates no folders; long file names work up to the
  file system's limit and are refused, naming the user's file, beyond it.
"""

from __future__ import annotations

import concurrent.futures as cf
import errno
import importlib.metadata as md
import os
import re
import signal
import subprocess
import sys
import textwrap
import threading
import time
import warnings
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest

import lgraph as lg
from lgraph import plugins
from lgraph.animation import frames as animation
from lgraph.animation.frames import ExecutorError
from lgraph.cli import main
from lgraph.output._atomic import Terminated, name_max, signals_as_exception
from lgraph.plugins import PluginError, PluginWarning

ROOT = Path(__file__).resolve().parents[1]
POSIX = pytest.mark.skipif(not hasattr(signal, "SIGHUP"), reason="POSIX signals needed")

SCENE_FILE = """
[projector]
kind = "central"
azimuth = 35
elevation = 25
distance = 16

[[object]]
surface = "ellipsoid"
params = { a = 3, b = 2, c = 1.3 }
families = [{ name = "lines_of_curvature", n1 = 10, n2 = 12 }]
"""

SMALL_SCENE = """
[projector]
kind = "parallel"
direction = [1, 2, 3]

[[object]]
surface = "sphere"
params = { r = 1 }
"""

OLD = b"GIF89a the old animation, to be kept"


def _parts(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.rglob("*") if p.name.endswith(".part"))


def _small_drawing() -> lg.Drawing:
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(2, 2))
    return sc.render(lg.ParallelProjector(direction=(1, 2, 3)))


# -- processes ---------------------------------------------------------------------------
def _descendants(pid: int) -> dict[int, Any]:
    """The processes below ``pid``: pid -> a token of its identity (start time),
    with psutil when installed, else from /proc (Linux)."""
    try:
        import psutil
    except ImportError:
        psutil = None
    if psutil is not None:
        try:
            return {c.pid: c.create_time() for c in psutil.Process(pid).children(recursive=True)}
        except psutil.Error:
            return {}
    if not os.path.isdir("/proc/self"):
        pytest.skip("neither psutil nor /proc: cannot list child processes")
    parents: dict[int, list[int]] = {}
    starts: dict[int, str] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        stat = _proc_stat(int(entry))
        if stat is not None:
            parents.setdefault(int(stat[1]), []).append(int(entry))
            starts[int(entry)] = stat[19]
    out: dict[int, Any] = {}
    todo = [pid]
    while todo:
        for child in parents.get(todo.pop(), []):
            out[child] = starts[child]
            todo.append(child)
    return out


def _proc_stat(pid: int) -> list[str] | None:
    """Fields 3.. of /proc/<pid>/stat (state, ppid, ...), or None."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    return text[text.rindex(")") + 2 :].split()


def _running(pid: int, token: Any) -> bool:
    """Whether the process ``pid`` seen with ``token`` still runs (not a zombie)."""
    try:
        import psutil
    except ImportError:
        stat = _proc_stat(pid)
        return stat is not None and stat[19] == token and stat[0] not in ("Z", "X")
    try:
        p = psutil.Process(pid)
        return p.create_time() == token and p.status() != psutil.STATUS_ZOMBIE
    except psutil.Error:
        return False


def _wait_gone(procs: dict[int, Any], timeout: float = 15.0) -> list[int]:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        alive = [pid for pid, tok in procs.items() if _running(pid, tok)]
        if not alive:
            return []
        time.sleep(0.1)
    return alive


def _kill(procs: dict[int, Any]) -> None:
    for pid, tok in procs.items():
        if _running(pid, tok):
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass


def _wait_for_frames(proc: subprocess.Popen, folder: Path, timeout: float = 90.0) -> None:
    """Until the animation's temporary file holds its first frames."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        assert proc.poll() is None, "the animation ended before it could be stopped"
        for name in _parts(folder):
            try:
                if (folder / name).stat().st_size > 0:
                    return
            except FileNotFoundError:
                pass
        time.sleep(0.02)
    raise AssertionError("no frames were written in time")


ANIMATE_SCRIPT = """
import sys
sys.path.insert(0, {root!r})
import lgraph as lg
from lgraph.scenefile import load_scene_file

scene, _, _ = load_scene_file({scene!r})
lg.animate(scene, lg.orbit(elevation=25, frames=200), {out!r}, workers={workers},
           hidden_lines=True, progress=False)
"""


@POSIX
@pytest.mark.parametrize(
    ("how", "workers", "signum"),
    [
        ("cli", 1, "SIGTERM"),
        ("cli", 2, "SIGTERM"),
        ("cli", 2, "SIGHUP"),
        ("script", 1, "SIGHUP"),
        ("script", 2, "SIGTERM"),
    ],
)
def test_a_stop_signal_mid_animation_cleans_up_and_ends_the_process(
    tmp_path: Path, how: str, workers: int, signum: str
) -> None:
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE_FILE)
    out = tmp_path / "turn.gif"
    out.write_bytes(OLD)
    if how == "cli":
        cmd = [sys.executable, "-m", "lgraph", "animate", str(scene), "-o", str(out),
               "--frames", "200", "--hidden-lines", "--workers", str(workers)]  # fmt: skip
    else:
        code = ANIMATE_SCRIPT.format(
            root=str(ROOT), scene=str(scene), out=str(out), workers=workers
        )
        cmd = [sys.executable, "-c", textwrap.dedent(code)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    # stderr to a file: a worker left behind would hold a pipe open for ever
    with open(tmp_path / "stderr.txt", "w") as err:
        proc = subprocess.Popen(cmd, cwd=tmp_path, env=env, stderr=err)
    procs: dict[int, Any] = {}
    try:
        _wait_for_frames(proc, tmp_path)
        procs = _descendants(proc.pid)
        if workers > 1:
            assert len(procs) >= workers  # the pool's workers are there
        proc.send_signal(getattr(signal, signum))
        t0 = time.monotonic()
        rc = proc.wait(timeout=30)
        took = time.monotonic() - t0
        left = _wait_gone(procs)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        _kill(procs)
    stderr = (tmp_path / "stderr.txt").read_text()
    number = getattr(signal, signum)
    if how == "cli":  # the shell's status of a stopped command, and a message
        assert rc == 128 + number, stderr
        assert f"lgraph animate: terminated by {signum}" in stderr
    else:  # a library call: cleaned up, then the signal's default action
        assert rc == -number, stderr
    assert "Traceback" not in stderr
    # at once: a worker ended while sending its frames must not hold the pool up
    assert took < 8, f"{took:.1f} s from the signal to the end"
    assert left == [], f"worker processes left running: {left}"
    assert _parts(tmp_path) == []
    assert out.read_bytes() == OLD  # the old file at the target is intact


@POSIX
def test_workers_of_a_parent_killed_outright_end_by_themselves(tmp_path: Path) -> None:
    """SIGKILL cannot be caught (its temporary file stays, hidden, never taken
    for the output), but the pool's workers notice and end."""
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE_FILE)
    out = tmp_path / "turn.gif"
    out.write_bytes(OLD)
    cmd = [sys.executable, "-m", "lgraph", "animate", str(scene), "-o", str(out),
           "--frames", "200", "--hidden-lines", "--workers", "2"]  # fmt: skip
    with open(tmp_path / "stderr.txt", "w") as err:
        proc = subprocess.Popen(cmd, env={**os.environ, "PYTHONPATH": str(ROOT)}, stderr=err)
    procs: dict[int, Any] = {}
    try:
        _wait_for_frames(proc, tmp_path)
        procs = _descendants(proc.pid)
        assert len(procs) >= 2
        proc.kill()
        assert proc.wait(timeout=30) == -signal.SIGKILL
        left = _wait_gone(procs, timeout=10)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        _kill(procs)
    assert left == [], f"worker processes left running: {left}"
    assert out.read_bytes() == OLD


SLOW_BACKEND = """
import sys, time
sys.path.insert(0, {root!r})
from lgraph import backends
from lgraph.cli import main

def write_slow(drawing, path, **options):
    with open(path, "w") as f:
        f.write("partial")
        f.flush()
        print("WRITING", flush=True)
        time.sleep(60)

backends.register_backend(".slow", write_slow)
sys.exit(main(["render", {scene!r}, "-o", {out!r}]))
"""


@POSIX
def test_a_sigterm_during_lgraph_render_keeps_the_old_file(tmp_path: Path) -> None:
    scene = tmp_path / "s.toml"
    scene.write_text(SMALL_SCENE)
    out = tmp_path / "fig.slow"
    out.write_bytes(b"old figure")
    code = textwrap.dedent(SLOW_BACKEND.format(root=str(ROOT), scene=str(scene), out=str(out)))
    proc = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        assert proc.stdout.readline().strip() == "WRITING"
        assert _parts(tmp_path)  # mid-save
        proc.send_signal(signal.SIGTERM)
        _, stderr = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 128 + signal.SIGTERM
    assert stderr.strip() == "lgraph render: terminated by SIGTERM"
    assert _parts(tmp_path) == [] and out.read_bytes() == b"old figure"


# -- the mechanism ---------------------------------------------------------------------------
@POSIX
def test_signals_raise_terminated_and_the_previous_handlers_come_back() -> None:
    before = {s: signal.getsignal(s) for s in (signal.SIGTERM, signal.SIGHUP)}
    with pytest.raises(Terminated) as e:
        with signals_as_exception(take_default=False):
            with signals_as_exception():  # nested: the outer one decides
                assert signal.getsignal(signal.SIGTERM) is not before[signal.SIGTERM]
                os.kill(os.getpid(), signal.SIGTERM)
                time.sleep(5)  # interrupted
    assert e.value.signum == signal.SIGTERM and e.value.exit_status == 143
    assert str(e.value) == "terminated by SIGTERM"
    assert {s: signal.getsignal(s) for s in before} == before


@POSIX
def test_after_cleaning_up_the_previous_handler_takes_the_signal() -> None:
    seen: list[int] = []
    previous = signal.signal(signal.SIGHUP, lambda signum, frame: seen.append(signum))
    cleaned = []
    try:
        with pytest.raises(Terminated):
            with signals_as_exception():
                try:
                    os.kill(os.getpid(), signal.SIGHUP)
                    time.sleep(5)
                finally:
                    cleaned.append(seen[:])  # the cleanup runs before the handler
        assert cleaned == [[]] and seen == [signal.SIGHUP]
        # a signal swallowed inside the work is not lost
        seen.clear()
        with pytest.raises(Terminated):
            with signals_as_exception():
                try:
                    os.kill(os.getpid(), signal.SIGHUP)
                    time.sleep(5)
                except BaseException:  # noqa: BLE001 - as careless code does
                    pass
        assert seen == [signal.SIGHUP]
    finally:
        signal.signal(signal.SIGHUP, previous)


@POSIX
def test_an_ignored_signal_stays_ignored() -> None:
    previous = signal.signal(signal.SIGHUP, signal.SIG_IGN)
    try:
        with signals_as_exception():
            assert signal.getsignal(signal.SIGHUP) == signal.SIG_IGN
            os.kill(os.getpid(), signal.SIGHUP)  # nothing happens
            time.sleep(0.05)
    finally:
        signal.signal(signal.SIGHUP, previous)


def test_outside_the_main_thread_nothing_is_installed() -> None:
    seen = []

    def work() -> None:
        with signals_as_exception():
            seen.append(signal.getsignal(signal.SIGTERM))

    before = signal.getsignal(signal.SIGTERM)
    t = threading.Thread(target=work)
    t.start()
    t.join()
    assert seen == [before]


# -- executors ---------------------------------------------------------------------------
class GarbageExecutor(cf.Executor):
    """An executor whose futures hold whatever ``result(batch)`` gives
    (``result(batch, run)`` with ``run()`` the true frames, if it takes two)."""

    def __init__(self, result: Any) -> None:
        self.result = result

    def submit(self, fn: Any, *args: Any, **kwargs: Any) -> Any:
        batch = args[-1]  # the batch of views is the last argument
        if self.result.__code__.co_argcount == 2:
            value = self.result(batch, lambda: fn(*args, **kwargs))
        else:
            value = self.result(batch)
        if not isinstance(value, cf.Future) and value == "no future":
            return None
        fut: cf.Future = cf.Future()
        if isinstance(value, BaseException):
            fut.set_exception(value)
        elif value == "cancelled":
            fut.cancel()
        else:
            fut.set_result(value)
        return fut


@pytest.fixture
def small_scene() -> lg.Scene:
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(3, 4))
    return sc


@pytest.mark.parametrize(
    ("result", "message"),
    [
        (lambda b: "garbage", "returned a str ('garbage') for frames 0 to 1, not a list"),
        (lambda b: None, "returned a NoneType (None) for frames 0 to 1, not a list"),
        (lambda b: 42, "returned an int (42) for frames 0 to 1"),
        (lambda b: [None] * len(b), "returned a NoneType (None) for frame 0, not a frame"),
        (lambda b: [b"not png"] * len(b), "returned a bytes (b'not png') for frame 0"),
        (lambda b: [3.5], "returned 1 frames for frames 0 to 1, 2 expected"),
        (lambda b: "no future", "submit() returned a NoneType (None), not a future"),
    ],
)
def test_an_executor_returning_garbage_is_named_with_the_frame(
    small_scene: lg.Scene, tmp_path: Path, monkeypatch, result: Any, message: str
) -> None:
    monkeypatch.setattr(animation, "BATCH_FRAMES", 2)
    out = tmp_path / "t.gif"
    out.write_bytes(OLD)
    views = lg.orbit(elevation=25, frames=4)
    with pytest.raises(TypeError, match="animate: the executor") as e:
        lg.animate(small_scene, views, out, width=40, progress=False,
                   executor=GarbageExecutor(result))  # fmt: skip
    assert message in str(e.value)
    assert out.read_bytes() == OLD and _parts(tmp_path) == []


def test_the_frame_index_counts_the_batches_before(small_scene, tmp_path, monkeypatch) -> None:
    monkeypatch.setattr(animation, "BATCH_FRAMES", 2)

    def second_bad(batch: list, run: Any) -> Any:
        frames = run()
        return frames if batch[0] is views[0] else [frames[0], "x"]

    views = lg.orbit(elevation=25, frames=4)
    with pytest.raises(TypeError, match=r"returned a str \('x'\) for frame 3, not a frame"):
        lg.animate(small_scene, views, tmp_path / "t.gif", width=40, progress=False,
                   executor=GarbageExecutor(second_bad))  # fmt: skip
    assert _parts(tmp_path) == []


@pytest.mark.parametrize(
    ("result", "message"),
    [
        (lambda b: "cancelled", "the executor cancelled frames 0 to 1 (was it shut down?)"),
        (
            lambda b: BrokenProcessPool("a worker died"),
            "the executor's workers died while rendering frames 0 to 1",
        ),
    ],
)
def test_an_executor_that_lost_the_frames_says_so(
    small_scene, tmp_path, monkeypatch, result, message
) -> None:
    monkeypatch.setattr(animation, "BATCH_FRAMES", 2)
    with pytest.raises(ExecutorError, match=re.escape(message)):
        lg.animate(small_scene, lg.orbit(elevation=25, frames=4), tmp_path / "t.gif",
                   width=40, progress=False, executor=GarbageExecutor(result))  # fmt: skip
    assert list(tmp_path.iterdir()) == []


def test_the_command_line_reports_a_lost_cluster_in_one_line(tmp_path, capsys, monkeypatch):
    def lost(*args: Any, **kwargs: Any) -> Any:
        raise ExecutorError("animate: the Dask cluster lost its workers while rendering ...")

    monkeypatch.setattr(animation, "animate", lost)
    scene = tmp_path / "s.toml"
    scene.write_text(SMALL_SCENE)
    assert main(["animate", str(scene), "-o", str(tmp_path / "t.gif"), "--frames", "2"]) == 1
    err = capsys.readouterr().err
    assert err == "lgraph animate: error: the Dask cluster lost its workers while rendering ...\n"


def _worker_pids(dask_worker: Any = None) -> int:
    return os.getpid()


def test_a_dask_cluster_that_loses_its_only_worker_says_so(tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed")
    try:
        cluster = distributed.LocalCluster(
            n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None
        )
    except Exception as e:  # noqa: BLE001 - no cluster here (sandbox, no sockets)
        pytest.skip(f"distributed cannot start a local cluster here: {e}")
    out = tmp_path / "turn.gif"
    out.write_bytes(OLD)
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(10, 12))
    stop = threading.Event()
    try:
        with distributed.Client(cluster, timeout=30) as client:
            client.wait_for_workers(1, timeout=30)
            pids = list(client.run(_worker_pids).values())

            def kill_when_frames_come() -> None:  # the only worker dies mid-run
                while not stop.is_set():
                    if any((tmp_path / p).stat().st_size > 0 for p in _parts(tmp_path)):
                        for pid in pids:
                            os.kill(pid, signal.SIGKILL)
                        return
                    time.sleep(0.02)

            killer = threading.Thread(target=kill_when_frames_come, daemon=True)
            killer.start()
            t0 = time.monotonic()
            with pytest.raises(ExecutorError) as e:
                lg.animate(scene, lg.orbit(elevation=25, frames=120), out, hidden_lines=True,
                           progress=False, executor=client.get_executor())  # fmt: skip
            assert time.monotonic() - t0 < 30
    finally:
        stop.set()
        cluster.close(timeout=30)
    message = str(e.value)
    assert message.startswith("animate: the Dask cluster lost its workers while rendering frames")
    assert cluster.scheduler_address in message
    assert isinstance(e.value.__cause__, cf.CancelledError)
    assert out.read_bytes() == OLD and _parts(tmp_path) == []


# -- plugins ------------------------------------------------------------------------------
PLUGIN = '''\
import sys
import attrs
import lgraph as lg

NUMBER = 3


def quitter(r=1.0):
    """A surface factory that exits."""
    sys.exit(3)


@attrs.frozen
class QuitBall(lg.Sphere):
    def __attrs_post_init__(self):
        sys.exit(4)


def write_quit(drawing, path, **options):
    with open(path, "w") as f:
        f.write("half")
    sys.exit(5)
'''

EXITS_ON_IMPORT = """\
import sys
sys.exit(3)
"""


class FakeEntryPoint:
    """An importlib.metadata.EntryPoint with the distribution it came from."""

    def __init__(self, name: str, value: str, group: str, dist: str) -> None:
        self._ep = md.EntryPoint(name, value, group)
        self.name, self.value, self.group = name, value, group
        self.dist = SimpleNamespace(name=dist, version="1.0")

    def load(self) -> Any:
        return self._ep.load()


@pytest.fixture
def bad_plugins(tmp_path, monkeypatch):
    """Plugins that exit or are not callable, served as entry points."""
    (tmp_path / "lgraph_test_quits.py").write_text(PLUGIN)
    (tmp_path / "lgraph_test_exits_on_import.py").write_text(EXITS_ON_IMPORT)
    monkeypatch.syspath_prepend(str(tmp_path))
    entries = [
        ("surface", "quitter", "lgraph_test_quits:quitter"),
        ("surface", "quit_ball", "lgraph_test_quits:QuitBall"),
        ("surface", "number", "lgraph_test_quits:NUMBER"),
        ("surface", "exits", "lgraph_test_exits_on_import:Thing"),
        ("backend", "quit", "lgraph_test_quits:write_quit"),
        ("backend", "num", "lgraph_test_quits:NUMBER"),
    ]
    eps = [FakeEntryPoint(n, v, plugins.GROUPS[k], "bad-plugin") for k, n, v in entries]
    monkeypatch.setattr(md, "entry_points", lambda **kw: [e for e in eps if e.group == kw["group"]])
    plugins._reset()
    yield
    plugins._reset()
    for mod in ("lgraph_test_quits", "lgraph_test_exits_on_import"):
        sys.modules.pop(mod, None)


def _render(tmp_path: Path, surface: str, out: str = "fig.svg") -> list[str]:
    scene = tmp_path / f"{surface}.toml"
    scene.write_text(SMALL_SCENE.replace('"sphere"', f'"{surface}"'))
    return ["render", str(scene), "-o", str(tmp_path / out)]


def test_plugins_that_exit_or_are_not_callable_fail_to_load_and_are_listed(
    bad_plugins, capsys
) -> None:
    with pytest.warns(PluginWarning, match=r"surface plugin 'exits' .*SystemExit: 3"):
        stand_in = plugins.get_surface("exits")
    with pytest.raises(PluginError, match="surface plugin 'exits' from bad-plugin 1.0"):
        stand_in(r=1)
    with pytest.warns(
        PluginWarning, match=r"'lgraph_test_quits:NUMBER' is not a class or function \(int 3\)"
    ):
        number = plugins.get_surface("number")
    with pytest.raises(PluginError, match=r"lgraph_test_quits:NUMBER"):
        number(r=1)
    assert main(["plugins"]) == 0  # still works, the broken ones listed as failed
    out, err = capsys.readouterr()
    rows = {line.split()[0]: line for line in out.splitlines() if "bad-plugin" in line}
    assert "failed: SystemExit: 3" in rows["exits"]
    assert (
        "failed: TypeError: 'lgraph_test_quits:NUMBER' is not a class or function" in rows["number"]
    )
    assert "failed: TypeError" in rows["num"]
    assert rows["quitter"].rstrip().endswith("ok") and rows["quit"].rstrip().endswith("ok")
    assert "Traceback" not in err


@pytest.mark.parametrize(
    ("surface", "message"),
    [
        (
            "quitter",
            "surface plugin 'quitter' from bad-plugin 1.0 (lgraph_test_quits:quitter) "
            "called sys.exit(3)",
        ),
        (
            "quit_ball",
            "surface plugin 'quit_ball' from bad-plugin 1.0 "
            "(lgraph_test_quits:QuitBall) called sys.exit(4)",
        ),
        (
            "number",
            "surface plugin 'number' from bad-plugin 1.0 (lgraph_test_quits:NUMBER) "
            "failed to load (TypeError: 'lgraph_test_quits:NUMBER' is not a class or function",
        ),
        (
            "exits",
            "surface plugin 'exits' from bad-plugin 1.0 "
            "(lgraph_test_exits_on_import:Thing) failed to load",
        ),
    ],
)
def test_lgraph_render_names_a_plugin_that_exits_or_is_not_callable(
    bad_plugins, tmp_path, capsys, surface, message
) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PluginWarning)
        assert main(_render(tmp_path, surface)) == 2
    err = capsys.readouterr().err
    assert err.startswith("lgraph render: error:") and message in err, err
    assert "Traceback" not in err and len(err.splitlines()) == 1
    assert not (tmp_path / "fig.svg").exists()


@pytest.mark.parametrize(
    ("suffix", "message"),
    [
        (
            "quit",
            "backend plugin 'quit' from bad-plugin 1.0 (lgraph_test_quits:write_quit) "
            "called sys.exit(5)",
        ),
        ("num", "backend plugin 'num' from bad-plugin 1.0 (lgraph_test_quits:NUMBER) failed"),
    ],
)
def test_lgraph_render_names_a_backend_plugin_that_exits_or_is_not_callable(
    bad_plugins, tmp_path, capsys, suffix, message
) -> None:
    out = tmp_path / f"fig.{suffix}"
    out.write_text("old figure")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PluginWarning)
        assert main(_render(tmp_path, "sphere", out.name)) == 2
    err = capsys.readouterr().err
    assert err.startswith("lgraph render: error:") and message in err, err
    assert "Traceback" not in err and len(err.splitlines()) == 1
    assert out.read_text() == "old figure" and _parts(tmp_path) == []


def test_a_factory_that_exits_raises_a_plugin_error_in_a_program(bad_plugins) -> None:
    factory = plugins.get_surface("quitter")
    with pytest.raises(PluginError, match=r"surface plugin 'quitter' .* called sys.exit\(3\)"):
        factory(r=1)


def test_a_sys_exit_that_is_not_a_plugins_still_exits(monkeypatch) -> None:
    from lgraph import cli

    def leave(args: Any) -> int:
        sys.exit(7)

    monkeypatch.setattr(cli, "_plugins", leave)
    with pytest.raises(SystemExit) as e:
        main(["plugins"])
    assert e.value.code == 7


# -- paths -------------------------------------------------------------------------------
def test_dot_dot_in_an_output_creates_no_folders(tmp_path, capsys, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    scene = tmp_path / "s.toml"
    scene.write_text(SMALL_SCENE)
    assert main(["render", "s.toml", "-o", "a/b/../../x.svg"]) == 0
    assert (tmp_path / "x.svg").exists() and not (tmp_path / "a").exists()
    assert main(["render", str(scene), "-o", str(tmp_path / "c" / "d" / ".." / "y.svg")]) == 0
    assert (tmp_path / "c" / "y.svg").exists() and not (tmp_path / "c" / "d").exists()
    assert main(["animate", "s.toml", "-o", "e/f/../../t.gif", "--frames", "2",
                 "--width", "32"]) == 0  # fmt: skip
    assert (tmp_path / "t.gif").exists() and not (tmp_path / "e").exists()
    assert main(["animate", "s.toml", "-o", "g/h/../frames", "--frames", "2",
                 "--width", "32"]) == 0  # fmt: skip
    assert (tmp_path / "g" / "frames" / "frame_0000.png").exists()
    assert not (tmp_path / "g" / "h").exists()
    assert _parts(tmp_path) == []
    d = _small_drawing()
    d.save(tmp_path / "m" / "n" / ".." / ".." / "z.svg")  # Drawing.save: the same path
    assert (tmp_path / "z.svg").exists() and not (tmp_path / "m").exists()


@pytest.mark.skipif(not hasattr(os, "symlink"), reason="symbolic links needed")
def test_dot_dot_is_lexical_even_after_a_symbolic_link(tmp_path, capsys, monkeypatch) -> None:
    """The documented choice: ``link/../x.svg`` is ``./x.svg``, the path as
    written, not the folder beside the link's target."""
    (tmp_path / "elsewhere" / "inner").mkdir(parents=True)
    (tmp_path / "here").mkdir()
    os.symlink(tmp_path / "elsewhere" / "inner", tmp_path / "here" / "link")
    monkeypatch.chdir(tmp_path / "here")
    (tmp_path / "here" / "s.toml").write_text(SMALL_SCENE)
    assert main(["render", "s.toml", "-o", "link/../x.svg"]) == 0
    assert (tmp_path / "here" / "x.svg").exists()
    assert not (tmp_path / "elsewhere" / "x.svg").exists()


def _long_name(tmp_path: Path, n_bytes: int, suffix: str) -> str:
    return "f" * (n_bytes - len(suffix)) + suffix


def test_a_254_character_file_name_is_written(tmp_path: Path, capsys) -> None:
    if name_max(tmp_path) < 254:
        pytest.skip("this file system takes shorter names")
    scene = tmp_path / "s.toml"
    scene.write_text(SMALL_SCENE)
    svg = tmp_path / _long_name(tmp_path, 254, ".svg")
    assert main(["render", str(scene), "-o", str(svg)]) == 0, capsys.readouterr().err
    assert svg.exists()
    pdf = tmp_path / _long_name(tmp_path, 254, ".pdf")
    _small_drawing().save(pdf)
    assert pdf.read_bytes().startswith(b"%PDF")
    gif = tmp_path / _long_name(tmp_path, 254, ".gif")
    assert main(["animate", str(scene), "-o", str(gif), "--frames", "2", "--width", "32"]) == 0
    assert gif.exists()
    assert _parts(tmp_path) == []


def test_a_file_name_too_long_is_refused_naming_the_users_file(tmp_path: Path, capsys) -> None:
    limit = name_max(tmp_path)
    scene = tmp_path / "s.toml"
    scene.write_text(SMALL_SCENE)
    before = sorted(p.name for p in tmp_path.iterdir())
    for suffix, command in ((".svg", "render"), (".gif", "animate")):
        name = _long_name(tmp_path, limit + 1, suffix)
        out = tmp_path / "new" / name  # its folder is not created either
        assert main([command, str(scene), "-o", str(out)]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"lgraph {command}: error: output '{out}': file name too long")
        assert f"({limit + 1} bytes; the file system allows {limit})" in err
        assert ".part" not in err and "Traceback" not in err
    with pytest.raises(OSError) as e:
        _small_drawing().save(tmp_path / _long_name(tmp_path, limit + 1, ".pdf"))
    assert e.value.errno == errno.ENAMETOOLONG
    assert e.value.filename == str(tmp_path / _long_name(tmp_path, limit + 1, ".pdf"))
    assert "Drawing.save: file name too long" in str(e.value) and ".part" not in str(e.value)
    with pytest.raises(OSError, match="animate: file name too long") as e:
        scene_obj = lg.Scene()
        scene_obj.add(lg.Sphere(1), lg.ParameterLines(2, 2))
        lg.animate(scene_obj, lg.orbit(elevation=25, frames=2),
                   tmp_path / _long_name(tmp_path, limit + 1, ".gif"), width=32,
                   progress=False)  # fmt: skip
    assert sorted(p.name for p in tmp_path.iterdir()) == before


GALLERY_SCRIPT = """
import sys
sys.path.insert(0, {root!r})
from lgraph.gallery import build_gallery

build_gallery({out!r}, jobs={jobs}, source_dir={src!r})
"""

SLOW_FIGURE = '''
"""A figure that takes its time."""
import pathlib, time
import lgraph as lg


def build():
    pathlib.Path({mark!r}).write_text("started")
    time.sleep(120)
    scene = lg.Scene()
    scene.add(lg.Sphere(1))
    return scene, lg.ParallelProjector(direction=(1, 2, 3))
'''


@POSIX
@pytest.mark.parametrize("jobs", [1, 2])
def test_a_stop_signal_ends_the_gallery_and_its_workers(tmp_path: Path, jobs: int) -> None:
    """The gallery does not take a stop for a failing figure and go on: the
    signal ends it (its default action, from a program), workers included."""
    src, out = tmp_path / "src", tmp_path / "out"
    src.mkdir()
    for k in range(2):
        mark = tmp_path / f"started{k}"
        (src / f"slow_{k}.py").write_text(SLOW_FIGURE.format(mark=str(mark)))
    code = GALLERY_SCRIPT.format(root=str(ROOT), out=str(out), jobs=jobs, src=str(src))
    with open(tmp_path / "stderr.txt", "w") as err:
        proc = subprocess.Popen([sys.executable, "-c", textwrap.dedent(code)], stderr=err)
    procs: dict[int, Any] = {}
    try:
        deadline = time.monotonic() + 60
        while not any(tmp_path.glob("started*")):
            assert proc.poll() is None, (tmp_path / "stderr.txt").read_text()
            assert time.monotonic() < deadline, "no figure started in time"
            time.sleep(0.02)
        procs = _descendants(proc.pid)
        proc.send_signal(signal.SIGTERM)
        rc = proc.wait(timeout=30)
        left = _wait_gone(procs, timeout=3)  # ended, not left to finish their figure
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        _kill(procs)
    assert rc == -signal.SIGTERM, (tmp_path / "stderr.txt").read_text()
    assert left == [], f"worker processes left running: {left}"
    assert not (out / "index.html").exists()  # it stopped, it did not go on


@POSIX
def test_lgraph_gallery_stops_on_a_signal_with_the_shells_status(tmp_path: Path) -> None:
    """``lgraph gallery`` under SIGTERM: exit status 143 and one line, as the
    other commands (not a figure reported failed and the next one begun)."""
    cmd = [sys.executable, "-m", "lgraph", "gallery", str(tmp_path / "out"),
           "--jobs", "2", "--only", "fig_7_1", "fig_7_3"]  # fmt: skip
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    with open(tmp_path / "stderr.txt", "w") as err, open(tmp_path / "stdout.txt", "w") as out:
        proc = subprocess.Popen(cmd, env=env, stderr=err, stdout=out)
    procs: dict[int, Any] = {}
    try:
        deadline = time.monotonic() + 60
        while "building" not in (tmp_path / "stdout.txt").read_text():
            assert proc.poll() is None, (tmp_path / "stderr.txt").read_text()
            assert time.monotonic() < deadline, "the gallery did not start in time"
            time.sleep(0.02)
        time.sleep(0.5)  # the workers are at their figures
        procs = _descendants(proc.pid)
        proc.send_signal(signal.SIGTERM)
        rc = proc.wait(timeout=30)
        left = _wait_gone(procs, timeout=3)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        _kill(procs)
    stderr = (tmp_path / "stderr.txt").read_text()
    assert rc == 128 + signal.SIGTERM, stderr
    assert "lgraph gallery: terminated by SIGTERM" in stderr
    assert "Traceback" not in stderr
    assert left == [], f"worker processes left running: {left}"
