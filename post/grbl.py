"""GRBL 1.1 routers: no tool changer, no length offsets, no canned cycles, no macros.

A tool change becomes a spindle stop and an ``M00`` pause with a comment naming the tool;
the operator changes the bit, re-zeroes Z on the plate top and presses cycle start.
"""
from __future__ import annotations

from .gcode import GcodePost, comment_text


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

    def preamble(self, program):
        return ["G21 G17 G90 G94"]

    def tool_change(self, op, first):
        label = comment_text(op.tool.describe())
        if first:
            return [f"(LOAD {label}, ZERO Z ON THE PLATE TOP)"]
        return ["M05", f"G00 Z{self.n(op.safe_z)}", f"(CHANGE TO {label}, ZERO Z ON THE PLATE TOP)", "M00"]

    def length_offset(self, op):
        return [f"G00 Z{self.n(op.safe_z)}"]

    def ending(self, program):
        return ["M05", "M30"]
