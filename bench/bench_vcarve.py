"""V-carve: the sample sign's 20 characters (samples/jobs/vcarve-sign.toml: "Kezuri Workshop" in
Blender's font, "削り工房 欅 鬱" in its bundled Noto Sans CJK) planned by the core with a 60 deg
V-bit, once without a depth limit and once at 2 mm max depth with a 1 mm end mill clearing the
flat (the pocket planner); the outlines are laid out by Blender once, outside the timing.  CPU
seconds (time.process_time), best of 3.

FreeCAD side by side: Debian's FreeCAD (0.20.2, ``apt-get install freecad``, a few minutes here)
has the CAM (Path) workbench's V-carve, built on the same Boost.Polygon Voronoi.  Where
``freecadcmd`` is installed the last row times its path step on the same faces, headless
(:mod:`freecad_vcarve`); where not, the row says so.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import time

from timing import best_of

LATIN = ("Kezuri Workshop", None, 28.0)
KANJI = ("削り工房 欅 鬱", "Noto Sans CJK Regular.woff2", 60.0)


def sign_loops() -> list:
    import bpy  # noqa: F401  (Blender lays the text out)

    from kezuri.operators import vcarve as shell

    found = []
    for body, font, size in (LATIN, KANJI):
        spec = shell.text_spec({"body": body, "size": size, **({"font": font} if font else {})}, "bench")
        found.append(shell.text_loops(spec, ".", "bench"))
    return found


def cpu_best_of(repeats: int, work) -> float:
    return best_of(repeats, work, time.process_time)


def run() -> list:
    from kezuri.toolpath.engines import region as rg
    from kezuri.toolpath.operations.pocket import pocket
    from kezuri.toolpath.operations.vcarve import vcarve

    latin, kanji = sign_loops()
    characters = sum(1 for c in LATIN[0] + KANJI[0] if not c.isspace())
    segments = sum(len(loop) for loop in latin + kanji)
    rows = []
    cases = (("no depth limit", vcarve.VCarveSettings(tool=vcarve.vbit(3, 60.0, 25.4, flute_length=25.0))),
             ("2 mm max depth + 1 mm end mill", vcarve.VCarveSettings(max_depth=2.0,
                                                                        clear_tool=pocket.end_mill(4, 1.0))))
    for label, settings in cases:
        def work():
            return [vcarve.plan(latin, settings, name="latin"), vcarve.plan(kanji, settings, name="kanji")]
        results = work()
        moves = sum(len(op) for result in results for op in result.operations)
        seconds = cpu_best_of(3, work)
        rows.append({"name": f"vcarve: {characters}-character sign (Latin + kanji), {label}", "seconds": seconds,
                     "target_s": 2.0, "notes": f"{segments} outline segments, {moves} moves; CPU s, best of 3"})
    groups = [[loop.tolist() for loop in rg.loops(part)] for loops in (latin, kanji)
              for part in rg.components(rg.from_loops(loops), 0.0)]
    rows.append(freecad_row(groups))
    return rows


def freecad_row(groups) -> dict:
    """FreeCAD's V-carve path step (:mod:`freecad_vcarve`) on the same faces, or why it cannot run."""
    import json
    import tempfile

    command = shutil.which("freecadcmd") or shutil.which("FreeCADCmd")
    name = "vcarve: FreeCAD 0.20 V-carve (buildPathMedial), same sign"
    if command is None:
        return {"name": name, "seconds": float("nan"), "target_s": None,
                "notes": "not run: FreeCAD is not installed (apt-get install freecad)"}
    with tempfile.TemporaryDirectory() as folder:
        given, taken = os.path.join(folder, "in.json"), os.path.join(folder, "out.json")
        with open(given, "w") as stream:
            json.dump({"groups": groups}, stream)
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "freecad_vcarve.py")
        done = subprocess.run([command, script], capture_output=True, text=True, timeout=900,
                              env=dict(os.environ, KEZURI_VCARVE_IN=given, KEZURI_VCARVE_OUT=taken))
        if not os.path.exists(taken):
            return {"name": name, "seconds": float("nan"), "target_s": None,
                    "notes": f"not run: freecadcmd failed ({(done.stdout + done.stderr).strip()[-120:]})"}
        found = json.load(open(taken))
    return {"name": name, "seconds": found["seconds"], "target_s": None,
            "notes": f"FreeCAD {'.'.join(found['version'])} headless, {found['faces']} faces, {found['commands']} "
                     "path commands; CPU s, best of 3 (no depth limit: FreeCAD clamps at FinalDepth, clears no flat)"}
