"""W5 in Blender and in batch: operators, CDL import, elbow, batch files and reports."""
import json
import xml.etree.ElementTree as ET

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import panels  # noqa: E402
from blender_helpers import draw_panel, run_batch  # noqa: E402
from test_unfold import PAPER_CDL  # noqa: E402

PAPER_EDGES = [104.40307, 101.98039, 100.49876, 107.70330]
PAPER_DIAGONALS = [150.00000, 141.77447]



@pytest.fixture
def scene(empty_scene):
    scene = empty_scene
    return scene


def flat_edge_lengths(obj):
    mesh = obj.data
    co = np.array([v.co for v in mesh.vertices])
    return {tuple(sorted(e.vertices)): np.linalg.norm(co[e.vertices[0]] - co[e.vertices[1]]) for e in mesh.edges}


def test_unfold_operator_lays_out_an_isometric_flat_pattern(scene):
    assert bpy.ops.kezuri.unfold_quad(divisions=5, direction="vertical", tool_diameter=10.0) == {"FINISHED"}
    part = bpy.data.objects["Kezuri Sheet part (triangulated)"]
    flat = bpy.data.objects["Kezuri Sheet flat pattern"]
    assert len(part.data.polygons) == len(flat.data.polygons) == 10
    part_edges, flat_edges = flat_edge_lengths(part), flat_edge_lengths(flat)
    assert part_edges.keys() == flat_edges.keys()
    for key in part_edges:
        assert flat_edges[key] == pytest.approx(part_edges[key], rel=1e-5)   # float32 mesh storage
    flat_z = np.array([v.co.z for v in flat.data.vertices])
    assert np.allclose(flat_z, 0)
    # Beside the part, not on top of it.
    assert min(v.co.x for v in flat.data.vertices) > max(v.co.x for v in part.data.vertices)
    assert scene.kezuri.sheet.direction == "vertical"      # the redo settings are kept in the scene
    # The punched sheet beside the flat pattern: the part fell out of the skeleton.
    punched = bpy.data.objects["Kezuri Sheet punched part"]
    skeleton = bpy.data.objects["Kezuri Sheet skeleton"]
    assert min(v.co.x for v in punched.data.vertices) > max(v.co.x for v in flat.data.vertices)
    assert max(v.co.x for v in punched.data.vertices) < max(v.co.x for v in skeleton.data.vertices)


def test_unfold_in_a_metre_scene_has_the_same_physical_size(scene):
    scene.unit_settings.scale_length = 1.0
    bpy.ops.kezuri.unfold_quad(divisions=5)
    part = bpy.data.objects["Kezuri Sheet part (triangulated)"]
    zs = [v.co.z for v in part.data.vertices]
    assert max(zs) == pytest.approx(0.1)      # 100 mm = 0.1 m


def test_cdl_import_then_unfold(scene, tmp_path):
    path = tmp_path / "quad.cdl"
    path.write_text(PAPER_CDL)
    scene.kezuri.sheet.corners = [0.0] * 12
    assert bpy.ops.kezuri.import_cdl(filepath=str(path)) == {"FINISHED"}
    assert np.allclose(np.array(scene.kezuri.sheet.corners).reshape(4, 3),
                       [[0, 0, 0], [0, 30, 100], [100, 50, 100], [100, 40, 0]])
    assert "Kezuri Sheet imported quad" in bpy.data.objects


def test_corners_from_selected_face(scene):
    mesh = bpy.data.meshes.new("Quad")
    mesh.from_pydata([(0, 0, 0), (0, 30, 100), (100, 50, 100), (100, 40, 0)], [], [(0, 1, 2, 3)])
    obj = bpy.data.objects.new("Quad", mesh)
    scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.kezuri.quad_from_selection() == {"FINISHED"}
    assert np.allclose(np.array(scene.kezuri.sheet.corners).reshape(4, 3)[1], [0, 30, 100])


def test_collinear_corners_are_refused(scene):
    scene.kezuri.sheet.corners = [0, 0, 0, 10, 0, 0, 20, 0, 0, 0, 10, 0]
    with pytest.raises(RuntimeError, match="collinear|degenerate|straight line"):
        bpy.ops.kezuri.unfold_quad()


def test_elbow_operator_adds_pieces_and_patterns(scene):
    assert bpy.ops.kezuri.add_elbow(elbow_diameter=100, elbow_radius=150, elbow_angle=90,
                                    elbow_pieces=5) == {"FINISHED"}
    pieces = [o for o in bpy.data.objects if o.name.startswith("Kezuri Elbow piece")]
    patterns = [o for o in bpy.data.objects if o.name.startswith("Kezuri Elbow pattern")]
    assert len(pieces) == len(patterns) == 5
    from kezuri.operators.convert import curve_points
    xs = curve_points(patterns[0])[:, 0]
    width = xs.max() - xs.min()
    assert width == pytest.approx(np.pi * 100, rel=1e-5)


