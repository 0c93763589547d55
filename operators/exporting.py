"""What the milling export operators share: the post chosen in the file browser (the scene's post
at first), the file name from the output folder and the post's extension, and the export (through
the gate, with the panel's override) reported back."""
from __future__ import annotations

import os

import bpy
from bpy_extras.io_utils import ExportHelper

from .common import run_reported
from .preferences import scene_output_dir, scene_post
from .translations import translate_message


class MillingExport(ExportHelper):
    """Mixed into an ExportHelper operator with a ``post`` enum.  The operator sets
    ``file_suffix`` and implements ``extension_for(post)`` and ``write(context) -> path``."""

    file_suffix = ""

    def invoke(self, context, event):
        self.post = scene_post(context.scene, context)
        self.filename_ext = self.extension_for(self.post)
        folder = scene_output_dir(context.scene, context)
        name = bpy.path.clean_name(context.scene.name) + self.file_suffix + self.filename_ext
        self.filepath = os.path.join(folder, name)
        return ExportHelper.invoke(self, context, event)

    def check(self, context):
        self.filename_ext = self.extension_for(self.post)
        return ExportHelper.check(self, context)

    def execute(self, context):
        def work():
            path = self.write(context)
            self.report({"INFO"}, translate_message(f"Wrote {path}"))
            return {"FINISHED"}
        return run_reported(self, work)
