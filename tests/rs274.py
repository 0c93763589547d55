"""LinuxCNC's standalone interpreter ``rs274`` as the independent judge of our G-code.

``run(text)`` feeds a program to ``rs274 -g`` and returns its canonical machining calls; a
program rs274 rejects raises ``AssertionError`` with what it printed.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile

import numpy as np

RS274 = shutil.which("rs274")
CALL = re.compile(r"^\s*\d+\s+N\.+\s+([A-Z_]+)\((.*)\)\s*$")


def available() -> bool:
    return RS274 is not None


def run(text: str, tools=()) -> list:
    """Canonical calls as (name, [numbers or words]) in program order.  ``tools``: tool numbers for a
    tool table of our own (rs274 -t; its built-in table knows T1..T3 only), as a machine would have."""
    with tempfile.TemporaryDirectory() as folder:
        source = os.path.join(folder, "in.ngc")
        output = os.path.join(folder, "out.txt")
        with open(source, "w") as stream:
            stream.write(text)
        table = []
        if tools:
            table = ["-t", os.path.join(folder, "tool.tbl")]
            with open(table[1], "w") as stream:
                stream.write("".join(f"T{int(t)} P{int(t)} Z0 D10 ;\n" for t in sorted(set(tools))))
        # rs274 keeps its tool table in $HOME/.tool.mmap (created and truncated at every start):
        # a home of its own, so two runs at once (tests side by side) cannot share it
        done = subprocess.run([RS274, *table, "-g", source, output], stdin=subprocess.DEVNULL, capture_output=True,
                              text=True, timeout=120, env=dict(os.environ, HOME=folder))
        printed = done.stdout + done.stderr
        canon = open(output).read() if os.path.exists(output) else ""
    if done.returncode != 0 or re.search(r"error", printed + canon, re.IGNORECASE):
        raise AssertionError(f"rs274 rejected the program (exit {done.returncode}):\n{printed[-2000:]}\n"
                             f"{canon[-1000:]}")
    calls = []
    for line in canon.splitlines():
        match = CALL.match(line)
        if match:
            args = [a.strip() for a in match.group(2).split(",")] if match.group(2).strip() else []
            calls.append((match.group(1), args))
    return calls


def motion_endpoints(calls) -> tuple:
    """(kinds, points (n, 3), rotary (n, 3) a/b/c) of every STRAIGHT_TRAVERSE/STRAIGHT_FEED/ARC_FEED.

    ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end, a, b, c[, u, v, w])
    in the XY plane: the end point is (first_end, second_end, axis_end).
    """
    kinds, points, rotary = [], [], []
    for name, args in calls:
        if name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            values = [float(a) for a in args]
            kinds.append("rapid" if name == "STRAIGHT_TRAVERSE" else "feed")
            points.append(values[:3])
            rotary.append(values[3:6])
        elif name == "ARC_FEED":
            values = [float(a) for a in args]
            kinds.append("cw" if values[4] < 0 else "ccw")
            points.append([values[0], values[1], values[5]])
            rotary.append(values[6:9])
    return kinds, np.array(points, float).reshape(-1, 3), np.array(rotary, float).reshape(-1, 3)
