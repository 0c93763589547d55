"""V-carving checked on SIMULATED cuts (the height field), against closed forms worked out here:
a strip of width w carved with an angle a is w / (2 tan(a/2)) deep on its centre line and, at a
cell centre a distance d from the nearer wall, d / tan(a/2) deep; the carved outline at the top
lies within 0.02 mm of the design (every cell centre 0.02 mm inside is cut, none 0.02 mm outside
is); with a maximum depth the floor is flat at it.  Letters (Latin and kanji, from Blender's fonts)
the same way; every program read by LinuxCNC's rs274 and the controller-rules reader on every
milling post; hostile regions refused by name within a time limit."""
import math
import re
import time

import numpy as np
import pytest

import controller_rules
import rs274
from kezuri.post import registry
from kezuri.toolpath.engines import region as rg
from kezuri.toolpath.ir.program import Program, Tool
from kezuri.toolpath.job import Job, JobOperation, Setup, plan_job
from kezuri.toolpath.operations.vcarve import vcarve as vc
from kezuri.toolpath.operations.vcarve.kind import VCarveGeometry
from kezuri.toolpath.simulate import simulate

CELL = 0.05
CONTROLS = {"fanuc": "fanuc-mill", "linuxcnc": "linuxcnc", "grbl": "grbl"}


def strip(w, length=30.0):
    return np.array([[0, 0], [length, 0], [length, w], [0, w]], float)


def simulated(loops, settings, cell=CELL):
    result = vc.plan(loops, settings)
    x0, y0, x1, y1 = rg.from_loops(loops).bounds()
    sim = simulate(result.operations, (x0 - 2, y0 - 2, -25, x1 + 2, y1 + 2, 0), cell=cell)
    return result, sim


def cells(sim):
    hf = sim.heightfield
    x, y = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    return np.column_stack([x.ravel(), y.ravel()]), (hf.top - np.maximum(hf.heights, hf.bottom)).ravel()


def outline_errors(loops, sim, band=0.02):
    """(cells 0.02 mm inside the design left uncut, cells 0.02 mm outside it cut)."""
    design = rg.from_loops(loops)
    xy, depth = cells(sim)
    inner = rg.contains_points(rg.offset(design, -band), xy)
    outer = ~rg.contains_points(rg.offset(design, band), xy)
    return int(np.sum(inner & (depth <= 1e-6))), int(np.sum(outer & (depth > 1e-6)))


@pytest.mark.parametrize("angle, w", [(60.0, 6.0), (90.0, 5.0), (30.0, 3.0)])
def test_a_strip_is_w_over_2_tan_half_angle_deep_on_its_centre_line(angle, w):
    settings = vc.VCarveSettings(tool=vc.vbit(3, angle, 12.7, flute_length=20.0))
    result, sim = simulated([strip(w)], settings)
    assert sim.findings == []
    tan = math.tan(math.radians(angle) / 2)
    xy, depth = cells(sim)
    # away from the ends (the corners' bisectors), every cell's depth is its distance to the nearer wall / tan
    middle = (xy[:, 0] > w) & (xy[:, 0] < 30 - w) & (xy[:, 1] > 0) & (xy[:, 1] < w)
    expected = np.minimum(xy[middle, 1], w - xy[middle, 1]) / tan
    assert np.abs(depth[middle] - expected).max() < 0.005
    # on the centre line itself (cell centres 0.025 mm off it: sample the closed form there, and at y = w/2)
    centre = middle & (np.abs(xy[:, 1] - w / 2) <= CELL / 2 + 1e-9)
    assert depth[centre].max() == pytest.approx((w / 2 - np.abs(xy[centre, 1] - w / 2).min()) / tan, abs=0.002)
    assert result.deepest == pytest.approx(w / (2 * tan), abs=0.002)
    assert outline_errors([strip(w)], sim) == (0, 0)


L_SHAPE = np.array([[0, 0], [20, 0], [20, 8], [8, 8], [8, 20], [0, 20]], float)


def ring(r_out, r_in, n=256):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return [np.column_stack([r_out * np.cos(a), r_out * np.sin(a)]), np.column_stack([r_in * np.cos(a), r_in * np.sin(a)])]


@pytest.mark.parametrize("name, loops", [("L", [L_SHAPE]), ("ring", ring(8.0, 5.0)),
                                         ("star", [np.array([[10 * math.cos(t) * (1 if k % 2 == 0 else 0.4),
                                                              10 * math.sin(t) * (1 if k % 2 == 0 else 0.4)]
                                                             for k, t in enumerate(np.linspace(0, 2 * np.pi, 10,
                                                                                               endpoint=False))])])])
