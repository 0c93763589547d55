"""The punching simulation of this tree against another commit's, side by side in one session.

    nice .venv/bin/python bench/punch_against.py 495f8bd [PIECES ...]      (default 15 60 120)

The other commit is checked out into a temporary ``git worktree`` (removed at the end); each side
punches bench_punch's elbow (400 mm pipe, this tree's programs) in a child process of its own,
best CPU of 3, and the results are compared piece by piece: hits, pieces, joints held, gouge
lines, the largest difference of scallop and of areas."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

CHILD = r"""
import json, sys, time
root, bench, pieces = sys.argv[1], sys.argv[2], int(sys.argv[3])
sys.path.insert(0, root)
from batch import import_package
import_package()
sys.path.insert(0, bench)
from bench_punch import elbow_programs
from kezuri.toolpath.operations.sheetmetal import punch
programs = elbow_programs(pieces=pieces)
best = None
for _ in range(3):
    started, out = time.process_time(), []
    for text, outline, joints in programs:
        r = punch.simulate_punching(text, punch_diameter=10.0, pattern=outline, joints=joints)
        out.append([r.hits, r.pieces, r.held_by_joints, [g.line for g in r.gouges], r.max_scallop_mm,
                    r.part_area_mm2, r.removed_area_mm2])
    cpu = time.process_time() - started
    best = cpu if best is None else min(best, cpu)
print(json.dumps({"cpu_s": best, "results": out}))
"""


def punched(root: str, pieces: int) -> dict:
    done = subprocess.run([sys.executable, "-c", CHILD, root, HERE, str(pieces)], capture_output=True, text=True,
                          cwd=root)
    if done.returncode:
        raise RuntimeError(done.stderr[-3000:])
    return json.loads(done.stdout.strip().splitlines()[-1])


def main(argv: list) -> int:
    commit, pieces = argv[0], [int(p) for p in argv[1:]] or [15, 60, 120]
    other = os.path.join(tempfile.mkdtemp(prefix="kezuri-against-"), "tree")
    subprocess.run(["git", "worktree", "add", "--detach", other, commit], cwd=ROOT, check=True, capture_output=True)
    try:
        print(f"load {os.getloadavg()[0]:.1f}")
        for n in pieces:
            before, now = punched(other, n), punched(ROOT, n)
            pairs = list(zip(before["results"], now["results"]))
            same = all(a[:4] == b[:4] for a, b in pairs)
            scallop = max(abs((a[4] or 0.0) - (b[4] or 0.0)) for a, b in pairs)
            areas = max(max(abs(a[5] - b[5]) / a[5], abs(a[6] - b[6]) / a[6]) for a, b in pairs)
            print(f"{n} pieces: {commit} {before['cpu_s']:.2f} s CPU, this tree {now['cpu_s']:.2f} s; hits, pieces, "
                  f"joints and gouge lines equal: {same}; scallops differ by {scallop:.1e} mm, areas by {areas:.1e}")
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", other], cwd=ROOT, capture_output=True)
        shutil.rmtree(os.path.dirname(other), ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
