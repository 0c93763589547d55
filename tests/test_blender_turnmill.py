"""W4 in Blender and batch: both ray engines agree, face colours, paths, NC and CL data."""
import json

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import rs274  # noqa: E402
from kezuri.operators import panels, samples  # noqa: E402
from kezuri.operators import turnmill as shell  # noqa: E402
from kezuri.toolpath.operations.turnmill import turnmill as core  # noqa: E402
from blender_helpers import draw_panel, run_batch  # noqa: E402




@pytest.fixture
def scene(empty_scene):
    scene = empty_scene
    samples.turnmill_part(scene)
    return scene


def test_blender_bvh_and_trimesh_engines_give_the_same_labels():
    vertices, faces, _ = core.sample_part(segments=96)
    bvh = core.classify_faces(vertices, faces, shell.BVHRayEngine(vertices, faces))
    tri = core.classify_faces(vertices, faces, core.TrimeshRayEngine(vertices, faces))
    assert np.array_equal(bvh, tri)
    assert {int(k) for k in np.unique(bvh)} >= {core.NEITHER, core.RADIAL, core.AXIAL}


def test_classify_colours_the_faces(scene):
    assert bpy.ops.kezuri.turnmill_classify() == {"FINISHED"}
    part = scene.kezuri.turnmill.part
    attribute = part.data.color_attributes[shell.ATTRIBUTE]
    first_corner = np.array([p.loop_start for p in part.data.polygons])
    colours = np.array([tuple(d.color) for d in attribute.data])[first_corner]
    normals = np.array([tuple(p.normal) for p in part.data.polygons])
    centres = np.array([tuple(p.center) for p in part.data.polygons])
    # The end face (normal +Z at z = 0) is axial (green); the bar's outside surface radial (blue).
    end_face = (normals[:, 2] > 0.99) & np.isclose(centres[:, 2], 0.0)
    side = (np.abs(normals[:, 2]) < 1e-6) & (np.hypot(centres[:, 0], centres[:, 1]) > 42.0)
    assert end_face.any() and side.any()
    assert np.allclose(colours[end_face], shell.LABEL_COLOURS[core.AXIAL], atol=1e-6)
    assert np.allclose(colours[side], shell.LABEL_COLOURS[core.RADIAL], atol=1e-6)


def test_generate_and_export_xzc_linuxcnc_and_cl(scene, tmp_path):
    assert bpy.ops.kezuri.turnmill_generate() == {"FINISHED"}
    names = {o.name for o in bpy.data.collections["Kezuri"].objects}
    assert {"Kezuri Turn-Mill radial finishing", "Kezuri Turn-Mill axial finishing"} <= names
    for post, ext in (("linuxcnc", ".ngc"), ("xzc", ".nc"), ("cldata", ".cl")):
        path = tmp_path / f"part{ext}"
        assert bpy.ops.kezuri.turnmill_export(filepath=str(path), post=post) == {"FINISHED"}
        assert path.stat().st_size > 1000
    if rs274.available():
        kinds, points, rotary = rs274.motion_endpoints(rs274.run((tmp_path / "part.ngc").read_text()))
        assert np.max(np.abs(np.diff(rotary[:, 2]))) <= 180 + 1e-6


def test_empty_selection_is_a_clear_error(scene):
    scene.kezuri.turnmill.selected_only = True
    for polygon in scene.kezuri.turnmill.part.data.polygons:
        polygon.select = False
    with pytest.raises(RuntimeError, match="no faces are selected"):
        bpy.ops.kezuri.turnmill_generate()


def test_non_manifold_part_is_refused(scene):
    mesh = bpy.data.meshes.new("Fins")
    mesh.from_pydata([(0, 0, 0), (10, 0, 0), (0, 10, 0), (0, -10, 0), (0, 0, 10)], [],
                     [(0, 1, 2), (0, 1, 3), (0, 1, 4)])            # three faces on one edge
    obj = bpy.data.objects.new("Fins", mesh)
    scene.collection.objects.link(obj)
    scene.kezuri.turnmill.part = obj
    with pytest.raises(RuntimeError, match="more than two faces|non-manifold"):
        bpy.ops.kezuri.turnmill_generate()


def test_part_off_the_axis_is_refused(scene):
    scene.kezuri.turnmill.part.location.x = 200
    with pytest.raises(RuntimeError, match="axis|stock"):
        bpy.ops.kezuri.turnmill_generate()


def test_turnmill_panel(scene):
    layout = draw_panel(panels.KEZURI_PT_turnmill, bpy.context)
    assert {"part", "stock_radius", "engine"} <= set(layout.props)
    assert {"kezuri.turnmill_classify", "kezuri.turnmill_generate", "kezuri.turnmill_export"} <= \
        set(layout.operators)


def test_batch_turnmill_report(tmp_path):
    done = run_batch("turnmill", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["rays"] > 10000 and report["classification_seconds"] > 0
    labels = {f["label"] for f in report["faces"]}
    assert labels <= {"radial", "axial", "both", "none"} and {"radial", "axial", "none"} <= labels
    for face in report["faces"]:
        assert len(face["centroid"]) == 3
    end_face = [f for f in report["faces"] if abs(f["centroid"][2]) < 1e-6 and np.hypot(*f["centroid"][:2]) < 40]
    assert end_face and all(f["label"] == "axial" for f in end_face)
    assert [op["name"] for op in report["operations"]] == ["radial roughing", "radial finishing", "axial roughing",
                                                           "axial finishing"]
    simulation = report["simulation"]
    assert simulation["engine"] == "radiusmap+heightfield"
    assert simulation["gouges"] == [] and simulation["rapid_collisions"] == [] and simulation["max_gouge_mm"] == 0
    # what the sample's features take out of the bar, less the ball's fillets in their corners
    assert 18000 < simulation["removed_volume_mm3"] < 21000
    assert (tmp_path / "turnmill.png").stat().st_size > 10000
    assert (tmp_path / "turnmill-toolpaths.png").stat().st_size > 10000


def test_the_panel_reports_the_faces_it_skips_and_what_the_machine_cannot_take(empty_scene, tmp_path, capfd):
    """A hex bar with a cross hole: Generate and Export warn about the hole's 64 faces, and Export
    about the program's size against the 0i-T's 512 kB and its blocks under 7.5 ms."""
    from test_turnmill_unmachined import hex_bar_with_hole

    vertices, faces, stock = hex_bar_with_hole()
    mesh = bpy.data.meshes.new("Hex bar")
    mesh.from_pydata(vertices.tolist(), [], faces.tolist())
    mesh.update()
    part = bpy.data.objects.new("Hex bar", mesh)
    empty_scene.collection.objects.link(part)
    props = empty_scene.kezuri.turnmill
    props.part = part
    props.stock_radius, props.stock_z_min, props.stock_z_max = stock.radius, stock.z_min, stock.z_max
    capfd.readouterr()
    assert bpy.ops.kezuri.turnmill_generate() == {"FINISHED"}
    assert "not machined: 64 faces, 752.8 mm2" in "".join(capfd.readouterr())
    path = tmp_path / "hex.nc"
    assert bpy.ops.kezuri.turnmill_export(filepath=str(path), post="xzc") == {"FINISHED"}
    said = "".join(capfd.readouterr())
    size = len(path.read_bytes()) / 1024
    assert "not machined: 64 faces" in said
    assert f"the turnmill-xzc program is {size:,.1f} kB, larger than the 512 kB program memory" in said
    assert "inverse-time blocks shorter than the 7.5 ms" in said
