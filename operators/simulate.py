"""W6 in Blender: the carved stock before any NC is written, and the safety findings.

The Simulate operator cuts the stock of one workflow's job (any workflow of the table with a
simulation: engraving, rotary pockets, STEP-NC, turn-mill) with that workflow's design limits,
shows the result as a mesh coloured by depth and lists the findings in the panel
(:mod:`.simview` does the work).
"""
from __future__ import annotations

import bpy
from bpy.props import EnumProperty, IntProperty

from . import simview
from .common import SteppedOperator
from .limits import check_group
from .translations import translate_message
from .workflows import WORKFLOWS, simulated, workflow_of


def _workflow_items(self, context):
    return _ITEMS


_ITEMS = [(w.key, w.label, w.description) for w in simulated()]


def simulation_request(scene, workflow: str, engine: str = "heightfield", cell: float = 0.1):
    """Read the job of the workflow ``workflow`` (its key, e.g. "ENGRAVE") from the scene; see
    :func:`simview.simulation_request`."""
    return simview.simulation_request(workflow_of(workflow), scene, engine, cell)


def simulate_job(scene, workflow: str, engine: str = "heightfield", cell: float = 0.1,
                 progress=None) -> simview.SimulationJob:
    """Plan the workflow's job from the scene and cut its stock with it."""
    return simulation_request(scene, workflow, engine, cell)(progress)


class KEZURI_OT_simulate(SteppedOperator, bpy.types.Operator):
    """Cut the stock with the job's toolpaths and check for gouges, rapids through material and moves outside the machine"""  # noqa: E501

    bl_idname = "kezuri.simulate"
    bl_label = "Simulate"
    bl_options = {"REGISTER", "UNDO"}
    progress_label = "simulate"

    workflow: EnumProperty(name="Job", items=_ITEMS, default=_ITEMS[0][0])

    def prepare(self, context):
        props = context.scene.kezuri.simulation
        check_group(props, "simulation")
        return simulation_request(context.scene, self.workflow, props.engine, props.cell)

    def finish(self, context, job):
        simview.show_simulation(context.scene, job)
        simview.store_findings(context.scene, job)
        for finding in job.result.findings[:10]:
            self.report({"WARNING"}, translate_message(finding.message))
        self.report({"INFO"}, translate_message(f"Removed {job.result.removed_volume_mm3 / 1000:.1f} cm^3 in "
                              f"{job.result.seconds:.1f} s; {len(job.result.findings)} finding(s)"))
        return {"FINISHED"}


class KEZURI_OT_frame_finding(bpy.types.Operator):
    """Put the 3D cursor on a finding and centre the view on it"""

    bl_idname = "kezuri.frame_finding"
    bl_label = "Show Finding"
    bl_options = {"REGISTER"}

    index: IntProperty(default=0, min=0)

    @classmethod
    def description(cls, context, properties):
        """The finding's whole message (the button shows its kind and move)."""
        items = context.scene.kezuri.simulation.findings
        if properties.index < len(items):
            return translate_message(items[properties.index].message)
        return bpy.app.translations.pgettext_tip(cls.__doc__)

    def execute(self, context):
        items = context.scene.kezuri.simulation.findings
        if self.index >= len(items):
            return {"CANCELLED"}
        context.scene.cursor.location = items[self.index].location
        if context.area is not None and context.area.type == "VIEW_3D":
            bpy.ops.view3d.view_center_cursor()
        return {"FINISHED"}


CLASSES = (KEZURI_OT_simulate, KEZURI_OT_frame_finding)
__all__ = ["CLASSES", "WORKFLOWS", "simulate_job", "simulation_request"]
