"""The export gate: a program is simulated on its stock before it is written, and a program the
simulation finds fault with (a gouge, a rapid into material, a plunge a tool cannot make, a cut
below the stock into the fixture, a cut with the spindle stopped, a move outside the travel, a
program wider or taller than the machine profile's travel or lifting Z above its reach) is
not written unless the user overrides it knowingly:

* in the panel, Simulate & Check lists the findings and offers "Write despite these findings";
  the override holds for exactly the findings it names (a different finding stops the export again);
* in batch, ``--allow-findings``; a refusal exits with status 3 (bad input is 2).

Either way the report records what was found and whether it was overridden.
"""
from __future__ import annotations

import time

from ..toolpath.ir import machine as machines
from ..toolpath import simulate as core
from ..toolpath.pictures.setupsheet import stock_entry
from ..toolpath.ir.errors import InputError
from . import simview

GATE_CELL = 0.1        # mm: the height field the gate cuts (the batch preview's cell)
GATE_COARSEST = 1.6    # mm: the coarsest the gate goes to on a stock too large for GATE_CELL
REFUSED_STATUS = 3     # batch's exit status when the gate refuses a program


class GateRefused(InputError):
    """The simulation found faults in the program; nothing was written."""

    def __init__(self, message: str, findings: list):
        super().__init__(message)
        self.findings = findings


def describe(finding) -> str:
    """One line per finding: the simulation's own message (operation, move, where, how deep)."""
    return finding.message


def finding_key(finding) -> str:
    """A finding as an override names it: its kind, operation and move (not its wording or the
    position, which the simulation's cell size shifts)."""
    return simview.gate_key(finding)


def signature(findings) -> str:
    """What an override acknowledges: the findings' keys, in order."""
    return "\n".join(finding_key(f) for f in findings)


def machine_findings(program, machine) -> list:
    """``travel`` findings where the program does not fit the machine profile (its extent along an
    axis beyond the travel, a Z above what the machine reaches): see :func:`machine.travel_problems`."""
    operations = getattr(program, "operations", program)
    return [core.Finding("travel", message, op, move)
            for op, move, message in machines.travel_problems(operations, machine)]


def check(setup, allow: bool | str = False, progress=None, machine=None):
    """Simulate ``setup`` (a workflow's :class:`SimulationSetup`) and decide; ``machine``: the
    machine profile every move must fit (:func:`machine_findings`).

    ``allow``: True (batch's ``--allow-findings``) overrides any findings; a string (the panel's
    acknowledged :func:`signature`) overrides exactly those findings.  Returns
    ``(simulation job, gate report)``; raises :class:`GateRefused` (nothing written) otherwise.
    """
    started = time.perf_counter()
    cell = GATE_CELL
    while True:     # a stock too large for 0.1 mm cells (a 1200 x 600 mm sign) is checked on coarser ones
        try:
            job = simview.run_setup(setup, "heightfield", cell, progress)
            break
        except core.CellTooFine as error:
            if cell * 2 > GATE_COARSEST:
                raise core.SimulationError(f"{setup.name}: the export gate simulates every program before writing "
                                           f"it, and cannot on this job's stock even at {cell:g} mm: {error}") from None
            cell *= 2
        except core.CellError as error:     # the cell is the gate's, not one the user gave: say whose
            raise core.SimulationError(f"{setup.name}: the export gate simulates every program on a {cell:g} mm "
                                       f"grid before writing it, and cannot on this job's stock: {error}") from None
    faults = core.blocking(job.result.findings)
    if machine is not None:
        faults += machine_findings(setup.program, machine)
    report = {"findings": [{"kind": f.kind, "operation": f.operation, "move": f.move, "message": f.message,
                            "depth_mm": None if f.depth_mm is None else round(float(f.depth_mm), 4)}
                           for f in faults],
              "overridden": False, "seconds": round(time.perf_counter() - started, 3), "cell_mm": cell,
              # what was checked: the setup sheet reads these
              "program": getattr(setup.program, "name", setup.name), "stock": stock_entry(setup.stock),
              "work_offset": getattr(setup.program, "work_offset", "")}
    if faults:
        acknowledged = allow is True or (isinstance(allow, str) and allow and allow == signature(faults))
        if not acknowledged:
            listed = "; ".join(describe(f) for f in faults[:5])
            more = f" (and {len(faults) - 5} more)" if len(faults) > 5 else ""
            raise GateRefused(f"not written: the simulation found {len(faults)} fault(s) in the {setup.name} "
                              f"program: {listed}{more}. Fix the job, or override knowingly "
                              f"(batch: --allow-findings; panel: Simulate & Check > Write despite these findings)",
                              faults)
        report["overridden"] = True
    return job, report


def allow_findings_argument(parser) -> None:
    """Batch's override of the gate, the same option on every command that writes a program."""
    parser.add_argument("--allow-findings", action="store_true",
                        help="write the program even if the simulation finds gouges, rapids into material ... "
                             "(the report records it)")
