"""W3: Part 21 parse speed on a large generated file, and the conversion of ISO 14649 Example 1."""
from __future__ import annotations

import os
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


def run():
    from kezuri.toolpath.operations import stepnc
    rows = explicit_rows()
    text = large_file()
    size_mb = len(text.encode()) / 1e6
    started = time.perf_counter()
    stepnc.parse_part21(text)
    parse_s = time.perf_counter() - started
    rows.append({"name": f"stepnc: parse a {size_mb:.1f} MB Part 21 file", "seconds": parse_s,
                 "notes": f"{size_mb / parse_s:.1f} MB/s"})
    if os.path.isfile(EX1):
        started = time.perf_counter()
        for _ in range(5):
            stepnc.to_program(stepnc.load_workplan(EX1))
        rows.append({"name": "stepnc: ex1.stp read + converted", "seconds": (time.perf_counter() - started) / 5,
                     "notes": "mean of 5"})
    return rows
