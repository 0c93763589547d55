"""An ISO 14649 (STEP-NC) workplan as an operation kind of the job model: the file's workingsteps,
in the order to cut and without those switched off, become its IR operations (:mod:`.workplan`)."""
from __future__ import annotations

from dataclasses import dataclass, field

from ...job import OperationKind, Part
from ... import workload
from .errors import StepNcError
from .solids import fixture_clearance, stock_box
from .workplan import LoadedWorkplan, nothing_to_machine, skipped_workingsteps, to_program, workplan_from_text


@dataclass(frozen=True)
class StepncGeometry:
    """The workplan: the ISO 14649 file's Part 21 text (the file is the source of truth; the plan
    reads it afresh), and ``loaded``, that text already read by the caller (None: the plan reads
    it; a big file of explicit toolpaths takes seconds to read)."""

    text: str
    loaded: LoadedWorkplan | None = field(default=None, compare=False, repr=False, metadata={"derived": True})


@dataclass(frozen=True)
class StepncSettings:
    """What the workplan list sets: ``order``, the workingstep instance ids in the order to cut
    (every workingstep once; None: the workplan's order); ``enabled``, the ids to cut (None: all)."""

    order: tuple | None = None
    enabled: tuple | None = None


@dataclass(frozen=True)
class StepncOutcome:
    """The workplan as the shell shows and reports it: ``loaded`` (the file read), ``program``
    (its workingsteps planned, notes: the file's warnings and the plan's), ``fixture_clearance``
    (how far below the stock's bottom the workplan's through holes take a tool, for the gate)."""

    loaded: LoadedWorkplan
    program: object
    fixture_clearance: float


class StepncKind(OperationKind):
    key = "stepnc"
    label = "STEP-NC Workplan"
    families = ("milling",)
    settings_type = StepncSettings

    def workload(self, setup, settings, geometry: StepncGeometry) -> list:
        return workload.stepnc(setup.name, len(geometry.text))

    def plan(self, setup, settings: StepncSettings, geometry: StepncGeometry, progress=None) -> Part:
        report = progress or (lambda fraction, text="": None)
        report(0.0, "reading")
        loaded = geometry.loaded if geometry.loaded is not None else workplan_from_text(geometry.text)
        if not loaded.workingsteps:
            raise StepNcError(nothing_to_machine(loaded.warnings))
        if settings.enabled is not None and not settings.enabled:
            raise StepNcError("every workingstep is switched off: nothing to export")
        program = to_program(loaded, order=settings.order, enabled=settings.enabled, name=setup.name,
                             progress=lambda fraction, text="": report(0.1 + 0.9 * fraction, text))
        if not program.operations:
            raise StepNcError(nothing_to_machine(program.notes))
        program.work_offset, program.rapid_rate = setup.work_offset, setup.rapid_rate
        outcome = StepncOutcome(loaded, program, fixture_clearance(loaded))
        # no design layer: the gate checks the workplan's cuts against its stock and the fixture clearance
        return Part(tuple(program.operations), stock_box(loaded, program), None, tuple(program.notes),
                    tuple(skipped_workingsteps(program.notes)), None, outcome,
                    fixture_clearance=outcome.fixture_clearance)
