"""Every panel export writes the setup sheet beside its program (``<program>-setup-sheet.html``), as
every batch command writes its sheet: engrave, carve, rotary, turn-mill, STEP-NC workplan, the
job list's Export, and sheet metal's Sheet and Elbow exports (one sheet for all the elbow's pieces).  The program and the sheet are written both or neither: a folder in the way of
the sheet's path leaves no program behind (nor the hidden staging folder), and the error names the
path.  The sheet names the program file and its size as written (read back with
tests/sheet_reader.py, an independent html.parser reader).  The English sheet of a panel export is
the batch sheet of the same job (batch run in this process on the same scene, same post) in every
part, the pictures too: the panel's sheet has batch's toolpaths and simulated-result pictures, the
same PNG bytes (Sheet and Elbow: batch's flat-pattern picture) (README "Setup sheet").  STEP-NC's
toolpaths picture draws the workplan's solids as shown in the scene, as batch draws them."""
import contextlib
import io
import os

import pytest

bpy = pytest.importorskip("bpy")

from sheet_reader import read_sheet  # noqa: E402

from kezuri.operators import plancache, samples  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIXTURES = os.environ.get("KEZURI_FIXTURES", os.path.join(os.path.dirname(__file__), "fixtures"))
EX1 = os.path.join(FIXTURES, "iso14649", "ex1.stp")


from test_hostile_batch import BATCH  # noqa: E402  (batch.py loaded once for the in-process suites)


def run_batch(out, *argv) -> None:
    stderr = io.StringIO()
    with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", *argv, "--out", str(out)])
        except SystemExit as exit_:
            status = exit_.code
    assert status in (0, None), stderr.getvalue()[-2000:]


def engrave_scene(scene):
    samples.name_plate(scene)


def carve_scene(scene):
    samples.set_millimetres(scene)
    assert bpy.ops.kezuri.carve_sample(sample="wave") == {"FINISHED"}


def rotary_scene(scene):
    samples.rotary_block(scene)


def turnmill_scene(scene):
    samples.turnmill_part(scene)


def stepnc_scene(scene):
    assert bpy.ops.kezuri.import_stepnc(filepath=EX1) == {"FINISHED"}


def job_scene(scene):
    samples.name_plate(scene)
    scene.kezuri.machine.post = "linuxcnc"
    assert bpy.ops.kezuri.job_add(kind="engrave") == {"FINISHED"}


# (scene builder, the export operator's name, post, program file name)
EXPORTS = {
    "engrave": (engrave_scene, "engrave_export", "linuxcnc", "plate.ngc"),
    "carve": (carve_scene, "carve_export", "linuxcnc", "relief.ngc"),
    "rotary": (rotary_scene, "rotary_export", "linuxcnc", "bowl.ngc"),
    "turnmill": (turnmill_scene, "turnmill_export", "xzc", "shaft.nc"),
    "stepnc": (stepnc_scene, "stepnc_export", "linuxcnc", "ex1.ngc"),
    "job": (job_scene, "job_export", "linuxcnc", "plate-job.ngc"),
}


def export(name: str, path, **options):
    _, operator, post, _ = EXPORTS[name]
    plancache.cache_of(bpy.context.scene).clear()
    return getattr(bpy.ops.kezuri, operator)(filepath=str(path), post=post, **options)


def sheet_of(path):
    return read_sheet(open(path, encoding="utf-8").read())


