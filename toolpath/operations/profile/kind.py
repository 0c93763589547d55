"""Profile / cut-out as an operation kind of the job model (:mod:`.profile`).

Its design layer: the band of the part's edge (:data:`profile.KEEP_BAND` wide, starting
:data:`profile.KEEP_MARGIN` inside the outline) must stand, not cut through
(:data:`profile.STAND` above the cut's bottom, so an engraving or a blind hole in the part beside
it is no gouge); the area it speaks for is the kerf on the waste side (with room for the leads),
whose floor is the cut's depth; a cut through lets the tool go the breakthrough below the stock's
bottom (``fixture_clearance``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...engines import region as rg
from ...job import DesignLayer, OperationKind, Part
from ... import workload
from ...simulate import BoxStock
from . import contours as ct
from . import profile


@dataclass(frozen=True)
class ProfileGeometry:
    """The shape's closed outlines ((k, 2) point tuples, work mm), the stock's ``thickness`` and
    its top Z; ``what`` names the shape in messages (the object)."""

    loops: tuple
    thickness: float
    top: float = 0.0
    what: str = "shape"
    name: str = "profile"


def design_layer(result: profile.ProfileResult, settings: profile.ProfileSettings, bottom: float) -> DesignLayer:
    region = result.region
    reach = settings.allowance + settings.tool.diameter + 2 * settings.lead_radius + 1.0
    margin, band = profile.KEEP_MARGIN, profile.KEEP_BAND
    if settings.side == "inside":
        area = ct.offset(region, margin) - ct.offset(region, -reach)
        keep = ct.offset(region, margin + band) - ct.offset(region, margin)
    else:
        inset = margin + (settings.tool.radius if settings.side == "on" else 0.0)
        area = ct.offset(region, reach) - ct.offset(region, -inset)
        keep = ct.offset(region, -inset) - ct.offset(region, -inset - band)
    stand = max(result.floor, bottom) + profile.STAND
    keep_loops = [np.asarray(loop) for loop in rg.loops(keep)]
    keep_regions = ((keep_loops, stand),) if keep_loops else ()
    return DesignLayer(result.floor - margin, keep_regions, tuple(np.asarray(loop) for loop in rg.loops(area)))


class ProfileKind(OperationKind):
    key = "profile"
    label = "Profile"
    families = ("milling",)
    settings_type = profile.ProfileSettings

    def workload(self, setup, settings, geometry: ProfileGeometry) -> list:
        thickness = float(geometry.thickness)
        settings.check(thickness)
        _, perimeter, _ = workload.outline_measures(geometry.loops)
        return workload.profile(geometry.name, perimeter, settings.cut_depth(thickness), settings)

    def plan(self, setup, settings, geometry: ProfileGeometry, progress=None) -> Part:
        loops = [np.asarray(loop, float) for loop in geometry.loops]
        result = profile.plan(loops, settings, float(geometry.thickness), float(geometry.top), name=geometry.name,
                              what=geometry.what)
        bottom = float(geometry.top) - float(geometry.thickness)
        stock = setup.stock
        if stock is None:
            reach = settings.tool.diameter + settings.allowance + 2 * settings.lead_radius + 5.0
            points = np.vstack(loops)
            (x0, y0), (x1, y1) = points.min(axis=0) - reach, points.max(axis=0) + reach
            stock = BoxStock(float(x0), float(y0), bottom, float(x1), float(y1), float(geometry.top))
        clearance = max(0.0, bottom - result.floor)
        return Part((result.operation,), stock, design_layer(result, settings, bottom), tuple(result.warnings), (),
                    None, result, fixture_clearance=clearance)
