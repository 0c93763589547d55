"""The machine profile: what the machine a program runs on can do, chosen once per job.

A post knows the *control* (its words, ranges and sequences: :class:`post.registry.ControllerLimits`);
the profile knows the *machine* that control drives: how far each axis travels, how high the tool
can be lifted above the work zero, how a tool gets into the spindle (a changer, or the operator at
an ``M00`` pause), what ``M06`` does on its own, the fastest spindle and feed, and for a control
that stores its programs, how much memory it has and how short a block it can process in time.
Posts write their program frames from it (where the tool goes before XY moves after a start or a
tool load), the export gate checks every move against it, and the report says what it assumed.

A turret punch's profile also says where the sheet sits: the program origin the control is given
(``G92``), and where the clamps hold the sheet, with the dead zone around each where no hit may fall.

Every length is in millimetres, every feed in mm/min.  Profiles are immutable values; a user's
profile is a preset with fields replaced (:meth:`MachineProfile.replace`), checked by
:meth:`MachineProfile.validate` like the IR's :meth:`~.program.Operation.validate`.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError

# How the frames lift Z before XY moves (at the start, after a tool load and at the end):
#   "reference"  the control's reference-position return in machine coordinates (Fanuc G91 G28 Z0.)
#   "machine"    a rapid to a machine-coordinate Z (G53 G00 Z<machine_top_z>; needs a homed machine)
#   "clearance"  a rapid to the clearance height above the work zero (G00 Z<clearance_z>), for
#                machines that are not homed (most hobby routers)
RETRACTS = ("reference", "machine", "clearance")
# How a tool gets into the spindle: "atc" a changer (M06), "manual" the operator at a pause (M00, or
# an M06 that stops and asks).
TOOL_CHANGES = ("atc", "manual")
FAMILIES = ("milling", "cxz", "xzc", "punch")


class MachineError(InputError):
    """A machine profile that cannot describe a machine, or a program the machine cannot run."""


@dataclass(frozen=True)
class Clamp:
    """A clamp holding the sheet on a turret punch: its centre along the sheet's clamped edge (X,
    from the sheet origin) and the dead zone around it where no hit may fall (width along X,
    depth into the sheet along Y)."""

    x: float
    width: float = 80.0
    depth: float = 50.0


@dataclass(frozen=True)
class MachineProfile:
    name: str                                  # key: what batch --machine and job files name
    label: str                                 # what the panel shows
    family: str                                # milling, cxz (rotary table), xzc (turn-mill), punch
    description: str = ""
    travel: tuple = (600.0, 600.0, 100.0)      # X, Y, Z travel (mm); an axis the machine lacks: 0
    clearance_max: float = 50.0                # highest Z above the work zero the tool reaches (mm)
    clearance_z: float = 20.0                  # the frames' safe height above the work zero (mm)
    retract: str = "clearance"                 # RETRACTS
    machine_top_z: float = 0.0                 # machine-coordinate Z of the top of travel ("machine")
    tool_change: str = "atc"                   # TOOL_CHANGES
    m6_retracts: bool = False                  # M06 lifts Z to the change position by itself
    max_spindle_rpm: float = 24000.0
    min_spindle_rpm: float = 0.0
    max_feed: float = 10000.0                  # mm/min, cutting
    rapid_rate: float = 5000.0                 # mm/min, for cycle-time estimates
    memory_kb: float | None = None             # program memory (kB); None: streamed, no limit
    block_ms: float | None = None              # shortest block processed at full speed (ms); None: any
    max_table_rpm: float | None = None         # rotary table / C axis (rev/min), where there is one
    # Turret punch: the sheet's origin as the control is told it (G92 X.. Y..) and the clamps on
    # the sheet's edge along X (Y = 0 of the sheet).
    sheet_origin: tuple | None = None
    clamps: tuple = ()
    sheet_max: tuple | None = None             # largest sheet (X, Y) the table holds (mm)
    sheet_margin: float = 10.0                 # skeleton kept between the part's hits and the sheet's
                                               # edges and the clamps' dead zones (mm)
    arcs: bool = True                          # milling posts write polylines that follow circles as G2/G3
                                               # arcs (toolpath.ir.arcfit); False: every move as planned
    source: str = ""                           # where the preset's numbers come from

    def __post_init__(self):
        self.validate()

    def replace(self, **changes) -> "MachineProfile":
        return dataclasses.replace(self, **changes)

    def validate(self) -> None:
        def bad(field, value, why):
            raise MachineError(f"machine profile {self.label or self.name!r}: {field} = {value!r} {why}")

        if self.family not in FAMILIES:
            bad("family", self.family, f"is not one of {', '.join(FAMILIES)}")
        if self.retract not in RETRACTS:
            bad("retract", self.retract, f"is not one of {', '.join(RETRACTS)}")
        if self.tool_change not in TOOL_CHANGES:
            bad("tool change", self.tool_change, f"is not one of {', '.join(TOOL_CHANGES)}")
        if len(self.travel) != 3 or not all(_finite(t) and t >= 0 for t in self.travel):
            bad("travel", self.travel, "must be three lengths >= 0 (X, Y, Z)")
        for field in ("clearance_max", "clearance_z", "max_spindle_rpm", "max_feed", "rapid_rate"):
            value = getattr(self, field)
            if not (_finite(value) and value > 0):
                bad(field.replace("_", " "), value, "must be a positive number")
        if not (_finite(self.min_spindle_rpm) and 0 <= self.min_spindle_rpm <= self.max_spindle_rpm):
            bad("min spindle rpm", self.min_spindle_rpm, f"must lie in 0..{self.max_spindle_rpm:g}")
        if self.clearance_z > self.clearance_max:
            bad("clearance z", self.clearance_z, f"is above the {self.clearance_max:g} mm the machine reaches "
                                                 "above the work zero")
        if self.travel[2] > 0 and self.clearance_max > self.travel[2]:
            bad("clearance max", self.clearance_max, f"is more than the {self.travel[2]:g} mm Z travel")
        if not _finite(self.machine_top_z):
            bad("machine top z", self.machine_top_z, "must be a number")
        for field in ("memory_kb", "block_ms", "max_table_rpm"):
            value = getattr(self, field)
            if value is not None and not (_finite(value) and value > 0):
                bad(field.replace("_", " "), value, "must be a positive number or unset")
        if self.sheet_origin is not None and (len(self.sheet_origin) != 2
                                              or not all(_finite(v) for v in self.sheet_origin)):
            bad("sheet origin", self.sheet_origin, "must be two numbers (X, Y)")
        if self.sheet_max is not None and (len(self.sheet_max) != 2
                                           or not all(_finite(v) and v > 0 for v in self.sheet_max)):
            bad("sheet max", self.sheet_max, "must be two positive lengths (X, Y)")
        if not isinstance(self.arcs, bool):
            bad("arcs", self.arcs, "must be true or false")
        if not (_finite(self.sheet_margin) and self.sheet_margin >= 0):
            bad("sheet margin", self.sheet_margin, "must be a length >= 0")
        for clamp in self.clamps:
            if not (isinstance(clamp, Clamp) and _finite(clamp.x) and _finite(clamp.width) and clamp.width > 0
                    and _finite(clamp.depth) and clamp.depth > 0):
                bad("clamps", clamp, "must be clamps with a position and a positive width and depth")

    def reach_problem(self, z: float, what: str) -> str | None:
        """Why a Z of ``z`` above the work zero (``what`` names it: "operation 'roughing': safe Z
        (the workflow's Safe Z)") cannot be written for this machine, or None if it can."""
        if z > self.clearance_max + 1e-9:
            return (f"{what} {z:g} mm is above the {self.clearance_max:g} mm the machine {self.label!r} reaches "
                    f"above the work zero (machine setting Z Reach); lower it or raise Z Reach if the machine "
                    f"really reaches it")
        return None

    def summary(self) -> dict:
        """The profile as report.json records it."""
        return {"name": self.name, "label": self.label, "family": self.family, "travel_mm": list(self.travel),
                "z_reach_mm": self.clearance_max, "clearance_height_mm": self.clearance_z, "retract": self.retract,
                "machine_top_z": self.machine_top_z, "tool_change": self.tool_change,
                "m6_retracts": self.m6_retracts, "max_spindle_rpm": self.max_spindle_rpm,
                "max_feed": self.max_feed, "rapid_rate": self.rapid_rate, "arcs": self.arcs}

    @property
    def manual_change(self) -> bool:
        return self.tool_change == "manual"

    def describe(self) -> list:
        """What the program assumes of the machine, one line each (for headers and reports)."""
        x, y, z = self.travel
        lines = [f"machine: {self.label}",
                 f"travel X {x:g} Y {y:g} Z {z:g} mm, tool reaches Z {self.clearance_max:g} above the work zero",
                 {"reference": "Z retract: reference return in machine coordinates",
                  "machine": f"Z retract: machine Z {self.machine_top_z:g}",
                  "clearance": f"Z retract: Z {self.clearance_z:g} above the work zero"}[self.retract],
                 ("tool change: manual, at a pause" if self.manual_change else
                  "tool change: by the changer" + (", which lifts Z" if self.m6_retracts else ""))]
        if self.memory_kb is not None:
            lines.append(f"program memory {self.memory_kb:g} kB")
        if self.family == "punch":
            if self.sheet_origin is not None:
                lines.append("sheet origin G92 X{:g} Y{:g}".format(*self.sheet_origin))
            if self.sheet_max is not None:
                lines.append("sheet up to {:g} x {:g} mm".format(*self.sheet_max))
            lines += [f"clamp {i} at X {c.x:g}: dead zone X {c.x - c.width / 2:g}..{c.x + c.width / 2:g}, "
                      f"Y 0..{c.depth:g}" for i, c in enumerate(self.clamps, start=1)]
        return lines


def travel_problems(operations, profile: MachineProfile) -> list:
    """Where a program does not fit the machine: ``(operation index, move index, message)`` per axis.

    The program's extent along X, Y and Z (every move's end point, each operation's start, its
    safe and clearance heights, and the height the frames lift to on a machine without a
    machine-coordinate retract) must fit the axis's travel, and no Z may lie above the height the
    tool reaches over the work zero.  Where the work zero sits in the machine is the operator's
    setting, so the extent (highest less lowest), not the absolute position, is what is checked.
    """
    found = []
    spans = {}
    for index, op in enumerate(operations):
        xyz = np.asarray(op.xyz, float).reshape(-1, 3)
        start = np.asarray(op.start, float).reshape(1, 3)
        points = np.vstack([start, xyz]) if len(xyz) else start
        heights = [float(op.safe_z), float(op.clearance_z)]
        if profile.retract == "clearance":
            heights.append(float(profile.clearance_z))
        for axis, column in (("X", 0), ("Y", 1), ("Z", 2)):
            values = points[:, column]
            low_move, high_move = int(np.argmin(values)) - 1, int(np.argmax(values)) - 1
            low, high = float(values.min()), float(values.max())
            if axis == "Z" and max(heights) > high:
                high, high_move = max(heights), -1
            span = spans.setdefault(axis, [math.inf, -math.inf, None, None])
            if low < span[0]:
                span[0], span[2] = low, (index, max(low_move, 0))
            if high > span[1]:
                span[1], span[3] = high, (index, max(high_move, 0))
    for column, axis in enumerate("XYZ"):
        if axis not in spans:
            continue
        low, high, (low_op, low_move), (high_op, high_move) = spans[axis]
        travel = float(profile.travel[column])
        if high - low > travel + 1e-6:
            found.append((high_op, high_move,
                          f"the program spans {high - low:.3f} mm along {axis} (from {low:.3f} to {high:.3f}), more "
                          f"than the {travel:g} mm {axis} travel of the machine {profile.label!r} (machine setting "
                          f"Travel {axis})"))
        if axis == "Z" and high > profile.clearance_max + 1e-6:
            found.append((high_op, high_move,
                          f"the program lifts Z to {high:.3f} mm above the work zero, higher than the "
                          f"{profile.clearance_max:g} mm the machine {profile.label!r} reaches (machine setting "
                          f"Z Reach)"))
    return found


def _finite(value) -> bool:
    try:
        return math.isfinite(float(value))
    except (TypeError, ValueError):
        return False


# Presets: a few common machine kinds.  Travel and speeds are typical of the class, not of one model:
# the user sets their own in the panel or the job file; what matters for safety (how Z is lifted,
# what a tool change does, how high Z reaches) follows the control's documented behaviour.
PRESETS = {p.name: p for p in (
    MachineProfile(
        "grbl-router", "Hobby router (GRBL)", "milling",
        "GRBL 1.1 hobby router, not homed, bits changed by hand at an M00 pause, Z zeroed on the top",
        travel=(800.0, 800.0, 100.0), clearance_max=60.0, clearance_z=20.0, retract="clearance",
        tool_change="manual", max_spindle_rpm=24000.0, min_spindle_rpm=0.0, max_feed=5000.0,
        rapid_rate=5000.0,
        source="Grbl v1.1 wiki: no tool changer (M6 is not supported), G53 only on a homed machine "
               "($22 homing), soft limits alarm past $130-$132 travel; the spindle is a trim router.  Reach: "
               "100 mm of Z travel less a 20 mm board and the bit's stick-out leaves about 60 mm above the top"),
    MachineProfile(
        "linuxcnc-manual", "LinuxCNC mill, manual tool change", "milling",
        "LinuxCNC router or mill, homed, M6 stops and asks for the tool (hal_manualtoolchange)",
        travel=(600.0, 400.0, 150.0), clearance_max=80.0, clearance_z=20.0, retract="machine",
        machine_top_z=0.0, tool_change="manual", m6_retracts=False, max_spindle_rpm=24000.0,
        max_feed=6000.0, rapid_rate=6000.0,
        source="LinuxCNC 2.9 INI [EMCIO]: TOOL_CHANGE_QUILL_UP unset, so M6 does not move Z; "
               "G53 G0 Z0 after homing with HOME = 0 at the top of Z"),
    MachineProfile(
        "linuxcnc-atc", "LinuxCNC mill with tool changer", "milling",
        "LinuxCNC mill, homed, tool changer; M6 lifts Z (TOOL_CHANGE_QUILL_UP = 1)",
        travel=(600.0, 400.0, 400.0), clearance_max=150.0, clearance_z=50.0, retract="machine",
        machine_top_z=0.0, tool_change="atc", m6_retracts=True, max_spindle_rpm=12000.0,
        max_feed=10000.0, rapid_rate=15000.0,
        source="LinuxCNC 2.9 INI [EMCIO] TOOL_CHANGE_QUILL_UP = 1: Z goes to machine zero before a change"),
    MachineProfile(
        "fanuc-vmc", "Machining centre (Fanuc 0i-MF)", "milling",
        "Fanuc 0i-MF vertical machining centre with a tool changer",
        travel=(800.0, 500.0, 500.0), clearance_max=300.0, clearance_z=100.0, retract="reference",
        tool_change="atc", m6_retracts=False, max_spindle_rpm=24000.0, max_feed=10000.0,
        rapid_rate=24000.0, memory_kb=512.0, block_ms=1.0,
        source="FANUC Series 0i-MODEL F operator's manual B-64604EN: reference position return G28, "
               "part program storage 512 kB standard; 24000 rpm: the spindle of FANUC's own ROBODRILL "
               "compact machining centres (high-speed option), so the routers' speeds fit"),
    MachineProfile(
        "wood-lathe-cxz", "CNC wood lathe, rotary face plate (C-X-Z)", "cxz",
        "Rotating face plate (C) with a ball bit on X and Z (seed 001)",
        travel=(300.0, 0.0, 150.0), clearance_max=100.0, clearance_z=20.0, retract="reference",
        tool_change="atc", max_spindle_rpm=24000.0, max_feed=5000.0, rapid_rate=5000.0,
        max_table_rpm=30.0,
        source="seed 001 (rotating-table C-X-Z machining of a wooden bento box)"),
    MachineProfile(
        "wood-lathe-cxz-linuxcnc", "CNC wood lathe, LinuxCNC (C-X-Z)", "cxz",
        "Rotating face plate (C) with a ball bit on X and Z, homed LinuxCNC control (seed 001)",
        travel=(300.0, 0.0, 150.0), clearance_max=100.0, clearance_z=20.0, retract="machine",
        machine_top_z=0.0, tool_change="atc", m6_retracts=False, max_spindle_rpm=24000.0, max_feed=5000.0,
        rapid_rate=5000.0, max_table_rpm=30.0,
        source="seed 001; LinuxCNC 2.9 G53 (machine coordinates) after homing with HOME = 0 at the top of Z"),
    MachineProfile(
        "fanuc-0it-turnmill", "Turn-mill (Fanuc 0i-T)", "xzc",
        "Fanuc 0i-T turning centre with driven tools and a C axis (seed 003)",
        travel=(300.0, 0.0, 600.0), clearance_max=200.0, clearance_z=50.0, retract="reference",
        tool_change="atc", max_spindle_rpm=6000.0, max_feed=5000.0, rapid_rate=12000.0,
        memory_kb=512.0, block_ms=7.5, max_table_rpm=100.0,
        source="FANUC Series 0i-TC operator's manual B-64114EN: reference position return G28 U W; "
               "part program storage 512 kB; block processing time for short blocks"),
    MachineProfile(
        "amada-04p", "Turret punch (Amada 04P)", "punch",
        "Amada turret punch press with the 04P control (seed 004)",
        travel=(1270.0, 1270.0, 0.0), clearance_max=1.0, clearance_z=1.0, retract="reference",
        tool_change="atc", max_spindle_rpm=1.0, max_feed=1.0, rapid_rate=60000.0,
        sheet_origin=(1000.0, 1040.0), clamps=(Clamp(200.0), Clamp(700.0)), sheet_max=(1270.0, 1270.0),
        sheet_margin=10.0,
        source="seed 004 (G92 X1000. Y1040. program origin, Table 2); Amada ARIES 245 (04PA control) "
               "programming manual, 1988: sheet coordinates from the sheet's lower-left corner (first "
               "quadrant, the clamped edge along X), G92 establishing the coordinate system, G27/G25 auto "
               "repositioning of the clamps, G50 home return; PTC Creo NC Sheetmetal, CL output: the tool "
               "centre keeps the clearance plus half the tool width from a clamp's boundary. Clamp centres "
               "(X 200, 700), their 80 x 50 mm dead zones, the 1270 x 1270 mm (50 x 50 in) sheet and the "
               "10 mm skeleton margin are typical of the class, not one model's: set the machine's own"),
)}
# The machine a post's program assumes when the user picks only the post (``Post.default_machine``
# names one of these; a post that names none gets its family's).
DEFAULT_FOR_FAMILY = {"milling": "fanuc-vmc", "cxz": "wood-lathe-cxz", "xzc": "fanuc-0it-turnmill",
                      "punch": "amada-04p"}


def preset(name: str) -> MachineProfile:
    """The preset called ``name``; an unknown name is refused listing those that exist."""
    try:
        return PRESETS[name]
    except (KeyError, TypeError):
        raise MachineError(f"unknown machine {name!r}: the presets are {', '.join(PRESETS)}") from None


def presets(family: str | None = None) -> list:
    return [p for p in PRESETS.values() if family is None or p.family == family]
