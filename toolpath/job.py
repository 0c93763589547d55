"""The job: one piece of stock on one machine, an ordered list of operations, one program.

A :class:`Job` is a :class:`Setup` (machine profile, post, work offset, stock) and an ordered
list of :class:`JobOperation` (an operation kind's key, a name, the kind's settings, its geometry
in work mm, and whether it is switched on).  Each operation kind (one package under
``operations/``) subclasses :class:`OperationKind`; declaring the class registers it under its
``key``, as posts register themselves.  ``plan(setup, settings, geometry, progress)`` returns a
:class:`Part`: its IR operations (one per tool), warnings, the items it skipped, the stock it
works on and its **design layer** (what the finished part must keep where it cut).

:func:`plan_job` plans the switched-on operations in order.  Each operation's fingerprint hashes
its kind, name, settings and geometry, the setup, and the fingerprint of the operation before it
(the stock it starts from), so with a ``cache`` (fingerprint -> Part) changing one operation
re-plans it and those after it and nothing before; the result says which were re-planned.
:meth:`PlannedJob.program` puts the parts' operations into one Program (tool numbers checked
across the job: one number, one tool) and :meth:`PlannedJob.simulation` gives the export gate the
whole program on the job's stock with the design layers laid in order (a later layer replaces
what earlier ones said inside its area).
"""
from __future__ import annotations

import dataclasses
import hashlib
import importlib
import importlib.util
import pkgutil
import time
from dataclasses import dataclass, field

import numpy as np

from .engines import region as rg
from .ir.errors import InputError
from .ir.program import Program


class JobError(InputError):
    """A job that cannot be planned as given: the message names the operation and what is wrong."""


@dataclass(frozen=True)
class Setup:
    """Where the job runs: ``machine`` (a MachineProfile or None: the post's own), ``post`` (its
    name), the work offset, the rapid rate for time estimates, the stock (a BoxStock or
    CylinderStock in work mm; None: the first operation's own stock) and its ``material`` (a key
    of ``feeds.materials.MATERIALS``, "" for none: the feeds are then not checked; it does not
    change a plan, so it is not part of the fingerprints); ``feeds``: the records of the feeds the
    calculator gave the operations' settings (``feeds.operationfeeds``; the settings hold the
    values, so it is not part of the fingerprints either)."""

    name: str = "job"
    post: str = ""
    machine: object = None
    work_offset: str = "G54"
    rapid_rate: float = 5000.0
    stock: object = None
    material: str = ""
    feeds: tuple = ()


@dataclass(frozen=True)
class DesignLayer:
    """What the finished part must keep where an operation cut: ``design`` (a number: a floor
    plane; a function z(x, y); a mesh with vertices and faces) and ``keep_regions`` (loops, or
    (loops, z_min) pairs, nothing cut inside), as :func:`simulate.simulate` takes them; ``area``:
    the loops (work mm, even-odd) the layer speaks for, None for the whole stock."""

    design: object = None
    keep_regions: tuple = ()
    area: tuple | None = None

    def limits(self) -> dict:
        """The layer as keyword arguments of ``simulate.simulate``."""
        extra = {}
        if self.design is not None:
            extra["design"] = self.design
        if self.keep_regions:
            extra["keep_regions"] = list(self.keep_regions)
        return extra


@dataclass(frozen=True)
class Part:
    """What one operation of the job planned.

    ``operations``: IR operations as they are cut; ``macro_operations``: the same for a post
    that honours the IR's texture request (the untextured path), None when there is no such
    variant.  ``stock``: the stock the part works on; ``design``: its :class:`DesignLayer`;
    ``result``: the kind's own result (what the shell shows and reports); ``notes``: what the
    program's header says of it (None: its warnings); ``fixture_clearance``: how far below the
    stock's bottom its tools may go (a drill breaking through onto a spoil board)."""

    operations: tuple
    stock: object
    design: DesignLayer | None = None
    warnings: tuple = ()
    skipped: tuple = ()
    macro_operations: tuple | None = None
    result: object = None
    seconds: float = 0.0
    notes: tuple | None = None          # the program header's notes (None: the warnings)
    fixture_clearance: float = 0.0      # how far below the stock's bottom it may cut (a drill through)
    post_options: tuple = ()            # (name, value) pairs the post is made with (a table's top speed)


