"""Drilling as an operation kind of the job model (:mod:`.drill`, :mod:`.helix`, :mod:`.order`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...job import DesignLayer, OperationKind, Part
from ... import workload
from ...simulate import BoxStock
from . import drill
from .helix import FIT, plan_helix
from .order import short_order

DISC_SIDES = 48
MARGIN = 0.05      # mm beyond a hole's radius the hole's design layer speaks for


@dataclass(frozen=True)
class DrillGeometry:
    """The hole centres ((x, y), ...) in work mm and the stock's top Z there; for holes found in
    the model also their ``diameters`` (mm), ``bottoms`` (Z; None: the settings' depth) and
    ``through`` (bools); ``bottom``: the stock's bottom Z where it is known (None: below the holes)."""

    holes: tuple
    top: float = 0.0
    diameters: tuple | None = None
    bottoms: tuple | None = None
    through: tuple | None = None
    bottom: float | None = None


def selected(geometry: DrillGeometry, settings: drill.DrillSettings):
    """(points, diameters, bottoms Z, through) of the holes the diameter filter keeps, in order."""
    points = drill.check_holes(geometry.holes)
    n = len(points)
    diameters = np.array(geometry.diameters if geometry.diameters is not None else [settings.tool.diameter] * n, float)
    bottoms = np.array([geometry.top - settings.depth if b is None else b
                        for b in (geometry.bottoms if geometry.bottoms is not None else [None] * n)], float)
    through = np.array(geometry.through if geometry.through is not None else [False] * n, bool)
    if not (len(diameters) == len(bottoms) == len(through) == n):
        raise drill.DrillError(f"{n} holes but {len(diameters)} diameters, {len(bottoms)} bottoms, "
                               f"{len(through)} through flags")
    keep = diameters >= settings.min_diameter - 1e-9
    if settings.max_diameter:
        keep &= diameters <= settings.max_diameter + 1e-9
    if not keep.any():
        raise drill.DrillError(f"no hole is between min_diameter {settings.min_diameter:g} mm and max_diameter "
                               f"{settings.max_diameter:g} mm; the holes are "
                               f"{', '.join(f'{d:g}' for d in sorted(set(np.round(diameters, 3))))} mm")
    return points[keep], diameters[keep], bottoms[keep], through[keep]


class DrillKind(OperationKind):
    key = "drill"
    label = "Drilling"
    families = ("milling",)
    settings_type = drill.DrillSettings

    def workload(self, setup, settings, geometry: DrillGeometry) -> list:
        settings.check()
        points = drill.check_holes(geometry.holes)
        bottoms = [b for b in (geometry.bottoms or ()) if b is not None]
        depth = max([settings.depth] + [geometry.top - b for b in bottoms])
        return workload.drill(setup.name, len(points), depth, settings)

    def plan(self, setup, settings, geometry: DrillGeometry, progress=None) -> Part:
        settings.check()
        points, diameters, bottoms, through = selected(geometry, settings)
        if settings.order == "shortest":
            order = short_order(points, start=(0.0, 0.0))
            points, diameters, bottoms, through = points[order], diameters[order], bottoms[order], through[order]
        top = geometry.top
        # a through hole: the drill's full diameter past the bottom by the breakthrough, its point beyond
        drilled_bottoms = np.where(through, bottoms - settings.breakthrough - settings.point_length(), bottoms)
        milled = (diameters > settings.tool.diameter + FIT) if settings.helix else np.zeros(len(points), bool)
        warnings = []
        wide = np.flatnonzero(~milled & (diameters > settings.tool.diameter + FIT))
        for i in wide:
            warnings.append(f"hole at X{points[i][0]:g} Y{points[i][1]:g} is {diameters[i]:g} mm wide, the drill "
                            f"{settings.tool.diameter:g} mm: drilled at the drill's size (turn helix milling on)")
        operations = []
        if settings.spot:
            operations.append(drill.plan(points, settings, "spot drill", top, settings.spot_depth,
                                         settings.spot_tool))
        depths = top - drilled_bottoms[~milled]
        keys = np.round(depths, 6)          # holes within a micron of one depth share one cycle
        for key in sorted(set(keys.tolist())):
            group = keys == key
            depth = float(depths[group][0])
            operations.append(drill.plan(points[~milled][group], settings, "drill" if len(set(keys.tolist())) == 1
                                         else f"drill {depth:.3f} mm", top, depth))
        if milled.any():
            milled_bottoms = np.where(through, bottoms - settings.breakthrough, bottoms)[milled]
            operations.append(plan_helix(points[milled], diameters[milled], milled_bottoms, settings, top))
        radii = np.where(milled, diameters / 2, settings.tool.radius) + MARGIN
        angles = np.linspace(0.0, 2 * np.pi, DISC_SIDES, endpoint=False)
        discs = tuple(np.column_stack([x + r * np.cos(angles), y + r * np.sin(angles)])
                      for (x, y), r in zip(points, radii))
        floor = float(min(drilled_bottoms.min(), np.where(milled, bottoms - settings.breakthrough, np.inf).min()))
        (x0, y0), (x1, y1) = points.min(axis=0) - radii.max() - 5.0, points.max(axis=0) + radii.max() + 5.0
        stock_bottom = geometry.bottom if geometry.bottom is not None else floor - 5.0
        stock = setup.stock or BoxStock(float(x0), float(y0), stock_bottom, float(x1), float(y1), top)
        design = DesignLayer(floor - 0.01, (), discs)
        clearance = 0.0
        if through.any():
            clearance = settings.breakthrough + settings.point_length() + 0.01
        return Part(tuple(operations), stock, design, tuple(warnings), (), None, operations[-1],
                    fixture_clearance=clearance)
