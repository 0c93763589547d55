"""Run every benchmark (bench/bench_*.py), print a table and write JSON.

    .venv/bin/python bench/run.py [--json bench/results.json] [--only NAME]

Each module exposes ``run() -> list[dict]`` with keys name, seconds, target_s (or None), notes.
Speed targets live here, never in unit tests.
"""
from __future__ import annotations

import argparse
import glob
import importlib
import json
import os
import platform
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--json", default=os.path.join(HERE, "results.json"))
    parser.add_argument("--only", help="run only bench_<ONLY>.py")
    args = parser.parse_args()
    sys.path.insert(0, ROOT)
    from batch import import_package
    import_package()
    sys.path.insert(0, HERE)
    rows = []
    for path in sorted(glob.glob(os.path.join(HERE, "bench_*.py"))):
        name = os.path.basename(path)[len("bench_"):-3]
        if args.only and name != args.only:
            continue
        module = importlib.import_module(f"bench_{name}")
        for row in module.run():
            row.setdefault("target_s", None)
            row.setdefault("notes", "")
            row["ok"] = row["target_s"] is None or row["seconds"] <= row["target_s"]
            rows.append(row)
    width = max(len(r["name"]) for r in rows) if rows else 10
    print(f"{'benchmark':<{width}}  {'seconds':>9}  {'target':>8}  ok   notes")
    for r in rows:
        target = f"{r['target_s']:.2f}" if r["target_s"] is not None else "-"
        print(f"{r['name']:<{width}}  {r['seconds']:9.3f}  {target:>8}  {'yes' if r['ok'] else 'NO ':<4} {r['notes']}")
    with open(args.json, "w") as stream:
        json.dump({"machine": {"python": platform.python_version(), "cpus": os.cpu_count(),
                               "processor": platform.processor() or platform.machine()},
                   "results": rows}, stream, indent=2)
    print(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
