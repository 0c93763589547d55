"""Which tool reaches which face of a turn-mill part (seed 003, step 1 of :mod:`.turnmill`).

Each face gets area-weighted sample points.  Each point is lifted a little along the face normal
and casts a ray in the candidate direction: for the radial tool the point's position projected
onto XY, pointing away from the axis; for the axial tool +Z.  A face is reachable from a direction
when every sample faces it (normal . direction > 0) and no sample's ray hits the mesh; one blocked
sample turns the face down, as in the paper.  Labels are bit sets: NEITHER 0, RADIAL 1, AXIAL 2,
BOTH 3.
"""
from __future__ import annotations

import math

import numpy as np

from ...engines.meshrays import RayEngine, TrimeshRayEngine, check_mesh, face_normals, face_samples
from ...ir.program import TOOL_DIRECTIONS
from .errors import TurnMillError

NEITHER, RADIAL, AXIAL, BOTH = 0, 1, 2, 3      # face labels: bit 1 = radial, bit 2 = axial
LABEL_NAMES = ("neither", "radial", "axial", "both")
DIRECTIONS = TOOL_DIRECTIONS

FACING = 1e-6            # normal . direction above this counts as facing the tool
LIFT = 1e-4              # ray origins are lifted this fraction of the part size along the normal
RAY_BATCH = 50_000       # rays cast at once between progress reports


def classify_faces(vertices, faces, engine: RayEngine | None = None, sample_spacing: float = 2.0,
                   progress=None) -> np.ndarray:
    """Label each face NEITHER / RADIAL / AXIAL / BOTH ((m,) int8) by casting rays from its samples.
    ``progress``: optional callable(fraction, text), called between batches of rays."""
    v, f = check_mesh(vertices, faces)
    if not (isinstance(sample_spacing, (int, float)) and math.isfinite(sample_spacing) and sample_spacing > 0):
        raise TurnMillError(f"sample spacing must be a number > 0, got {sample_spacing!r}")
    engine = TrimeshRayEngine(v, f) if engine is None else engine
    triangles = v[f]
    normals, _ = face_normals(triangles)
    points, owner = face_samples(triangles, sample_spacing)
    n = normals[owner]
    origins = points + LIFT * float(np.ptp(v, axis=0).max()) * n

    rho = np.hypot(points[:, 0], points[:, 1])
    radial = np.zeros_like(points)
    on_axis = rho <= 1e-9
    radial[~on_axis, :2] = points[~on_axis, :2] / rho[~on_axis, None]
    axial = np.broadcast_to(np.array([0.0, 0.0, 1.0]), points.shape)

    labels = np.zeros(len(f), dtype=np.int8)
    for half, (bit, directions) in enumerate(((RADIAL, radial), (AXIAL, axial))):
        facing = np.einsum("ij,ij->i", n, directions) > FACING
        report = None if progress is None else \
            (lambda fraction, half=half: progress((half + fraction) / 2, f"casting {DIRECTIONS[half]} rays"))
        labels[_reachable(engine, origins, directions, facing, owner, len(f), report)] |= bit
    return labels


def _reachable(engine, origins, directions, facing, owner, face_count, progress=None) -> np.ndarray:
    """Faces all of whose samples face the direction and see out along it unblocked."""
    samples = np.bincount(owner, minlength=face_count)
    all_facing = np.bincount(owner, weights=(~facing).astype(float), minlength=face_count) == 0
    cast = np.flatnonzero(all_facing[owner])
    hits = []
    for start in range(0, len(cast), RAY_BATCH):
        batch = cast[start:start + RAY_BATCH]
        batch_hits = np.asarray(engine.intersects_any(origins[batch], directions[batch]))
        if batch_hits.shape != (len(batch),):
            raise TurnMillError(f"the ray engine returned {batch_hits.shape} results for {len(batch)} rays")
        hits.append(batch_hits)
        if progress is not None:
            progress(min(1.0, (start + len(batch)) / len(cast)))
    hits = np.concatenate(hits) if hits else np.zeros(0, bool)
    blocked = np.bincount(owner[cast], weights=hits.astype(bool).astype(float), minlength=face_count)
    return (samples > 0) & all_facing & (blocked == 0)


def path_faces(vertices, faces, labels) -> tuple[np.ndarray, np.ndarray]:
    """(radial face ids, axial face ids) to machine.  A face labelled BOTH goes to the direction
    it faces more squarely (at its centroid), so it is cut once."""
    v, f = check_mesh(vertices, faces)
    labels = np.asarray(labels)
    if labels.shape != (len(f),) or not np.all(np.isin(labels, (NEITHER, RADIAL, AXIAL, BOTH))):
        raise TurnMillError(f"labels must be {len(f)} values from NEITHER, RADIAL, AXIAL, BOTH")
    triangles = v[f]
    normals, _ = face_normals(triangles)
    centre = triangles.mean(axis=1)
    rho = np.maximum(np.hypot(centre[:, 0], centre[:, 1]), 1e-12)
    radial_facing = (normals[:, 0] * centre[:, 0] + normals[:, 1] * centre[:, 1]) / rho
    radial = (labels == RADIAL) | ((labels == BOTH) & (radial_facing >= normals[:, 2]))
    axial = (labels == AXIAL) | ((labels == BOTH) & ~radial)
    return np.flatnonzero(radial), np.flatnonzero(axial)
