"""The Blender shell, run for real with the bpy wheel in background mode."""
import os
import re

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import kezuri  # noqa: E402  (loaded by conftest from the repository root)
from blender_helpers import draw_panel  # noqa: E402
import rs274  # noqa: E402
from kezuri.operators import engrave as shell  # noqa: E402
from kezuri.operators import panels, samples  # noqa: E402



@pytest.fixture
def scene(empty_scene):
    scene = empty_scene
    samples.name_plate(scene)
    return scene


def test_register_and_unregister_twice_cleanly(empty_scene):
    for _ in range(2):
        kezuri.unregister()
        assert not hasattr(bpy.types.Scene, "kezuri")
        assert not hasattr(bpy.ops.kezuri, "engrave_generate") or \
            "engrave_generate" not in dir(bpy.types)
        kezuri.register()
        assert hasattr(bpy.types.Scene, "kezuri")
        assert bpy.ops.kezuri.engrave_generate.get_rna_type() is not None


def test_generate_operator_builds_the_preview_and_rerun_replaces_it(scene):
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    first = sorted(o.name for o in bpy.data.collections["Kezuri"].objects)
    assert "Kezuri Engrave roughing (gouge texture)" in first
    assert "Kezuri Engrave band finishing" in first
    assert "Kezuri Engrave burr contour" in first
    assert any(name.endswith("rapids") for name in first)
    rough = bpy.data.objects["Kezuri Engrave roughing (gouge texture)"]
    z = shell.convert.curve_points(rough)[:, 2]
    # mm scene: 1 unit = 1 mm; the cuts lie in the plate (top Z 0), the deepest gouge 2.8 mm down;
    # the feed plunges into it start at the 2 mm approach gap (their own object, in the legend's red)
    assert z.min() == pytest.approx(-2.8, abs=1e-5) and z.max() < 0.0
    plunges = shell.convert.curve_points(bpy.data.objects["Kezuri Engrave roughing (gouge texture) plunges"])
    assert plunges[:, 2].max() == pytest.approx(2.0, abs=1e-5)
    assert bpy.ops.kezuri.engrave_generate() == {"FINISHED"}
    assert sorted(o.name for o in bpy.data.collections["Kezuri"].objects) == first


def test_export_operator_writes_a_program_rs274_accepts(scene, tmp_path):
    path = str(tmp_path / "plate.ngc")
    assert bpy.ops.kezuri.engrave_export(filepath=path, post="linuxcnc") == {"FINISHED"}
    text = open(path).read()
    if rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
        feed_z = points[np.array(kinds) == "feed"][:, 2]
        assert feed_z.min() == pytest.approx(-2.8, abs=1e-3)


def test_letters_never_cut_in_the_blender_sample(scene):
    from kezuri.toolpath.engines import region
    job = shell.run_engrave(scene, bpy.context.evaluated_depsgraph_get())
    glyph_loops = [loop for _, loops in
                   [(o.name, shell.convert.outlines_in_work(o, bpy.context.evaluated_depsgraph_get(), job.plate.frame))
                    for o in [scene.kezuri.engrave.letters]] for loop in loops]
    glyphs = region.from_loops(glyph_loops)
    assert region.area(glyphs) > 1000          # the word "Kezuri" at 48 mm is a real area
    for op in job.baked.operations:
        below = op.xyz[op.xyz[:, 2] < 0]
        assert not region.contains_points(glyphs, below[:, :2]).any(), op.name


def test_a_counter_too_small_for_the_tool_is_named_in_the_nc_header_and_marked_in_the_picture(scene, tmp_path):
    from kezuri.toolpath.pictures import picture_jobs
    from kezuri.toolpath.engines import region
    scene.kezuri.engrave.letters.data.size = 8.0        # "Kezuri" 8 mm high: the e's eye is narrower than 1 mm
    path = str(tmp_path / "plate.ngc")
    assert bpy.ops.kezuri.engrave_export(filepath=path, post="linuxcnc") == {"FINISHED"}
    notes = re.findall(r"\(NOTE: BAND FINISHING: THE TOOL IS TOO BIG TO ENTER A GAP OF ([\d.]+) MM\^2 IN 'E' "
                       r"\[U\+0065\] OF LETTERS 'LETTERS' NEAR X(-?[\d.]+) Y(-?[\d.]+); IT IS LEFT UNCUT\)",
                       open(path).read())
    assert len(notes) == 1
    area, x, y = (float(v) for v in notes[0])
    # the place named lies in a counter of the word: inside its outline, outside its strokes,
    # in the second glyph from the left (K, e, ...), and the gap is one the 1 mm tool cannot enter
    job = shell.run_engrave(scene, bpy.context.evaluated_depsgraph_get())
    loops = shell.convert.outlines_in_work(scene.kezuri.engrave.letters, bpy.context.evaluated_depsgraph_get(),
                                           job.plate.frame)
    strokes = region.from_loops(loops)
    filled = region.from_loops([loop for loop in region.loops(strokes) if region.signed_area(loop) > 0])
    point = np.array([[x, y]])
    assert region.contains_points(filled, point)[0] and not region.contains_points(strokes, point)[0]
    pieces = sorted(region.components(strokes), key=lambda piece: piece.bounds()[0])
    assert pieces[1].bounds()[0] <= x <= pieces[1].bounds()[2]
    assert 0 < area < 2.0
    marks = shell.uncut_marks(job.result)
    assert [label for *_, label in marks] == [f"UNCUT 'e' {area:.2f} MM2"]
    picture = picture_jobs.toolpath_picture(job.baked.operations, shell.simulation(job).stock, marks=marks)
    assert f"UNCUT 'e' {area:.2f} MM2" in picture.texts and "LEFT UNCUT (1)" in picture.texts


