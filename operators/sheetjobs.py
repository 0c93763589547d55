"""The sheet-metal jobs the Sheet Metal panel, its exports and batch share: a twisted quad or a
pipe elbow unfolded, each flat pattern's turret-punch program planned and punched out of the
sheet (the simulation), the export gate on what it found, and the NC, DXF and SVG texts.  No
Blender data is read here: ``props`` is the scene's sheet settings or a copy of them, so an
export's work can run in steps away from the scene (``progress(fraction, text)``)."""
from __future__ import annotations

import contextlib
import os
import time
from dataclasses import dataclass

import numpy as np

from .. import post as posts
from ..post import flat_export, write_atomic
from ..post.output import OutputError, atomic_path
from ..toolpath.ir import machine
from ..toolpath.job import Job, JobOperation, Setup, plan_job
from ..toolpath.operations.sheetmetal import nibbling, placement, punch
from ..toolpath.operations.sheetmetal.kind import PunchGeometry, PunchSettings
from ..toolpath.operations.sheetmetal import unfold as core
from ..toolpath.ir.errors import InputError
from . import gate
from .limits import SettingError, check_group
from .properties import ELBOW_SETTINGS, UNFOLD_SETTINGS

GAP_MM = 20.0   # flat patterns are laid out this far beside the part
POST_FAMILIES = ("punch",)
PUNCH_POST = "amada-04p"

SETUP_NAMES = {"sheet_origin": "G92 Origin", "sheet_size": "Sheet", "clamps": "Clamps", "joints": "Micro-Joints",
               "joint_width": "Joint Width"}


def parse_clamps(text: str, width: float, depth: float, name: str = "Clamps") -> tuple:
    """Clamps from their centres along the clamped edge, "200, 700" (mm); none from an empty text."""
    found = []
    for item in str(text).replace(";", ",").split(","):
        if not item.strip():
            continue
        try:
            x = float(item)
        except ValueError:
            raise SettingError(f"{name}: {item.strip()!r} is not a number of mm (give clamp centres like "
                               f"\"200, 700\")") from None
        if not (abs(x) < 1e5):
            raise SettingError(f"{name}: {item.strip()!r} is not a position on the sheet")
        found.append(machine.Clamp(x, width, depth))
    return tuple(found)


def punch_profile(props, names: dict = SETUP_NAMES) -> machine.MachineProfile:
    """The Amada 04P preset with the sheet, G92 origin and clamps the panel (or batch) gives."""
    check_group(props, "sheet", ["sheet_origin", "sheet_size", "clamp_width", "clamp_depth", "joints", "joint_width"])
    clamps = parse_clamps(props.clamps, props.clamp_width, props.clamp_depth, names["clamps"])
    return machine.preset(PUNCH_POST).replace(sheet_origin=tuple(props.sheet_origin), clamps=clamps,
                                              sheet_max=tuple(props.sheet_size))


@dataclass
class PunchJob:
    """One part's program on the sheet: where it sits, its nibbling lines and their simulation."""

    nc: str
    punched: punch.PunchResult
    placement: placement.Placement
    nibbling: nibbling.Nibbling
    offset: np.ndarray          # added to the pattern's coordinates to put it on the sheet


def punch_settings(props) -> PunchSettings:
    """The punch program's settings from the sheet panel (or batch's options)."""
    return PunchSettings(props.station, props.tool_diameter, props.pitch, props.thickness, props.joints,
                         props.joint_width)


def punch_job(pattern, props, profile=None, progress=None) -> PunchJob:
    """Plan the flat ``pattern`` as a job of one punching operation (its tool-centre contour placed
    on the sheet clear of the clamps, nibbled round: merged lines, micro-joints, each hit once),
    write the program and punch it out of the sheet.  ``progress(fraction, text)``: planning
    takes the first tenth, the punching simulation the rest."""
    profile = punch_profile(props) if profile is None else profile
    setup = Setup(name="punch", post=PUNCH_POST, machine=profile)
    operation = JobOperation("punch", "punch", punch_settings(props), PunchGeometry(np.asarray(pattern)))
    planning, punching = share(progress, 0.0, 0.1), share(progress, 0.1, 1.0)
    plan = plan_job(Job(setup, (operation,)), progress=planning).parts[0].result
    nc = posts.create(POST_FAMILIES, PUNCH_POST).to_text(plan.program)
    punched = punch.simulate_punching(nc, punch_diameter=props.tool_diameter, pattern=plan.pattern,
                                      joints=plan.nibbling.joints, progress=punching)
    return PunchJob(nc, punched, plan.placement, plan.nibbling, plan.offset)