@pytest.mark.parametrize("name", sorted(EXPORTS))
def test_each_panel_export_writes_the_sheet_beside_the_program(empty_scene, tmp_path, name):
    EXPORTS[name][0](empty_scene)
    program = tmp_path / EXPORTS[name][3]
    assert export(name, program) == {"FINISHED"}
    sheet = tmp_path / (program.stem + "-setup-sheet.html")
    assert sorted(os.listdir(tmp_path)) == sorted([program.name, sheet.name])       # no staging folder left
    page = sheet_of(sheet)
    data = program.read_bytes()
    lines = len(data.decode("ascii").splitlines())
    assert page.rows("programs") == [{"File": program.name, "Size (bytes)": f"{len(data):,}", "Lines": f"{lines:,}"}]
    assert page.attrs["gate"]["data-status"] == "passed"
    assert len(page.rows("operations")) >= 1 and len(page.rows("tools")) >= 1
    assert page.texts["job"].startswith(f"Setup sheet: {name}: ")      # titled as batch titles it: "<workflow>: <program>"
    pictures = page.picture_bytes()     # the toolpaths and the result as batch draws them (1200 x 800 PNGs)
    assert [image["alt"] for image in page.images()] == ["Toolpaths", "Result"]
    assert len(pictures) == len(page.images())
    for png in pictures:
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and png[16:24] == (1200).to_bytes(4, "big") + (800).to_bytes(4, "big")
    # the option off: the program alone, the sheet of the run before replaced by nothing new
    again = tmp_path / "again" / program.name
    again.parent.mkdir()
    assert export(name, again, setup_sheet=False) == {"FINISHED"}
    assert os.listdir(again.parent) == [program.name] and again.read_bytes() == data


@pytest.mark.parametrize("name", ["engrave", "job"])
def test_a_folder_in_the_way_of_the_sheet_leaves_neither_file(empty_scene, tmp_path, name):
    EXPORTS[name][0](empty_scene)
    program = tmp_path / EXPORTS[name][3]
    in_the_way = tmp_path / (program.stem + "-setup-sheet.html")
    in_the_way.mkdir()
    with pytest.raises(RuntimeError) as error:
        export(name, program)
    assert str(in_the_way) in str(error.value) and "in the way" in str(error.value)
    assert os.listdir(tmp_path) == [in_the_way.name] and os.listdir(in_the_way) == []
    # an old program there stays as it was
    program.write_text("old\n")
    with pytest.raises(RuntimeError):
        export(name, program)
    assert program.read_text() == "old\n" and sorted(os.listdir(tmp_path)) == sorted([in_the_way.name, program.name])


def test_a_folder_in_the_way_of_the_program_leaves_no_sheet(empty_scene, tmp_path):
    engrave_scene(empty_scene)
    program = tmp_path / "plate.ngc"
    program.mkdir()
    with pytest.raises(RuntimeError, match=str(program).replace(".", r"\.")):
        export("engrave", program)
    assert os.listdir(tmp_path) == ["plate.ngc"] and os.listdir(program) == []


# batch command and its options for the same job as the panel's scene; the program batch writes
BATCH_RUNS = {
    "engrave": (("engrave", "--post", "linuxcnc"), "engrave.ngc"),
    # a material: each tool's chip load in the tools table, the feeds' warnings in the notes
    "engrave-hardwood": (("engrave", "--post", "linuxcnc", "--material", "hardwood"), "engrave.ngc"),
    "carve-hardwood": (("carve", "--post", "linuxcnc", "--material", "hardwood"), "carve.ngc"),
    "rotary-hardwood": (("rotary", "--post", "linuxcnc", "--material", "hardwood"), "rotary.ngc"),
    "carve": (("carve", "--post", "linuxcnc"), "carve.ngc"),
    "rotary": (("rotary", "--post", "linuxcnc"), "rotary.ngc"),
    "turnmill": (("turnmill", "--post", "xzc"), "turnmill.nc"),
    "stepnc": (("stepnc", "--post", "linuxcnc"), "stepnc.ngc"),
}


