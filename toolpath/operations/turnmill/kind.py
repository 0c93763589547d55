"""Turn-mill as an operation kind of the job model: the faces classified by the tool directions that
reach them, then radial and axial roughing and finishing on the X-Z-C turn-mill centre
(:mod:`.turnmill`)."""
from __future__ import annotations

import time
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from ...engines.meshrays import TrimeshRayEngine, check_mesh, face_samples
from ...job import DesignLayer, OperationKind, Part
from ... import workload
from ...simulate import as_stock
from . import turnmill
from .turnreach import NEITHER, classify_faces


@dataclass(frozen=True)
class TurnMillGeometry:
    """The part and its bar in work mm: ``vertices`` (n, 3) and ``faces`` (m, 3) of the part mesh
    around the Z (C) axis; ``stock`` the round bar (:class:`turnmill.Stock`); ``selected`` a face
    mask (None: every face): unselected faces still block rays but get no paths and are not
    reported as not machined; ``engine`` what casts the rays: a class (or function) that takes
    (vertices, faces) and gives a RayEngine: the core's trimesh one by default, the shell's BVH
    one inside Blender."""

    vertices: np.ndarray
    faces: np.ndarray
    stock: turnmill.Stock
    selected: np.ndarray | None = None
    engine: object = TrimeshRayEngine


@dataclass(frozen=True)
class TurnMillOutcome:
    """The turn-mill plan as the shell shows and reports it: ``plan`` (the program, every face's
    label (unselected faces too), the layers, the skipped features), the checked mesh, the rays
    cast (two per sample) and the seconds the classification took."""

    plan: turnmill.TurnMillPlan
    vertices: np.ndarray
    faces: np.ndarray
    rays: int
    classification_seconds: float


def unmachined_warnings(plan: turnmill.TurnMillPlan) -> list:
    """One line for each feature no tool reaches (as in the NC header)."""
    return [f"not machined: {feature.describe()} (neither the radial nor the axial tool reaches it)"
            for feature in plan.skipped]


class TurnMillKind(OperationKind):
    key = "turnmill"
    label = "Turn-Mill"
    families = ("xzc",)
    settings_type = turnmill.TurnMillSettings

    def workload(self, setup, settings, geometry: TurnMillGeometry) -> list:
        try:
            vertices = np.asarray(geometry.vertices, float)
            faces = np.asarray(geometry.faces, np.int64)
        except (TypeError, ValueError):
            return []           # the plan refuses the mesh by name (check_mesh)
        if vertices.ndim != 2 or vertices.shape[1] != 3 or faces.ndim != 2 or faces.shape[1] != 3 \
                or not len(faces) or faces.min() < 0 or faces.max() >= len(vertices):
            return []
        triangles = vertices[faces]
        areas = np.linalg.norm(np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]),
                               axis=1) / 2.0
        return workload.turnmill(setup.name, areas, settings)

    def plan(self, setup, settings, geometry: TurnMillGeometry, progress=None) -> Part:
        report = progress or (lambda fraction, text="": None)
        vertices, faces = check_mesh(geometry.vertices, geometry.faces)
        engine = geometry.engine(vertices, faces)
        started = time.perf_counter()
        labels = classify_faces(vertices, faces, engine, settings.sample_spacing,
                                lambda fraction, text="": report(0.6 * fraction, text))
        seconds = time.perf_counter() - started
        samples, _ = face_samples(vertices[faces], settings.sample_spacing)
        selected = geometry.selected
        machined = labels if selected is None else np.where(selected, labels, NEITHER)
        result = turnmill.plan(vertices, faces, geometry.stock, settings, engine, labels=machined, name=setup.name,
                               progress=lambda fraction, text="": report(0.6 + 0.4 * fraction, text),
                               reported=selected)
        result.labels = labels
        outcome = TurnMillOutcome(result, vertices, faces, 2 * len(samples), seconds)
        design = DesignLayer(SimpleNamespace(vertices=vertices, faces=faces))
        return Part(tuple(result.program.operations), as_stock(geometry.stock), design,
                    tuple(unmachined_warnings(result)), tuple(result.skipped), None, outcome,
                    notes=tuple(result.program.notes))