def placement_report(jobs: list) -> dict:
    """The report's ``sheet`` entry: where each part sits, the clamps, the joints."""
    first = jobs[0].placement
    return {
        "sheet_mm": list(first.sheet),
        "clamp_zones": [[round(v, 3) for v in z] for z in first.zones],
        "parts": [{"where": j.placement.where, "offset": [round(v, 3) for v in j.placement.offset],
                   "hits_within": [round(v, 3) for v in j.placement.envelope],
                   "lines": len(j.nibbling.lines), "merged_points": j.nibbling.merged,
                   "joints": len(j.nibbling.joints), "joint_width_mm": round(j.nibbling.joint_width, 4),
                   "joint_webs_mm": j.punched.joint_widths_mm} for j in jobs],
    }


@dataclass
class UnfoldJob:
    quad: core.TwistedQuad
    contour: np.ndarray        # tool-centre contour around the flat pattern (mm)
    nc: str                    # the turret-punch program
    punched: punch.PunchResult  # that program read back and punched out of the sheet
    punching: PunchJob = None  # where it sits on the sheet, its lines and joints


def corners_mm(props) -> np.ndarray:
    check_group(props, "sheet", ["corners"])
    return np.array(props.corners, float).reshape(4, 3)


# How messages name the settings: the panel and its labels, or batch's command and options.
PANEL_NAMES = {"where": "Sheet Metal", "pitch": "Nibbling Pitch", "tool_diameter": "Tool Diameter",
               "corners": "Quad corners (mm)", "diameter": "Pipe Diameter"}
UNFOLD_NAMES = {"where": "unfold", "pitch": "--pitch", "tool_diameter": "--tool-diameter",
                "corners": "--corners, --cdl or --blend"}
ELBOW_NAMES = {"where": "elbow", "pitch": "Nibbling Pitch", "tool_diameter": "Tool Diameter", "diameter": "--diameter"}


def check_pitch(props, names: dict = PANEL_NAMES) -> None:
    """The nibbling pitch against the punch: hits a diameter or more apart leave webs between
    them, and the part never falls out of the sheet."""
    if props.pitch >= props.tool_diameter:
        raise SettingError(f"{names['where']}: {names['pitch']} = {props.pitch:g} mm must be less than "
                           f"{names['tool_diameter']} = {props.tool_diameter:g} mm: hits a diameter or more apart "
                           f"leave webs, and the part stays in the sheet")


def check_contour(contour: np.ndarray, props, what: str, names: dict = PANEL_NAMES) -> None:
    """A cut contour the turret punch can run, before its program is written: within the
    coordinates the control addresses, and within the hits one program may have.  ``what``:
    the setting that made the contour, as the user gave it."""
    reach = posts.find(POST_FAMILIES, PUNCH_POST).limits.coordinate
    extent = float(np.abs(contour).max())
    if extent > reach:
        size = np.ptp(contour, axis=0)
        raise SettingError(f"{names['where']}: {what}: the cut contour is {size[0]:.1f} x {size[1]:.1f} mm and "
                           f"reaches {extent:.1f} mm from the program's origin, beyond the {reach:.2f} mm the "
                           f"turret punch control addresses")
    hits = punch.hit_count(contour, props.pitch)
    if hits > punch.MAX_HITS:
        raise SettingError(f"{names['where']}: {names['pitch']} = {props.pitch:g} mm: {what} takes {hits} hits, "
                           f"more than the {punch.MAX_HITS} one program may have; raise the pitch")


def word_error(resolution: float, line_mm: float) -> float:
    """How far the NC words alone can put a hit of a line ``line_mm`` long off its exact place:
    its start (X, Y) rounded to ``resolution`` mm and its direction (J) to ``resolution`` degrees."""
    return resolution / 2 * 2 ** 0.5 + line_mm * np.sin(np.radians(resolution / 2))