@pytest.mark.parametrize("name", sorted(BATCH_RUNS))
def test_the_panel_sheet_is_the_batch_sheet_but_its_pictures(empty_scene, tmp_path, name):
    """Batch builds its scene (the sample) and writes its sheet; the panel exports that same scene
    to a file of the same name: every table, the setup facts, the gate, the notes and the title
    are the batch sheet's; only batch's pictures are missing."""
    argv, program_name = BATCH_RUNS[name]
    run_batch(tmp_path / "batch", *argv)
    scene = bpy.context.scene
    if name == "stepnc":        # batch's scene names the sample it converted where batch kept it, in --out
        assert scene.kezuri.stepnc.filepath == str(tmp_path / "batch" / "sample.stp")
    panel = tmp_path / "panel" / program_name
    panel.parent.mkdir()
    _, operator, post, _ = EXPORTS[name.split("-")[0]]
    plancache.cache_of(scene).clear()
    assert getattr(bpy.ops.kezuri, operator)(filepath=str(panel), post=post) == {"FINISHED"}
    assert panel.read_bytes() == (tmp_path / "batch" / program_name).read_bytes()
    batch_page = sheet_of(tmp_path / "batch" / "setup-sheet.html")
    panel_page = sheet_of(panel.parent / (panel.stem + "-setup-sheet.html"))
    assert panel_page.tables == batch_page.tables
    for ident in ("job", "gate", "notes"):
        assert panel_page.texts.get(ident) == batch_page.texts.get(ident), ident
    assert panel_page.texts["setup"] == batch_page.texts["setup"]
    assert panel_page.title == batch_page.title
    # batch's pictures, byte for byte the PNGs batch wrote: the toolpaths and the simulated result
    # (STEP-NC's toolpaths over the workplan's solids batch showed in the scene)
    workflow = name.split("-")[0]
    batch_pngs = [(tmp_path / "batch" / f"{workflow}-toolpaths.png").read_bytes(),
                  (tmp_path / "batch" / f"{workflow}.png").read_bytes()]
    assert [image["alt"] for image in batch_page.images()] == ["Toolpaths", "Result"]
    assert batch_page.picture_bytes() == batch_pngs
    assert [image["alt"] for image in panel_page.images()] == ["Toolpaths", "Result"]
    assert panel_page.picture_bytes() == batch_pngs
    assert panel_page.rows("programs")[0]["File"] == program_name
    if name.endswith("-hardwood"):      # the feeds were checked: a chip load for every tool
        assert all(row["Chip load (mm)"] != "\u2014" for row in panel_page.rows("tools"))


def test_the_sheet_metal_exports_write_their_sheet_with_the_programs(empty_scene, tmp_path):
    quad = tmp_path / "quad" / "unfold.nc"
    elbow = tmp_path / "elbow" / "elbow.dxf"
    quad.parent.mkdir()
    elbow.parent.mkdir()
    assert bpy.ops.kezuri.sheet_export(filepath=str(quad)) == {"FINISHED"}
    assert bpy.ops.kezuri.elbow_export(filepath=str(elbow)) == {"FINISHED"}
    pieces = empty_scene.kezuri.sheet.elbow_pieces
    assert sorted(os.listdir(quad.parent)) == ["unfold-setup-sheet.html", "unfold.dxf", "unfold.nc", "unfold.svg"]
    assert sorted(os.listdir(elbow.parent)) == sorted(["elbow-setup-sheet.html", "elbow.dxf", "elbow.svg",
                                                       *[f"elbow-{i}.nc" for i in range(1, pieces + 1)]])
    for folder, names in ((quad.parent, ["unfold.nc"]), (elbow.parent, [f"elbow-{i}.nc" for i in range(1, pieces + 1)])):
        page = sheet_of(folder / (names[0].split("-")[0].split(".")[0] + "-setup-sheet.html"))
        assert [(row["File"], row["Size (bytes)"]) for row in page.rows("programs")] == \
            [(name, f"{os.path.getsize(folder / name):,}") for name in names]
        assert page.attrs["gate"]["data-status"] == "passed"
    # the option off: the files as before the sheet
    off = tmp_path / "off" / "unfold.nc"
    off.parent.mkdir()
    assert bpy.ops.kezuri.sheet_export(filepath=str(off), setup_sheet=False) == {"FINISHED"}
    assert sorted(os.listdir(off.parent)) == ["unfold.dxf", "unfold.nc", "unfold.svg"]
    # a folder in the way of the sheet: none of the four files
    blocked = tmp_path / "blocked" / "unfold.nc"
    (blocked.parent / "unfold-setup-sheet.html").mkdir(parents=True)
    with pytest.raises(RuntimeError, match="unfold-setup-sheet.html: a folder of that name is in the way"):
        bpy.ops.kezuri.sheet_export(filepath=str(blocked))
    assert os.listdir(blocked.parent) == ["unfold-setup-sheet.html"]


