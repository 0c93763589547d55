"""Engraving as an operation kind of the job model: the gouge-texture roughing, the band finishing
around the letters and the burr contour on a flat or curved plate (:mod:`.engrave`,
:mod:`.surface_engrave`)."""
from __future__ import annotations

from dataclasses import dataclass

from ...job import DesignLayer, OperationKind, Part
from ... import workload
from . import engrave, surface_engrave


@dataclass(frozen=True)
class EngraveGeometry:
    """The plate and the letters in work mm (the plate's top at Z = 0): ``plate_outline``, the
    plate face's closed loops; ``letters``, ((object name, (loop, ...)), ...); ``texts``, ((object
    name, its text), ...) of the Text objects; ``surface``, a surface_engrave.Surface for a curved
    plate or None; ``characters``, ((object name, character, index in its text, (loop, ...)), ...):
    the Text objects' characters one by one, to name those too fine for the tool."""

    plate_outline: tuple
    plate_thickness: float
    letters: tuple
    texts: tuple = ()
    surface: object = None
    characters: tuple = ()

    @property
    def letter_loops(self) -> list:
        return [loop for _, loops in self.letters for loop in loops]


@dataclass(frozen=True)
class EngraveOutcome:
    """The engraving as the shell shows and reports it: ``result`` (the plan, roughing untextured
    with its texture request), ``baked`` (the program with the texture applied), ``depths`` (the
    gouge depths in order), ``surface`` (the surface_engrave.SurfaceJob on a curved plate)."""

    result: engrave.EngraveResult
    baked: object
    depths: list
    surface: object = None


class EngraveKind(OperationKind):
    key = "engrave"
    label = "Engraving"
    families = ("milling",)
    settings_type = engrave.EngraveSettings

    def workload(self, setup, settings, geometry: EngraveGeometry) -> list:
        settings.validate()
        plate, _, _ = workload.outline_measures(geometry.plate_outline)
        _, letters, _ = workload.outline_measures(geometry.letter_loops)
        return workload.engrave(setup.name, plate, letters, settings)

    def plan(self, setup, settings, geometry: EngraveGeometry, progress=None) -> Part:
        outline = list(geometry.plate_outline)
        letters = [(name, list(loops)) for name, loops in geometry.letters]
        texts = dict(geometry.texts)
        thickness = float(geometry.plate_thickness)
        if geometry.surface is not None:
            curved = surface_engrave.plan(outline, letters, geometry.surface, settings, name=setup.name,
                                          progress=progress, plate_thickness=thickness, texts=texts,
                                          characters=list(geometry.characters))
            for program in (curved.result.program, curved.baked, curved.macro):
                program.work_offset, program.rapid_rate = setup.work_offset, setup.rapid_rate
                program.notes = list(curved.result.warnings)
            limits = surface_engrave.simulation_limits(geometry.surface, outline, geometry.letter_loops,
                                                       curved.result.program, settings.band_depth, -thickness)
            stock = surface_engrave.plate_stock(geometry.surface, outline, thickness)
            outcome = EngraveOutcome(curved.result, curved.baked, curved.depths, curved)
            macro = curved.macro
        else:
            result = engrave.plan(outline, letters, settings, name=setup.name, progress=progress,
                                  plate_thickness=thickness, texts=texts, characters=list(geometry.characters))
            result.program.work_offset = setup.work_offset
            result.program.rapid_rate = setup.rapid_rate
            result.program.notes = list(result.warnings)
            baked, depths = engrave.bake(result.program)
            limits = engrave.simulation_limits(geometry.letter_loops, result.program, settings.band_depth)
            stock = engrave.plate_stock(outline, thickness)
            outcome = EngraveOutcome(result, baked, depths)
            macro = result.program
        design = DesignLayer(limits.get("design"), tuple(limits.get("keep_regions", ())), tuple(outline))
        return Part(tuple(outcome.baked.operations), stock, design, tuple(outcome.result.warnings),
                    tuple(outcome.result.skipped), tuple(macro.operations), outcome)
