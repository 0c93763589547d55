"""LinuxCNC (rs274ngc) dialect: checked in the tests by LinuxCNC's own ``rs274`` interpreter."""
from __future__ import annotations

from .gcode import GcodePost, comment_text
from .registry import ControllerLimits

# LinuxCNC 2.9 documentation, "G-code overview" and "G-Codes" / "M-Codes" pages.
LINUXCNC_SOURCE = (
    "LinuxCNC 2.9 G-Code reference: G93/G94/G95 feed rate mode (G93: an F word on every G1/G2/G3 "
    "block; F 0 is an error); G43/G49 tool length offset (H = tool table entry >= 0); M6 tool change "
    "(T >= 0); G-code overview: numbers (N line numbers 0..99999), S >= 0; M2/M30 program end, "
    "% program delimiters optional")
LINUXCNC_LIMITS = ControllerLimits(
    feed_per_minute=(1e-4, 1e9), inverse_time_feed=(1e-4, 1e9), spindle_rpm=(0, 1e9), tool_number=(0, 99999),
    length_offset=(0, 99999), sequence_number=(0, 99999), coordinate=None, resolution=0.0001,
    decimal_point=False, inverse_time_every_block=True, tool_changer=True,
    tool_change=("M05", "G49", "T.. M06", "S.. M03", "G43 H.."),
    program_start=("%", "G21 G17 G40 G49 G80 G90 G94"), program_end=("M05", "G49", "M30", "%"),
    source=LINUXCNC_SOURCE, max_line_length=252,
    line_length_source=("rs274ngc reads a line into a buffer of LINELEN = 255 bytes (the G-code overview: 'a maximum "
                        "(currently 256) to the number of characters allowed on a line'); a line that fills it with "
                        "its newline and end mark is 'Command too long': 252 characters is the longest LinuxCNC's own "
                        "rs274 accepts (tests/test_line_length.py)"),
    arc_end_tolerance=0.005,
    arc_source=("LinuxCNC 2.9 G-Codes, G2/G3 Arc, center format: 'It is an error if ... the distance from the current "
                "point to the center differs from the distance from the end point to the center by more than "
                "(.05 inch/.5 mm) OR ((.0005 inch/.005mm) AND .1% of radius)': 0.005 mm passes at any radius"))


class LinuxCNCPost(GcodePost):
    name = "linuxcnc"
    label = "LinuxCNC"
    label_ja = "LinuxCNC"
    description = "LinuxCNC / rs274ngc router or mill (.ngc)"
    description_ja = "LinuxCNC / rs274ngc のルーターまたはフライス盤（.ngc）"
    family = "milling"
    order = 20
    extension = ".ngc"
    decimals = 4
    limits = LINUXCNC_LIMITS

    # LinuxCNC G-code reference, "G81 Drilling Cycle", "G82 Drilling Cycle, Dwell" (P in seconds),
    # "G83 Peck Drilling Cycle" (Q the increment, > 0), "G98/G99 Canned Cycle Return Level", "G80".
    canned_cycles = True

    default_machine = "linuxcnc-manual"
    states_machine = True

    def tool_change(self, op, first):
        """Spindle stopped, Z lifted (unless the profile says M6 lifts it: TOOL_CHANGE_QUILL_UP),
        the length offset cancelled, then M6; on a manual change M6 stops and asks for the tool
        (hal_manualtoolchange), so the comment says which."""
        ask = ([f"(THE TOOL CHANGE ASKS FOR {comment_text(op.tool.describe())}: LOAD IT, THEN CONTINUE. Z IS "
                f"LIFTED BEFORE XY MOVES)"] if self.machine.manual_change else [])
        return ["M05", *self.offset_off(lift=not self.machine.m6_retracts), *ask, f"T{op.tool.number} M06"]

    def offset_off(self, lift: bool = True) -> list:
        """The length offset cancelled and Z lifted: to the machine's top with the offset off (the
        spindle's gauge line to Machine Top Z whatever the tool), or to the clearance height while
        the tool's offset still counts (the tip at that height above the work zero)."""
        if not lift:
            return ["G49"]
        if self.machine.retract == "machine":
            return ["G49", *self.lift()]
        return [*self.lift(), "G49"]

    def after_load(self, op, first):
        """Z first: G53 to the top of travel (homed), or with the new tool's offset the clearance height."""
        if self.machine.retract == "clearance":
            return [f"G43 H{op.tool.number}", *self.lift()]
        return self.lift()

    def preamble(self, program):
        # G64 P: path blending within 0.01 mm, so texture ramps are cut as written.
        return ["G21 G17 G40 G49 G80 G90 G94", "G64 P0.01"]

    def length_offset(self, op):
        if self.machine.retract == "clearance":       # G43 H is already on (after_load)
            return [f"G00 Z{self.n(op.safe_z)}"]
        return [f"G43 H{op.tool.number}", f"G00 Z{self.n(op.safe_z)}"]

    def ending(self, program):
        return ["M05", *self.offset_off(), "M30"]
