"""What every NC export operator shares: the post chosen in the file browser (the job's preferred
post at first: the scene's for milling, the panel's where the job has its own), the file name from
the output folder, the scene and the post's extension, and the export (through the gate, with the
panel's override) reported back."""
from __future__ import annotations

import dataclasses
import inspect
import os
import secrets
from dataclasses import dataclass, field

import bpy
from bpy.props import BoolProperty
from bpy_extras.io_utils import ExportHelper

from .. import post as posts
from ..post.capacity import program_findings
from ..post.output import OutputError, Staging, write_atomic
from .common import SteppedOperator
from .preferences import scene_output_dir, scene_post
from .plancache import replanned_message
from .translations import interface_language, translate_message


def spindle_options(families, post_name: str, orient: bool, given_as: str = "Orient Spindle (M19)") -> dict:
    """The post's keyword for Machine & Stock's Orient Spindle (M19): only the posts that write
    M19 before a tool change (the Fanuc ones) take it; any other refuses it, naming where it
    was given (the check box, or batch's --orient-spindle), rather than write a program without it."""
    if not orient:
        return {}
    if "orient_spindle" not in inspect.signature(posts.find(families, post_name).__init__).parameters:
        raise posts.PostError(f"{given_as}: the {post_name} post does not write M19 before a tool change; "
                              f"pick a Fanuc post or switch it off")
    return {"orient_spindle": True}


def machine_post(families, post_name: str, work_offset: str | None, orient_spindle: bool = False, machine=None):
    """The post ``post_name`` set up for the machine: its work offset, M19 where asked, and the
    machine profile its frames are written for (None: the post's own default machine)."""
    options = {} if machine is None else {"machine": machine}
    return posts.create(families, post_name, work_offset=work_offset,
                        **spindle_options(families, post_name, orient_spindle), **options)


def orient_spindle_argument(parser) -> None:
    """Batch's ``--orient-spindle`` (Machine & Stock's check box)."""
    parser.add_argument("--orient-spindle", action="store_true",
                        help="Fanuc posts: M19 before each tool change (other posts refuse it)")


def batch_orient_spindle(args, scene, families, post_name: str) -> None:
    """Batch, before any work: ``--orient-spindle`` (or the .blend's check box) against the post."""
    machine = scene.kezuri.machine
    if args.orient_spindle:
        machine.orient_spindle = True
    spindle_options(families, post_name, machine.orient_spindle,
                    "--orient-spindle" if args.orient_spindle else "Orient Spindle (M19) of the .blend")


def write_program(path: str, text: str, post, findings: list | None = None) -> str:
    """Write the NC text (atomically); what the machine cannot take of it (``post.capacity``: a
    program larger than its memory, blocks shorter than its block time) is added to ``findings``.
    Only a program the control stores is measured, one with a program number (O0001): a program
    streamed from disk (LinuxCNC, GRBL) is not, as the turn-mill workflow's own exports do
    (:func:`.turnmill.machine_findings`); the LinuxCNC turn-mill post on its default machine, the
    Fanuc 0i-T, was told its program passes the 0i-T's 512 kB."""
    if findings is not None and getattr(post, "program_number", None):
        findings += program_findings(text, post.machine, f"the {post.name} program")
    return write_atomic(path, text)


def warn(findings, report: dict) -> None:
    """Batch: the machine's findings printed and added to the report's warnings."""
    import sys

    for finding in findings:
        print(f"kezuri: warning: {finding}", file=sys.stderr)
    report["warnings"] = list(report.get("warnings") or []) + list(findings)


def report_findings(operator, findings) -> None:
    """Show what the program leaves out or the machine cannot take (``post.capacity``'s findings,
    faces not machined) as warnings in the panel's report."""
    for finding in findings:
        operator.report({"WARNING"}, translate_message(finding))


@dataclass
class ProgramSheet:
    """What the setup sheet beside a panel's program shows, as the workflow's batch sheet does:
    the IR ``program`` written, the gate's ``gate`` report, the ``machine`` profile (None: the
    post's own), the post's ``post`` label, the batch report's ``workflow`` name (the sheet's
    title "<workflow>: <program>"), the workflow's ``warnings`` (before the findings on the
    written program), the feeds check's ``feeds`` entries ([] with no material) and
    ``pictures() -> [(caption, PNG bytes)]``: the pictures as batch draws them (the toolpaths),
    called only when the sheet is written, on the export's worker (None: no pictures)."""

    program: object
    gate: dict | None
    machine: object
    post: str
    workflow: str
    warnings: list = field(default_factory=list)
    feeds: list = field(default_factory=list)
    pictures: object = None


