"""Preview meshes of a simulated stock: a height field as a relief of columns (min-pooled to a
cell budget), a turned bar less the air the height field opened."""
from __future__ import annotations

import math

import numpy as np
from manifold3d import Manifold, Mesh

from . import radiusmap as rmap
from .stock import CylinderStock, HeightField, stock_box, stock_solid

# ----- height field -> mesh -------------------------------------------------------------------------

def _pooled(heights: np.ndarray, max_cells) -> tuple:
    """(heights min-pooled to at most ``max_cells`` cells, block size): each block keeps its deepest cut."""
    nx, ny = heights.shape
    if max_cells is None or nx * ny <= max_cells:
        return heights, 1
    block = math.ceil(math.sqrt(nx * ny / max_cells))
    padded = np.pad(heights, ((0, -nx % block), (0, -ny % block)), mode="edge")
    return padded.reshape(padded.shape[0] // block, block, padded.shape[1] // block, block).min(axis=(1, 3)), block


def _relief_mesh(heights: np.ndarray, x0, y0, x1, y1, cx, cy, bottom):
    """A closed mesh of columns over the rectangle: vertices at the cell centres (x0 + (i + 0.5)
    cx, ...) plus a ring on the rectangle's edge (heights copied outward), walls, a flat bottom."""
    xs = np.concatenate([[x0], np.minimum(x0 + (np.arange(heights.shape[0]) + 0.5) * cx, x1), [x1]])
    ys = np.concatenate([[y0], np.minimum(y0 + (np.arange(heights.shape[1]) + 0.5) * cy, y1), [y1]])
    z = np.pad(heights, 1, mode="edge")
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    top_vertices = np.column_stack([gx.ravel(), gy.ravel(), z.ravel()])
    w, h = len(xs), len(ys)
    ids = np.arange(w * h).reshape(w, h)
    a, b, c, d = ids[:-1, :-1].ravel(), ids[1:, :-1].ravel(), ids[1:, 1:].ravel(), ids[:-1, 1:].ravel()
    top_faces = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    # The boundary ring, counter-clockwise seen from above, then walls and a bottom fan.
    ring = np.concatenate([ids[:, 0], ids[-1, 1:], ids[-2::-1, -1], ids[0, -2:0:-1]])
    low_vertices = top_vertices[ring].copy()
    low_vertices[:, 2] = bottom
    n_top = len(top_vertices)
    low = n_top + np.arange(len(ring))
    centre = n_top + len(ring)
    nxt = np.roll(np.arange(len(ring)), -1)
    walls = np.concatenate([np.column_stack([ring, low, low[nxt]]), np.column_stack([ring, low[nxt], ring[nxt]])])
    fan = np.column_stack([np.full(len(ring), centre), low[nxt], low])
    vertices = np.vstack([top_vertices, low_vertices, [[(x0 + x1) / 2, (y0 + y1) / 2, bottom]]])
    return vertices, np.vstack([top_faces, walls, fan])


def heightfield_mesh(hf: HeightField, stock, max_cells):
    heights = np.where(hf.inside, hf.heights, hf.top)
    np.clip(heights, hf.bottom + 1e-3, hf.top, out=heights)
    # pooled in the heights' own precision, widened after (the minimum of a block is exact either
    # way): no float64 copy of a whole 72 M-cell sign
    heights, block = _pooled(heights, max_cells)
    heights = heights.astype(float)
    (x0, y0, _), (x1, y1, _) = stock_box(stock)
    cx, cy = block * hf.cell_x, block * hf.cell_y
    vertices, faces = _relief_mesh(heights, x0, y0, x1, y1, cx, cy, hf.bottom)
    if isinstance(stock, CylinderStock):
        return manifold_arrays(solid_of(vertices, faces) ^ stock_solid(stock, max(cx, cy) / 4))
    return vertices, faces


def _filled_heights(hf: HeightField, cut: np.ndarray, stock: CylinderStock) -> np.ndarray:
    """The material's top over the height field's square: the cut cells' heights (kept 1 um
    above the bottom), the top elsewhere, and in the cells outside the bar the height of the
    bar's edge next to them (so a cut reaching the edge reaches it all along)."""
    heights = np.where(cut, np.clip(hf.heights, hf.bottom + 1e-3, hf.top), hf.top).astype(float)
    outside = np.nonzero(~hf.inside)
    if len(outside[0]):
        # the cell under the point that far inward: its centre lies within the bar
        edge = stock.radius - math.hypot(hf.cell_x, hf.cell_y) / 2 * 1.001
        x, y = hf.x()[outside[0]], hf.y()[outside[1]]
        scale = np.minimum(1.0, max(edge, 0.0) / np.maximum(np.hypot(x, y), 1e-12))
        i = np.clip(np.floor((x * scale - hf.x0) / hf.cell_x).astype(np.int64), 0, hf.shape[0] - 1)
        j = np.clip(np.floor((y * scale - hf.y0) / hf.cell_y).astype(np.int64), 0, hf.shape[1] - 1)
        heights[outside] = heights[i, j]
    return heights


def turned_mesh(rm: rmap.RadiusMap, hf: HeightField | None, stock: CylinderStock, max_cells):
    """The bar of the radius map, less the air the height field's cuts opened above it.

    The air is a box over the cut cells minus their columns (uncut cells stand above the box;
    the cells outside the bar have the height of its edge next to them),
    so only the cut area meets the bar in the boolean, and no faces of the two coincide.  The
    box starts 1 mm below the deepest cut; the bar below it never meets the air, so only the
    bar's columns above a ring under the box go through the boolean (closed by a fan there),
    and the rest of the bar's side joins the result at that ring."""
    grid = rmap.mesh_grid(rm, stock.bottom, stock.top, max_cells)
    cut = None if hf is None else hf.inside & (hf.heights < hf.top - 1e-6)
    if cut is None or not cut.any():
        return rmap.grid_mesh(grid)
    nx, ny = hf.shape
    filled = _filled_heights(hf, cut, stock)
    cut = filled < hf.top      # with the cells outside the bar next to a cut edge
    i, j = np.nonzero(cut)
    i0, i1, j0, j1 = max(i.min() - 2, 0), min(i.max() + 3, nx), max(j.min() - 2, 0), min(j.max() + 3, ny)
    heights = filled[i0:i1, j0:j1]
    heights[~cut[i0:i1, j0:j1]] = hf.top + 1.0
    heights, block = _pooled(heights, max_cells)
    cx, cy = block * hf.cell_x, block * hf.cell_y
    x0, y0 = hf.x0 + i0 * hf.cell_x, hf.y0 + j0 * hf.cell_y
    x1, y1 = x0 + heights.shape[0] * cx, y0 + heights.shape[1] * cy
    # one more cell all round (uncut but where the cut reaches the square's edge), so that the
    # relief's vertices stay at the cells' centres and the box reaches past the bar's edge there
    columns = solid_of(*_relief_mesh(np.pad(heights, 1, mode="edge"), x0 - cx, y0 - cy,
                                      x1 + cx, y1 + cy, cx, cy, hf.bottom - 2.0))
    box_bottom = max(float(heights.min()) - 1.0, hf.bottom - 1.0)
    box = Manifold.cube([x1 - x0 + cx, y1 - y0 + cy, hf.top + 0.5 - box_bottom]).translate(
        [x0 - cx / 2, y0 - cy / 2, box_bottom])
    zs = grid[0, :, 2]
    split = int(np.searchsorted(zs, box_bottom - 0.5, side="right")) - 1   # last ring 0.5 mm under the box
    if split < 1:
        return manifold_arrays(solid_of(*rmap.grid_mesh(grid)) - (box - columns))
    top_vertices, top_faces = manifold_arrays(solid_of(*rmap.grid_mesh(grid[:, split:])) - (box - columns))
    return _joined(grid[:, :split + 1], top_vertices, top_faces)


def _joined(lower: np.ndarray, top_vertices, top_faces):
    """The open lower part of a bar (a ``mesh_grid`` run closed only at its bottom) joined to the
    solid above it, which was closed by a fan on the lower part's last ring: the fan's plane is
    dropped from the solid and its ring vertices are the lower part's (equal in float32, the
    solid's precision)."""
    vertices, faces = rmap.grid_mesh(lower, top_cap=False)
    vertices = vertices.astype(np.float32).astype(float)
    ring = lower.shape[1] - 1 + lower.shape[1] * np.arange(lower.shape[0])
    plane = vertices[ring[0], 2]
    on_plane = top_vertices[:, 2] == plane
    top_faces = top_faces[~on_plane[top_faces].all(axis=1)]
    key = {(x, y): int(k) for x, y, k in zip(vertices[ring, 0], vertices[ring, 1], ring)}
    kept = ~on_plane
    index = np.empty(len(top_vertices), np.int64)
    index[kept] = len(vertices) + np.arange(int(kept.sum()))
    for k in np.unique(top_faces[on_plane[top_faces]]):     # the ring where the side meets the plane
        index[k] = key[(top_vertices[k, 0], top_vertices[k, 1])]
    return np.vstack([vertices, top_vertices[kept]]), np.vstack([faces, index[top_faces]])


# ----- a turned bar for pictures: no boolean --------------------------------------------------------

TILE = 16      # top-face tiles of at most this many cells, ...
TILE_OF_RADIUS = 1 / 32     # ... and at most this share of the bar's radius: untouched ones are one flat
                            # quad, and the end face's edge (pulled onto the bar) is a polygon this fine


def turned_surface(rm: rmap.RadiusMap, hf: HeightField | None, stock: CylinderStock, max_cells):
    """A triangle surface that looks like :func:`turned_mesh` (its side and bottom are the same
    grid) without a boolean: for pictures, not a closed solid.

    The bar's side is pressed down onto the height field where the axial cuts opened it, and the
    end face is the height field's surface over the stock's square (vertices at the cell centres,
    a ring on the square's edge; each flat tile of cells one quad) pulled in along the radius
    onto the bar's side where it lies outside it.  Cells outside the bar take the height of the
    bar's edge next to them."""
    grid = rmap.mesh_grid(rm, stock.bottom, stock.top, max_cells)
    cut = None if hf is None else hf.inside & (hf.heights < hf.top - 1e-6)
    if cut is None or not cut.any():
        vertices, faces = rmap.grid_mesh(grid)
        return vertices, np.vstack([_side(grid, np.zeros(grid.shape[:2], bool), rm.radius), faces[-2 * len(grid):]])
    heights = _filled_heights(hf, cut, stock)
    side_vertices, side_faces = rmap.grid_mesh(grid, top_cap=False)
    i = np.clip(np.floor((side_vertices[:, 0] - hf.x0) / hf.cell_x).astype(np.int64), 0, hf.shape[0] - 1)
    j = np.clip(np.floor((side_vertices[:, 1] - hf.y0) / hf.cell_y).astype(np.int64), 0, hf.shape[1] - 1)
    pressed = side_vertices[:, 2] > heights[i, j]
    side_vertices[pressed, 2] = heights[i, j][pressed]
    side_faces = np.vstack([_side(grid, pressed[:grid.shape[0] * grid.shape[1]].reshape(grid.shape[:2]), rm.radius),
                            side_faces[-len(grid):]])
    tile = int(np.clip(TILE_OF_RADIUS * stock.radius / max(hf.cell_x, hf.cell_y), 1, TILE))
    top_vertices, top_faces = _tiled_top(heights, hf, tile)
    _pull_in(top_vertices, grid)
    return np.vstack([side_vertices, top_vertices]), np.vstack([side_faces, top_faces + len(side_vertices)])


def _side(grid: np.ndarray, pressed: np.ndarray, radius: float) -> np.ndarray:
    """The triangles of the side of ``mesh_grid`` ``grid`` (as :func:`.radiusmap.grid_mesh` numbers
    its vertices, no caps), each run of uncut quads up a strip (both edges at the bar's radius,
    no vertex ``pressed`` down, above the bottom row) as one quad: they are one rectangle."""
    n_theta, columns = grid.shape[:2]
    ids = np.arange(n_theta * columns).reshape(n_theta, columns)
    nxt = np.roll(ids, -1, axis=0)
    plain = (np.hypot(grid[..., 0], grid[..., 1]) >= radius - 1e-9) & ~pressed
    plain &= np.roll(plain, -1, axis=0)
    quad = plain[:, :-1] & plain[:, 1:]               # quad (i, c): strip i, rows c .. c + 1
    quad[:, 0] = False                                # the bottom row stays (it is drawn as the side)
    run = np.zeros((n_theta, columns + 1), bool)
    run[:, 1:-1] = quad
    starts = np.nonzero(run[:, 1:] & ~run[:, :-1])    # (strip, first quad) of each run ...
    ends = np.nonzero(run[:, :-1] & ~run[:, 1:])      # ... (strip, one past its last quad), in the same order
    i, c = np.nonzero(~quad)
    a = np.concatenate([ids[i, c], ids[starts]])
    b = np.concatenate([nxt[i, c], nxt[starts]])
    top = (ends[0], ends[1])
    c2 = np.concatenate([nxt[i, c + 1], nxt[top]])
    d = np.concatenate([ids[i, c + 1], ids[top]])
    return np.concatenate([np.column_stack([a, b, c2]), np.column_stack([a, c2, d])])


def _tiled_top(heights: np.ndarray, hf: HeightField, tile: int):
    """The end face over the stock's square: (vertices, triangles) of the grid of cell centres
    plus an edge ring (heights copied outward), tiles of ``tile`` cells that are flat as two
    triangles, the others cell by cell."""
    (x0, y0), (x1, y1) = (hf.x0, hf.y0), (hf.x0 + hf.shape[0] * hf.cell_x, hf.y0 + hf.shape[1] * hf.cell_y)
    xs = np.concatenate([[x0], hf.x(), [x1]])
    ys = np.concatenate([[y0], hf.y(), [y1]])
    z = np.pad(heights, 1, mode="edge")
    w, h = z.shape
    ids = np.arange(w * h).reshape(w, h)
    # tile (a, b) spans vertices a*tile .. min((a+1)*tile, w-1)
    ta, tb = -(-(w - 1) // tile), -(-(h - 1) // tile)
    padded = np.pad(z, ((0, ta * tile + 1 - w), (0, tb * tile + 1 - h)), mode="edge")

    def over_tiles(reduce):      # over each tile's vertices, its far edges included
        return reduce(np.stack([reduce(padded[:-1, :-1].reshape(ta, tile, tb, tile), axis=(1, 3)),
                                reduce(padded[tile::tile, :-1].reshape(ta, tb, tile), axis=2),
                                reduce(padded[:-1, tile::tile].reshape(ta, tile, tb), axis=1),
                                padded[tile::tile, tile::tile]]), axis=0)
    blocks = over_tiles(np.max) != over_tiles(np.min)     # not flat: cell by cell
    fine = np.repeat(np.repeat(blocks, tile, axis=0), tile, axis=1)[:w - 1, :h - 1]
    qa, qb = np.nonzero(fine)
    a, b, c, d = ids[qa, qb], ids[qa + 1, qb], ids[qa + 1, qb + 1], ids[qa, qb + 1]
    fa, fb = np.nonzero(~blocks)
    a0, a1 = fa * tile, np.minimum((fa + 1) * tile, w - 1)
    b0, b1 = fb * tile, np.minimum((fb + 1) * tile, h - 1)
    a = np.concatenate([a, ids[a0, b0]])
    b = np.concatenate([b, ids[a1, b0]])
    c = np.concatenate([c, ids[a1, b1]])
    d = np.concatenate([d, ids[a0, b1]])
    faces = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    used = np.zeros(w * h, bool)
    used[faces] = True
    index = np.cumsum(used) - 1
    k = np.flatnonzero(used)
    vertices = np.column_stack([xs[k // h], ys[k % h], z.reshape(-1)[k]])
    return vertices, index[faces]


def _pull_in(vertices: np.ndarray, grid: np.ndarray) -> None:
    """Move (k, 3) vertices lying outside the bar of ``mesh_grid`` ``grid`` in along the radius
    onto its side (the nearest of its vertices' radii), in place."""
    n_theta = grid.shape[0]
    radii = np.hypot(grid[..., 0], grid[..., 1])
    zs = grid[0, :, 2]
    theta = np.arctan2(vertices[:, 1], vertices[:, 0])
    i = np.rint(np.mod(theta, 2 * math.pi) / (2 * math.pi / n_theta) - 0.5).astype(np.int64) % n_theta
    k = np.clip(np.searchsorted(zs, vertices[:, 2]), 1, len(zs) - 1)
    k -= (vertices[:, 2] - zs[k - 1]) < (zs[k] - vertices[:, 2])
    r = np.hypot(vertices[:, 0], vertices[:, 1])
    limit = radii[i, k]
    outside = r > limit
    vertices[outside, :2] *= (limit[outside] / r[outside])[:, None]


# ----- solids <-> triangle arrays ---------------------------------------------------------------------

def solid_of(vertices, faces) -> Manifold:
    return Manifold(Mesh(vert_properties=np.ascontiguousarray(vertices, np.float32),
                         tri_verts=np.ascontiguousarray(faces, np.uint32)))


def manifold_arrays(solid: Manifold):
    mesh = solid.to_mesh()
    return np.asarray(mesh.vert_properties[:, :3], float), np.asarray(mesh.tri_verts, np.int64)
