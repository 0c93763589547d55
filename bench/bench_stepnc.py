"""W3: Part 21 parse speed on a large generated file, and the conversion of ISO 14649 Example 1."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
EX1 = os.path.join(HERE, "..", "tests", "fixtures", "iso14649", "ex1.stp")


def large_file(pockets: int = 400) -> str:
    """A plate with many pockets written by our own writer (each pocket ~25 instances)."""
    from kezuri.toolpath.operations import stepnc
    from kezuri.toolpath.ir.program import Tool

    specs = []
    for k in range(pockets):
        x, y = 10 + (k % 20) * 30, 10 + (k // 20) * 30
        specs.append(stepnc.PocketSpec(f"P{k}", ((x, y), (x + 20, y), (x + 20, y + 15), (x + 5, y + 20), (x, y + 15)),
                                       5.0))
    return stepnc.pockets_to_part21(((0, 0, -20), (620, 620, 0)), specs, Tool(1, "flat", 4.0))


def _cpu(call):
    """(result, CPU seconds, peak traced MB) of call()."""
    import gc
    import tracemalloc
    gc.collect()
    tracemalloc.start()
    started = time.process_time()
    result = call()
    seconds = time.process_time() - started
    peak = tracemalloc.get_traced_memory()[1] / 1e6
    tracemalloc.stop()
    return result, seconds, peak


def explicit_rows(megabytes: float = 50.0) -> list:
    """Issue #32 item 4: a generated file of explicit toolpaths (see stepnc_bigfile.py), read by the
    token parser alone (the reader before the fast path, ``fast=False``) and as it reads now, in
    the same run; CPU seconds, and peak memory traced separately (tracing slows the parse)."""
    import stepnc_bigfile
    from kezuri.toolpath.operations import stepnc
    from kezuri.toolpath.operations.stepnc import part21

    text = stepnc_bigfile.explicit_toolpath_file(megabytes)
    size_mb = len(text.encode()) / 1e6
    rows, speeds = [], {}
    for label, fast in (("token parser (before)", False), ("fast path", True)):
        started = time.process_time()
        parsed = part21.parse_part21(text, fast=fast)
        seconds = time.process_time() - started
        count = len(parsed.instances)
        del parsed
        _, _, peak = _cpu(lambda fast=fast: len(part21.parse_part21(text, fast=fast).instances))
        speeds[label] = size_mb / seconds
        rows.append({"name": f"stepnc: read {size_mb:.0f} MB of explicit toolpaths, {label}", "seconds": seconds,
                     "target_s": size_mb / 10.0 if fast else None,
                     "notes": f"{size_mb / seconds:.1f} MB/s CPU; {count} instances; peak {peak:.0f} MB "
                              f"traced (text {len(text) / 1e6:.0f} MB)"})
    rows[-1]["notes"] += f"; {speeds['fast path'] / speeds['token parser (before)']:.1f}x the token parser"
    return rows


BASE_COMMIT = "495f8bd"     # before the big-file conversion work (issue 32)
ROOT = os.path.dirname(HERE)


def _batch_child(tree: str, path: str, out: str) -> tuple:
    """(CPU seconds, peak RSS MB, NC text) of ``batch.py stepnc`` from ``tree`` in a child process."""
    command = [sys.executable, os.path.join(tree, "batch.py"), "stepnc", "--input", path, "--post", "linuxcnc",
               "--out", out]
    child = subprocess.Popen(command, cwd=tree, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    if child.returncode:
        raise RuntimeError(f"{command} exited {child.returncode}")
    with open(os.path.join(out, "stepnc.ngc"), encoding="utf-8") as nc:
        text = nc.read()
    return usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, text


def end_to_end_rows(sizes=(5.0, 15.0, 50.0), base: str = BASE_COMMIT) -> list:
    """Issue #32 item 4 beyond the parser: the whole ``batch.py stepnc`` (read, convert with the
    in-process stock, post, the gate's simulation, previews, report) of generated files of
    ``sizes`` MB, each in a child process (CPU seconds, peak RSS), and of the largest from ``base``
    too (a temporary git worktree), in the same run.  Target: twice the parse alone (CPU, here)."""
    import numpy as np
    import stepnc_bigfile
    from kezuri.toolpath.operations.stepnc import part21

    rows, points = [], []
    with tempfile.TemporaryDirectory(prefix="kezuri-bench-stepnc-") as scratch:
        base_tree = os.path.join(scratch, "base")
        made = subprocess.run(["git", "-C", ROOT, "worktree", "add", "--detach", base_tree, base],
                              capture_output=True).returncode == 0
        try:
            for n, megabytes in enumerate(sizes):
                path = os.path.join(scratch, f"big{n}.stp")
                text = stepnc_bigfile.explicit_toolpath_file(megabytes)
                with open(path, "w", encoding="utf-8") as out:
                    out.write(text)
                size_mb = len(text.encode()) / 1e6
                started = time.process_time()
                part21.parse_part21(text)
                parse_s = time.process_time() - started
                del text
                seconds, peak, nc = _batch_child(ROOT, path, os.path.join(scratch, f"out{n}"))
                points.append((size_mb, seconds))
                row = {"name": f"stepnc: batch {size_mb:.0f} MB explicit toolpaths end to end", "seconds": seconds,
                       "target_s": 2 * parse_s, "notes": f"{seconds / parse_s:.1f}x the parse ({parse_s:.1f} s CPU); "
                                                         f"peak {peak:.0f} MB RSS"}
                if made and n == len(sizes) - 1:
                    before, before_peak, old_nc = _batch_child(base_tree, path, os.path.join(scratch, "base-out"))
                    rows.append({"name": f"stepnc: batch {size_mb:.0f} MB explicit toolpaths end to end, base {base}",
                                 "seconds": before, "target_s": None,
                                 "notes": f"{before / parse_s:.1f}x the parse; peak {before_peak:.0f} MB RSS"})
                    row["notes"] += (f"; {before / seconds:.1f}x less CPU than {base}, peak {before_peak:.0f} MB "
                                     f"there; NC text {'identical' if old_nc == nc else 'DIFFERS'}")
                rows.append(row)
        finally:
            if made:
                subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", base_tree], capture_output=True)
    if len(points) > 1:
        x, y = np.log([p[0] for p in points]), np.log([p[1] for p in points])
        rows[-1]["notes"] += f"; CPU ~ size^{np.polyfit(x, y, 1)[0]:.2f} over {len(points)} sizes"
    return rows


def run():
    from kezuri.toolpath.operations import stepnc
    rows = explicit_rows() + end_to_end_rows()
    text = large_file()
    size_mb = len(text.encode()) / 1e6
    started = time.perf_counter()
    stepnc.parse_part21(text)
    parse_s = time.perf_counter() - started
    rows.append({"name": f"stepnc: parse a {size_mb:.1f} MB Part 21 file", "seconds": parse_s,
                 "notes": f"{size_mb / parse_s:.1f} MB/s"})
    if os.path.isfile(EX1):
        # warm-up: the first conversion loads the in-process stock's compiled kernel (about 0.26 s
        # here against 0.015 s a conversion), which a mean of 5 would spread over the rows' figure
        stepnc.to_program(stepnc.load_workplan(EX1))
        started = time.perf_counter()
        for _ in range(5):
            stepnc.to_program(stepnc.load_workplan(EX1))
        rows.append({"name": "stepnc: ex1.stp read + converted", "seconds": (time.perf_counter() - started) / 5,
                     "notes": "mean of 5, after a warm-up conversion (the compiled kernels loaded)"})
    return rows
