"""Pockets on a rotating table (C-X-Z) as an operation kind of the job model: roughing, wall
finishing and the bottom spiral of every pocket (:mod:`.rotary`)."""
from __future__ import annotations

from dataclasses import dataclass

from ...job import OperationKind, Part
from ... import workload
from ...simulate import BoxStock
from . import rotary
from .rotary_pocket import Block, RotarySettings


@dataclass(frozen=True)
class RotaryGeometry:
    """The block (a rotary_pocket.Block: its top centre on the table's axis, top at Z = 0) and the
    pockets (rotary_pocket.Pocket, outlines in the part frame, work mm), in the order to cut."""

    block: Block
    pockets: tuple


class RotaryKind(OperationKind):
    key = "rotary"
    label = "Rotary Pockets"
    families = ("cxz",)
    settings_type = RotarySettings

    def workload(self, setup, settings, geometry: RotaryGeometry) -> list:
        settings.validate()
        estimates = []
        for pocket in geometry.pockets:
            area, perimeter, _ = workload.outline_measures([pocket.outline])
            estimates += workload.rotary(pocket.name, area, perimeter, float(pocket.depth), settings,
                                         pocket.bottom != "flat")
        return estimates

    def plan(self, setup, settings, geometry: RotaryGeometry, progress=None) -> Part:
        result = rotary.plan(geometry.block, list(geometry.pockets), settings, name=setup.name, progress=progress)
        result.program.work_offset = setup.work_offset
        # the cycle times are the plan's, at settings.rapid_rate (the per-pocket reports hold them)
        b = geometry.block
        stock = BoxStock(-b.size_x / 2, -b.size_y / 2, -b.thickness, b.size_x / 2, b.size_y / 2, 0.0)
        # no design layer: the gate checks the pockets' cuts against the block only
        return Part(tuple(result.program.operations), stock, None, (), (), None, result,
                    notes=tuple(result.program.notes), post_options=(("max_table_rpm", settings.max_table_rpm),))
