"""What every NC export operator shares: the post chosen in the file browser (the job's preferred
post at first: the scene's for milling, the panel's where the job has its own), the file name from
the output folder, the scene and the post's extension, and the export (through the gate, with the
panel's override) reported back."""
from __future__ import annotations

import inspect
import os
from dataclasses import dataclass, field

import bpy
from bpy_extras.io_utils import ExportHelper

from .. import post as posts
from ..post.capacity import program_findings
from ..post.output import write_atomic
from .common import SteppedOperator
from .preferences import scene_output_dir, scene_post
from .plancache import replanned_message
from .translations import translate_message


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
class Exported:
    """What an export's work returns: the written ``path``, the operation names re-planned (None:
    the export does not plan through the scene's plans), what the machine cannot take of the
    program (``findings``), and ``then(scene)``: what to record in the scene afterwards (on the
    main thread), or None."""

    path: str
    replanned: list | None = None
    findings: list = field(default_factory=list)
    then: object = None


def stages(progress, share: float = 0.5) -> tuple:
    """(planning's progress, the gate's progress): ``progress`` split at ``share``; a stage's call
    returns what ``progress`` returns (False or JobCancelled: cancelled)."""
    if progress is None:
        return None, None
    return (lambda f, text="": progress(share * f, text or "planning"),
            lambda f, text="": progress(share + (1 - share) * f, text or "checking"))


def milling_export_request(scene, post_name: str, target: str, families, compute, export):
    """A milling workflow's panel export (engrave, carve): the Machine & Stock settings read here
    (main thread); ``work(progress) -> Exported`` runs ``compute(planning)`` (the workflow's plan)
    and ``export(job, post_name, target, work_offset, allow=, orient_spindle=, machine=, findings=,
    progress=)`` without touching Blender data."""
    from .machines import scene_machine

    machine = scene.kezuri.machine
    offset, orient = machine.work_offset, machine.orient_spindle
    allow, profile = scene.kezuri.simulation.acknowledged, scene_machine(machine, families, post_name)

    def work(progress=None) -> Exported:
        planning, checking = stages(progress)
        job, findings = compute(planning), []
        written = export(job, post_name, target, offset, allow=allow, orient_spindle=orient, machine=profile,
                         findings=findings, progress=checking)
        return Exported(written, job.replanned, findings)
    return work


class NCExport(SteppedOperator, ExportHelper):
    """Mixed into an ExportHelper operator with a ``post`` enum of ``post_families``.  The operator
    sets ``file_suffix`` and implements ``export_request(context)``: it reads the scene (main thread)
    and returns ``compute(progress) -> Exported``, which plans, checks through the gate and writes
    the file without touching Blender data.  After the file browser (or from the job list's button)
    the work runs in steps with a progress bar and Esc to cancel, as Generate does; a cancelled
    export writes nothing (the file is written after the last progress call).  From a script or in
    background mode it runs at once.  ``preferred_post`` names the post the file browser starts
    with (None: the enum's own default)."""

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

    def export_request(self, context):
        raise NotImplementedError

    def prepare(self, context):
        if not self.properties.is_property_set("post"):
            # run from a script without a post (invoke sets it from the file browser): the
            # job's own post, as the file browser would have started with, not the enum's default
            preferred = self.preferred_post(context)
            if preferred is not None:
                self.post = preferred
        return self.export_request(context)

    def execute(self, context):
        return self.start_stepped(context)

    def finish(self, context, exported: Exported):
        if exported.then is not None:
            exported.then(context.scene)
        self.report({"INFO"}, translate_message(f"Wrote {exported.path}"))
        if exported.replanned is not None:
            self.report({"INFO"}, translate_message(replanned_message(list(exported.replanned))))
        report_findings(self, exported.findings)
        return {"FINISHED"}