def nc_for_units(unit_mm, system="METRIC"):
    scene = bpy.context.scene
    samples.clear_scene(scene)
    scene.unit_settings.system = system
    scene.unit_settings.scale_length = unit_mm / 1000.0
    samples.name_plate(scene, unit_mm=unit_mm)
    job = shell.run_engrave(scene, bpy.context.evaluated_depsgraph_get(), post_name="linuxcnc")   # its machine's Safe Z
    from kezuri.post import milling_post
    return milling_post("linuxcnc").to_text(job.baked)


def same_program(a: str, b: str, tolerance: float = 2e-4, centre_tolerance: float = 2e-3):
    """Same blocks and words; numbers equal to the last written digit.

    Blender stores vertices in float32, so the same letters modelled in metres and in
    millimetres differ by ~1e-6 mm, which can flip the 4th decimal of a coordinate.  An arc's
    centre (I, J) is fitted to the chords' ends, and moves along the bisector of its two ends
    by more: a few thousandths of a millimetre, the arc through the same ends staying as close.
    """
    lines_a, lines_b = a.splitlines(), b.splitlines()
    assert len(lines_a) == len(lines_b)
    number = re.compile(r"-?\d+\.\d*|-?\d+")
    for la, lb in zip(lines_a, lines_b):
        assert number.sub("#", la) == number.sub("#", lb), (la, lb)
        va = np.array([float(v) for v in number.findall(la)])
        vb = np.array([float(v) for v in number.findall(lb)])
        allowed = np.array([centre_tolerance if word[:1] in "IJ" else tolerance for word in la.split()
                            if number.search(word)])
        assert np.all(np.abs(va - vb) <= allowed), (la, lb)


def test_metres_millimetres_and_inches_give_the_same_nc():
    in_mm = nc_for_units(1.0)
    in_m = nc_for_units(1000.0)
    in_inch = nc_for_units(25.4, "IMPERIAL")
    same_program(in_mm, in_m)
    same_program(in_mm, in_inch)
    assert "X-100." in in_mm      # the plate edge at -100 mm, not -0.1 or -100000


@pytest.mark.parametrize("panel, expected_props, expected_ops", [
    (panels.KEZURI_PT_machine, {"post", "work_offset", "plate", "origin"}, set()),
    (panels.KEZURI_PT_engrave, {"letters"}, {"kezuri.engrave_generate", "kezuri.engrave_export"}),
    (panels.KEZURI_PT_engrave_texture, {"stepover", "base_depth", "quantum", "amplitude", "spacing", "seed",
                                        "motion"}, set()),
    (panels.KEZURI_PT_engrave_finish, {"finish_diameter", "band_width", "band_depth", "band_stepover"}, set()),
])
def test_panels_draw_their_properties(scene, panel, expected_props, expected_ops):
    layout = draw_panel(panel, bpy.context)
    assert expected_props <= set(layout.props)
    assert expected_ops <= set(layout.operators)
    assert panel.bl_category == "CAM" and panel.bl_region_type == "UI"


def test_no_plate_is_a_clear_error_and_writes_nothing(scene, tmp_path):
    scene.kezuri.stock.plate = None
    path = tmp_path / "x.nc"
    with pytest.raises(RuntimeError, match="plate"):
        bpy.ops.kezuri.engrave_export(filepath=str(path), post="fanuc")
    assert not path.exists()


def test_open_outline_names_the_object(scene, tmp_path):
    curve = bpy.data.curves.new("OpenStroke", type="CURVE")
    spline = curve.splines.new("POLY")
    spline.points.add(2)
    for p, co in zip(spline.points, [(-30, 0, 0, 1), (0, 10, 0, 1), (30, 0, 0, 1)]):
        p.co = co
    obj = bpy.data.objects.new("OpenStroke", curve)
    scene.collection.objects.link(obj)
    scene.kezuri.engrave.letters = obj
    path = tmp_path / "x.nc"
    with pytest.raises(RuntimeError, match="OpenStroke.*open"):
        bpy.ops.kezuri.engrave_export(filepath=str(path), post="fanuc")
    assert not path.exists()


def test_letters_outside_the_plate_are_refused(scene):
    scene.kezuri.engrave.letters.location.x = 150
    with pytest.raises(RuntimeError, match="outside the plate"):
        bpy.ops.kezuri.engrave_generate()


