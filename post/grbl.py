"""GRBL 1.1 routers: no tool changer, no length offsets, no canned cycles, no macros.

A tool change becomes a spindle stop and an ``M00`` pause with a comment naming the tool;
the operator changes the bit, re-zeroes Z on the plate top and presses cycle start.
"""
from __future__ import annotations

from .gcode import GcodePost, comment_text
from .registry import ControllerLimits

GRBL_LIMITS = ControllerLimits(
    feed_per_minute=(1e-3, 1e9), inverse_time_feed=(1e-3, 1e9), spindle_rpm=(0, 1e9), tool_number=None,
    length_offset=None, sequence_number=(0, 9999999), coordinate=None, resolution=0.001, decimal_point=False,
    inverse_time_every_block=True, tool_changer=False,
    tool_change=("M05", "G00 Z..", "(CHANGE TO ...)", "M00"),
    program_start=("G21 G17 G90 G94",), program_end=("M05", "M30"),
    source=("Grbl v1.1 wiki, 'Grbl v1.1 Commands' (G-code supported: G0-G3, G17-G19, G20/G21, G28/G30, "
            "G43.1/G49 dynamic length offset only, G54-G59, G90/G91, G93/G94, M0/M2/M30, M3-M5, M7-M9; "
            "N line numbers up to 9999999; no M6 tool change, no G43 H) and grbl/protocol.h "
            "(80-character line buffer)"),
    max_line_length=79,
    line_length_source=("grbl/protocol.h LINE_BUFFER_SIZE 80 and protocol.c: a line keeps at most LINE_BUFFER_SIZE - 1 "
                        "= 79 characters once spaces and comments are dropped, else 'error:11 Max characters per line "
                        "exceeded'; comments are kept to 79 characters too, so every line also fits the 128-byte serial "
                        "buffer (serial.h RX_BUFFER_SIZE) that character-counting senders fill"),
    arc_end_tolerance=0.005,
    arc_source=("grbl/gcode.c (v1.1), center-format arcs: the start and end radii differing by more than 0.005 mm "
                "and by more than 0.1 % of the radius, or by more than 0.5 mm, fail with STATUS_GCODE_INVALID_TARGET, "
                "'error:33' (Grbl v1.1 wiki, Interface: 'The motion command has an invalid target. G2, G3 ... if the "
                "arc is impossible to generate'): 0.005 mm passes at any radius.  Grbl then cuts the arc in chords "
                "within $12 'Arc tolerance, mm' (default 0.002 mm, Grbl v1.1 wiki, Configuration) of it"))


class GrblPost(GcodePost):
    name = "grbl"
    label = "GRBL"
    label_ja = "GRBL"
    description = "GRBL 1.1 hobby router: no tool changer, M00 pause at each tool change"
    description_ja = "GRBL 1.1 のホビー用ルーター：自動工具交換装置なし、工具交換のたびに M00 で一時停止"
    family = "milling"
    order = 30
    extension = ".nc"
    decimals = 3
    percent_wrapped = False
    limits = GRBL_LIMITS

    def preamble(self, program):
        return ["G21 G17 G90 G94"]

    default_machine = "grbl-router"
    states_machine = True
    tool_changes = ("manual",)      # Grbl 1.1 has no M6: every change is the operator's, at M00

    def lift_text(self) -> str:
        machine = self.machine
        return (f"MACHINE Z {self.n(machine.machine_top_z)}" if machine.retract == "machine"
                else f"Z {self.n(machine.clearance_z)}")

    def tool_change(self, op, first):
        """At the start the operator has loaded the bit and zeroed Z on the plate top (the tool
        touches it); at a later change the program stops at M00 with Z lifted.  Either way the
        program lifts Z before it moves XY (:meth:`after_load`), and the comment says so."""
        label = comment_text(op.tool.describe())
        if first:
            return [f"(BEFORE THE START: LOAD {label}, ZERO Z ON THE PLATE TOP. THE PROGRAM LIFTS TO "
                    f"{self.lift_text()} BEFORE XY)"]
        return ["M05", *self.lift(), f"(CHANGE TO {label}, ZERO Z ON THE PLATE TOP, CYCLE START. THE PROGRAM "
                                      f"LIFTS TO {self.lift_text()} BEFORE XY)", "M00"]

    def length_offset(self, op):
        return [f"G00 Z{self.n(op.safe_z)}"]

    def ending(self, program):
        return ["M05", *self.lift(), "M30"]
