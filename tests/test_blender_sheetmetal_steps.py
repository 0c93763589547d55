"""The Sheet and Elbow exports run in steps like every NC export (tests/test_blender_export_steps.py):
reading the panel writes nothing; the work (punching every program out of the sheet, the gate,
the files) driven a step at a time by SteppedJob, as the modal operator drives it, writes the same
bytes as the export run at once and as the unstepped functions batch calls; cancelled half way
(Esc: SteppedOperator.modal calling SteppedJob.cancel, which these tests call) it writes nothing;
and it writes all its files or none (a folder in the way of the last one: none of them)."""
import os

import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import common, sheetjobs, sheetmetal  # noqa: E402
from test_blender_export_steps import cancelled_half_way, stepped  # noqa: E402

QUAD = ["quad.nc", "quad.dxf", "quad.svg"]


def elbow_names(pieces: int) -> list:
    return ["elbow.dxf", "elbow.svg", *[f"elbow-{k}.nc" for k in range(1, pieces + 1)]]


def contents(folder, names) -> dict:
    return {name: (folder / name).read_bytes() for name in names}


def test_the_sheet_and_elbow_exports_are_stepped_operators():
    for cls in (sheetmetal.KEZURI_OT_sheet_export, sheetmetal.KEZURI_OT_elbow_export):
        assert issubclass(cls, common.SteppedOperator), cls.bl_idname
        assert "prepare" in vars(cls), f"{cls.bl_idname} prepares its work in steps"


def check_steps(tmp_path, request, unstepped, operator, names):
    """``request(path)``: the export's work; ``unstepped(path)``: the files as batch (and the
    export before it was stepped) writes them; ``operator(path)``: the export run at once."""
    cancelled, done, whole, plain = (tmp_path / name for name in ("cancelled", "stepped", "whole", "plain"))
    for folder in (cancelled, done, whole, plain):
        folder.mkdir()
    target = str(cancelled / names[0])
    work = request(target)
    assert os.listdir(cancelled) == []                 # reading the panel writes nothing
    cancelled_half_way(work)
    assert os.listdir(cancelled) == []                 # no file, no temporary file
    written = stepped(request(str(done / names[0]))).result()
    assert sorted(os.path.basename(path) for path in written) == sorted(names)
    assert sorted(os.listdir(done)) == sorted(names)
    assert operator(str(whole / names[0])) == {"FINISHED"}
    unstepped(str(plain / names[0]))
    assert contents(done, names) == contents(whole, names) == contents(plain, names)
    assert all(len(data) > 500 for data in contents(done, names).values())


def test_sheet_export_in_steps(empty_scene, tmp_path):
    sheet = empty_scene.kezuri.sheet
    check_steps(tmp_path, lambda path: sheetmetal.sheet_export_request(empty_scene, path, False),
                lambda path: sheetjobs.unfold_files(sheetjobs.run_unfold(sheetjobs.corners_mm(sheet), sheet), path),
                lambda path: bpy.ops.kezuri.sheet_export(filepath=path), QUAD)


@pytest.mark.parametrize("pieces, joints", [(5, 0), (3, 2)])
def test_elbow_export_in_steps(empty_scene, tmp_path, pieces, joints):
    sheet = empty_scene.kezuri.sheet
    sheet.elbow_pieces, sheet.joints = pieces, joints

    def unstepped(path):
        elbow = sheetjobs.run_elbow(sheet)
        return sheetjobs.elbow_files(elbow, path, sheet, sheetjobs.elbow_punching(elbow, sheet))
    check_steps(tmp_path, lambda path: sheetmetal.elbow_export_request(empty_scene, path, False), unstepped,
                lambda path: bpy.ops.kezuri.elbow_export(filepath=path), elbow_names(pieces))


def test_the_work_copies_the_settings_so_a_later_edit_does_not_change_what_it_writes(empty_scene, tmp_path):
    """The work reads no Blender data: settings changed in the panel while it runs (the viewport
    stays usable) do not reach the files it writes."""
    sheet = empty_scene.kezuri.sheet
    joints = sheet.joints
    work = sheetmetal.elbow_export_request(empty_scene, str(tmp_path / "a" / "elbow.dxf"), False)
    sheet.joints = joints + 1
    stepped(work).result()
    sheet.joints = joints
    assert bpy.ops.kezuri.elbow_export(filepath=str(tmp_path / "b" / "elbow.dxf")) == {"FINISHED"}
    assert contents(tmp_path / "a", elbow_names(5)) == contents(tmp_path / "b", elbow_names(5))


@pytest.mark.parametrize("idname, names", [("sheet_export", QUAD), ("elbow_export", elbow_names(5))])
def test_all_files_or_none(empty_scene, tmp_path, idname, names):
    """A folder in the way of the last file: the export is refused naming it and none of the
    others is written (before, the NC and DXF were written and the SVG failed)."""
    (tmp_path / names[-1]).mkdir()
    operator = getattr(bpy.ops.kezuri, idname)
    with pytest.raises(RuntimeError, match=f"cannot write {tmp_path / names[-1]}"):
        operator(filepath=str(tmp_path / names[0]))
    assert os.listdir(tmp_path) == [names[-1]] and os.listdir(tmp_path / names[-1]) == []
    os.rmdir(tmp_path / names[-1])
    assert operator(filepath=str(tmp_path / names[0])) == {"FINISHED"}
    sheet = os.path.splitext(names[0])[0].split("-")[0] + "-setup-sheet.html"      # and its setup sheet
    assert sorted(os.listdir(tmp_path)) == sorted([*names, sheet])


def test_a_refusal_in_the_work_writes_nothing(empty_scene, tmp_path):
    """The quad ten times the paper's at a 0.1 mm pitch: its contour takes more hits than one
    program may have (20,000), found by the work after the settings were read; the refusal comes
    out of result() naming the panel's settings, and nothing is on disk."""
    sheet = empty_scene.kezuri.sheet
    sheet.corners = [10 * v for v in sheet.corners]
    sheet.pitch = 0.1
    job = common.SteppedJob(sheetmetal.sheet_export_request(empty_scene, str(tmp_path / "quad.nc"), False),
                            step_seconds=0.0)
    while not job.step():
        pass
    with pytest.raises(sheetjobs.SettingError, match=r"Sheet Metal: Nibbling Pitch = 0\.1 mm: the flat pattern of "
                                                      r"Quad corners \(mm\) takes \d+ hits, more than the 20000"):
        job.result()
    assert os.listdir(tmp_path) == []