def test_nan_vertex_is_refused(scene):
    mesh = bpy.data.meshes.new("Broken")
    mesh.from_pydata([(0, 0, 0), (10, 0, 0), (float("nan"), 10, 0)], [], [(0, 1, 2)])
    obj = bpy.data.objects.new("Broken", mesh)
    scene.collection.objects.link(obj)
    scene.kezuri.engrave.letters = obj
    with pytest.raises(RuntimeError, match="Broken.*non-finite"):
        bpy.ops.kezuri.engrave_generate()


def test_zero_stepover_is_refused(scene):
    scene.kezuri.engrave.stepover = 0.0
    with pytest.raises(RuntimeError, match=r"Stepover = 0 is outside the allowed range 0 < Stepover <= 100 mm"):
        bpy.ops.kezuri.engrave_generate()


def test_export_path_uses_the_post_extension():
    assert shell.extension_for("linuxcnc") == ".ngc"
    assert shell.extension_for("fanuc-macro") == ".nc"


def test_letters_from_mesh_faces_and_closed_curves(scene):
    """An 'L' as mesh faces (two quads) and an 'O' as two closed curve loops: both engrave."""
    mesh = bpy.data.meshes.new("MeshL")
    mesh.from_pydata([(-60, -20, 0), (-50, -20, 0), (-50, 20, 0), (-60, 20, 0), (-30, -20, 0), (-30, -10, 0),
                      (-50, -10, 0)], [], [(0, 1, 2, 3), (1, 4, 5, 6)])
    mesh_obj = bpy.data.objects.new("MeshL", mesh)
    curve = bpy.data.curves.new("CurveO", type="CURVE")
    for size in (20, 10):
        spline = curve.splines.new("POLY")
        spline.points.add(3)
        for p, (x, y) in zip(spline.points, [(0, 0), (size, 0), (size, size), (0, size)]):
            p.co = (x + 20 - size / 2, y - size / 2, 0, 1)
        spline.use_cyclic_u = True
    curve_obj = bpy.data.objects.new("CurveO", curve)
    collection = bpy.data.collections.new("Lettering")
    scene.collection.children.link(collection)
    for obj in (mesh_obj, curve_obj):
        collection.objects.link(obj)
    scene.kezuri.engrave.letters = None
    scene.kezuri.engrave.letters_collection = collection
    job = shell.run_engrave(scene, bpy.context.evaluated_depsgraph_get())
    from kezuri.toolpath.engines import region
    band = job.baked.operations[1]
    ring_points = band.xyz[band.xyz[:, 2] < 0][:, :2]
    # The band runs inside the O's counter (a 10 mm hole) and around the L.
    assert region.contains_points(region.rectangle(15.6, -4.4, 24.4, 4.4), ring_points).any()
    assert region.contains_points(region.rectangle(-65, -25, -25, 25), ring_points).any()
    l_shape = region.from_loops([[(-60, -20), (-30, -20), (-30, -10), (-50, -10), (-50, 20), (-60, 20)]])
    o_ring = region.from_loops([[(10, -10), (30, -10), (30, 10), (10, 10)], [(15, -5), (25, -5), (25, 5), (15, 5)]])
    for op in job.baked.operations:
        below = op.xyz[op.xyz[:, 2] < 0][:, :2]
        assert not region.contains_points(l_shape + o_ring, below).any(), op.name


def test_a_base_depth_through_the_sample_plate_is_refused_in_the_shell_and_in_batch(scene, tmp_path):
    import subprocess
    import sys
    thickness = scene.kezuri.stock.plate.dimensions.z       # the sample plate, in mm (a millimetre scene)
    assert thickness == pytest.approx(20.0)
    scene.kezuri.engrave.base_depth = -30.0
    with pytest.raises(Exception, match=r"base depth -30 mm - amplitude 0\.8 mm cuts to Z -30\.8, through the "
                                        r"20 mm plate") as error:
        shell.run_engrave(scene, bpy.context.evaluated_depsgraph_get())
    assert isinstance(error.value, ValueError)               # an InputError: shown to the user, not a bug
    blend = tmp_path / "deep.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend), copy=True)
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    done = subprocess.run([sys.executable, os.path.join(root, "batch.py"), "engrave", "--blend", str(blend),
                           "--out", str(tmp_path / "out")], capture_output=True, text=True, timeout=600, cwd=root)
    assert done.returncode == 2, done.stderr[-2000:]
    assert "through the 20 mm plate" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "out" / "engrave.nc").exists() and not list((tmp_path / "out").glob("*.n*"))


def test_a_scripted_export_without_a_post_writes_the_scenes_post(scene, tmp_path):
    """``bpy.ops.kezuri.engrave_export(filepath=...)`` from a script: the post is the scene's (as the
    file browser would start with), not the operator's first choice; an explicit post still wins."""
    scene.kezuri.machine.post = "linuxcnc"
    path = tmp_path / "plate.ngc"
    assert bpy.ops.kezuri.engrave_export(filepath=str(path)) == {"FINISHED"}
    text = path.read_text()
    assert "(POST: LINUXCNC)" in text and not text.startswith("%\nO")
    explicit = tmp_path / "plate.nc"
    assert bpy.ops.kezuri.engrave_export(filepath=str(explicit), post="fanuc") == {"FINISHED"}
    assert "(POST: FANUC)" in explicit.read_text()