class OperationKind:
    """An operation kind: subclass with ``key``, ``label``, ``families`` (the machine families
    whose posts write it) and ``settings_type``, and implement :meth:`plan`; declaring the
    subclass in ``operations/<kind>/kind.py`` is all it takes (:func:`kinds`)."""

    key = ""
    label = ""
    families: tuple = ()
    settings_type: type = object

    def plan(self, setup: Setup, settings, geometry, progress=None) -> Part:
        raise NotImplementedError

    def workload(self, setup: Setup, settings, geometry) -> list:
        """The estimates of :mod:`toolpath.workload` for this operation, made from its settings and
        the size of its geometry before any planning; an estimate past its limit raises
        :class:`~toolpath.workload.WorkloadError`.  Default: nothing to estimate."""
        return []


def kinds() -> dict:
    """Every declared operation kind by key: each package under ``operations/`` declares its kind
    in its ``kind`` module, imported here (the folder is the list; nothing is registered anywhere:
    the kinds are the subclasses of :class:`OperationKind` that name a key)."""
    from . import operations
    for package in pkgutil.iter_modules(operations.__path__):
        if package.ispkg and importlib.util.find_spec(f"{operations.__name__}.{package.name}.kind") is not None:
            importlib.import_module(f"{operations.__name__}.{package.name}.kind")
    found, pending = {}, list(OperationKind.__subclasses__())
    while pending:
        cls = pending.pop()
        pending += cls.__subclasses__()
        if not cls.key:
            continue
        known = found.get(cls.key)
        if known is not None and (known.__module__, known.__qualname__) != (cls.__module__, cls.__qualname__):
            raise JobError(f"operation kind {cls.key!r} is declared twice")
        found[cls.key] = cls
    return found


def kind_of(key: str) -> OperationKind:
    known = kinds()
    if key not in known:
        raise JobError(f"unknown operation kind {key!r}; the kinds are {', '.join(sorted(known))}")
    return known[key]()


@dataclass(frozen=True)
class JobOperation:
    kind: str
    name: str
    settings: object
    geometry: object
    enabled: bool = True


@dataclass(frozen=True)
class Job:
    setup: Setup
    operations: tuple = ()


# ----- fingerprints -------------------------------------------------------------------------------

def _feed(digest, value) -> None:
    """Hash a value: arrays by dtype, shape and bytes; dataclasses, mappings and sequences by parts
    (a dataclass field with ``metadata={"derived": True}`` is left out: the others make it)."""
    if isinstance(value, np.ndarray):
        digest.update(f"nd{value.dtype.str}{value.shape}".encode())
        digest.update(np.ascontiguousarray(value).tobytes())
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        digest.update(type(value).__qualname__.encode())
        for item in dataclasses.fields(value):
            if item.metadata.get("derived"):        # made from the other fields (a file's text read)
                continue
            digest.update(item.name.encode())
            _feed(digest, getattr(value, item.name))
    elif isinstance(value, dict):
        digest.update(b"{")
        for key in sorted(value, key=repr):
            _feed(digest, key)
            _feed(digest, value[key])
        digest.update(b"}")
    elif isinstance(value, (list, tuple)):
        digest.update(b"[" if isinstance(value, list) else b"(")
        for item in value:
            _feed(digest, item)
        digest.update(b"]")
    elif hasattr(value, "vertices") and hasattr(value, "faces"):
        _feed(digest, np.asarray(value.vertices))
        _feed(digest, np.asarray(value.faces))
    elif isinstance(value, (str, bytes, int, float, bool, type(None))):
        digest.update(repr(value).encode())
    elif isinstance(value, type):
        digest.update(value.__qualname__.encode())
    else:
        digest.update(repr(value).encode())


