"""``import lgraph`` stays light: no scipy, reportlab or pillow until a
surface, family or backend needs them (timing is in benchmarks/bench_import.py)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

PROBE = """
import sys
sys.path.insert(0, {root!r})
import lgraph as lg
heavy = sorted(m for m in sys.modules if m.split(".")[0] in ("scipy", "reportlab", "PIL"))
print("AFTER-IMPORT", heavy)
sc = lg.Scene(); sc.add(lg.Sphere(1), lg.ParameterLines(3, 3))
d = sc.render(lg.ParallelProjector(direction=(1, 2, 3)))
heavy = sorted({{m.split(".")[0] for m in sys.modules}} & {{"scipy", "reportlab", "PIL"}})
print("AFTER-SPHERE", heavy)
"""


def test_import_lgraph_loads_no_scipy_reportlab_or_pillow() -> None:
    r = subprocess.run(
        [sys.executable, "-c", PROBE.format(root=str(ROOT))],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    assert "AFTER-IMPORT []" in r.stdout
    # a sphere scene needs none of them either (the backends load theirs on save)
    assert "AFTER-SPHERE []" in r.stdout