@pytest.mark.parametrize("command, target", [("unfold", "unfold.nc"), ("elbow", "elbow.dxf")])
def test_the_sheet_metal_panel_sheet_is_the_batch_sheet(empty_scene, tmp_path, command, target):
    run_batch(tmp_path / "batch", command)
    panel = tmp_path / "panel" / target
    panel.parent.mkdir()
    operator = bpy.ops.kezuri.sheet_export if command == "unfold" else bpy.ops.kezuri.elbow_export
    assert operator(filepath=str(panel)) == {"FINISHED"}
    batch_page = sheet_of(tmp_path / "batch" / "setup-sheet.html")
    panel_page = sheet_of(panel.parent / f"{command}-setup-sheet.html")
    assert panel_page.tables == batch_page.tables
    for ident in ("job", "setup", "gate", "notes"):
        assert panel_page.texts.get(ident) == batch_page.texts.get(ident), ident
    # batch's picture of the flat pattern(s), the same PNG bytes
    drawn = (tmp_path / "batch" / f"{command}.png").read_bytes()
    assert [image["alt"] for image in panel_page.images()] == [image["alt"] for image in batch_page.images()]
    assert [image["alt"] for image in panel_page.images()] == ["Result"]
    assert panel_page.picture_bytes() == batch_page.picture_bytes() == [drawn]


def test_esc_half_way_leaves_neither_file_nor_the_staging_folder(empty_scene, tmp_path):
    """The export's work as the operator runs it (through exporting.program_and_sheet), driven a
    step at a time as the modal operator drives it: cancelled half way it leaves the folder empty;
    run to the end it writes the program and its sheet, the program byte for byte the one the
    operator writes at once."""
    from test_blender_export_steps import cancelled_half_way, stepped

    from kezuri.operators import engrave as engrave_shell
    from kezuri.operators import exporting

    engrave_scene(empty_scene)
    depsgraph = bpy.context.evaluated_depsgraph_get()

    def work(path):
        plancache.cache_of(empty_scene).clear()
        return exporting.program_and_sheet(
            lambda staged: engrave_shell.nc_export_request(empty_scene, depsgraph, "linuxcnc", staged), path, "en")
    target = tmp_path / "plate.ngc"
    cancelled_half_way(work(str(target)))
    assert os.listdir(tmp_path) == []
    done = stepped(work(str(target))).result()
    assert done.path == str(target)
    assert sorted(os.listdir(tmp_path)) == ["plate-setup-sheet.html", "plate.ngc"]
    whole = tmp_path / "whole" / "plate.ngc"
    whole.parent.mkdir()
    assert export("engrave", whole) == {"FINISHED"}
    assert whole.read_bytes() == target.read_bytes()


@pytest.mark.xfail(not bpy.app.build_options.international, strict=True,
                   reason="the bpy wheel is built without translations: its interface cannot be Japanese")
def test_a_panel_export_writes_the_sheet_in_the_interface_language(empty_scene, tmp_path):
    from kezuri.operators import translations
    translations.register()
    engrave_scene(empty_scene)
    view = bpy.context.preferences.view
    saved = view.language, view.use_translate_interface
    try:
        view.language = "ja_JP"
        view.use_translate_interface = True
        assert translations.interface_language() == "ja"
        assert export("engrave", tmp_path / "plate.ngc") == {"FINISHED"}
    finally:
        view.language, view.use_translate_interface = saved
    text = (tmp_path / "plate-setup-sheet.html").read_text(encoding="utf-8")
    assert '<html lang="ja">' in text and "段取り" in text
