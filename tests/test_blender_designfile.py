"""Designs from drawing programs in the shell (operators/designfile.py): File > Import > Kezuri design
and the CAM tab's button make curve objects at the scene's unit scale; batch's --svg / --dxf options;
a job file's ``design = "sign.svg"`` read by an engraving as its letters, end to end."""
import argparse
import contextlib
import io
import math
import os
import types

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")
from blender_helpers import draw_panel  # noqa: E402
from test_hostile import time_limit  # noqa: E402
from test_hostile_batch import BATCH  # noqa: E402

from kezuri.operators import convert, designfile, panels  # noqa: E402
from kezuri.toolpath.engines.designshapes import DesignFileError  # noqa: E402

SIGN = """<?xml version="1.0" encoding="UTF-8"?>
<svg width="60mm" height="30mm" viewBox="0 0 60 30" xmlns="http://www.w3.org/2000/svg"
     xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape">
  <g inkscape:groupmode="layer" inkscape:label="Letters" id="layer1">
    <rect id="bar" x="5" y="10" width="20" height="10"/>
    <circle id="dot" cx="45" cy="15" r="8"/>
  </g>
  <g inkscape:groupmode="layer" inkscape:label="Marks" id="layer2">
    <path id="tick" d="M 0,0 L 5,5"/>
  </g>
</svg>
"""
CIRCLE_AREA = math.pi * 64
TOL = 0.01


def area(points):
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


@pytest.fixture
def sign(tmp_path):
    path = tmp_path / "sign.svg"
    path.write_text(SIGN, encoding="utf-8")
    return str(path)


def spline_points(spline):
    co = np.empty(len(spline.points) * 4)
    spline.points.foreach_get("co", co)
    return co.reshape(-1, 4)[:, :2]


@pytest.mark.parametrize("scale_length", [0.001, 1.0])
def test_import_makes_curves_per_layer_at_the_scene_unit_scale(empty_scene, sign, scale_length):
    empty_scene.unit_settings.scale_length = scale_length
    assert bpy.ops.kezuri.import_design(filepath=sign) == {"FINISHED"}
    letters, marks = bpy.data.objects["sign Letters"], bpy.data.objects["sign Marks (open)"]
    assert letters.type == "CURVE" and letters.data.dimensions == "2D"
    assert [s.type for s in letters.data.splines] == ["POLY", "POLY"]
    assert all(s.use_cyclic_u for s in letters.data.splines) and not marks.data.splines[0].use_cyclic_u
    mm_per_unit = scale_length * 1000
    bar = spline_points(letters.data.splines[0]) * mm_per_unit
    assert bar.min(axis=0) == pytest.approx([5, 10], abs=1e-4) and bar.max(axis=0) == pytest.approx([25, 20], abs=1e-4)
    # read back as a workflow reads a curve: the filled 2-D curve is the region of both loops
    frame = convert.WorkFrame(convert.mm_per_unit(empty_scene), (0.0, 0.0, 0.0))
    loops = convert.outlines_in_work(letters, bpy.context.evaluated_depsgraph_get(), frame)
    total = sum(abs(area(loop)) for loop in loops)
    assert total == pytest.approx(200 + CIRCLE_AREA, abs=2 * math.pi * 8 * TOL + 1e-3)
    assert {letters, marks} <= set(bpy.context.selected_objects)


def test_import_has_undo_and_a_menu_entry_and_a_cam_tab_button(empty_scene):
    assert "UNDO" in designfile.KEZURI_OT_import_design.bl_options
    holder = types.SimpleNamespace(layout=types.SimpleNamespace(calls=[]))
    holder.layout.operator = lambda idname, **kw: holder.layout.calls.append((idname, kw.get("text")))
    designfile.menu_import(holder, bpy.context)
    assert holder.layout.calls == [("kezuri.import_design", "Kezuri design (.svg/.dxf)")]
    assert (bpy.types.TOPBAR_MT_file_import, designfile.menu_import) in designfile.MENUS
    assert "kezuri.import_design" in draw_panel(panels.KEZURI_PT_joblist, bpy.context).operators


def test_import_errors_name_the_file_and_element(empty_scene, tmp_path):
    bad = tmp_path / "broken.svg"
    bad.write_text('<svg xmlns="http://www.w3.org/2000/svg"><path id="p" d="M 0 0 L nan 1"/></svg>')
    with pytest.raises(RuntimeError, match=r"broken\.svg: <path id='p'> \(line 1\): path data"):
        bpy.ops.kezuri.import_design(filepath=str(bad))
    with pytest.raises(RuntimeError, match=r"no such file"):
        bpy.ops.kezuri.import_design(filepath=str(tmp_path / "gone.dxf"))
    assert not bpy.data.objects


def options(*argv):
    parser = argparse.ArgumentParser()
    designfile.design_arguments(parser)
    return parser.parse_args(list(argv))


def test_batch_options_give_loops_per_layer(sign, tmp_path):
    found = designfile.design_loops(options("--svg", sign))
    assert [name for name, _ in found] == ["sign Letters"]         # the open tick has no closed loop
    bar, dot = sorted((abs(area(loop)) for loop in found[0][1]), key=lambda a: abs(a - 200))
    assert bar == pytest.approx(200) and CIRCLE_AREA - 2 * math.pi * 8 * TOL <= dot <= CIRCLE_AREA
    assert [n for n, _ in designfile.design_loops(options("--svg", sign, "--layer", "Letters"))] == ["sign Letters"]
    with pytest.raises(DesignFileError, match=r"sign\.svg: no layer 'Cut'; its layers are 'Letters', 'Marks'"):
        designfile.design_loops(options("--svg", sign, "--layer", "Cut"))
    with pytest.raises(DesignFileError, match=r"--scale 2: a scale is for a DXF file without units"):
        designfile.design_loops(options("--svg", sign, "--scale", "2"))
    dxf = tmp_path / "inch.dxf"
    dxf.write_text("".join(f"{c:>3}\n{v}\n" for c, v in [
        (0, "SECTION"), (2, "ENTITIES"), (0, "CIRCLE"), (8, "HOLES"), (10, 0.0), (20, 0.0), (40, 0.5),
        (0, "ENDSEC"), (0, "EOF")]))
    (name, loops), = designfile.design_loops(options("--dxf", str(dxf), "--scale", "25.4"))
    exact = math.pi * 12.7 ** 2
    assert name == "inch HOLES" and exact - 2 * math.pi * 12.7 * TOL <= abs(area(loops[0])) <= exact
    with pytest.raises(SystemExit):
        with contextlib.redirect_stderr(io.StringIO()):
            options("--svg", sign, "--dxf", str(dxf))