@dataclass
class Exported:
    """What an export's work returns: the written ``path``, the operation names re-planned (None:
    the export does not plan through the scene's plans), what the machine cannot take of the
    program (``findings``), and ``then(scene)``: what to record in the scene afterwards (on the
    main thread), or None; ``sheet``: what its setup sheet shows (None: it writes none)."""

    path: str
    replanned: list | None = None
    findings: list = field(default_factory=list)
    then: object = None
    sheet: ProgramSheet | None = None


def stages(progress, share: float = 0.5) -> tuple:
    """(planning's progress, the gate's progress): ``progress`` split at ``share``; a stage's call
    returns what ``progress`` returns (False or JobCancelled: cancelled)."""
    if progress is None:
        return None, None
    return (lambda f, text="": progress(share * f, text or "planning"),
            lambda f, text="": progress(share + (1 - share) * f, text or "checking"))


def milling_export_request(scene, post_name: str, target: str, families, compute, export, workflow: str):
    """A milling workflow's panel export (engrave, carve): the Machine & Stock settings read here
    (main thread); ``work(progress) -> Exported`` runs ``compute(planning)`` (the workflow's plan)
    and ``export(job, post_name, target, work_offset, allow=, orient_spindle=, machine=, findings=,
    progress=, sheet=)`` without touching Blender data; ``export`` fills the ``sheet`` dict with the
    ``program`` written, the ``gate`` report, the ``machine`` and the workflow's ``warnings``, and
    the feeds are checked here in the scene's material, as batch ``workflow`` checks them."""
    from .machines import scene_machine
    from .workflowfeeds import panel_check

    machine = scene.kezuri.machine
    offset, orient = machine.work_offset, machine.orient_spindle
    allow, profile = scene.kezuri.simulation.acknowledged, scene_machine(machine, families, post_name)
    feeds_check, label = panel_check(scene), posts.find(families, post_name).label

    def work(progress=None) -> Exported:
        planning, checking = stages(progress)
        job, findings, sheet = compute(planning), [], {}
        written = export(job, post_name, target, offset, allow=allow, orient_spindle=orient, machine=profile,
                         findings=findings, progress=checking, sheet=sheet)
        feeds = feeds_check(sheet["program"], sheet["machine"], findings)
        return Exported(written, job.replanned, findings,
                        sheet=ProgramSheet(sheet["program"], sheet["gate"], sheet["machine"], label, workflow,
                                           sheet["warnings"], feeds, sheet.get("pictures")))
    return work


class BesideStaging(Staging):
    """:class:`~..post.output.Staging` for one panel export: a hidden folder beside ``target``,
    named here and made by the first file written into it (so an export cancelled before its work
    starts leaves nothing behind)."""

    def __init__(self, target: str):
        self.out = os.path.dirname(os.path.abspath(target))
        self.folder = os.path.join(self.out, f".kezuri-staging-{secrets.token_hex(4)}")


def program_and_sheet(request, target: str, language: str | None):
    """A panel export's work, its program and its setup sheet written all or none.

    ``request(path)`` is the workflow's ``work(progress) -> Exported`` writing its program to
    ``path``; here ``path`` lies in a hidden folder beside ``target``.  The work writes the program
    there, the sheet (``<program>-setup-sheet.html``, in ``language``: "en", "ja"; None: no sheet)
    is written there from the program as written, and only then are both moved beside each other
    at ``target`` (a folder in the way of either is found before the first moves).  A failure, a
    refusal by the gate or Esc removes the folder and leaves ``target``'s folder as it was.  Runs
    ``request`` and reads the tool library (for the tools' stick-out) here, on the main thread."""
    from .batchio import write_program_sheet
    from .toolstore import library_or_none, stick_outs

    target = os.path.abspath(target)
    staging = BesideStaging(target)
    staged = os.path.join(staging.folder, os.path.basename(target))
    work = request(staged)
    library = library_or_none() if language else None

    def run(progress=None) -> Exported:
        try:
            exported = work(progress)
            if os.path.abspath(exported.path) != staged:
                raise RuntimeError(f"the export wrote {exported.path}, not {staged}")
            sheet = exported.sheet
            if language and sheet is not None:
                report = {"gate": sheet.gate, "feeds": list(sheet.feeds),
                          "warnings": list(sheet.warnings) + list(exported.findings)}
                program = (sheet.gate or {}).get("program") or sheet.program.name
                write_program_sheet(staged, sheet.program, report, sheet.machine, sheet.post, language,
                                    job_name=f"{sheet.workflow}: {program}",
                                    stick_out=stick_outs(sheet.program.summary(), library),
                                    pictures=sheet.pictures() if sheet.pictures is not None else ())
            staging.commit()
        except OutputError as error:        # named by the paths the user gave, not the hidden folder's
            raise OutputError(staging.final(str(error))) from None
        finally:
            staging.discard()
        # the pictures' drawing let go (it holds the gate's height field) once the sheet is written
        sheet = exported.sheet and dataclasses.replace(exported.sheet, pictures=None)
        return dataclasses.replace(exported, path=target, findings=staging.final(list(exported.findings)), sheet=sheet)
    return run


