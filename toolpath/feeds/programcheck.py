"""The check before export: each operation of a planned program, its spindle speed and cutting feed
against its tool and the job's material (:func:`.calculator.check`).

An operation's cutting feed is the feed that carries the most of its cutting length (its plunges
and links at other feeds are not its chip load); its fastest feed is checked for overload too.  A
tool's flutes and material come from ``known`` (the user's tool library, matched by the shell on
number, kind and diameter); a tool not found there is taken as a 2-flute carbide router bit, as
the charts' are, and the entry says it was assumed.
"""
from __future__ import annotations

import numpy as np

from . import calculator, materials

CUTTING = (1, 2, 3)     # FEED, ARC_CW, ARC_CCW move kinds (toolpath.ir.program)


def cutting_feeds(op) -> tuple:
    """(the feed carrying the most cutting length, the fastest feed) of an IR operation, mm/min;
    (None, None) when it has no cutting move with a feed."""
    kinds = np.asarray(op.kind)
    feeds = np.asarray(op.feed, float)
    xyz = np.asarray(op.xyz, float)
    if len(kinds) == 0:
        return None, None
    start = np.asarray(op.start if op.start is not None else xyz[0], float)
    before = np.vstack([start[None, :], xyz[:-1]])
    lengths = np.linalg.norm(xyz - before, axis=1)
    mask = np.isin(kinds, CUTTING) & np.isfinite(feeds) & (feeds > 0)
    if not mask.any():
        return None, None
    by_feed = {}
    for value, length in zip(feeds[mask], lengths[mask]):
        by_feed[float(value)] = by_feed.get(float(value), 0.0) + float(length)
    main = max(by_feed, key=lambda f: (by_feed[f], f))
    return main, max(by_feed)


def check_program(operations, material: str, machine=None, tool_material: str = "carbide",
                  known: dict | None = None) -> list:
    """One entry per operation (report.json's ``feeds``): its tool, rpm, cutting feed, the chip
    load they give, the band and the flags.  ``material``: a key of :data:`materials.MATERIALS`;
    ``known``: {tool number: (flutes, tool material)} for the tools whose make is known."""
    m = materials.material(material)
    entries = []
    for op in getattr(operations, "operations", operations):
        tool = op.tool
        flutes, given_material = (known or {}).get(tool.number, (None, None))
        t_material = given_material or tool_material
        entry = {"operation": op.name, "tool": tool.describe(), "tool_number": tool.number, "material": m.key}
        main, fastest = cutting_feeds(op)
        rpm = float(op.spindle_rpm or 0.0)
        if main is None or rpm <= 0:
            entry.update({"checked": False, "why": "no cutting move with a feed, or no spindle speed"})
            entries.append(entry)
            continue
        kind = tool.kind if tool.kind in calculator.TOOL_KINDS else "flat"
        found = calculator.check(kind, tool.diameter, m, rpm, main, flutes, t_material, machine)
        flags = list(found.flags)
        if fastest > main:
            extra = calculator.flags_for(rpm, fastest, calculator.teeth(kind, found.flutes), *found.band, None,
                                         found.per)
            flags += [f for f in extra if f.kind == "overload"]
        entry.update({"checked": True, "spindle_rpm": rpm, "feed_mm_min": main, "fastest_feed_mm_min": fastest,
                      "flutes": found.flutes, "tool_material": found.tool_material,
                      "assumed": [name for name, given in (("flutes", flutes), ("tool material", given_material))
                                  if given is None],
                      "chip_load_mm": round(found.chip_load, 4), "chip_load_per": found.per, "band_mm": [round(v, 4) for v in found.band],
                      "flags": [f.as_dict() for f in flags], "notes": list(found.notes),
                      "source": found.sources["chip_load"]})
        entries.append(entry)
    return entries


def warnings(entries: list) -> list:
    """One line per flag: "feeds: operation 'x' (T2 6 mm ball end mill) in hardwood: <flag>"."""
    return [f"feeds: operation {e['operation']!r} ({e['tool']}) in {e['material']}: {flag['message']}"
            for e in entries for flag in e.get("flags", ())]


def chip_loads(entries: list) -> dict:
    """{tool number: [chip loads (mm) it runs at]} for the setup sheet."""
    found = {}
    for e in entries:
        if e.get("checked"):
            found.setdefault(e["tool_number"], []).append(e["chip_load_mm"])
    return found