def punch_gate(results: list, allow: bool) -> dict:
    """The export gate of a punching job: a part that stays in the sheet other than by the
    micro-joints the job left (held by them is the intended result), a part that falls free
    though joints were asked for, or a hit biting into
    the part deeper than the simulation's tolerance and what the NC words' two decimals can put
    it off by (:func:`word_error`), is not written unless ``allow``.  Returns the report's
    ``gate`` entry; raises :class:`gate.GateRefused`."""
    started = time.perf_counter()
    resolution = posts.find(POST_FAMILIES, PUNCH_POST).limits.resolution
    findings = []
    for index, result in enumerate(results, start=1):
        which = f"piece {index}: " if len(results) > 1 else ""
        if result.joints and result.part_separated:
            findings.append({"kind": "joints do not hold", "piece": index, "line": None, "depth_mm": None,
                             "message": f"{which}the part falls free: its {result.joints} micro-joint(s) leave no web"})
        elif not result.part_separated and not result.held_by_joints:
            findings.append({"kind": "part in sheet", "piece": index, "line": None, "depth_mm": None,
                             "message": f"{which}the part stays in the sheet (webs between the hits)"})
        findings += [{"kind": "gouge", "piece": index, "line": g.line, "depth_mm": round(g.depth_mm, 4),
                      "message": which + g.message}
                     for g in result.gouges if g.depth_mm > result.tolerance + word_error(resolution, g.line_mm)]
    report = {"findings": findings, "overridden": False, "seconds": round(time.perf_counter() - started, 3)}
    if findings:
        if not allow:
            listed = "; ".join(f["message"] for f in findings[:5])
            more = f" (and {len(findings) - 5} more)" if len(findings) > 5 else ""
            raise gate.GateRefused(f"not written: the punching simulation found {len(findings)} fault(s): "
                                   f"{listed}{more}. Fix the job, or override knowingly (batch: --allow-findings; "
                                   f"panel: Write Despite Findings in the export's file browser)", findings)
        report["overridden"] = True
    return report


def run_unfold(corners, props, names: dict = PANEL_NAMES, progress=None) -> UnfoldJob:
    check_group(props, "sheet", list(UNFOLD_SETTINGS))
    check_pitch(props, names)
    quad = core.unfold_twisted_quad(corners, props.divisions, props.direction)
    contour = core.compensate_outline(quad.pattern.outline, props.tool_diameter)
    check_contour(contour, props, f"the flat pattern of {names['corners']}", names)
    job = punch_job(quad.pattern.outline, props, progress=progress)
    return UnfoldJob(quad, contour, job.nc, job.punched, job)


def punch_report(results: list, thickness: float) -> dict:
    """The ``simulation`` entry of a batch report for one or more punched parts."""
    gouges = [{"line": g.line, "depth_mm": round(g.depth_mm, 4), "xy": [round(v, 3) for v in g.xy],
               "message": g.message, "part": index + 1}
              for index, result in enumerate(results) for g in result.gouges]
    removed = sum(r.removed_area_mm2 for r in results)
    return {
        "engine": "crosssection",
        "tolerance_mm": results[0].tolerance,
        "seconds": round(sum(r.seconds for r in results), 3),
        "hits": sum(r.hits for r in results),
        "parts_separated": [r.part_separated for r in results],
        "held_by_joints": [r.held_by_joints for r in results],
        "part_area_mm2": [round(r.part_area_mm2, 2) for r in results],
        "pattern_area_mm2": [round(r.pattern_area_mm2, 2) for r in results],
        "removed_area_mm2": round(removed, 2),
        "removed_volume_mm3": round(removed * thickness, 1),
        "max_scallop_mm": round(max(r.max_scallop_mm or 0.0 for r in results), 4),
        "gouges": gouges,
        "max_gouge_mm": round(max(r.max_gouge_mm for r in results), 4),
        "rapid_collisions": [],
    }


def punch_warnings(results: list) -> list:
    """What the punching simulation found that the shop must hear about."""
    warnings = []
    for index, result in enumerate(results):
        which = f"part {index + 1}: " if len(results) > 1 else ""
        if result.joints and result.part_separated:
            warnings.append(f"{which}the part falls free: its micro-joints leave no web")
        elif not result.part_separated and not result.held_by_joints:
            warnings.append(f"{which}the part stays in the sheet: hits further apart than the punch leave webs "
                            f"(lower the pitch below the {result.punch_diameter:g} mm punch)")
        warnings += [f"{which}{g.message}" for g in result.gouges]
    return warnings


def unfold_texts(job: UnfoldJob, base_path: str) -> list:
    """(path, text) of the NC (.nc), DXF and SVG beside each other."""
    outline = job.quad.pattern.outline
    bends = job.quad.pattern.bend_lines()
    stem = os.path.splitext(base_path)[0]
    return [(stem + posts.extension(POST_FAMILIES, PUNCH_POST), job.nc),
            (stem + ".dxf", flat_export.to_dxf([outline], punch_paths=[job.contour], bend_lines=bends)),
            (stem + ".svg", flat_export.to_svg([outline], punch_paths=[job.contour], bend_lines=bends))]


def unfold_files(job: UnfoldJob, base_path: str) -> list:
    """NC (.nc), DXF and SVG beside each other; each written atomically."""
    return [write_atomic(path, text) for path, text in unfold_texts(job, base_path)]


