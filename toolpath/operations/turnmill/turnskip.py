"""What a turn-mill plan leaves unmachined: the faces neither tool reaches, named and grouped.

Classification (:mod:`.turnreach`) labels a face NEITHER when the radial and the axial tool both
fail to see it (a cross hole's wall, an undercut, the underside of a shoulder).  Such a face is
still cut where the ball's side sweeps it on its way along a neighbouring face: a pocket's wall
beside the axial floor passes and their roughing copies, a groove's shoulder beside the radial
layers.  There the ball leaves the fillet any ball end mill leaves in a concave corner: where
three faces meet at right angles, the corner point lies r * sqrt(3) from the centre of the ball
touching all three.  So a face counts as machined when every sample point on it (the
classification's samples, :func:`meshrays.face_samples`) has a ball centre of the plan within
:func:`reach` of it: that corner distance, widened by half the larger of the roughing step and
the stepover (the gap between neighbouring ball positions) and by the chordal tolerance.  A
cross hole's wall lies much further from every ball centre (the hex bar's 8 mm hole in the tests:
6.3 mm and more, against 5.2 mm for the 6 mm ball); the sample part's walls and shoulders, all
swept, lie within 4.5 mm.  Faces on the stock's own surface (the
chuck-side face, the bar's outside, the end face) have nothing to remove and are never counted.

The faces left are grouped into features (faces joined by shared edges), each with its face
count, area, bounding box, axial range (Z) and radial range (distance from the axis), for the
report, the NC header and the picture.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...engines.facets import connected
from ...engines.meshrays import face_normals, face_samples

SAMPLE_CHUNK = 20_000        # sample points tested at once against the ball centres
NOTE_FEATURES = 4            # features named one by one in the NC header; the rest summed up


@dataclass(frozen=True)
class SkippedFeature:
    """Edge-connected faces no tool reaches.  ``faces``: their ids in the mesh given; lengths mm."""

    faces: np.ndarray
    area: float
    lo: tuple
    hi: tuple
    radius: tuple            # (least, greatest) distance of its vertices from the axis

    def describe(self) -> str:
        lo, hi = self.lo, self.hi
        return (f"{len(self.faces)} faces, {self.area:.1f} mm2, Z {lo[2]:.2f} to {hi[2]:.2f}, "
                f"X {lo[0]:.2f} to {hi[0]:.2f}, Y {lo[1]:.2f} to {hi[1]:.2f}, "
                f"radius {self.radius[0]:.2f} to {self.radius[1]:.2f}")

    def as_dict(self) -> dict:
        return {"faces": len(self.faces), "area_mm2": round(self.area, 3),
                "box_min": [round(float(x), 4) for x in self.lo], "box_max": [round(float(x), 4) for x in self.hi],
                "z": [round(float(self.lo[2]), 4), round(float(self.hi[2]), 4)],
                "radius": [round(float(r), 4) for r in self.radius]}


def reach(radius: float, roughing_step: float, stepover: float, tolerance: float) -> float:
    """How far from a ball centre a surface point still counts as cut (module notes): the corner
    of three faces at right angles round a ball touching them, r * sqrt(3), across the gap of
    ball positions a roughing step or a stepover apart, plus the tolerance."""
    step = max(roughing_step, stepover)
    return math.sqrt(3.0 * radius * radius + 0.25 * step * step) + tolerance


def on_stock_surface(vertices: np.ndarray, faces: np.ndarray, stock, tolerance: float) -> np.ndarray:
    """(m,) bool: the face's three vertices lie on one face of the bar (its outside, its end face,
    its chuck-side face), within ``tolerance``."""
    tri = vertices[faces]
    rho = np.hypot(tri[..., 0], tri[..., 1])
    z = tri[..., 2]
    return (np.all(np.abs(rho - stock.radius) <= tolerance, axis=1)
            | np.all(np.abs(z - stock.z_max) <= tolerance, axis=1)
            | np.all(np.abs(z - stock.z_min) <= tolerance, axis=1))


def reached(points: np.ndarray, centres: np.ndarray, distance: float) -> np.ndarray:
    """(k,) bool: some centre lies within ``distance`` of the point (a hash grid of cell
    ``distance``: only the 27 cells round a point's own are searched)."""
    found = np.zeros(len(points), bool)
    if not len(points) or not len(centres):
        return found
    origin = centres.min(axis=0) - distance
    cell = np.floor((centres - origin) / distance).astype(np.int64)
    shape = cell.max(axis=0) + 3
    key = (cell[:, 0] * shape[1] + cell[:, 1]) * shape[2] + cell[:, 2]
    order = np.argsort(key, kind="stable")
    key, sorted_centres = key[order], centres[order]
    offsets = np.array([(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)])
    offsets = offsets[np.argsort(np.abs(offsets).sum(axis=1), kind="stable")]   # own cell first: most stop there
    limit = distance * distance
    for begin in range(0, len(points), SAMPLE_CHUNK):
        chunk = points[begin:begin + SAMPLE_CHUNK]
        hit = np.zeros(len(chunk), bool)
        base = np.floor((chunk - origin) / distance).astype(np.int64)
        for offset in offsets:
            todo = np.flatnonzero(~hit)
            if not len(todo):
                break
            c = base[todo] + offset
            inside = np.all((c >= 0) & (c < shape), axis=1)
            todo, c = todo[inside], c[inside]
            k = (c[:, 0] * shape[1] + c[:, 1]) * shape[2] + c[:, 2]
            start, stop = np.searchsorted(key, k, "left"), np.searchsorted(key, k, "right")
            count = stop - start
            if not count.sum():
                continue
            owner = np.repeat(todo, count)
            index = np.repeat(start - np.cumsum(count) + count, count) + np.arange(int(count.sum()))
            gap = sorted_centres[index] - chunk[owner]
            close = np.einsum("ij,ij->i", gap, gap) <= limit
            hit[owner[close]] = True
        found[begin:begin + len(chunk)] = hit
    return found


def unreached_faces(vertices, faces, candidates: np.ndarray, centres: np.ndarray, distance: float,
                    spacing: float) -> np.ndarray:
    """The candidate face ids with a sample point no ball centre comes within ``distance`` of."""
    if not len(candidates):
        return candidates
    points, owner = face_samples(vertices[faces[candidates]], spacing)
    missed = ~reached(points, centres, distance)
    bad = np.zeros(len(candidates), bool)
    bad[owner[missed]] = True
    return candidates[bad]


def features(vertices: np.ndarray, faces: np.ndarray, ids: np.ndarray) -> list:
    """The faces ``ids`` grouped by shared edges into :class:`SkippedFeature` s, largest first."""
    ids = np.asarray(ids, np.int64)
    if not len(ids):
        return []
    sub = faces[ids]
    edges = np.sort(sub[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    owner = np.repeat(np.arange(len(ids)), 3)
    edge_key = edges[:, 0] * (int(faces.max()) + 1) + edges[:, 1]
    order = np.argsort(edge_key, kind="stable")
    same = np.flatnonzero(edge_key[order][1:] == edge_key[order][:-1])
    group = connected(len(ids), owner[order][same], owner[order][same + 1])
    _, areas = face_normals(vertices[sub])
    found = []
    for root in np.unique(group):
        members = np.flatnonzero(group == root)
        corners = vertices[sub[members]].reshape(-1, 3)
        rho = np.hypot(corners[:, 0], corners[:, 1])
        found.append(SkippedFeature(ids[members], float(areas[members].sum()), tuple(corners.min(axis=0)),
                                    tuple(corners.max(axis=0)), (float(rho.min()), float(rho.max()))))
    return sorted(found, key=lambda feature: (-feature.area, feature.lo[2]))


def notes(found: list) -> list:
    """Header lines naming what is not machined (the largest features one by one)."""
    if not found:
        return []
    count = sum(len(f.faces) for f in found)
    area = sum(f.area for f in found)
    lines = [f"NOT MACHINED: {count} faces, {area:.1f} mm2 in {len(found)} features neither tool reaches"]
    lines += [f"NOT MACHINED {k + 1}: {f.describe()}" for k, f in enumerate(found[:NOTE_FEATURES])]
    rest = found[NOTE_FEATURES:]
    if rest:
        lines.append(f"NOT MACHINED: {len(rest)} more features, {sum(len(f.faces) for f in rest)} faces, "
                     f"{sum(f.area for f in rest):.1f} mm2")
    return lines
