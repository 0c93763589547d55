"""What a workflow gives the rest of the shell: one :class:`Workflow` per ``operators/<workflow>.py``.

The table of them is :mod:`.workflows`; registration, the Simulate panel and operator, batch's
commands and the demo loop over it, so adding a workflow is one core module, one operators module
exposing ``WORKFLOW``, one line in the table, and its tests.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable


@dataclass(frozen=True)
class SimulationSetup:
    """What the material-removal simulation of a job cuts: the program on its stock, with the
    workflow's design limits (``extra``: keyword arguments of ``toolpath.simulate.simulate``)."""

    program: object
    stock: object
    extra: dict
    frame: object          # convert.WorkFrame: where the work frame sits in the scene
    name: str


@dataclass(frozen=True)
class BatchCommand:
    """``batch.py <name> [options] --out DIR``: ``arguments(parser)`` adds the options,
    ``run(args)`` writes the files into ``args.out`` and returns the report (a dict)."""

    name: str
    help: str
    arguments: Callable
    run: Callable
    demo: tuple | None = ()     # the command line of the demo run (None: not in the demo)
    more_demos: tuple = ()      # further demo runs: (sub-folder, command line) pairs


@dataclass(frozen=True)
class Workflow:
    key: str                          # enum identifier ("ENGRAVE")
    label: str                        # "Engraving"
    description: str
    classes: tuple = ()               # Blender classes to register
    menus: tuple = ()                 # (menu, draw function) pairs
    post_families: tuple = ()         # which posts write its programs (post registry families)
    # (scene, depsgraph) -> compute(progress) -> job: read the scene, plan without touching Blender.
    request: Callable | None = None
    # job -> SimulationSetup: what the Simulate operator and the export gate cut.
    simulation: Callable | None = None
    commands: tuple = field(default_factory=tuple)
    button: str = ""                  # short text on the Simulate panel's button (default: label)
    kind: str = ""                    # its operation kind in the job model (toolpath/operations/<kind>)
    # (scene, depsgraph, jobfile.JobEntry, post name) -> (JobOperation, Setup or None, WorkFrame or None):
    # one operation of a job file, its objects and settings read from the scene.
    job_operation: Callable | None = None
    # the kind's settings as panel properties: a PropertyGroup class, registered as scene.kezuri.<kind>
    # (its property names, units and defaults those of the kind's job-file settings)
    settings_group: type | None = None
    # the job list's sub-panels for a row of the kind: ((label, (property names, ...)), ...), the first open
    settings_panels: tuple = ()

    @property
    def short_label(self) -> str:
        return self.button or self.label
