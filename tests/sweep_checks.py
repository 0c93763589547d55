"""Independent checks of swept solids for the manifold engine's tests: how far points lie
outside the exact sweep of a ball along a level polyline, and points sampled on a solid's surface
(numpy only: nothing of the engine under test)."""
from __future__ import annotations

import numpy as np


def depth_outside_ball_sweep(vertices, tips, r):
    """How far each point lies outside ball + shank swept along the level tip polyline (exact:
    distance to the centre segments, and the shank above them)."""
    centres = tips + [0, 0, r]
    a, b = centres[:-1], centres[1:]
    worst = np.zeros(len(vertices))
    for start in range(0, len(vertices), 2000):
        v = vertices[start:start + 2000, None, :]
        d = b - a
        t = np.clip(np.einsum("vsk,sk->vs", v - a, d) / np.einsum("sk,sk->s", d, d), 0, 1)
        near = a + t[..., None] * d
        ball = np.linalg.norm(v - near, axis=2) - r
        shank = np.where(v[..., 2] >= near[..., 2], np.linalg.norm((v - near)[..., :2], axis=2) - r, np.inf)
        worst[start:start + 2000] = np.min(np.minimum(ball, shank), axis=1)
    return worst


def surface_samples(solid, per_triangle=3, seed=1):
    """Random points on every triangle of the solid (and its vertices)."""
    mesh = solid.to_mesh()
    v = np.asarray(mesh.vert_properties, float)[:, :3]
    t = v[np.asarray(mesh.tri_verts)]
    w = np.random.default_rng(seed).dirichlet(np.ones(3), size=(len(t), per_triangle))
    return np.vstack([v, np.einsum("tsk,tkd->tsd", w, t).reshape(-1, 3)])
