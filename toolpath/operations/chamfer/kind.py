"""Chamfering as an operation kind of the job model (:mod:`.chamfer`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...engines import region
from ...job import DesignLayer, OperationKind, Part
from ... import workload
from ...simulate import BoxStock
from . import chamfer

MARGIN = 0.05      # mm beyond the V-bit's reach the design layer speaks for


@dataclass(frozen=True)
class ChamferGeometry:
    """Closed outlines ((k, 2) arrays, work mm, even-odd: an outline inside another is a hole's
    edge) whose top edges are chamfered, and the stock's top Z there."""

    loops: tuple
    top: float = 0.0


class ChamferKind(OperationKind):
    key = "chamfer"
    label = "Chamfer"
    families = ("milling",)
    settings_type = chamfer.ChamferSettings

    def workload(self, setup, settings, geometry: ChamferGeometry) -> list:
        _, _, points = workload.outline_measures(geometry.loops)
        return workload.chamfer(setup.name, points)

    def plan(self, setup, settings, geometry: ChamferGeometry, progress=None) -> Part:
        op = chamfer.plan(geometry.loops, settings, top=geometry.top)
        width, depth, offset, tip = settings.geometry()
        material = region.from_loops(geometry.loops, "chamfer outline")
        reach = offset + width + MARGIN
        # the layer speaks for the waste beside the edges, where the tip runs (nothing to keep there);
        # the flank's cut into the material, within the width of the edges, is judged by the layers
        # of the operations before (a chamfer deeper than what they leave there is a finding)
        waste = region.loops(region.offset(material, reach) - material)
        points = np.vstack([np.asarray(loop, float)[:, :2] for loop in geometry.loops])
        (x0, y0), (x1, y1) = points.min(axis=0) - reach - 5.0, points.max(axis=0) + reach + 5.0
        stock = setup.stock or BoxStock(float(x0), float(y0), geometry.top - tip - 5.0, float(x1), float(y1),
                                        geometry.top)
        design = DesignLayer(None, (), tuple(waste))
        return Part((op,), stock, design, (), (), None, op)
