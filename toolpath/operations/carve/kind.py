"""Carving as an operation kind of the job model: Z-level roughing, the ball finishing raster, the
steep-region cleanup and the wall pass over a design mesh (:mod:`.carve`)."""
from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from ...job import DesignLayer, OperationKind, Part
from ... import workload
from ...engines.meshdata import inside_out
from ...simulate import BoxStock
from . import carve


@dataclass(frozen=True)
class CarveGeometry:
    """The design mesh in work mm (``vertices`` (n, 3), ``faces`` (m, 3)) and how far the stock's
    top stands above the design's highest point (``stock_above``, mm)."""

    vertices: np.ndarray
    faces: np.ndarray
    stock_above: float = 0.0


class CarveKind(OperationKind):
    key = "carve"
    label = "Carving"
    families = ("milling",)
    settings_type = carve.CarveSettings

    def workload(self, setup, settings, geometry: CarveGeometry) -> list:
        settings.check()
        vertices = np.asarray(geometry.vertices, float).reshape(-1, 3)
        vertices = vertices[np.isfinite(vertices).all(axis=1)]
        if not len(vertices):
            return []           # the plan refuses the mesh by name
        size = tuple(float(x) for x in vertices.max(axis=0) - vertices.min(axis=0))
        return workload.carve(setup.name, size, float(geometry.stock_above), settings)

    def plan(self, setup, settings, geometry: CarveGeometry, progress=None) -> Part:
        vertices, faces = carve.check_mesh(geometry.vertices, geometry.faces)
        flipped = inside_out(vertices, faces)      # the gate's rule (simulate.checks.check_design_mesh)
        if flipped:
            faces = faces[:, ::-1].copy()
        result = carve.plan(vertices, faces, settings, name=setup.name,
                            stock_top=float(vertices[:, 2].max()) + float(geometry.stock_above), progress=progress)
        if flipped:
            warning = "the design mesh was inside out (its normals pointed inward); its faces were flipped"
            result.warnings.insert(0, warning)
            result.program.notes.insert(0, warning)
        result.program.work_offset = setup.work_offset
        result.program.rapid_rate = setup.rapid_rate
        design = DesignLayer(SimpleNamespace(vertices=vertices, faces=faces))
        return Part(tuple(result.program.operations), BoxStock(*result.stock), design, tuple(result.warnings),
                    (), None, SimpleNamespace(result=result, vertices=vertices, faces=faces),
                    notes=tuple(result.program.notes))
