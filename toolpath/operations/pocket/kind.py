"""Pocketing as an operation kind of the job model (:mod:`.pocket`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...engines import region as rg
from ...job import DesignLayer, OperationKind, Part
from ... import workload
from ...simulate import BoxStock
from . import pocket

KEEP_MARGIN = 0.02       # mm: the walls may stand this far from the outline (the offsets' chord error)
KEEP_BAND = 2.0          # mm round the outside of the pocket that must stand


@dataclass(frozen=True)
class PocketGeometry:
    """The pocket's loops (work mm, read even-odd: inner loops are islands), its name, the stock's top Z and,
    for the stock and what must stand outside the pocket, the plate's outline and thickness
    (empty: a box 5 mm round the region)."""

    loops: tuple
    name: str = "pocket"        # the operation's name (messages and the program's comments)
    top: float = 0.0
    plate_outline: tuple = ()
    plate_thickness: float = 0.0


def design_layer(region, floor: float) -> DesignLayer:
    """The pocket's area is the region, its floor the depth; the islands and a band of KEEP_BAND
    round the outside stand (a band, not the whole stock: a keep region stands over every other
    operation of the job, which may cut elsewhere)."""
    outers = [loop for loop in rg.loops(region) if rg.signed_area(loop) > 0]
    filled = rg.from_loops(outers, "pocket") if len(outers) == 1 else rg.union_of_faces(outers, "pocket")
    keep = rg.offset(filled, KEEP_BAND) - rg.offset(region, KEEP_MARGIN)
    area = rg.offset(region, 2 * KEEP_MARGIN)
    return DesignLayer(floor, (list(rg.loops(keep)),) if keep.area() > 0 else (), tuple(rg.loops(area)))


class PocketKind(OperationKind):
    key = "pocket"
    label = "Pocket"
    families = ("milling",)
    settings_type = pocket.PocketSettings

    def workload(self, setup, settings, geometry: PocketGeometry) -> list:
        settings.check(geometry.name)
        area, _, _ = workload.outline_measures(geometry.loops)
        return workload.pocket(geometry.name, area, settings.depth, settings)

    def plan(self, setup, settings, geometry: PocketGeometry, progress=None) -> Part:
        result = pocket.plan(geometry.loops, settings, name=geometry.name, top=geometry.top, progress=progress)
        stock = setup.stock or self.stock(geometry, result.region, settings)
        design = design_layer(result.region, geometry.top - settings.depth)
        return Part(tuple(result.operations), stock, design, tuple(result.warnings), (), None, result)

    @staticmethod
    def stock(geometry: PocketGeometry, region, settings) -> BoxStock:
        if geometry.plate_outline:
            points = np.vstack([np.asarray(loop, float) for loop in geometry.plate_outline])
            (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
            bottom = geometry.top - geometry.plate_thickness
        else:
            (x0, y0), (x1, y1) = np.subtract(region.bounds()[:2], 5.0), np.add(region.bounds()[2:], 5.0)
            bottom = geometry.top - settings.depth - 5.0
        return BoxStock(float(x0), float(y0), float(bottom), float(x1), float(y1), float(geometry.top))
