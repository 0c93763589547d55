"""Speeds and feeds of a STEP-NC operation from its MILLING_TECHNOLOGY: units converted, missing
values (the workingstep is skipped) and values the tool cannot run (noted).  Split from workplan.py."""
from __future__ import annotations

import math

from ...ir.program import Tool
from .errors import StepNcError
from .process import DrillingOperation


class MissingTechnology(StepNcError):
    """A workingstep whose technology gives no feed or no spindle speed: it is skipped, not the file."""


# Plausibility of the technology (flagged in the notes, never silently written):
MAX_SPINDLE_RPM = 100000.0      # above this an "rev/s" spindle is taken to be rpm (2012-era files)
MIN_RPM_AS_WRITTEN = 100.0      # ... when the value itself reads as a plausible rpm
MAX_CUTTING_SPEED = 1500.0      # m/min at the tool's rim: beyond carbide in aluminium
MAX_FEED = 60000.0              # mm/min
MAX_CHIP_RATIO = 0.05           # feed per tooth (mm) at most this times the tool diameter
MIN_CHIP = 0.001                # mm per tooth: below this the tool rubs instead of cutting
DRILL_FEED_RATIO = 0.1          # a drill's feed per revolution at most this times its diameter


def feed_and_speed(operation, tool: Tool, notes: list | None = None, need_feed: bool = True) -> tuple:
    """(feed mm/min, spindle rpm, clockwise) from MILLING_TECHNOLOGY; the spindle may come from
    the cutting speed and the feed from the feed per tooth.  A spindle in rev/s that would exceed
    MAX_SPINDLE_RPM while the number itself is a plausible rpm is read as rpm (with a note);
    speeds and feeds the tool cannot run are noted.  Raises MissingTechnology when there is no
    feed or no spindle speed."""
    technology = operation.its_technology
    notes = [] if notes is None else notes
    rpm = technology.spindle_rpm
    if rpm is not None and rpm > MAX_SPINDLE_RPM and MIN_RPM_AS_WRITTEN <= abs(technology.spindle) <= MAX_SPINDLE_RPM:
        notes.append(f"#{technology.id} MILLING_TECHNOLOGY: spindle {technology.spindle:g} rev/s would be "
                     f"S{rpm:.0f}; the file gives rpm where ISO 14649 says rev/s (as 2012-era generators "
                     f"wrote it): S{abs(technology.spindle):.0f} written")
        rpm = abs(technology.spindle)
    if rpm is None and technology.cutspeed:
        rpm = technology.cutspeed * 60000.0 / (math.pi * tool.diameter)
    if rpm is None:
        raise MissingTechnology(f"#{technology.id} MILLING_TECHNOLOGY: neither spindle nor cutspeed is given")
    if not rpm > 0:
        given = (f"spindle {technology.spindle:g} rev/s" if technology.spindle_rpm is not None
                 else f"cutspeed {technology.cutspeed:g} m/s")
        raise StepNcError(f"#{technology.id} MILLING_TECHNOLOGY: spindle speed {rpm:g} rpm ({given}); a cutting "
                          "operation needs a turning spindle")
    feed = technology.feed_mm_min
    teeth = operation.its_tool.its_tool_body.number_of_teeth
    if feed is None and technology.feedrate_per_tooth and teeth:
        feed = technology.feedrate_per_tooth * teeth * rpm
    if (not feed or feed <= 0) and not need_feed:      # explicit toolpaths may give their own (freeform)
        return None, rpm, technology.spindle_clockwise
    if not feed or feed <= 0:
        raise MissingTechnology(f"#{technology.id} MILLING_TECHNOLOGY: no positive feedrate (nor "
                                "feedrate_per_tooth with a known number of teeth)")
    notes += _implausible(technology, operation, tool, feed, rpm, teeth)
    return feed, rpm, technology.spindle_clockwise


def _implausible(technology, operation, tool: Tool, feed: float, rpm: float, teeth) -> list:
    """Notes on speeds and feeds the tool cannot run."""
    found = []
    what = f"#{technology.id} MILLING_TECHNOLOGY"
    speed = math.pi * tool.diameter * rpm / 1000.0
    if rpm > MAX_SPINDLE_RPM:
        found.append(f"{what}: S{rpm:.0f} is beyond any spindle (more than {MAX_SPINDLE_RPM:.0f} rpm)")
    elif speed > MAX_CUTTING_SPEED:
        found.append(f"{what}: S{rpm:.0f} runs the {tool.diameter:g} mm tool's rim at {speed:.0f} m/min (more "
                     f"than {MAX_CUTTING_SPEED:.0f} m/min)")
    if feed > MAX_FEED:
        found.append(f"{what}: feed {feed:.0f} mm/min is more than {MAX_FEED:.0f} mm/min (was the feedrate "
                     "written in another unit than m/s?)")
    if isinstance(operation, DrillingOperation):
        per_rev = feed / rpm
        if per_rev > DRILL_FEED_RATIO * tool.diameter:
            found.append(f"{what}: {per_rev:.3g} mm per revolution is too much for the {tool.diameter:g} mm "
                         f"tool (at most {DRILL_FEED_RATIO * tool.diameter:.3g})")
    elif teeth:
        chip = feed / (rpm * teeth)
        if chip > MAX_CHIP_RATIO * tool.diameter:
            found.append(f"{what}: {chip:.3g} mm per tooth is too much for the {tool.diameter:g} mm tool with "
                         f"{teeth} teeth (at most {MAX_CHIP_RATIO * tool.diameter:.3g})")
        elif chip < MIN_CHIP:
            found.append(f"{what}: {chip:.3g} mm per tooth is below {MIN_CHIP:g} mm: the tool rubs")
    return found
