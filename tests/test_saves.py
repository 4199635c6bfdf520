"""Saves are atomic even when the process is told to stop: a SIGTERM or
SIGHUP during a save leaves no temporary file, and errors name the target."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import lgraph as lg

ROOT = Path(__file__).resolve().parents[1]

SLOW_SAVE = """
import sys, time
sys.path.insert(0, {root!r})
import lgraph as lg
from lgraph import backends

def write_slow(drawing, path, **options):
    with open(path, "w") as f:
        f.write("partial")
        f.flush()
        print("WRITING", flush=True)
        time.sleep(60)

backends.register_backend(".slow", write_slow)
sc = lg.Scene(); sc.add(lg.Sphere(1), lg.ParameterLines(2, 2))
sc.render(lg.ParallelProjector(direction=(1, 2, 3))).save({out!r})
"""


@pytest.mark.skipif(not hasattr(signal, "SIGHUP"), reason="POSIX signals needed")
@pytest.mark.parametrize("signum", ["SIGTERM", "SIGHUP"])
def test_a_signal_during_a_save_leaves_no_temporary_file(tmp_path: Path, signum: str) -> None:
    out = tmp_path / "fig.slow"
    code = textwrap.dedent(SLOW_SAVE.format(root=str(ROOT), out=str(out)))
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "WRITING"
        assert [p.name for p in tmp_path.iterdir() if p.name.endswith(".part")]  # mid-save
        proc.send_signal(getattr(signal, signum))
        rc = proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert rc == -getattr(signal, signum)  # the signal's default action still ends it
    assert list(tmp_path.iterdir()) == []


def test_save_errors_name_the_target_path(tmp_path: Path, monkeypatch) -> None:
    from lgraph.output import backends

    def write_denied(drawing, path, **options):
        raise PermissionError(13, "Permission denied", str(path))

    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(2, 2))
    d = sc.render(lg.ParallelProjector(direction=(1, 2, 3)))
    monkeypatch.setitem(backends._BACKENDS, ".denied", write_denied)
    target = tmp_path / "fig.denied"
    with pytest.raises(PermissionError) as e:
        d.save(target)
    assert e.value.filename == str(target) and ".part" not in str(e.value)
    assert list(tmp_path.iterdir()) == []


def test_the_previous_signal_handler_is_restored(tmp_path: Path) -> None:
    before = signal.getsignal(signal.SIGTERM)
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(2, 2))
    sc.render(lg.ParallelProjector(direction=(1, 2, 3))).save(tmp_path / "a.svg")
    assert signal.getsignal(signal.SIGTERM) is before
    assert os.listdir(tmp_path) == ["a.svg"]


def test_a_stale_temporary_file_is_never_taken_for_the_output(tmp_path: Path) -> None:
    """A killed process (SIGKILL cannot be caught) may leave ``.fig.svg.*.part``
    behind; a later save writes its own temporary file and the target, and
    leaves the stale one alone (it is hidden and never has the target's name)."""
    stale = tmp_path / ".fig.svg.abc123.part"
    stale.write_text("half a figure")
    sc = lg.Scene()
    sc.add(lg.Sphere(1), lg.ParameterLines(2, 2))
    out = sc.render(lg.ParallelProjector(direction=(1, 2, 3))).save(tmp_path / "fig.svg")
    assert out.read_text().startswith("<?xml") or "<svg" in out.read_text()
    assert stale.read_text() == "half a figure"
    assert sorted(p.name for p in tmp_path.iterdir()) == [".fig.svg.abc123.part", "fig.svg"]