SHEET_DESCRIPTION = ("Also write <program>-setup-sheet.html beside the program, in the interface language: the "
                     "machine, stock and work zero, tools, operations, feeds and the export gate's result")


class NCExport(SteppedOperator, ExportHelper):
    """Mixed into an ExportHelper operator with a ``post`` enum of ``post_families``.  The operator
    sets ``file_suffix`` and implements ``export_request(context, path)``: it reads the scene (main
    thread) and returns ``compute(progress) -> Exported``, which plans, checks through the gate and
    writes the program to ``path`` without touching Blender data.  ``path`` is a staged one
    (:func:`program_and_sheet`): the program and its setup sheet (``setup_sheet``, on by default)
    are moved beside each other at ``filepath`` together.  After the file browser (or from the job list's button)
    the work runs in steps with a progress bar and Esc to cancel, as Generate does; a cancelled
    export writes nothing (the file is written after the last progress call).  From a script or in
    background mode it runs at once.  ``preferred_post`` names the post the file browser starts
    with (None: the enum's own default)."""

    setup_sheet: BoolProperty(name="Setup Sheet", default=True, description=SHEET_DESCRIPTION)

    file_suffix = ""
    post_families: tuple = ("milling",)
    progress_label = "export"

    def preferred_post(self, context) -> str | None:
        return scene_post(context.scene, context)

    def extension_for(self, post_name: str) -> str:
        return posts.extension(self.post_families, post_name)

    def invoke(self, context, event):
        preferred = self.preferred_post(context)
        if preferred is not None:
            try:
                self.post = preferred
            except TypeError:      # not one of this job's posts: the job's own default stays
                pass
        self.filename_ext = self.extension_for(self.post)
        folder = scene_output_dir(context.scene, context)
        name = bpy.path.clean_name(context.scene.name) + self.file_suffix + self.filename_ext
        self.filepath = os.path.join(folder, name)
        return ExportHelper.invoke(self, context, event)

    def check(self, context):
        self.filename_ext = self.extension_for(self.post)
        return ExportHelper.check(self, context)

    def export_request(self, context, path: str):
        raise NotImplementedError

    def prepare(self, context):
        if not self.properties.is_property_set("post"):
            # run from a script without a post (invoke sets it from the file browser): the
            # job's own post, as the file browser would have started with, not the enum's default
            preferred = self.preferred_post(context)
            if preferred is not None:
                self.post = preferred
        language = interface_language() if self.setup_sheet else None
        return program_and_sheet(lambda path: self.export_request(context, path), self.filepath, language)

    def execute(self, context):
        return self.start_stepped(context)

    def finish(self, context, exported: Exported):
        if exported.then is not None:
            exported.then(context.scene)
        self.report({"INFO"}, translate_message(f"Wrote {exported.path}"))
        if self.setup_sheet and exported.sheet is not None:
            from .batchio import SHEET_NAME
            sheet = os.path.splitext(exported.path)[0] + "-" + SHEET_NAME
            self.report({"INFO"}, translate_message(f"Wrote {sheet}"))
        if exported.replanned is not None:
            self.report({"INFO"}, translate_message(replanned_message(list(exported.replanned))))
        report_findings(self, exported.findings)
        return {"FINISHED"}