def fingerprint(setup: Setup, operation: JobOperation, before: str = "") -> str:
    """A hash of everything the operation's plan depends on: the setup, the operation (kind,
    name, settings, geometry) and ``before``, the fingerprint of the operation before it."""
    digest = hashlib.sha256()
    setup = dataclasses.replace(setup, material="", feeds=())    # the material checks the feeds, it plans nothing
    for value in (before, setup, operation.kind, operation.name, operation.settings, operation.geometry):
        _feed(digest, value)
    return digest.hexdigest()


# ----- planning -------------------------------------------------------------------------------------

@dataclass
class PlannedOperation:
    operation: JobOperation
    part: Part
    fingerprint: str
    replanned: bool


@dataclass
class PlannedJob:
    job: Job
    planned: list = field(default_factory=list)

    @property
    def parts(self) -> list:
        return [item.part for item in self.planned]

    def replanned(self) -> list:
        """Names of the operations planned by this call (the rest came from the cache)."""
        return [item.operation.name for item in self.planned if item.replanned]

    @property
    def warnings(self) -> list:
        return [warning for part in self.parts for warning in part.warnings]

    @property
    def stock(self):
        if self.job.setup.stock is not None:
            return self.job.setup.stock
        if not self.planned:
            raise JobError("the job has no operation switched on")
        return self.planned[0].part.stock

    def program(self, macro: bool = False) -> Program:
        """One Program of every part's operations in order; ``macro``: for a post that honours
        texture requests (the parts' macro variants where they have one)."""
        setup = self.job.setup
        operations = []
        for item in self.planned:
            part = item.part
            chosen = part.macro_operations if macro and part.macro_operations is not None else part.operations
            operations += list(chosen)
        check_tools(operations)
        notes = []
        for part in self.parts:
            for note in (part.warnings if part.notes is None else part.notes):
                if note not in notes:
                    notes.append(note)
        return Program(setup.name, operations, work_offset=setup.work_offset, rapid_rate=setup.rapid_rate,
                       notes=notes)

    def design_limits(self) -> dict:
        """The design layers laid in order, as keyword arguments of ``simulate.simulate``: one
        layer as it is; several as one function z(x, y) (each cell takes the last layer whose
        area holds it)."""
        clearance = max((part.fixture_clearance for part in self.parts), default=0.0)
        extra = {"fixture_clearance": clearance} if clearance > 0 else {}
        layers = [part.design for part in self.parts if part.design is not None]
        if not layers:
            return extra
        if len(layers) == 1:
            return {**layers[0].limits(), **extra}
        stock = self.stock
        top = float(getattr(stock, "z1", 0.0))      # a box's top; a cylinder stock's top face is z = 0
        return {"design": LaidDesign(tuple(layers), top), **extra}


    def simulation(self) -> tuple:
        """What the export gate cuts: (the whole program as cut, the job's stock, the design
        limits as keyword arguments of ``simulate.simulate``)."""
        return self.program(), self.stock, self.design_limits()


def check_tools(operations) -> None:
    """One number, one tool: two operations may not give one tool number to different tools."""
    seen = {}
    for op in operations:
        tool = op.tool
        known = seen.get(tool.number)
        if known is None:
            seen[tool.number] = (tool, op.name)
            continue
        other, where = known
        if (other.kind, other.diameter, other.corner_radius) != (tool.kind, tool.diameter, tool.corner_radius):
            raise JobError(f"tool number {tool.number} is the {other.describe()} in {where!r} but the "
                           f"{tool.describe()} in {op.name!r}: give one of them another tool number")


@dataclass(frozen=True)
class LaidDesign:
    """Design layers laid in order, read as a function z(x, y) on the simulation's cell grid: the
    lowest Z the finished part allows at each point, from the last layer whose area holds it
    (-inf where no layer speaks); every layer's keep regions stand over all (a hole drilled into
    an engraving's letter is a gouge of the letter)."""

    layers: tuple
    top: float = 0.0     # the stock's top: where a keep region without its own height is kept to

    def __call__(self, gx, gy):
        gx, gy = np.asarray(gx, float), np.asarray(gy, float)
        allowed = np.full(np.broadcast(gx, gy).shape, -np.inf)
        for layer in self.layers:
            inside = np.ones(allowed.shape, bool) if layer.area is None else _inside(layer.area, gx, gy)
            values = np.broadcast_to(_heights(layer.design, gx, gy), allowed.shape)
            allowed = np.where(inside, values, allowed)
        for layer in self.layers:       # what must stand stands, whatever a later layer cut around it
            for item in layer.keep_regions:
                loops, z_min = item if isinstance(item, tuple) else (item, self.top)
                allowed = np.where(_inside(loops, gx, gy), np.maximum(allowed, z_min), allowed)
        return allowed