def test_the_carved_top_outline_lies_within_0_02_mm_of_the_design(name, loops):
    _, sim = simulated(loops, vc.VCarveSettings())
    assert sim.findings == []
    assert outline_errors(loops, sim) == (0, 0)


def test_max_depth_cuts_a_flat_floor_with_the_end_mill_and_keeps_the_outline():
    rect = strip(20.0, 40.0)
    settings = vc.VCarveSettings(max_depth=2.0)
    result, sim = simulated([rect], settings)
    assert [op.tool.kind for op in result.operations] == ["flat", "vbit"]
    assert sim.findings == []
    xy, depth = cells(sim)
    r_max = 2.0 * math.tan(math.radians(30))
    # the floor: every cell farther than r_max from the walls is 2.0 deep, but in the flat floor's
    # four square corners, which the 3.175 mm end mill's radius cannot reach (reported, below)
    near_x = np.minimum(xy[:, 0], 40 - xy[:, 0])
    near_y = np.minimum(xy[:, 1], 20 - xy[:, 1])
    corner = (near_x < r_max + 1.6) & (near_y < r_max + 1.6)
    floor = (np.minimum(near_x, near_y) > r_max + 0.05)
    assert np.abs(depth[floor & ~corner] - 2.0).max() < 1e-3
    # the walls: distance / tan up to the floor
    wall = (xy[:, 0] > 10) & (xy[:, 0] < 30) & (xy[:, 1] > 0) & (xy[:, 1] < r_max)
    assert np.abs(depth[wall] - xy[wall, 1] / math.tan(math.radians(30))).max() < 0.005
    assert outline_errors([rect], sim) == (0, 0)
    assert sorted(np.round(result.left, 0).tolist()) == [[2.0, 2.0], [2.0, 18.0], [38.0, 2.0], [38.0, 18.0]]
    # what stands in those corners is lower than the bound the warning gives
    bound = float(re.search(r"ridges up to ([0-9.]+) mm", " ".join(result.warnings)).group(1))
    assert (2.0 - depth[floor & corner]).max() <= bound


def test_floor_parts_the_end_mill_cannot_reach_are_reported_by_place():
    result = vc.plan([strip(6.0)], vc.VCarveSettings(max_depth=3.0))
    assert len(result.left) == 1 and result.left[0] == pytest.approx((15.0, 3.0), abs=0.01)
    assert any("cannot reach 1 part(s) of the flat floor" in w and "X15.00 Y3.00" in w for w in result.warnings)


def text_loops(body, font=None, size=10.0):
    """The outlines of a Blender Text object (mm), as the shell's conversion would give them."""
    bpy = pytest.importorskip("bpy")
    curve = bpy.data.curves.new("VCarveText", "FONT")
    curve.body = body
    curve.size = size
    if font:
        curve.font = bpy.data.fonts.load(font, check_existing=True)
    obj = bpy.data.objects.new("VCarveText", curve)
    bpy.context.scene.collection.objects.link(obj)
    try:
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        mesh = evaluated.to_mesh()
        vertices = np.array([v.co[:2] for v in mesh.vertices])
        faces = [vertices[list(p.vertices)] for p in mesh.polygons]
        evaluated.to_mesh_clear()
    finally:
        bpy.data.objects.remove(obj)
        bpy.data.curves.remove(curve)
    return rg.loops(rg.union_of_faces(faces, body))


def cjk_font():
    bpy = pytest.importorskip("bpy")
    import os
    path = os.path.join(bpy.utils.system_resource("DATAFILES", path="fonts"), "Noto Sans CJK Regular.woff2")
    if not os.path.exists(path):
        pytest.skip("Blender's CJK font is not installed")
    return path


@pytest.mark.parametrize("body, font", [("Kezuri", None), ("欅鬱", "cjk")])
def test_letters_are_carved_to_their_outline(body, font):
    loops = text_loops(body, cjk_font() if font else None, size=12.0)
    settings = vc.VCarveSettings(tool=vc.vbit(3, 60.0, 6.35))
    result, sim = simulated(loops, settings)
    assert sim.findings == []
    assert outline_errors(loops, sim) == (0, 0)
    # the deepest point is the widest stroke's inscribed circle: no cell deeper than the planner says
    _, depth = cells(sim)
    assert depth.max() <= result.deepest + 1e-3


