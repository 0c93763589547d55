"""Drilling as an operation kind of the job model (:mod:`.drill`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...job import DesignLayer, OperationKind, Part
from ...simulate import BoxStock
from . import drill

DISC_SIDES = 48
MARGIN = 0.05      # mm beyond the drill's radius the hole's design layer speaks for


@dataclass(frozen=True)
class DrillGeometry:
    """The hole centres ((x, y), ...) in work mm and the stock's top Z there."""

    holes: tuple
    top: float = 0.0


class DrillKind(OperationKind):
    key = "drill"
    label = "Drilling"
    families = ("milling",)
    settings_type = drill.DrillSettings

    def plan(self, setup, settings, geometry: DrillGeometry, progress=None) -> Part:
        op = drill.plan(geometry.holes, settings, top=geometry.top)
        points = drill.check_holes(geometry.holes)
        radius = settings.tool.radius + MARGIN
        angles = np.linspace(0.0, 2 * np.pi, DISC_SIDES, endpoint=False)
        discs = tuple(np.column_stack([x + radius * np.cos(angles), y + radius * np.sin(angles)]) for x, y in points)
        floor = geometry.top - settings.depth
        (x0, y0), (x1, y1) = points.min(axis=0) - radius - 5.0, points.max(axis=0) + radius + 5.0
        stock = setup.stock or BoxStock(float(x0), float(y0), floor - 5.0, float(x1), float(y1), geometry.top)
        design = DesignLayer(floor - 0.01, (), discs)
        return Part((op,), stock, design, (), (), None, op)
