"""The workflow table: one entry per workflow, in the order the panel and the demo show them.

Registration (``operators/__init__``), the Simulate operator and panel, batch's commands and
the demo loop over :data:`WORKFLOWS`; nothing else lists the workflows.
"""
from __future__ import annotations

from . import carve, chamfer, drill, engrave, ncfile, pocket, profile, rotary, sheetmetal, stepnc, turnmill, vcarve

WORKFLOWS = (engrave.WORKFLOW, rotary.WORKFLOW, stepnc.WORKFLOW, turnmill.WORKFLOW, sheetmetal.WORKFLOW,
             carve.WORKFLOW, drill.WORKFLOW, pocket.WORKFLOW, profile.WORKFLOW, chamfer.WORKFLOW, vcarve.WORKFLOW,
             ncfile.WORKFLOW)


def simulated() -> list:
    """The workflows whose jobs the Simulate operator cuts."""
    return [w for w in WORKFLOWS if w.simulation is not None]


def workflow_of(key: str):
    for workflow in WORKFLOWS:
        if workflow.key == key:
            return workflow
    raise KeyError(f"no workflow {key!r}; the table has {', '.join(w.key for w in WORKFLOWS)}")


def commands() -> dict:
    """Batch commands by name: every workflow's."""
    return {command.name: command for workflow in WORKFLOWS for command in workflow.commands}


def settings_groups() -> list:
    """(kind, PropertyGroup class) of every operation kind whose settings have panel properties."""
    return [(w.kind, w.settings_group) for w in WORKFLOWS if w.settings_group is not None]


def job_items() -> list:
    """The CAM tab's job picker: (key, label, description) of every workflow with panels."""
    return [(w.key, w.label, w.description) for w in WORKFLOWS if w.classes]
