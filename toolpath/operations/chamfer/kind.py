"""Chamfering as an operation kind of the job model (:mod:`.chamfer`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...engines import region
from ...job import DesignLayer, OperationKind, Part
from ... import workload
from ...simulate import BoxStock
from . import chamfer
from .holes import check_holes, plan_holes

MARGIN = 0.05      # mm beyond the V-bit's reach the design layer speaks for


@dataclass(frozen=True)
class ChamferGeometry:
    """Closed outlines ((k, 2) arrays, work mm, even-odd: an outline inside another is a hole's
    edge) whose top edges are chamfered, and the stock's top Z there; ``holes``: round holes
    ((x, y, diameter), ...) whose top edges are chamfered along circles (:mod:`.holes`)."""

    loops: tuple = ()
    top: float = 0.0
    holes: tuple = ()


class ChamferKind(OperationKind):
    key = "chamfer"
    label = "Chamfer"
    families = ("milling",)
    settings_type = chamfer.ChamferSettings

    def workload(self, setup, settings, geometry: ChamferGeometry) -> list:
        _, _, points = workload.outline_measures(geometry.loops)
        return workload.chamfer(setup.name, points)

    def plan(self, setup, settings, geometry: ChamferGeometry, progress=None) -> Part:
        width, _, offset, tip = settings.geometry()
        operations, area, points, reach = [], [], [], offset + width + MARGIN
        if geometry.loops:
            operations.append(chamfer.plan(geometry.loops, settings, top=geometry.top))
            material = region.from_loops(geometry.loops, "chamfer outline")
            # the layer speaks for the waste beside the edges, where the tip runs (nothing to keep there);
            # the flank's cut into the material, within the width of the edges, is judged by the layers
            # of the operations before (a chamfer deeper than what they leave there is a finding)
            area += region.loops(region.offset(material, reach) - material)
            points += [np.asarray(loop, float)[:, :2] for loop in geometry.loops]
        if geometry.holes:
            holes = check_holes(geometry.holes)
            operations.append(plan_holes(holes, settings, top=geometry.top))
            # round a hole the waste is the hole, the drilling's area (its floor the hole's depth): the layer
            # speaks for nothing there, the tip in the hole and the flank in the ring round it are judged by
            # the layers before (the drilling's discs, the engraving's floor), as the flank at an edge is
            points += [holes[:, :2] - holes[:, 2:] / 2, holes[:, :2] + holes[:, 2:] / 2]
        if not operations:
            raise chamfer.ChamferError("chamfer: no edges and no holes to chamfer")
        points = np.vstack(points)
        (x0, y0), (x1, y1) = points.min(axis=0) - reach - 5.0, points.max(axis=0) + reach + 5.0
        stock = setup.stock or BoxStock(float(x0), float(y0), geometry.top - tip - 5.0, float(x1), float(y1),
                                        geometry.top)
        design = DesignLayer(None, (), tuple(area))
        return Part(tuple(operations), stock, design, (), (), None, operations[-1])
