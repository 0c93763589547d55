"""Arcs out (issue 29, target: curved-profile programs >= 3x smaller in bytes): the name plate's
curved profiles (its band finishing and burr contour round the letters of the built-in sample,
taken from Blender once) written by each milling post with and without arcs, side by side in one
run; the whole engraving (its gouge raster is straight lines, unchanged) for scale; and a
circle-heavy profile (30 round holes and 10 rounded slots cut out of a sign, their outlines
flattened by Clipper's offsets at the planners' 0.01 mm, as a profile or pocket pass makes them)."""
from __future__ import annotations

import time

TARGET_RATIO = 3.0


def circle_heavy():
    """A profile pass round 30 holes and 10 rounded slots: each outline a Clipper offset (round
    joins at the planners' 0.01 mm chord error), plunged into and cut once at Z -3."""
    import numpy as np

    from kezuri.toolpath.engines import region
    from kezuri.toolpath.ir.program import Operation, PathBuilder, Program, Tool

    rng = np.random.default_rng(29)
    loops = []
    for k in range(30):
        centre = np.array([20 + (k % 10) * 40, 20 + (k // 10) * 40], float)
        seed = centre + 0.01 * np.array([[0, 0], [1, 0], [0, 1]], float)
        grown = region.offset(region.from_loops([seed], "hole"), float(rng.uniform(3, 15)))
        loops += [np.asarray(p) for p in grown.to_polygons()]
    for k in range(10):
        x, y = 20 + k * 40, 150
        slot = np.array([[x, y], [x + 20, y], [x + 20, y + 1], [x, y + 1]], float)
        grown = region.offset(region.from_loops([slot], "slot"), float(rng.uniform(2, 6)))
        loops += [np.asarray(p) for p in grown.to_polygons()]
    path = PathBuilder(clearance_z=5.0, feed=1200.0, plunge_feed=300.0)
    for loop in loops:
        path.plunge(loop[0, 0], loop[0, 1], -3.0)
        ring = np.vstack([loop[1:], loop[:1]])
        path.polyline(np.column_stack([ring, np.full(len(ring), -3.0)]))
    path.retract()
    arrays = path.arrays()
    op = Operation("profile", Tool(1, "flat", 3.0), 18000, arrays["kind"], arrays["xyz"], arrays["feed"],
                   clearance_z=5.0, safe_z=5.0)
    return Program("circles", [op])


def run():
    from bench_engrave import sample_inputs

    from kezuri import post as posts
    from kezuri.toolpath.ir.program import Program
    from kezuri.toolpath.operations.engrave import engrave

    plate, letters = sample_inputs()
    baked = engrave.bake(engrave.plan(plate, letters).program)[0]
    profiles = Program("profiles", [op for op in baked.operations if op.name in ("band finishing", "burr contour")])
    rows = []
    circles = circle_heavy()
    for name in ("linuxcnc", "fanuc", "grbl"):
        made = posts.create("milling", name)
        plain = posts.create("milling", name, machine=made.machine.replace(arcs=False))
        for what, program in (("curved profiles", profiles), ("whole engraving", baked),
                              ("circle-heavy profile", circles)):
            started = time.perf_counter()
            fitted = made.to_text(program)
            seconds = time.perf_counter() - started
            unfitted = plain.to_text(program)
            ratio = len(unfitted) / len(fitted)
            target = f", target >= {TARGET_RATIO:g}x: {'met' if ratio >= TARGET_RATIO else 'NOT met'}" \
                if what != "whole engraving" else ""
            rows.append({"name": f"arcs: {name} {what}, posted with arcs", "seconds": seconds,
                         "notes": f"{len(unfitted):,} -> {len(fitted):,} bytes, {ratio:.2f}x smaller, "
                                  f"{fitted.count('G02') + fitted.count('G03'):,} arcs{target}",
                         "bytes_without_arcs": len(unfitted), "bytes_with_arcs": len(fitted),
                         "ratio": round(ratio, 3)})
    return rows
