"""The tool as facets within a tolerance (the manifold engine's pieces, see sweep.py): polygon sides
for a radius, the tool's end as rings along an area-equal corner, the tool's vertices."""
from __future__ import annotations

import math

import numpy as np

from ..ir.program import Tool


def segments_for(radius: float, tolerance: float) -> int:
    """Polygon sides (a multiple of 4) so a faceted sphere of this radius stays within
    ``tolerance`` of the true one (a facet's centre sags about twice the edge's sagitta)."""
    ratio = max(-1.0, 1.0 - tolerance / (2.0 * radius))
    n = math.ceil(math.pi / max(math.acos(ratio), 1e-6))
    return int(min(max(4 * math.ceil(n / 4), 8), 720))


def polygon_sides(radius: float, sagitta: float) -> int:
    """Sides (a multiple of 4) of a polygon inscribed in a circle of this radius whose edges sag
    at most ``sagitta`` from it (a 2-D outline; see :func:`segments_for` for spheres)."""
    return 4 * math.ceil(math.pi / math.acos(max(-1.0, 1.0 - sagitta / radius)) / 4)


def area_scale(steps: int) -> float:
    """Radius factor k for the inner vertices of a polygon along a quarter circle in ``steps``
    edges, its two ends kept on the circle, so it has the quarter's area: the two end
    triangles k R^2 sin(a) / 2 and the others (k R)^2 sin(a) / 2 add up to the sectors
    steps R^2 a / 2, a = (pi / 2) / steps.  Its inner vertices lie R (k - 1) outside the circle
    (~ R a^2 / 12, two thirds of the inscribed polygon's sagitta R a^2 / 8), its edges'
    middles up to ~ a third of that sagitta inside."""
    if steps < 2:
        return 1.0
    a = math.pi / 2 / steps
    ratio = steps * a / math.sin(a)
    if steps == 2:
        return ratio / 2
    return (-2.0 + math.sqrt(4.0 + 4.0 * (steps - 2) * ratio)) / (2.0 * (steps - 2))


def tool_rings(tool: Tool, tolerance: float, inset: float = 0.0) -> list:
    """The tool's end from the tip up, as (radius, height above the tip) rings on the surface of
    the tool shrunk by ``inset`` all round; the last ring is where the end meets the shank.

    Ball, flat and bull are a flat disc rounded by a corner radius; shrinking by ``inset``
    lifts the bottom by ``inset`` and takes ``inset`` off the corner radius (a corner sharper
    than ``inset`` becomes square on a disc ``inset`` smaller).  The corner's arc is an
    area-equal polygon from the bottom ring to the equator, both on it (see
    :func:`area_scale`): its inner vertices lie up to two thirds of its sagitta outside the
    arc, so a sweep of it is not biased to material left."""
    r = tool.radius
    if tool.shape.pointed:
        return [(0.0, 0.0), (r, r / tool.shape.tip_tan)]
    rc = max(tool.corner_radius - inset, 0.0)
    flat = r - inset - rc
    rings = [(flat, inset)]
    steps = max(1, segments_for(rc, tolerance) // 4) if rc > 0 else 0
    k = area_scale(steps)
    for i, beta in enumerate(np.arange(1, steps + 1) * (math.pi / 2 / max(steps, 1)), 1):
        radius = rc if i == steps else k * rc
        rings.append((flat + radius * math.sin(beta), inset + rc - radius * math.cos(beta)))
    return rings


def tool_points(tool: Tool, tolerance: float, height: float, inset: float = 0.0) -> np.ndarray:
    """Vertices of the tool, tip at the origin, up to ``height`` above the tip (at least 1 mm above
    its end), on the surface of the tool shrunk by ``inset``: inscribed polygons round its axis
    (a hull of the tool at two places is as wide as those polygons across the move, which is the
    true width when a vertex points across it), the area-equal one along its corner (see
    :func:`tool_rings`).  Their hull lies within the tolerance of the shrunk tool, beyond it by
    at most :func:`outside`."""
    rings = tool_rings(tool, tolerance, inset)
    rings.append((rings[-1][0], max(height, rings[-1][1] + 1.0)))
    n = segments_for(tool.radius, tolerance)
    around = np.arange(n) * (2 * math.pi / n)
    pts = []
    for radius, z in rings:
        if radius < 1e-12:
            pts.append(np.array([[0.0, 0.0, z]]))
        else:
            pts.append(np.column_stack([radius * np.cos(around), radius * np.sin(around), np.full(n, z)]))
    return np.vstack(pts)


def outside(tool: Tool, tolerance: float) -> float:
    """How far the vertices of :func:`tool_points` and :func:`tool_rings` (and so the pieces
    built of them) reach beyond the tool shrunk by ``inset``: the area-equal corner's
    rc (k - 1), at most two thirds of its sagitta (a sixth of ``tolerance`` where the facets
    are given half of it, as in :func:`segments_for`)."""
    rc = tool.corner_radius
    if tool.shape.pointed or rc <= 0:
        return 0.0
    return rc * (area_scale(max(1, segments_for(rc, tolerance) // 4)) - 1)