def _heights(design, gx, gy):
    if design is None:
        return np.full(gx.shape, -np.inf)
    if callable(design):
        return np.asarray(design(gx, gy), float)
    if hasattr(design, "vertices") and hasattr(design, "faces"):
        raise JobError("a design mesh can only be the job's one design layer for now")
    return np.full(gx.shape, float(design))


def _inside(loops, gx, gy) -> np.ndarray:
    """Which points of the grid (gx, gy from meshgrid, ij order) lie inside the loops (even-odd)."""
    if not len(loops):                  # a layer that speaks for nowhere (e.g. a chamfer of holes only)
        return np.zeros(np.broadcast(gx, gy).shape, bool)
    area = rg.from_loops([np.asarray(loop, float) for loop in loops], "design area")
    if gx.ndim == 2 and gx.shape[0] and gx.shape[1] and np.all(gx == gx[:, :1]) and np.all(gy == gy[:1, :]):
        return rg.grid_inside(area, gx[:, 0], gy[0, :])
    return rg.contains_points(area, np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape)


def estimate_job(job: Job) -> list:
    """(kind, the :mod:`toolpath.workload` estimates) of every switched-on operation, its machine
    family and settings type checked, made before any planning; an operation past a limit is
    refused (its name in front of the message when the job has several)."""
    active = [op for op in job.operations if op.enabled]
    found = []
    for op in active:
        kind = kind_of(op.kind)
        family = getattr(job.setup.machine, "family", None)
        if family is not None and kind.families and family not in kind.families:
            raise JobError(f"operation {op.name!r} ({kind.label}) runs on {', '.join(kind.families)} machines, "
                           f"not on the job's {family} machine")
        if not isinstance(op.settings, kind.settings_type):
            raise JobError(f"operation {op.name!r}: settings must be {kind.settings_type.__name__}, "
                           f"got {type(op.settings).__name__}")
        try:
            found.append((kind, kind.workload(job.setup, op.settings, op.geometry)))
        except InputError as error:
            if len(active) == 1:
                raise
            raise JobError(f"operation {op.name!r}: {error}") from None
    return found


def plan_job(job: Job, cache: dict | None = None, progress=None) -> PlannedJob:
    """Plan the switched-on operations in order (see the module docstring).  ``cache``: a dict
    fingerprint -> Part, read and filled; ``progress(fraction, text)``, returning False cancels."""
    active = [op for op in job.operations if op.enabled]
    if not active:
        raise JobError("the job has no operation switched on")
    names = [op.name for op in job.operations]
    for name in names:
        if names.count(name) > 1:
            raise JobError(f"two operations are named {name!r}: give each operation its own name")
    planned = PlannedJob(job)
    kinds_of = [kind for kind, _ in estimate_job(job)]
    before = ""
    for index, (op, kind) in enumerate(zip(active, kinds_of)):
        key = fingerprint(job.setup, op, before)
        part = None if cache is None else cache.get(key)
        replanned = part is None
        if part is None:
            started = time.perf_counter()
            try:
                part = kind.plan(job.setup, op.settings, op.geometry, _share(progress, index, len(active)))
            except InputError as error:
                if len(active) == 1:        # a job of one operation: the message as the workflow gives it
                    raise
                raise JobError(f"operation {op.name!r}: {error}") from None
            part = dataclasses.replace(part, seconds=time.perf_counter() - started)
            if cache is not None:
                cache[key] = part
        planned.planned.append(PlannedOperation(op, part, key, replanned))
        before = key
    return planned


def _share(progress, index: int, count: int):
    if progress is None:
        return None

    def report(fraction, *text):
        return progress((index + min(max(float(fraction), 0.0), 1.0)) / count, *text)
    return report
