"""numba's on-disk cache of our kernels: a first run fills an empty cache (and batch says it is
compiling, once), a second run loads everything and compiles nothing; the arc search that small
operations run interpreted gives the compiled search's answers."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from kezuri.toolpath.ir import arcfit_kernel

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NUMBA = arcfit_kernel.COMPILED

# A child process: batch's compile notice put in before numba is imported, then one small
# simulation (the flat end mill's kernels) and one arc search; prints what numba compiled.
CHILD = r"""
import json, sys
sys.path.insert(0, sys.argv[1])
import batch
batch.import_package()
from kezuri.operators.compilenotice import say_when_compiling
said = []
before = "numba" in sys.modules
say_when_compiling(said.append)
from kezuri.toolpath.engines import warmup
from kezuri.toolpath.simulate import BoxStock, simulate
from kezuri.toolpath.ir import arcfit_kernel
import numpy as np
from numba.core import event
compiled = []
class Count(event.Listener):
    def on_start(self, ev):
        compiled.append(ev.data["dispatcher"].py_func.__qualname__)
    def on_end(self, ev):
        pass
event.register("numba:compile", Count())
result = simulate([warmup._box_operation("flat", 1)], BoxStock(0.0, 0.0, -3.0, 8.0, 8.0, 0.0), cell=0.5)
angle = np.linspace(0.0, np.pi / 2, 33)
fitted = arcfit_kernel.fit_runs_for(arcfit_kernel.COMPILE_FROM)(4.0 * np.cos(angle), 4.0 * np.sin(angle),
                                                                np.array([0]), np.array([31]), 0.01, 3, 5000.0)
print("KEZURI-TEST " + json.dumps({"numba_before": before, "said": said, "compiled": compiled,
                                   "kernel": result.kernel, "fitted": fitted.tolist()}))
"""


def child(cache: str) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    env.pop("KEZURI_NO_NUMBA", None)
    done = subprocess.run([sys.executable, "-c", CHILD, ROOT], capture_output=True, text=True, timeout=600, env=env)
    lines = [line for line in done.stdout.splitlines() if line.startswith("KEZURI-TEST ")]
    assert lines, done.stderr[-3000:]
    return json.loads(lines[-1][len("KEZURI-TEST "):])


def cache_files(cache: str) -> dict:
    return {os.path.join(folder, name): os.path.getmtime(os.path.join(folder, name))
            for folder, _, names in os.walk(cache) for name in names}


@pytest.mark.skipif(not NUMBA, reason="numba is not available")
def test_an_empty_cache_is_filled_once_and_the_second_run_compiles_nothing(tmp_path):
    pytest.importorskip("bpy")
    cache = str(tmp_path / "numba-cache")
    first = child(cache)
    assert first["numba_before"] is False           # the notice waited for numba's import
    assert first["kernel"] == "numba"
    # the flat end mill's kernels (bands, stamps, ...) and the arc search were compiled, and said once
    assert {"cut_bands", "cut_stamps", "fit_runs"} <= set(first["compiled"])
    assert len(first["said"]) == 1 and "compiling the numba kernels" in first["said"][0]
    filled = cache_files(cache)
    names = {os.path.basename(path) for path in filled}
    assert any(name.startswith("kernel.cut_bands-") and name.endswith(".nbc") for name in names)
    assert any(name.startswith("arcfit_kernel.fit_runs-") and name.endswith(".nbc") for name in names)

    second = child(cache)
    assert second["compiled"] == [] and second["said"] == []
    assert second["kernel"] == "numba"
    assert cache_files(cache) == filled             # nothing written again
    # one arc: the quarter circle of radius 4 round the origin, counter-clockwise, ending at point 32
    assert second["fitted"] == first["fitted"]
    assert len(first["fitted"]) == 1
    run, end, cx, cy, turn = first["fitted"][0]
    assert run == 0
    assert (end, turn) == (32, 1) and abs(cx) < 1e-9 and abs(cy) < 1e-9


def polylines(rng) -> list:
    """Arcs (both ways, helices of chords, noisy), lines, zig-zags, a circle and a half, repeated points."""
    out = []
    for _ in range(60):
        n = int(rng.integers(3, 200))
        radius = float(rng.uniform(0.5, 300.0))
        sweep = float(rng.uniform(0.1, 3.0 * np.pi)) * (1 if rng.random() < 0.5 else -1)
        angle = rng.uniform(0, 2 * np.pi) + np.linspace(0.0, sweep, n)
        x, y = radius * np.cos(angle), radius * np.sin(angle)
        noise = float(rng.choice([0.0, 0.002, 0.02]))
        x, y = x + rng.normal(0, noise, n) if noise else x, y + rng.normal(0, noise, n) if noise else y
        out.append((x, y))
    for _ in range(20):
        n = int(rng.integers(3, 80))
        out.append((np.cumsum(rng.uniform(0.0, 2.0, n)), rng.uniform(-1.0, 1.0, n) * (rng.random() < 0.5)))
    out.append((np.array([0.0, 0.0, 0.0, 1.0]), np.array([0.0, 0.0, 0.0, 0.0])))
    return out


@pytest.mark.skipif(not NUMBA, reason="numba is not available")
def test_the_interpreted_arc_search_gives_the_compiled_answers():
    rng = np.random.default_rng(32)
    arcs = 0
    for x, y in polylines(rng):
        x, y = np.ascontiguousarray(x, np.float64), np.ascontiguousarray(y, np.float64)
        for tolerance in (0.001, 0.01, 0.1):
            compiled = arcfit_kernel.fit_run(x, y, tolerance, 3, 5000.0)
            interpreted = arcfit_kernel.interpreted_fit_run(x, y, tolerance, 3, 5000.0)
            np.testing.assert_array_equal(compiled[:, [0, 3]], interpreted[:, [0, 3]])
            np.testing.assert_allclose(compiled[:, 1:3], interpreted[:, 1:3], rtol=0, atol=1e-9)
            arcs += int(np.count_nonzero(compiled[:, 3]))
    assert arcs > 100            # the cases do exercise the arcs, not only lines


def test_small_operations_take_the_interpreted_search_large_ones_the_compiled():
    assert arcfit_kernel.fit_runs_for(arcfit_kernel.COMPILE_FROM) is (
        arcfit_kernel.fit_runs if NUMBA else arcfit_kernel.interpreted_fit_runs)
    if not (NUMBA and arcfit_kernel.fit_runs.signatures):       # compiled already here: it is used
        assert arcfit_kernel.fit_runs_for(100) is arcfit_kernel.interpreted_fit_runs
    assert arcfit_kernel.interpreted_fit_runs is not arcfit_kernel.fit_runs
    assert not hasattr(arcfit_kernel.interpreted_fit_runs, "signatures")     # plain Python, no dispatcher
    # the interpreted one calls the interpreted search of a run, not the compiled dispatcher
    assert arcfit_kernel.interpreted_fit_runs.__globals__["fit_run"] is arcfit_kernel.interpreted_fit_run
