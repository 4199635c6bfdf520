"""Frames on a Dask cluster: a LocalCluster of two worker processes.

The scene goes to each worker once (``client.scatter(broadcast=True)``), and
the animation equals a serial run byte for byte.
"""

from __future__ import annotations

import pytest
from PIL import Image

import lgraph as lg
from lgraph.animation import frames as animation
from lgraph.cli import main as cli_main

distributed = pytest.importorskip(
    "distributed", reason="dask.distributed is not installed (pip install 'lgraph[cluster]')"
)


SCENE_FILE = """
[projector]
kind = "parallel"
azimuth = 30
elevation = 20

[[object]]
surface = "sphere"
params = { r = 1 }
families = [{ name = "parameter_lines", n1 = 4, n2 = 8 }]
"""


def _loads() -> int:
    return animation.JOB_LOADS[0]


def test_frames_on_a_local_cluster_equal_a_serial_run(tmp_path, monkeypatch):
    monkeypatch.setattr(animation, "BATCH_FRAMES", 2)  # 3 batches of views for 2 workers
    scene = lg.Scene()
    scene.add(lg.Ellipsoid(3, 2, 1.3), lg.LinesOfCurvature(5, 6))
    # a lambda in the scene: Dask sends it with cloudpickle
    scene.add(lg.Curve(lambda t: [[0, 0, 1.3]] + 0 * t[:, None] + t[:, None] * [0, 0, 1], 0, 1))
    views = lg.orbit(elevation=25, frames=6)
    serial = lg.animate(scene, views, tmp_path / "s.gif", width=80, progress=False, workers=1)
    cluster = distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        death_timeout=60,
    )
    try:
        with distributed.Client(cluster, timeout=60) as client:
            client.wait_for_workers(2, timeout=60)
            out = lg.animate(scene, views, tmp_path / "d.gif", width=80, progress=False,
                             executor=client.get_executor())  # fmt: skip
            loads = client.run(_loads)
        # the command line, given the scheduler's address
        f = tmp_path / "scene.toml"
        f.write_text(SCENE_FILE, encoding="utf-8")
        gif = tmp_path / "cli.gif"
        argv = ["animate", str(f), "-o", str(gif), "--frames", "3", "--width", "64",
                "--scheduler", cluster.scheduler_address]  # fmt: skip
        assert cli_main(argv) == 0
    finally:
        cluster.close(timeout=30)
    with Image.open(gif) as im:
        assert im.n_frames == 3 and im.size[0] == 64
    assert out.read_bytes() == serial.read_bytes()
    assert len(loads) == 2
    assert sorted(loads.values()) == [1, 1]  # the scene reached each worker exactly once