def test_sheet_panel_draws_its_settings(scene):
    layout = draw_panel(panels.KEZURI_PT_sheet, bpy.context)
    assert {"divisions", "direction", "tool_diameter", "thickness", "pitch", "station", "corners"} <= \
        set(layout.props)
    assert {"kezuri.unfold_quad", "kezuri.sheet_export", "kezuri.import_cdl"} <= set(layout.operators)




@pytest.mark.parametrize("direction", ["horizontal", "vertical"])
def test_batch_unfold_reports_the_papers_numbers(tmp_path, direction):
    out = tmp_path / direction
    done = run_batch("unfold", "--corners", "0,0,0;0,30,100;100,50,100;100,40,0", "--divisions", "5",
                 "--direction", direction, "--tool-diameter", "10", "--thickness", "1.6", "--out", str(out))
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads((out / "report.json").read_text())
    assert report["edge_lengths"] == pytest.approx(PAPER_EDGES, abs=1e-5)
    assert report["diagonals"] == pytest.approx(PAPER_DIAGONALS, abs=1e-5)
    assert len(report["triangles"]) == 10
    for triangle in report["triangles"]:
        a3, a2 = np.array(triangle["3d"]), np.array(triangle["2d"])
        for i, j in ((0, 1), (1, 2), (2, 0)):
            assert np.linalg.norm(a2[i] - a2[j]) == pytest.approx(np.linalg.norm(a3[i] - a3[j]), abs=2e-6)
    nc = (out / "unfold.nc").read_text()
    assert nc.splitlines()[0].startswith("N000 G92 X1000.00 Y1040.00")
    assert nc.count("G72") == nc.count("G69") == len(report["cut_contour"])
    ET.fromstring((out / "unfold.svg").read_text())
    assert (out / "unfold.dxf").read_text().rstrip().endswith("EOF")
    assert (out / "unfold.png").stat().st_size > 10_000
    simulation = report["simulation"]
    assert simulation["engine"] == "crosssection" and simulation["parts_separated"] == [True]
    assert simulation["gouges"] == [] and simulation["max_gouge_mm"] == 0
    # the default 2 mm pitch with the 10 mm punch: cusps of 5 - sqrt(24) = 0.10 mm, corners a little more
    assert 0.09 < simulation["max_scallop_mm"] < 0.14
    pattern_area = abs(np.sum(np.cross(np.array(report["outline"]), np.roll(np.array(report["outline"]), -1, 0)))) / 2
    assert simulation["pattern_area_mm2"] == [pytest.approx(pattern_area, abs=0.01)]
    assert pattern_area < simulation["part_area_mm2"][0] < pattern_area * 1.005


def test_batch_unfold_reads_a_cdl_file_and_refuses_an_open_one(tmp_path):
    good = tmp_path / "paper.cdl"
    good.write_text(PAPER_CDL)
    done = run_batch("unfold", "--cdl", str(good), "--out", str(tmp_path / "a"))
    assert done.returncode == 0, done.stderr[-2000:]
    assert json.loads((tmp_path / "a" / "report.json").read_text())["corners"][2] == [100, 50, 100]
    broken = tmp_path / "open.cdl"
    broken.write_text(PAPER_CDL.replace("LINE 100.0000000000, 50.0000000000, 100.0000000000",
                                        "LINE 100.0000000000, 55.0000000000, 100.0000000000"))
    done = run_batch("unfold", "--cdl", str(broken), "--out", str(tmp_path / "b"))
    assert done.returncode == 2 and "CDL line" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "b" / "unfold.nc").exists()


def test_batch_elbow_reports_piece_outlines(tmp_path):
    done = run_batch("elbow", "--diameter", "100", "--bend-radius", "150", "--angle", "90", "--pieces", "4",
                 "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert len(report["pieces"]) == 4
    theta = np.radians(90 / 3)
    middle = report["pieces"][1]
    assert middle["shortest_mm"] == pytest.approx(2 * (150 - 50) * np.tan(theta / 2), abs=1e-3)
    assert middle["longest_mm"] == pytest.approx(2 * (150 + 50) * np.tan(theta / 2), abs=1e-3)
    outline = np.array(middle["outline"])
    assert outline[:, 0].max() - outline[:, 0].min() == pytest.approx(np.pi * 100, abs=1e-6)
    programs = sorted(tmp_path.glob("elbow-*.nc"))
    assert [p.name for p in programs] == [f"elbow-{i}.nc" for i in (1, 2, 3, 4)]
    assert all(p.read_text().rstrip().endswith("G50") for p in programs)
    simulation = report["simulation"]
    assert simulation["parts_separated"] == [True] * 4 and simulation["gouges"] == []
