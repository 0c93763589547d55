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


def run():
    from kezuri.toolpath.operations import stepnc
    text = large_file()
    size_mb = len(text.encode()) / 1e6
    started = time.perf_counter()
    stepnc.parse_part21(text)
    parse_s = time.perf_counter() - started
    rows = [{"name": f"stepnc: parse a {size_mb:.1f} MB Part 21 file", "seconds": parse_s,
             "notes": f"{size_mb / parse_s:.1f} MB/s"}]
    if os.path.isfile(EX1):
        started = time.perf_counter()
        for _ in range(5):
            stepnc.to_program(stepnc.load_workplan(EX1))
        rows.append({"name": "stepnc: ex1.stp read + converted", "seconds": (time.perf_counter() - started) / 5,
                     "notes": "mean of 5"})
    return rows
