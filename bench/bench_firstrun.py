"""Issue #32: the first run after an install, when numba's cache is empty and the kernels a run
needs are compiled, against a run that loads them from the cache; beside the same on the base
code (KEZURI_FIRSTRUN_BASE, default 495f8bd, checked out in a temporary ``git worktree``).

Each figure is ``batch.main`` in a fresh process (bpy imported and the extension registered
first, not timed), CPU (``time.process_time()``, every thread) and wall: the engrave sample
(``batch.py engrave --post linuxcnc``) and ``batch.py simulate`` of a 200-move pocket program
(bench_batch's).  "empty" runs with NUMBA_CACHE_DIR an empty folder; "warm" runs again on the
cache the empty run filled.  The tree under test is ``git archive HEAD`` (committed code).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

from bench_batch import pocket_nc

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BASE = os.environ.get("KEZURI_FIRSTRUN_BASE", "495f8bd")
RUNS = {"engrave": ["engrave", "--post", "linuxcnc"],
        "simulate": ["simulate", "--tool", "flat:6", "--stock", "box:0,0,-10,100,60,0"]}

DRIVER = r"""
import json, sys, time
root, argv = sys.argv[1], sys.argv[2:]
sys.path.insert(0, root)
import bpy  # noqa: F401  (start-up: not timed)
import batch
batch.load_extension()
cpu, wall = time.process_time(), time.perf_counter()
status = batch.main(["batch.py", *argv])
print("KEZURI-BENCH " + json.dumps({"cpu": time.process_time() - cpu, "wall": time.perf_counter() - wall,
                                    "status": status}))
"""


def timed(tree: str, argv: list, cache: str) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    env.pop("KEZURI_NO_NUMBA", None)
    done = subprocess.run([sys.executable, "-c", DRIVER, tree, *argv], capture_output=True, text=True,
                          timeout=900, env=env)
    for line in done.stdout.splitlines():
        if line.startswith("KEZURI-BENCH "):
            result = json.loads(line[len("KEZURI-BENCH "):])
            if result["status"] == 0:
                result["said"] = [text for text in done.stderr.splitlines() if "compiling the numba" in text]
                return result
    raise RuntimeError(f"batch {argv[0]} failed in {tree}: {done.stderr[-2000:]}")


def first_and_warm(tree: str, work: str) -> dict:
    """{run: (empty-cache figures, warm-cache figures)} for the tree at ``tree``."""
    figures = {}
    nc = pocket_nc(os.path.join(work, "pocket.ngc"))
    for name, argv in RUNS.items():
        argv = argv + (["--nc", nc] if name == "simulate" else [])
        cache = tempfile.mkdtemp(prefix="numba-cache-", dir=work)
        out = os.path.join(work, os.path.basename(tree), name)
        figures[name] = tuple(timed(tree, argv + ["--out", f"{out}-{attempt}"], cache) for attempt in ("empty", "warm"))
    return figures


def run() -> list:
    rows = []
    with tempfile.TemporaryDirectory() as work:
        now_tree, base_tree = os.path.join(work, "now"), os.path.join(work, "base")
        os.mkdir(now_tree)
        subprocess.run(f"git -C {ROOT} archive HEAD | tar -x -C {now_tree}", shell=True, check=True)
        subprocess.run(["git", "-C", ROOT, "worktree", "add", "--detach", "-q", base_tree, BASE], check=True)
        try:
            now, base = first_and_warm(now_tree, work), first_and_warm(base_tree, work)
        finally:
            subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", base_tree], check=False)
    for name in RUNS:
        (empty, warm), (base_empty, base_warm) = now[name], base[name]
        rows.append(dict(name=f"first {name}, empty numba cache (CPU s)", seconds=empty["cpu"], target_s=None,
                         notes=f"wall {empty['wall']:.2f}; {base_empty['cpu']:.2f} CPU / {base_empty['wall']:.2f} wall "
                               f"at {BASE}; {len(empty['said'])} line said"))
        rows.append(dict(name=f"{name}, warm numba cache (CPU s)", seconds=warm["cpu"], target_s=None,
                         notes=f"wall {warm['wall']:.2f}; {base_warm['cpu']:.2f} CPU / {base_warm['wall']:.2f} wall at {BASE}; "
                               f"first run costs {empty['cpu'] - warm['cpu']:+.2f} s CPU "
                               f"(at {BASE}: {base_empty['cpu'] - base_warm['cpu']:+.2f})"))
    return rows