JOB = """[setup]
name = "sign"
sample = "name_plate"
post = "linuxcnc"

[[operations]]
kind = "engrave"
name = "sign letters"
design = {{ file = "sign.svg", layer = "Letters", at = [-30.0, -15.0] }}
objects = {{ plate = "Plate", letters = "{letters}" }}
settings = {{ seed = 7 }}
"""


def test_a_job_files_design_is_read_by_the_engraving_as_its_letters(empty_scene, sign, tmp_path):
    from kezuri.operators import jobfile
    path = tmp_path / "sign.toml"
    path.write_text(JOB.format(letters="sign Letters"))
    data = jobfile.read(str(path))
    scene = jobfile.scene_for(data["setup"], str(path))
    job, frame, _ = jobfile.job_of(scene, jobfile.entries(data, scene, str(path)), "sign", "linuxcnc", "job")
    ((name, loops),) = job.operations[0].geometry.letters
    assert name == "sign Letters"
    # work zero at the plate's top centre: the 60 x 30 design centred by at = [-30, -15]
    bar = min(loops, key=lambda loop: loop[:, 0].min())
    assert bar.min(axis=0) == pytest.approx([-25, -5], abs=1e-4) and bar.max(axis=0) == pytest.approx([-5, 5], abs=1e-4)
    dot = max(loops, key=lambda loop: loop[:, 0].min())
    assert abs(area(dot)) == pytest.approx(CIRCLE_AREA, abs=2 * math.pi * 8 * TOL + 1e-3)
    assert dot.mean(axis=0) == pytest.approx([15, 0], abs=0.01)


def run_batch(*argv):
    stderr = io.StringIO()
    with time_limit(600), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = BATCH.main(["batch.py", *argv])
        except SystemExit as exit_:
            status = exit_.code
    return status, stderr.getvalue()


def test_batch_job_with_a_design_writes_the_program_and_refuses_a_bad_design_by_name(sign, tmp_path):
    path = tmp_path / "sign.toml"
    path.write_text(JOB.format(letters="sign Letters"))
    status, message = run_batch("job", str(path), "--out", str(tmp_path / "out"))
    assert status == 0, message[-2000:]
    assert os.path.isfile(tmp_path / "out" / "sign.ngc")
    (tmp_path / "sign.svg").write_text(SIGN.replace('r="8"', 'r="1e999"'))
    status, message = run_batch("job", str(path), "--out", str(tmp_path / "out2"))
    assert status == 2
    assert "job file sign.toml: operation 1 ('sign letters'): design.file = 'sign.svg': <circle id='dot'> " \
           "(line 6): r='1e999' is not a finite number" in message
    path.write_text(JOB.format(letters="sign Letters").replace('layer = "Letters", ', "wrong = 1, "))
    status, message = run_batch("job", str(path), "--out", str(tmp_path / "out3"))
    assert status == 2 and "design.wrong is not a key of a design" in message


def test_errors_and_notes_come_out_in_japanese_with_their_values(tmp_path):
    from kezuri.operators import translations
    from kezuri.toolpath.engines import svgfile
    bad = tmp_path / "bad.svg"
    bad.write_text('<svg xmlns="http://www.w3.org/2000/svg"><path id="p" d="M 0 0 L 5"/></svg>')
    with pytest.raises(DesignFileError) as raised:
        svgfile.read_svg(str(bad))
    japanese = translations.japanese_message(str(raised.value))
    assert japanese == "bad.svg: <path id='p'> (line 1)：パスデータ：10 文字目で 数値がありません（付近 'M 0 0 L 5'）"
    note = "part.dxf: skipped 2 TEXT (draws no cutting line), first at line 120"
    assert translations.japanese_message(note) == "part.dxf：TEXT を 2 個読み飛ばしました（削る線を描きません、最初は 120 行目）"


@pytest.mark.parametrize("scale", [-1.0, 0.0, float("nan")])
def test_the_dxf_scale_is_refused_not_clamped(empty_scene, tmp_path, scale):
    dxf = tmp_path / "part.dxf"
    dxf.write_text("".join(f"{c:>3}\n{v}\n" for c, v in [
        (0, "SECTION"), (2, "ENTITIES"), (0, "CIRCLE"), (8, "0"), (10, 0.0), (20, 0.0), (40, 5.0), (0, "ENDSEC"),
        (0, "EOF")]))
    with pytest.raises(RuntimeError, match=r"DXF Scale = (-1|0|nan): give a positive number"):
        bpy.ops.kezuri.import_design(filepath=str(dxf), scale=scale)
    assert not bpy.data.objects
    assert bpy.ops.kezuri.import_design(filepath=str(dxf), scale=2.0) == {"FINISHED"}
    spline = bpy.data.objects["part 0"].data.splines[0]
    assert np.abs(spline_points(spline)).max() == pytest.approx(10.0)      # r = 5 units of 2 mm, mm scene
