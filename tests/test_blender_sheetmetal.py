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
    # The punched sheet beside the flat pattern: the part (as it comes out at its joints) and the skeleton.
    punched = bpy.data.objects["Kezuri Sheet punched part"]
    skeleton = bpy.data.objects["Kezuri Sheet skeleton"]
    assert min(v.co.x for v in punched.data.vertices) > max(v.co.x for v in flat.data.vertices)
    assert max(v.co.x for v in punched.data.vertices) < max(v.co.x for v in skeleton.data.vertices)
    # the punched part is the flat pattern, moved along X only (its outline at the pattern's place;
    # within the nibbling's scallops, 0.12 mm)
    flat_xy = np.array([v.co[:2] for v in flat.data.vertices])
    part_xy = np.array([v.co[:2] for v in punched.data.vertices])
    assert part_xy[:, 1].min() == pytest.approx(flat_xy[:, 1].min(), abs=0.15)
    assert part_xy[:, 1].max() == pytest.approx(flat_xy[:, 1].max(), abs=0.15)
    assert np.ptp(part_xy[:, 0]) == pytest.approx(np.ptp(flat_xy[:, 0]), abs=0.3)


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
    # one line per corner of the contour, and the two micro-joints split two of them
    assert nc.count("G72") == nc.count("G69") == len(report["cut_contour"]) + 2
    ET.fromstring((out / "unfold.svg").read_text())
    assert (out / "unfold.dxf").read_text().rstrip().endswith("EOF")
    assert (out / "unfold.png").stat().st_size > 10_000
    simulation = report["simulation"]
    assert simulation["engine"] == "crosssection" and simulation["parts_separated"] == [False]
    assert simulation["held_by_joints"] == [True]          # by its two micro-joints, as meant
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
    assert simulation["parts_separated"] == [False] * 4 and simulation["gouges"] == []
    assert simulation["held_by_joints"] == [True] * 4


# ----- the punching job checked before anything is written ---------------------------------------

def test_batch_elbow_punches_each_piece_from_its_own_sheet(tmp_path):
    """Each piece's program has the piece's pattern on a sheet of its own, where the report says
    it sits (the others no longer stacked above the first), and its hits read back are the
    pattern compensated by the punch radius: within 0.01 mm of r from the pattern."""
    done = run_batch("elbow", "--diameter", "100", "--bend-radius", "150", "--angle", "90", "--pieces", "5",
                     "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["gate"] == {"findings": [], "overridden": False, "seconds": report["gate"]["seconds"]}
    from kezuri.toolpath.operations.sheetmetal import punch
    for index, piece in enumerate(report["pieces"], start=1):
        outline = np.array(piece["outline"]) - np.array(piece["outline"]).min(axis=0)
        program = punch.read_amada((tmp_path / f"elbow-{index}.nc").read_text())
        offset = np.array(report["sheet"]["parts"][index - 1]["offset"])
        assert offset[0] > 0 and offset[1] > 0
        assert program.hits.min(axis=0) == pytest.approx(offset - 5.0, abs=0.011)     # 10 mm punch, radius 5
        assert program.hits.max(axis=0) == pytest.approx(outline.max(axis=0) + 5.0 + offset, abs=0.011)


def test_the_punch_gate_refuses_a_bite_and_a_part_left_in_the_sheet():
    """The gate on real punching results: a hit biting 1 mm into the part, and hits a diameter
    apart (the part stays in the sheet), are refused naming the line; allowed, they are recorded
    as overridden.  Bites within what the NC words' two decimals explain pass."""
    from test_punch import RECT, rectangle_program

    from kezuri.operators import gate, sheetjobs
    from kezuri.toolpath.operations.sheetmetal import punch
    text = rectangle_program(2.0, 1.0)
    bigger = RECT + np.array([[-1.0, 0], [0, 0], [0, 0], [-1.0, 0]])
    bitten = punch.simulate_punching(text, punch_diameter=2.0, pattern=bigger)
    webbed = punch.simulate_punching(rectangle_program(2.0, 2.0), punch_diameter=2.0, pattern=RECT)
    clean = punch.simulate_punching(text, punch_diameter=2.0, pattern=RECT)
    with pytest.raises(gate.GateRefused, match=r"not written: the punching simulation found 1 fault\(s\): line 9: "
                                               r"a hit bites 1\.000 mm"):
        sheetjobs.punch_gate([bitten], False)
    with pytest.raises(gate.GateRefused, match="piece 2: the part stays in the sheet"):
        sheetjobs.punch_gate([clean, webbed], False)
    report = sheetjobs.punch_gate([bitten, webbed], True)
    assert report["overridden"] and [f["kind"] for f in report["findings"]] == ["gouge", "part in sheet"]
    assert sheetjobs.punch_gate([clean], False)["findings"] == []
    # the allowance: the simulation's tolerance, half the 0.01 mm increment both ways, and a line's
    # direction off by half of 0.01 degree along its length
    assert sheetjobs.word_error(0.01, 0.0) == pytest.approx(0.005 * np.sqrt(2))
    assert sheetjobs.word_error(0.01, 1000.0) == pytest.approx(0.005 * np.sqrt(2) + 1000 * np.sin(np.radians(0.005)))


def test_the_export_operators_refuse_what_the_machine_cannot_run(scene, tmp_path):
    """A pitch of a punch diameter or more, and a pipe too wide for the control, are refused
    naming the panel's settings; nothing is written."""
    sheet = scene.kezuri.sheet
    sheet.pitch, sheet.tool_diameter = 12.0, 10.0
    with pytest.raises(RuntimeError, match="Sheet Metal: Nibbling Pitch = 12 mm must be less than Tool Diameter = 10 mm"):
        bpy.ops.kezuri.sheet_export(filepath=str(tmp_path / "quad.nc"))
    with pytest.raises(RuntimeError, match="Nibbling Pitch = 12 mm must be less than"):
        bpy.ops.kezuri.elbow_export(filepath=str(tmp_path / "elbow.dxf"))
    sheet.pitch = 2.0
    sheet.elbow_diameter, sheet.elbow_radius = 4000.0, 5000.0
    with pytest.raises(RuntimeError, match=r"Sheet Metal: piece 1 of Pipe Diameter = 4000 mm: the cut contour is "
                                           r"12\d{3}\.\d x"):
        bpy.ops.kezuri.elbow_export(filepath=str(tmp_path / "elbow.dxf"))
    assert list(tmp_path.iterdir()) == []
    sheet.elbow_diameter, sheet.elbow_radius = 100.0, 150.0
    assert bpy.ops.kezuri.elbow_export(filepath=str(tmp_path / "elbow.dxf")) == {"FINISHED"}
    assert bpy.ops.kezuri.sheet_export(filepath=str(tmp_path / "quad.nc")) == {"FINISHED"}
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["elbow.dxf", "elbow.svg", *[f"elbow-{i}.nc" for i in range(1, 6)], "quad.nc", "quad.dxf", "quad.svg",
         "elbow-setup-sheet.html", "quad-setup-sheet.html"])
