"""Where a part goes on a turret punch's sheet: at positive sheet coordinates, clear of the clamps.

Sheet coordinates (the Amada 04P's, after its G92): X along the clamped edge, Y into the sheet,
both from the sheet's lower-left corner, so every hit of a part on the sheet is in the first
quadrant.  The clamps hold the sheet's edge at Y = 0; round each lies its dead zone (its width
along X, its depth into the sheet), where a hit would strike the clamp.  As CAM systems avoid
clamps (PTC Creo NC Sheetmetal: the tool centre keeps the clearance plus half the tool width from
the clamp's boundary), what is kept clear here is the hits' discs, not only their centres: the
part's *envelope* is its tool-centre contour grown by the punch radius, and that envelope keeps
the profile's ``sheet_margin`` from the sheet's edges and from every dead zone.

The part is placed in the first of these places that is clear and lies within the sheet
(``sheet_max``): at the sheet's corner (margin, margin); beside each clamp along the clamped
edge; above the clamps' dead zones.  When none is, :class:`PlacementError` names the clamp in the
way and the part's size.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...ir.errors import InputError
from ...ir.machine import MachineProfile
from ...ir.program import PunchProgram


class PlacementError(InputError):
    """A part that does not fit on the sheet clear of the clamps."""


@dataclass(frozen=True)
class Placement:
    """``offset`` (dx, dy) moves the tool-centre contour onto the sheet; ``envelope`` (x0, y0, x1,
    y1) is where the hits' discs then lie; ``zones`` the clamps' dead zones (x0, y0, x1, y1) each;
    ``sheet`` the sheet (X, Y) it was placed within."""

    offset: tuple
    envelope: tuple
    zones: tuple
    sheet: tuple
    where: str


def dead_zones(profile: MachineProfile) -> tuple:
    """(x0, y0, x1, y1) of every clamp's dead zone, in sheet coordinates."""
    return tuple((c.x - c.width / 2, 0.0, c.x + c.width / 2, c.depth) for c in profile.clamps)


def _overlaps(box, zone, margin: float) -> bool:
    return (box[0] < zone[2] + margin and zone[0] - margin < box[2]
            and box[1] < zone[3] + margin and zone[1] - margin < box[3])


def place(contour, punch_diameter: float, profile: MachineProfile) -> Placement:
    """Where the closed tool-centre ``contour`` (k, 2) of a punch ``punch_diameter`` across goes on
    the sheet of ``profile`` (see the module notes)."""
    pts = np.asarray(contour, float)
    if pts.ndim != 2 or pts.shape[1] != 2 or not np.all(np.isfinite(pts)):
        raise PlacementError("placing a part needs its contour as finite (x, y) points")
    r = float(punch_diameter) / 2
    low, high = pts.min(axis=0) - r, pts.max(axis=0) + r
    size = high - low
    margin = profile.sheet_margin
    zones = dead_zones(profile)
    sheet = profile.sheet_max
    if sheet is None:
        raise PlacementError(f"machine profile {profile.label!r} says no sheet size (sheet max): "
                             f"the part cannot be placed")
    above = max((z[3] for z in zones), default=0.0) + margin
    candidates = [((margin, margin), "at the sheet corner")]
    candidates += [((z[2] + margin, margin), f"beside clamp {i}") for i, z in enumerate(zones, start=1)]
    candidates.append(((margin, max(margin, above)), "above the clamps"))
    blocked = []
    for (x0, y0), where in candidates:
        box = (x0, y0, x0 + size[0], y0 + size[1])
        hit = next((i for i, z in enumerate(zones, start=1) if _overlaps(box, z, margin)), None)
        if hit is not None or box[2] > sheet[0] - margin or box[3] > sheet[1] - margin:
            blocked.append((where, hit, box))
            continue
        offset = (x0 - float(low[0]), y0 - float(low[1]))
        return Placement(offset, box, zones, tuple(sheet), where)
    first_clamp = next((i for _, i, _ in blocked if i is not None), None)
    why = []
    if first_clamp is not None:
        z = zones[first_clamp - 1]
        why.append(f"along the clamped edge it meets clamp {first_clamp} (dead zone X {z[0]:g}..{z[2]:g}, "
                   f"Y 0..{z[3]:g} mm)")
    if above + size[1] + margin > sheet[1]:
        why.append(f"above the clamps it would reach Y {above + size[1] + margin:.1f} mm (with the {margin:g} mm "
                   f"margin), past the sheet's {sheet[1]:g}")
    if size[0] + 2 * margin > sheet[0]:
        why.append(f"with the {margin:g} mm margins it needs {size[0] + 2 * margin:.1f} mm along X, more than the "
                   f"sheet's {sheet[0]:g}")
    raise PlacementError(f"the part and its punch hits take {size[0]:.1f} x {size[1]:.1f} mm and cannot be "
                         f"placed on the {sheet[0]:g} x {sheet[1]:g} mm sheet clear of the clamps: "
                         + "; ".join(why))


def describe(placement: Placement) -> list:
    """One line each, for the NC header and the report: where the part's hits lie."""
    x0, y0, x1, y1 = placement.envelope
    lines = [f"part on the sheet {placement.where}: hits within X {x0:.2f}..{x1:.2f} Y {y0:.2f}..{y1:.2f} "
             f"on a sheet {placement.sheet[0]:g} x {placement.sheet[1]:g}"]
    lines += [f"clamp {i} dead zone X {z[0]:g}..{z[2]:g} Y {z[1]:g}..{z[3]:g}"
              for i, z in enumerate(placement.zones, start=1)]
    return lines


def program(where: Placement, nibbled, station: int, thickness: float, profile: MachineProfile,
            name: str = "part") -> PunchProgram:
    """The part's punch program (the IR a punch post writes): its ``nibbled`` lines
    (:class:`.nibbling.Nibbling`, already moved onto the sheet by ``where.offset``) punched by turret
    ``station`` from a sheet ``thickness`` mm thick, with the profile's sheet origin, and notes saying
    where the part's hits lie, the clamps and the micro-joints."""
    return PunchProgram(name, [nibbled.operation(station, thickness)], origin=profile.sheet_origin,
                        notes=describe(where) + nibbled.describe())
