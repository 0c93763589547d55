"""W2: the three sample pockets of the bento block with P = 1 mm and alpha = 1 mm (core only)."""
from __future__ import annotations

from timing import best_of



def run():
    from kezuri.toolpath.operations.rotary import rotary

    block, pockets = rotary.sample_job()
    settings = rotary.RotarySettings(spacing=1.0, stepover=1.0)
    result = rotary.plan(block, pockets, settings)
    best = best_of(5, lambda: rotary.plan(block, pockets, settings))
    points = sum(r["points"] for r in result.reports)
    return [{"name": "rotary: three sample pockets, P = alpha = 1 mm", "seconds": best, "target_s": 0.25,
             "notes": f"{points} points; the paper's VB2008 program took 25 s"}]
