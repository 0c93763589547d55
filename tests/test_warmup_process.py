"""The kernel warm-up an interactive Blender starts at register runs in a child process (a
thread of Blender's crashed Blender 4.3: two LLVMs compiling at once) and leaves the machine
code in numba's on-disk cache, so a fresh process loads the kernels instead of compiling them:
numba's own dispatcher statistics say so (cache hits, no misses)."""
import json
import os
import subprocess
import sys

from kezuri import operators

HERE = os.path.dirname(os.path.abspath(__file__))

FRESH = r"""
import importlib.util, json, os, sys
root = sys.argv[1]
spec = importlib.util.spec_from_file_location("kezuri", os.path.join(root, "__init__.py"),
                                              submodule_search_locations=[root])
package = importlib.util.module_from_spec(spec); sys.modules["kezuri"] = package; spec.loader.exec_module(package)
from kezuri.toolpath.engines import warmup
from kezuri.toolpath.simulate import BoxStock, simulate
from kezuri.toolpath.simulate import CylinderStock, kernel
from kezuri.toolpath.engines import facets, facets_kernel, meshrays
simulate([warmup._box_operation("ball", 1)], BoxStock(0.0, 0.0, -3.0, 8.0, 8.0, 0.0), cell=0.5, kernel="numba")
# a turn-mill check against a design (the radius map's rays), and its part's mesh check and planning mesh
design = warmup._prism(30.0, -40.0, 0.0, sides=24)
simulate([warmup._radial_operation()], CylinderStock(35.0, 40.0, 0.0), cell=0.5, design=design, kernel="numba")
facets.planning_mesh(*meshrays.check_mesh(design.vertices, design.faces))
used = {module.__name__ + "." + name: (f.stats.cache_hits, f.stats.cache_misses)
        for module in (kernel, facets_kernel) for name, f in vars(module).items()
        if hasattr(f, "stats") and f.signatures}
print(json.dumps({name: [sum(h.values()), sum(m.values())] for name, (h, m) in used.items()}))
"""


def fresh_process_stats(cache_dir: str) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    done = subprocess.run([sys.executable, "-c", FRESH, os.path.dirname(HERE)], capture_output=True, text=True,
                          timeout=600, env=env)
    assert done.returncode == 0, done.stderr[-2000:]
    stats = json.loads(done.stdout.strip().splitlines()[-1])
    assert stats, "the simulation used no compiled kernel"
    return stats


def test_the_warm_up_process_leaves_the_kernels_in_numbas_cache(tmp_path, monkeypatch):
    assert __import__("numba")                  # a pinned dependency: the test fails without it
    cache = str(tmp_path / "warmed")
    monkeypatch.setenv("NUMBA_CACHE_DIR", cache)          # the child inherits it: an empty cache
    job = operators.start_warmup()
    job._process.wait(timeout=900)
    assert job.step()
    ran = job.result()
    assert "heightfield ball" in ran and "radius map" in ran and "nearest point" in ran
    stats = fresh_process_stats(cache)
    assert {"kezuri.toolpath.simulate.kernel.outer_rays", "kezuri.toolpath.engines.facets_kernel.face_pass",
            "kezuri.toolpath.engines.facets_kernel.edge_check"} <= set(stats), sorted(stats)
    for name, (hits, misses) in stats.items():
        assert hits >= 1 and misses == 0, (name, hits, misses)     # loaded from the cache, not compiled
    # and the statistics do tell the difference: with a cache nobody warmed, the kernels compile
    cold = fresh_process_stats(str(tmp_path / "cold"))
    assert any(misses >= 1 for _, misses in cold.values()), cold
