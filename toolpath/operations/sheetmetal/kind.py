"""Punching as an operation kind of the job model: a flat pattern nibbled out of the sheet on a
turret punch, placed clear of the clamps (:mod:`.placement`), its outline cut as merged nibbling
lines with micro-joints (:mod:`.nibbling`).

The part's operations are the IR's punch operations (:class:`...ir.program.PunchOperation`); its result keeps the
whole PunchProgram (with the G92 origin and the notes) the punch post writes; the shell punches
the written program out of the sheet (:func:`.punch.simulate_punching`) for the export gate.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...ir import machine
from ...ir.program import PunchProgram
from ...job import DesignLayer, OperationKind, Part
from ...simulate import BoxStock
from . import nibbling, placement, punch
from .unfold import compensate_outline


@dataclass(frozen=True)
class PunchSettings:
    """The punch program's settings: the turret ``station`` (T word), the round punch's
    ``tool_diameter`` (mm; the cut contour is offset by its radius), the nibbling ``pitch`` (Q, mm),
    the sheet ``thickness`` (mm), and the ``joints`` micro-joints of ``joint_width`` mm left on the
    outline.  Where the part goes (sheet size, G92 origin, clamps) is the setup's machine profile.
    :func:`.nibbling.nibble` and the post check the values (by name)."""

    station: int
    tool_diameter: float
    pitch: float
    thickness: float
    joints: int = nibbling.DEFAULT_JOINTS
    joint_width: float = nibbling.DEFAULT_JOINT_WIDTH


@dataclass(frozen=True)
class PunchGeometry:
    """The flat pattern of one part: its closed ``outline`` (k, 2) in mm, as unfolded (the part
    that must fall out of, or stay joined in, the sheet)."""

    outline: np.ndarray


@dataclass(frozen=True)
class PunchPlan:
    """What the shell shows and checks: the tool-centre ``contour`` round the outline (pattern
    coordinates), the ``placement`` on the sheet, the ``nibbling`` lines (moved onto the sheet),
    ``offset`` (added to pattern coordinates to put them on the sheet), the ``pattern`` on the
    sheet and the ``program`` (the IR's PunchProgram the punch post writes)."""

    contour: np.ndarray
    placement: placement.Placement
    nibbling: nibbling.Nibbling
    offset: np.ndarray
    pattern: np.ndarray
    program: PunchProgram


def punch_profile(setup) -> machine.MachineProfile:
    """The setup's punch machine, or the punch family's preset when the setup names none."""
    return setup.machine if setup.machine is not None else machine.preset(machine.DEFAULT_FOR_FAMILY["punch"])


class PunchKind(OperationKind):
    key = "punch"
    label = "Punching"
    families = ("punch",)
    settings_type = PunchSettings

    def plan(self, setup, settings: PunchSettings, geometry: PunchGeometry, progress=None) -> Part:
        profile = punch_profile(setup)
        outline = np.asarray(geometry.outline, float)
        contour = compensate_outline(outline, settings.tool_diameter)
        hits = punch.hit_count(contour, settings.pitch)
        if hits > punch.MAX_HITS:
            raise punch.PunchError(f"nibbling pitch {settings.pitch:g} mm: the flat pattern takes {hits} hits, "
                                   f"more than the {punch.MAX_HITS} one program may have; raise the pitch")
        where = placement.place(contour, settings.tool_diameter, profile)
        lines = nibbling.nibble(contour, settings.pitch, settings.tool_diameter, joints=settings.joints,
                                joint_width=settings.joint_width).moved(where.offset)
        thickness = settings.thickness
        if not (isinstance(thickness, (int, float, np.floating)) and np.isfinite(thickness) and thickness > 0):
            raise punch.PunchError(f"sheet thickness must be a finite number > 0 (mm), got {thickness!r}")
        offset = np.asarray(where.offset, float)
        on_sheet = outline + offset
        program = placement.program(where, lines, settings.station, thickness, profile)
        sheet = BoxStock(0.0, 0.0, -float(thickness), float(where.sheet[0]), float(where.sheet[1]), 0.0)
        design = DesignLayer(keep_regions=([on_sheet],))      # no hit inside the part
        return Part(tuple(program.operations), sheet, design, (), (), None,
                    PunchPlan(contour, where, lines, offset, on_sheet, program), notes=tuple(program.notes))