def posted(result, post):
    program = Program("vcarve", result.operations)
    return registry.find("milling", post)().to_text(program)


@pytest.mark.parametrize("post", sorted(CONTROLS))
def test_every_milling_post_writes_a_program_rs274_and_the_rules_read(post):
    result = vc.plan([L_SHAPE], vc.VCarveSettings(max_depth=2.0, tool=vc.vbit(3, 90.0, 12.7)))
    text = posted(result, post)
    assert controller_rules.check(text, CONTROLS[post]) == []
    if post == "linuxcnc" and rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text, tools=(3, 4)))
        assert points[:, 2].min() == pytest.approx(-2.0, abs=1e-4)
        # the V-bit never feeds straight down into material (it enters along its cone)
        kinds = np.array(kinds)
        step = points[1:] - points[:-1]
        down = (kinds[1:] == "feed") & (step[:, 2] < -1e-6) & (points[1:, 2] < -1e-4)
        assert np.all(np.hypot(step[down, 0], step[down, 1]) > 1e-4)


def test_a_job_of_one_vcarve_passes_its_own_check():
    geometry = VCarveGeometry((L_SHAPE,), "L")
    planned = plan_job(Job(Setup(name="vc"), (JobOperation("vcarve", "L", vc.VCarveSettings(max_depth=2.0), geometry),)))
    program, stock, limits = planned.simulation()
    sim = simulate(program, stock, cell=0.1, **limits)
    assert sim.findings == []


def test_tip_angle_is_the_tools_and_reaches_the_simulation():
    tool = vc.vbit(3, 60.0, 12.7)
    assert tool.shape.tip_angle_deg == 60.0 and tool.shape.tip_tan == pytest.approx(math.tan(math.radians(30)))
    assert Tool(3, "vbit", 12.7).shape.tip_angle_deg == 90.0
    assert "60 deg V-bit" in tool.describe()
    with pytest.raises(Exception, match="tip angle"):
        Tool(3, "flat", 6.0, tip_angle=60.0)
    with pytest.raises(Exception, match="from 1 to 179"):
        Tool(3, "vbit", 6.0, tip_angle=180.0)


@pytest.mark.parametrize("loops, message", [
    ([np.array([[0, 0], [10, 10], [10, 0], [0, 5]], float)], r"crosses itself"),
    ([np.array([[0, 0], [10, 0], [20, 0]], float)], r"encloses no area"),
    ([np.array([[0, 0], [0.01, 0], [0.01, 0.01], [0, 0.01]], float)], r"encloses no area"),
    ([np.array([[0, 0], [np.nan, 0], [1, 1]], float)], r"(?i)nan|not a number|finite"),
    ([np.array([[0, 0], [1e6, 0], [1e6, 1e6], [0, 1e6]], float)], r"(?i)beyond|wide|reach"),
    ([], r"no closed loop"),
])
def test_hostile_regions_are_refused_by_name_quickly(loops, message):
    started = time.process_time()
    with pytest.raises(vc.VCarveError, match=message):
        vc.plan(loops, vc.VCarveSettings(), name="sign")
    assert time.process_time() - started < 5.0


@pytest.mark.parametrize("changes, message", [
    ({"tool": Tool(3, "flat", 6.0)}, r"tool must be a V-bit"),
    ({"max_depth": -1.0}, r"max_depth must be 0 or more"),
    ({"max_depth": 20.0}, r"deeper than|max_depth can be"),
    ({"tolerance": 0.0}, r"tolerance must be from"),
    ({"inlay": "plug"}, r"inlay must be one of"),
    ({"inlay": "male"}, r"a male plug needs max_depth"),
    ({"inlay": "female", "start_depth": 3.0, "max_depth": 2.0}, r"bottoms out"),
    ({"feed": float("nan")}, r"feed must be a number"),
])
def test_bad_settings_are_refused_by_name(changes, message):
    with pytest.raises(vc.VCarveError, match=message):
        vc.plan([L_SHAPE], vc.VCarveSettings(**changes), name="sign")


def test_a_region_wider_than_the_bit_asks_for_max_depth():
    with pytest.raises(vc.VCarveError, match=r"wider than the .* set max_depth \(at most 5\.499 mm\)"):
        vc.plan([strip(20.0)], vc.VCarveSettings(tool=vc.vbit(3, 60.0, 6.35)))
