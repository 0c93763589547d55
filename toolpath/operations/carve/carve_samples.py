"""Sample designs for carving, built in code: closed meshes whose top is a height map.

``wave_relief``: a 120 x 80 mm plate whose top is a wave, z = -4 + 3 sin(2 pi x / 60) cos(2 pi y / 50).
``domed_plate``: a 160 x 60 mm name plate whose top is a spherical cap of radius 400 mm with a
raised, rounded ring along its edge (a frame for a name), on a 0.5 mm grid (a coarser one
leaves facet creases in the ring's hollow that no ball reaches).
``steep_ridge``: a 100 x 60 mm plate with a ridge along X: a crest rounded to 6 mm, flanks
sloping 55 degrees, feet filleted to 4 mm, the floor 10 mm below the crest (:func:`ridge_profile`).
``walled_block``: an 80 x 60 mm plate with a raised block whose walls stand one grid cell wide
(87 degrees on the 0.5 mm grid: a relief made from a height image has such walls): a 56 x 36 mm
rounded rectangle (8 mm corners), its top sloping 6 degrees towards -y (10 mm above the floor
along y = +18, 6.2 mm along y = -18), with a round pocket 14 mm across, 4 mm deep, in it (:data:`BLOCK`).
``vertical_block``: the same block with truly vertical walls (manifold3d booleans, its circles in
facets about 1 mm long; :func:`vertical_block`).
Work zero: the top of the stock (the design's highest point is at z = 0 or just below).
"""
from __future__ import annotations

import numpy as np


def heightmap_solid(x: np.ndarray, y: np.ndarray, top: np.ndarray, bottom: float) -> tuple:
    """A closed, outward-facing triangle mesh: the height map ``top`` (nx, ny) over the grid
    x (nx,) by y (ny,), four vertical sides and a flat bottom at ``bottom``."""
    nx, ny = len(x), len(y)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    upper = np.column_stack([gx.ravel(), gy.ravel(), np.asarray(top, float).ravel()])
    lower = upper.copy()
    lower[:, 2] = bottom
    vertices = np.vstack([upper, lower])
    index = np.arange(nx * ny).reshape(nx, ny)
    a, b = index[:-1, :-1].ravel(), index[1:, :-1].ravel()
    c, d = index[1:, 1:].ravel(), index[:-1, 1:].ravel()
    top_faces = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    bottom_faces = top_faces[:, ::-1] + nx * ny
    ring = np.concatenate([index[:, 0], index[-1, 1:], index[-2::-1, -1], index[0, -2:0:-1]])  # counter-clockwise
    p, q = ring, np.roll(ring, -1)
    side = np.vstack([np.column_stack([p, p + nx * ny, q + nx * ny]), np.column_stack([p, q + nx * ny, q])])
    return vertices, np.vstack([top_faces, bottom_faces, side]).astype(np.int64)


def wave_relief(cell: float = 1.0) -> tuple:
    x = np.linspace(-60, 60, int(round(120 / cell)) + 1)
    y = np.linspace(-40, 40, int(round(80 / cell)) + 1)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    top = -4.0 + 3.0 * np.sin(2 * np.pi * gx / 60) * np.cos(2 * np.pi * gy / 50)
    return heightmap_solid(x, y, top, -15.0)


def domed_plate(cell: float = 0.5) -> tuple:
    x = np.linspace(-80, 80, int(round(160 / cell)) + 1)
    y = np.linspace(-30, 30, int(round(60 / cell)) + 1)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    radius = 400.0
    dome = np.sqrt(radius ** 2 - gx ** 2 - gy ** 2) - radius - 2.0
    # a rounded ring 7 mm inside the edge, 1.2 mm high, 12 mm wide (a cosine bump)
    # (the distance inside a rectangle with 14 mm corner radii, so the ring has no crease)
    cx, cy = np.maximum(np.abs(gx) - 66, 0), np.maximum(np.abs(gy) - 16, 0)
    inset = np.where((cx > 0) & (cy > 0), 14 - np.hypot(cx, cy), np.minimum(80 - np.abs(gx), 30 - np.abs(gy)))
    bump = np.where(np.abs(inset - 7.0) < 6.0, 0.6 * (1 + np.cos(np.pi * (inset - 7.0) / 6.0)), 0.0)
    return heightmap_solid(x, y, dome + bump, -12.0)