def run_elbow(props, names: dict = PANEL_NAMES) -> core.Elbow:
    check_group(props, "sheet", [*ELBOW_SETTINGS, "tool_diameter", "thickness", "pitch", "station"])
    check_pitch(props, names)
    return core.unfold_elbow(props.elbow_angle, props.elbow_radius, props.elbow_diameter, props.elbow_pieces)


def elbow_layout(elbow: core.Elbow) -> list:
    """Each piece's flat outline (mm), placed one above the other with a gap."""
    placed, y = [], 0.0
    for piece in elbow.pieces:
        outline = np.asarray(piece.outline, float)
        outline = outline - [0.0, outline[:, 1].min() - y]
        placed.append(outline)
        y = outline[:, 1].max() + GAP_MM / 2
    return placed


def elbow_punching(elbow: core.Elbow, props, names: dict = PANEL_NAMES, progress=None) -> list:
    """Per piece: (turret-punch program, its punching simulation), with the sheet panel's punch.
    Each piece is punched from a sheet of its own, its pattern's lower left corner at the
    program's origin (as the first piece of the layout).  ``progress``: an equal share a piece."""
    contours = []
    for index, piece in enumerate(elbow.pieces, start=1):
        outline = np.asarray(piece.outline, float)
        outline = outline - outline.min(axis=0)
        contour = core.compensate_outline(outline, props.tool_diameter)
        check_contour(contour, props, f"piece {index} of {names['diameter']} = {elbow.diameter:g} mm", names)
        contours.append((outline, contour))
    jobs = []
    profile = punch_profile(props)
    for index, (outline, contour) in enumerate(contours, start=1):
        try:
            job = punch_job(outline, props, profile, share(progress, (index - 1) / len(contours),
                                                             index / len(contours)))
        except InputError as error:     # which piece's program: the message's line is that program's
            raise core.UnfoldError(f"elbow piece {index} of {len(elbow.pieces)}: {error}") from None
        jobs.append((job.nc, job.punched, job))
    return jobs


def elbow_texts(elbow: core.Elbow, base_path: str, props, punching: list | None = None) -> list:
    """(path, text) of the DXF and SVG of all the pieces, and of one turret-punch program per piece
    (<stem>-1.nc ...); every piece's program punched, unless ``punching`` from
    :func:`elbow_punching` is given."""
    stem = os.path.splitext(base_path)[0]
    outlines = elbow_layout(elbow)
    punch_paths = [core.compensate_outline(outline, props.tool_diameter) for outline in outlines]
    punching = elbow_punching(elbow, props) if punching is None else punching
    extension = posts.extension(POST_FAMILIES, PUNCH_POST)
    texts = [(stem + ".dxf", flat_export.to_dxf(outlines, punch_paths=punch_paths)),
             (stem + ".svg", flat_export.to_svg(outlines, punch_paths=punch_paths))]
    texts += [(f"{stem}-{index}{extension}", nc) for index, (nc, *_) in enumerate(punching, start=1)]
    return texts


def elbow_files(elbow: core.Elbow, base_path: str, props, punching: list | None = None) -> list:
    """:func:`elbow_texts` written, each atomically: every text is made before the first file."""
    return [write_atomic(path, text) for path, text in elbow_texts(elbow, base_path, props, punching)]


def write_all(texts: list) -> list:
    """Write every (path, text) or none (the panel's exports; batch stages its own ``--out``): each
    text (ASCII, or bytes as they are: a setup sheet's UTF-8) goes to a temporary file beside its
    path, and only once all are written are they renamed onto their paths, so a failure (a full
    disk, a folder in the way) writes none of them."""
    for path, _ in texts:           # found before anything is written or renamed
        if os.path.isdir(path):
            raise OutputError(f"cannot write {os.path.abspath(path)}: a folder of that name is in the way")
    with contextlib.ExitStack() as stack:
        temps = [(path, stack.enter_context(atomic_path(path)), text) for path, text in texts]
        for path, temp, text in temps:
            try:
                binary = isinstance(text, bytes)
                with open(temp, "wb" if binary else "w",
                          **({} if binary else {"encoding": "ascii", "newline": "\n"})) as stream:
                    stream.write(text)
                    stream.flush()
                    os.fsync(stream.fileno())
            except OSError as error:
                raise OutputError(f"cannot write {os.path.abspath(path)}: {error.strerror or error}") from None
    return [os.path.abspath(path) for path, _ in texts]


def share(progress, start: float, end: float):
    """``progress`` for a part of the work: its fraction 0..1 mapped to ``start``..``end`` (None: None)."""
    if progress is None:
        return None
    return lambda fraction, text="": progress(start + (end - start) * min(max(float(fraction), 0.0), 1.0), text)
