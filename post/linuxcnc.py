"""LinuxCNC (rs274ngc) dialect: checked in the tests by LinuxCNC's own ``rs274`` interpreter."""
from __future__ import annotations

from .gcode import GcodePost


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

    def preamble(self, program):
        # G64 P: path blending within 0.01 mm, so texture ramps are cut as written.
        return ["G21 G17 G40 G49 G80 G90 G94", "G64 P0.01"]

    def length_offset(self, op):
        return [f"G43 H{op.tool.number}", f"G00 Z{self.n(op.safe_z)}"]

    def ending(self, program):
        return ["M05", "G49", "M30"]