def ridge_profile(y: np.ndarray, slope_deg: float = 55.0, crest: float = 6.0, fillet: float = 4.0,
                  height: float = 10.0) -> np.ndarray:
    """Height of a ridge along X over ``y``: its crest (radius ``crest``) at z = 0 over y = 0,
    straight flanks at ``slope_deg``, concave fillets of radius ``fillet`` down to the floor at
    z = -``height``; symmetric in y."""
    t = np.radians(slope_deg)
    y1, z1 = crest * np.sin(t), -crest * (1 - np.cos(t))            # the crest's arc meets the flank
    z2 = -height + fillet * (1 - np.cos(t))                          # the flank meets the fillet
    y2 = y1 + (z1 - z2) / np.tan(t)
    yf = y2 + fillet * np.sin(t)                                      # the fillet meets the floor
    a = np.abs(np.asarray(y, float))
    return np.where(a <= y1, np.sqrt(np.maximum(crest ** 2 - a ** 2, 0)) - crest,
                    np.where(a <= y2, z1 - (a - y1) * np.tan(t),
                             np.where(a <= yf, -height + fillet - np.sqrt(np.maximum(fillet ** 2 - (yf - a) ** 2, 0)),
                                      -height)))


def steep_ridge(cell: float = 0.25) -> tuple:
    x = np.linspace(-50, 50, 51)                   # the ridge does not change along X
    y = np.linspace(-30, 30, int(round(60 / cell)) + 1)
    top = np.broadcast_to(ridge_profile(y), (len(x), len(y)))
    return heightmap_solid(x, y, top, -15.0)


BLOCK = {"floor": -10.0, "half": (20.0, 10.0), "corner": 8.0, "tilt_deg": 6.0, "pocket": (14.0, 0.0, 7.0),
         "depth": 4.0}
"""The walled block (mm, degrees): the block is the points within ``corner`` of the rectangle
|x| <= half[0], |y| <= half[1]; its top is z = tan(tilt) (y - half[1] - corner); the pocket
(centre x, centre y, radius) is ``depth`` below the top at its centre."""


def block_top(x, y) -> np.ndarray:
    """The walled block's height over the points x, y (the floor outside the block)."""
    b = BLOCK
    t = np.tan(np.radians(b["tilt_deg"]))
    (hx, hy), rc = b["half"], b["corner"]
    inside = np.hypot(np.maximum(np.abs(x) - hx, 0), np.maximum(np.abs(y) - hy, 0)) <= rc
    top = np.where(inside, t * (y - hy - rc), b["floor"])
    px, py, pr = b["pocket"]
    return np.where(np.hypot(x - px, y - py) <= pr, t * (py - hy - rc) - b["depth"], top)


def walled_block(cell: float = 0.5) -> tuple:
    x = np.linspace(-40, 40, int(round(80 / cell)) + 1)
    y = np.linspace(-30, 30, int(round(60 / cell)) + 1)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    return heightmap_solid(x, y, block_top(gx, gy), -15.0)



def vertical_block() -> tuple:
    """The walled block with vertical walls: the plate plus the extruded outline cut by the top's
    plane, minus the pocket's cylinder."""
    from manifold3d import CrossSection, JoinType, Manifold

    b = BLOCK
    floor, base = b["floor"], -15.0
    plate = Manifold.cube((80.0, 60.0, floor - base)).translate((-40.0, -30.0, base))
    (hx, hy), rc = b["half"], b["corner"]
    outline = CrossSection.square((2 * hx, 2 * hy), center=True).offset(rc, JoinType.Round, circular_segments=48)
    block = outline.extrude(-floor + 1.0).translate((0.0, 0.0, floor - 0.5))
    t = float(np.tan(np.radians(b["tilt_deg"])))
    # keep t y - z >= t (hy + rc): below the top's plane
    block = block.trim_by_plane((0.0, t, -1.0), t * (hy + rc) / float(np.sqrt(1 + t * t)))
    px, py, pr = b["pocket"]
    pocket = Manifold.cylinder(10.0, pr, circular_segments=44).translate((px, py, t * (py - hy - rc) - b["depth"]))
    mesh = ((plate + block) - pocket).to_mesh()
    return np.asarray(mesh.vert_properties, float)[:, :3].copy(), np.asarray(mesh.tri_verts, np.int64)


SAMPLES = {"wave": wave_relief, "dome": domed_plate, "ridge": steep_ridge, "walls": walled_block, "block": vertical_block}
