"""What every number of the panel and of batch may be: one table of ranges that mean something.

Blender clamps a property to its hard ``min``/``max`` without a word, so a value set from Python
(``bpy.ops``, a script, a .blend written elsewhere) or a batch argument would silently become
another job.  So the scene properties carry no hard limits for these numbers, only soft ones
(the UI slider, taken from this table by ``properties.py``), and every reader of the settings
checks the values against :data:`RANGES` before any work (:func:`check_group`); batch's numeric
options take their ranges from here too (``batchio.number(limit=...)``).  Nothing here imports
Blender, so batch and the tests read the same table.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..toolpath.ir.errors import MAX_REACH_MM, InputError

FLOAT_MAX = 3.4028234663852886e+38     # what Blender stores for inf: not a number anyone gave


@dataclass(frozen=True)
class Range:
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False          # lo itself is not allowed
    integer: bool = False
    unit: str = ""

    def allows(self, value) -> bool:
        value = float(value)
        if not math.isfinite(value) or abs(value) >= FLOAT_MAX:
            return False
        # Blender stores floats in single precision: 0.01 reads back as 0.0099999998
        slack = 0.0 if self.integer else 1e-6
        if self.lo is not None:
            lo = self.lo - slack * max(1.0, abs(self.lo))
            if value < lo or (self.lo_open and value <= self.lo):
                return False
        if self.hi is not None and value > self.hi + slack * max(1.0, abs(self.hi)):
            return False
        return True

    def text(self, name: str) -> str:
        """``0.1 <= Ball Diameter <= 100 mm``, ``Pitch >= 0.1 mm``."""
        unit = f" {self.unit}" if self.unit else ""
        if self.hi is None and self.lo is not None:
            return f"{name} {'>' if self.lo_open else '>='} {self.lo:g}{unit}"
        low = "" if self.lo is None else (f"{self.lo:g} <" if self.lo_open else f"{self.lo:g} <=")
        high = "" if self.hi is None else f"<= {self.hi:g}"
        return " ".join(part for part in (low, name, high) if part) + unit


def mm(lo=None, hi=None, lo_open=False) -> Range:
    return Range(lo, hi, lo_open, unit="mm")


def feed(lo=0.0) -> Range:
    return Range(lo, 100000.0, lo_open=lo == 0.0, unit="mm/min")


def rpm(lo=0.0) -> Range:
    return Range(lo, 100000.0, lo_open=lo == 0.0, unit="rpm")


def degrees(lo, hi) -> Range:
    return Range(lo, hi, unit="degrees")


TOOL_NUMBER = Range(0, 999, integer=True)
# A round turret punch: from the smallest made for a turret to the largest station of a thick
# turret (E station, 4-1/2 in = 114.3 mm); sheets up to 1/2 in (a thick turret punches 1/4 in).
PUNCH_DIAMETER = mm(0.5, 114.3)
DIAMETER = mm(0.1, 100.0)
HEIGHT = mm(0.0, 1000.0)

# group (the attribute of scene.kezuri, or "pocket" for an object's rotary pocket) -> property -> range
RANGES: dict = {
    "machine": {"rapid_rate": Range(1.0, 200000.0, unit="mm/min"), "travel_x": mm(0.0, MAX_REACH_MM),
                "travel_y": mm(0.0, MAX_REACH_MM), "travel_z": mm(0.0, MAX_REACH_MM),
                "z_reach": mm(0.0, MAX_REACH_MM, lo_open=True), "clearance_height": mm(0.0, MAX_REACH_MM, lo_open=True),
                "machine_top_z": mm(-MAX_REACH_MM, MAX_REACH_MM), "max_spindle": rpm(), "max_feed": feed()},
    "engrave": {
        "rough_diameter": DIAMETER, "rough_tool_number": TOOL_NUMBER, "stepover": mm(0.0, 100.0, lo_open=True),
        "raster_angle": degrees(-180.0, 180.0), "letter_clearance": mm(0.0, 100.0),
        "base_depth": mm(-100.0, 0.0), "quantum": mm(0.001, 10.0), "amplitude": mm(0.0, 50.0),
        "spacing": mm(0.1, 1000.0), "spacing_jitter": Range(0.0, 0.5), "seed": Range(0, 2**31 - 1, integer=True),
        "finish_diameter": mm(0.05, 100.0), "finish_tool_number": TOOL_NUMBER, "band_width": mm(0.0, 100.0),
        "band_depth": mm(-100.0, 0.0), "band_stepover": mm(0.0, 100.0, lo_open=True),
        "band_step_down": mm(0.0, 100.0, lo_open=True), "band_ramp_angle": Range(0.0, 45.0, lo_open=True,
                                                                                 unit="degrees"),
        "rough_rpm": rpm(), "finish_rpm": rpm(), "rough_feed": feed(), "finish_feed": feed(),
        "plunge_feed": feed(), "clearance_z": HEIGHT, "safe_z": HEIGHT,
    },
    "sheet": {
        "corners": mm(-MAX_REACH_MM, MAX_REACH_MM),
        "divisions": Range(1, 500, integer=True), "tool_diameter": PUNCH_DIAMETER, "thickness": mm(0.01, 12.7),
        "pitch": mm(0.1), "station": Range(1, 999, integer=True),
        "elbow_diameter": mm(0.1), "elbow_radius": mm(0.1), "elbow_angle": degrees(1.0, 180.0),
        "elbow_pieces": Range(2, 60, integer=True),
        "sheet_origin": mm(-9999.99, 9999.99), "sheet_size": mm(10.0, 9999.99), "clamp_width": mm(1.0, 1000.0),
        "clamp_depth": mm(1.0, 1000.0), "joints": Range(0, 8, integer=True), "joint_width": mm(0.05, 5.0),
    },
    "pocket": {"depth": mm(0.01, 1000.0), "wall_angle": degrees(0.0, 75.0), "sphere_radius": mm(0.1, 10000.0)},
    "rotary": {
        "tool_diameter": DIAMETER, "tool_number": TOOL_NUMBER, "flute_length": mm(0.1, 500.0),
        "spindle_rpm": rpm(), "cutting_speed": feed(1.0), "plunge_speed": feed(1.0),
        "spacing": mm(0.01, 100.0), "stepover": mm(0.01, 100.0), "step_down": mm(0.01, 100.0),
        "allowance": mm(0.0, 50.0), "wall_stepover": mm(0.01, 100.0),
        "max_table_rpm": Range(0.1, 1000.0, unit="rpm"),
    },
    "stepnc": {"tool_diameter": DIAMETER, "tool_number": TOOL_NUMBER, "flute_length": mm(0.1, 500.0),
               "feed": feed(1.0), "spindle_rpm": rpm(1.0)},
    "turnmill": {
        "stock_radius": mm(0.1, 1000.0), "stock_z_min": mm(-10000.0, 10000.0), "stock_z_max": mm(-10000.0, 10000.0),
        "tool_diameter": DIAMETER, "tolerance": mm(0.0001, 1.0), "sample_spacing": mm(0.01, 100.0),
        "feed": feed(1.0), "spindle_rpm": rpm(1.0),
    },
    "carve": {
        "stock_above": mm(0.0, 1000.0), "rough_diameter": DIAMETER, "rough_tool_number": TOOL_NUMBER,
        "allowance": mm(0.0, 50.0), "step_down": mm(0.01, 100.0), "rough_stepover": mm(0.01, 100.0),
        "finish_diameter": DIAMETER, "finish_tool_number": TOOL_NUMBER, "scallop": mm(0.0001),
        "raster_angle": degrees(-180.0, 180.0), "max_slope": degrees(0.0, 89.0),
        "sample_spacing": mm(0.01, 100.0), "rough_rpm": rpm(1.0), "finish_rpm": rpm(1.0),
        "rough_feed": feed(1.0), "finish_feed": feed(1.0), "plunge_feed": feed(1.0),
        "clearance": mm(0.1, 1000.0), "safe_z": mm(0.1, 1000.0),
    },
    "simulation": {"cell": mm(0.0, lo_open=True)},
}

# A tool's ranges: the soft limits of the preferences' old tool list (oldtools) and an NC file's tools.
LIBRARY = {"number": TOOL_NUMBER, "diameter": DIAMETER, "corner_radius": mm(0.0, 50.0),
           "flute_length": mm(0.1, 1000.0)}

# What a group is called in a message (the panel it is set in).
GROUP_NAMES = {"machine": "Machine & Stock", "engrave": "Engrave", "sheet": "Sheet Metal", "pocket": "Rotary Pocket",
               "rotary": "Rotary Pockets", "stepnc": "STEP-NC Workplan", "turnmill": "Turn-Mill", "carve": "Carve",
               "simulation": "Simulate & Check"}     # as the panels are named


def soft_limits(limit: Range) -> dict:
    """The keywords a property definition gets from its range: soft limits only (the UI slider);
    a hard limit would clamp a bad value into a good one before anyone could refuse it."""
    keywords = {}
    if limit.lo is not None:
        keywords["soft_min"] = int(limit.lo) if limit.integer else float(limit.lo)
    if limit.hi is not None:
        keywords["soft_max"] = int(limit.hi) if limit.integer else float(limit.hi)
    return keywords


def problem(group: str, name: str, label: str, value, where: str = "", limit: Range | None = None) -> str | None:
    """The message refusing ``value`` of property ``name`` (shown as ``label``), or None if allowed
    (``limit``: a range not in :data:`RANGES`, e.g. of :data:`LIBRARY`)."""
    limit = limit or RANGES[group][name]
    values = list(value) if isinstance(value, (list, tuple)) else [value]
    for index, item in enumerate(values):
        if limit.allows(item):
            continue
        shown = label if len(values) == 1 else f"{label} [{index + 1}]"
        place = where or GROUP_NAMES[group]
        given = math.copysign(math.inf, item) if abs(item) >= FLOAT_MAX else item    # Blender holds inf so
        return f"{place}: {shown} = {given:g} is outside the allowed range {limit.text(shown)}"
    return None


class SettingError(InputError):
    """A setting outside the range that means something (named, with its value and the range)."""


def check_group(props, group: str, names=None, where: str = "") -> None:
    """Refuse the first value of the property group ``props`` (``scene.kezuri.<group>``, an
    operator with the same properties, or an object's pocket) outside its range in :data:`RANGES`;
    ``names``: only these of its properties (default: all the group's numbers)."""
    for name in (RANGES[group] if names is None else [n for n in names if n in RANGES[group]]):
        rna = getattr(getattr(props, "properties", props), "bl_rna", None)     # an operator's are .properties
        prop = rna.properties.get(name) if rna is not None else None
        label = prop.name if prop is not None else name
        value = getattr(props, name)
        message = problem(group, name, label, tuple(value) if hasattr(value, "__len__") else value, where)
        if message:
            raise SettingError(message)
