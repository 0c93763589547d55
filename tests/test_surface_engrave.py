"""The gouge texture on a curved plate (toolpath/operations/engrave/surface_engrave.py), checked against closed forms:
a ball or a flat end resting on a sphere or a cylinder has its tip where elementary geometry says,
and every cut lies at the paper's depths below that, along the tool axis."""
import numpy as np
import pytest

from kezuri import post
from kezuri.toolpath.operations.engrave import engrave, surface_engrave as se
from kezuri.toolpath.engines import region as rg
from kezuri.toolpath.ir.program import FEED, Program
from kezuri.toolpath.simulate import simulate
from macrob import run_program
import rs274
from test_engrave import LETTERS, PLATE
import controller_rules
import test_macro_program as tm
from test_hostile import time_limit

R_DOME, R_CYL = 800.0, 150.0


def dome_z(x, y):
    return np.sqrt(R_DOME ** 2 - x ** 2 - y ** 2) - R_DOME


def cylinder_z(x, y):
    return np.sqrt(R_CYL ** 2 - y ** 2) - R_CYL


def ball_tip_on_sphere(x, y, r, radius=R_DOME):
    """A ball of radius r touching a sphere of radius R (centre (0, 0, -R)) from outside:
    its centre is R + r from the sphere's centre, the tip r below its centre."""
    return np.sqrt((radius + r) ** 2 - x ** 2 - y ** 2) - radius - r


def ball_tip_on_cylinder(x, y, r, radius=R_CYL):
    return np.sqrt((radius + r) ** 2 - y ** 2) - radius - r


def flat_tip_on_sphere(x, y, r, radius=R_DOME):
    """A flat end of radius r over a dome: its rim meets the highest point under it, the one
    nearest the dome's axis."""
    rho = np.maximum(np.hypot(x, y) - r, 0.0)
    return np.sqrt(radius ** 2 - rho ** 2) - radius


def flat_tip_on_cylinder(x, y, r, radius=R_CYL):
    return np.sqrt(radius ** 2 - np.maximum(np.abs(y) - r, 0.0) ** 2) - radius


PROGRESS = []


@pytest.fixture(scope="module")
def dome_job():
    surface = se.Surface(*se.dome(-101, -51, 101, 51, -20, cell=0.5), "dome")
    with time_limit(120):
        return se.plan(PLATE, LETTERS, surface, plate_thickness=20,
                       progress=lambda fraction, text: PROGRESS.append(fraction))


@pytest.fixture(scope="module")
def cylinder_job():
    surface = se.Surface(*se.cylinder(-101, -51, 101, 51, -20, cell=0.5), "cylinder")
    return se.plan(PLATE, LETTERS, surface, plate_thickness=20)


def cutting(op):
    keep = (op.kind == FEED) & (op.xyz[:, 2] < op.clearance_z - 1e-9)
    return op.xyz[keep]


def flat_depth_at(flat_op, xy, near):
    """The flat (baked) program's depth at points of its path: linear along each move; where
    several moves pass over a point (the band's levels and ramps), the one nearest ``near``."""
    starts = flat_op.start_points()
    out = np.full(len(xy), np.nan)
    for a, b in zip(starts[flat_op.kind == FEED], flat_op.xyz[flat_op.kind == FEED]):
        span = b[:2] - a[:2]
        length2 = float(span @ span)
        if length2 < 1e-18:
            continue
        t = (xy - a[:2]) @ span / length2
        off = np.linalg.norm(a[:2] + np.outer(t, span) - xy, axis=1)
        on = (t >= -1e-9) & (t <= 1 + 1e-9) & (off < 1e-6)
        depth = a[2] + t * (b[2] - a[2])
        closer = on & (np.isnan(out) | (np.abs(depth - near) < np.abs(out - near)))
        out[closer] = depth[closer]
    return out


@pytest.mark.parametrize("shape", ["dome", "cylinder"])
def test_every_cut_is_the_papers_depth_below_the_surface_along_the_tool_axis(shape, dome_job, cylinder_job):
    job = dome_job if shape == "dome" else cylinder_job
    baked_flat, depths = engrave.bake(job.result.program)
    assert depths == job.depths and len(depths) > 100
    for op, flat_op in zip(job.baked.operations, baked_flat.operations):
        points = cutting(op)
        x, y = points[:, 0], points[:, 1]
        r = op.tool.radius
        if op.tool.kind == "ball":
            touch = ball_tip_on_sphere(x, y, r) if shape == "dome" else ball_tip_on_cylinder(x, y, r)
        else:
            touch = flat_tip_on_sphere(x, y, r) if shape == "dome" else flat_tip_on_cylinder(x, y, r)
        depth = points[:, 2] - touch                      # below the touching tool, along its axis
        expected = flat_depth_at(flat_op, points[:, :2], depth)  # the flat plan's depth at that point
        assert np.isfinite(expected).mean() > 0.99
        ok = np.isfinite(expected)
        assert np.max(np.abs(depth[ok] - expected[ok])) < 2e-3   # mesh chords of a 0.5 mm grid
        # the paper's range, on its 0.2 mm grid at every gouge vertex; the band from the surface (its
        # ramps start there) to its -2.0
        if flat_op is baked_flat.operations[0]:
            assert depth.min() > -2.8 - 2e-3 and depth.max() < -1.2 + 2e-3
        else:
            assert depth.min() > -2.0 - 2e-3 and depth.max() < 2e-3
        # under the tip the cut is never deeper than the depth (the tool rests on the surface)
        below_surface = points[:, 2] - (dome_z(x, y) if shape == "dome" else cylinder_z(x, y))
        assert np.all(below_surface >= depth - 1e-9 - 2e-3)


def test_the_gouge_vertices_sit_on_the_paper_depth_grid(dome_job):
    op = dome_job.macro.operations[0]
    marks = op.texture_marks
    ends = (marks[:, 1] == 1.0) & np.isfinite(marks[:, 1])
    # with the depths added by the baked program, each gouge ends on base + 0.2 k
    baked = dome_job.baked.operations[0]
    x, y = baked.xyz[:, 0], baked.xyz[:, 1]
    depth = baked.xyz[:, 2] - ball_tip_on_sphere(x, y, 3.0)
    feeds = (baked.kind == FEED) & (baked.xyz[:, 2] < 0)
    levels = np.round((depth[feeds] + 2.0) / 0.2)
    on_grid = np.abs(depth[feeds] - (-2.0 + 0.2 * levels)) < 2e-3
    assert on_grid.mean() > 0.3 and ends.sum() > 100
    assert set(np.round(dome_job.depths, 3)) <= {round(-2.0 + 0.2 * k, 3) for k in range(-4, 5)}


def test_no_tool_reaches_into_the_letters(dome_job):
    """Independent check: every tool point's distance from the letters' outline, in XY, is at least
    the tool radius (less the polygon tolerance), so no part of a vertical tool is over a letter."""
    letters = rg.from_loops(LETTERS[0][1], "letters")
    for op in dome_job.baked.operations:
        points = cutting(op)[:, :2]
        inside = rg.contains_points(rg.offset(letters, op.tool.radius - 2 * rg.ARC_TOLERANCE), points)
        assert not inside.any(), op.name


def test_simulation_of_the_dome_job_finds_no_gouge_and_the_cut_depths(dome_job):
    surface = dome_job.surface
    loops = LETTERS[0][1]
    limits = se.simulation_limits(surface, PLATE, loops, dome_job.result.program, -2.0, -20.0)
    stock = se.plate_stock(surface, PLATE, 20.0)
    result = simulate(dome_job.baked, stock, cell=0.25, **limits)
    assert not result.findings, [f.message for f in result.findings[:3]]
    hf = result.heightfield
    gx, gy = np.meshgrid(hf.x(), hf.y(), indexing="ij")
    material = np.clip(hf.heights, hf.bottom, hf.top)
    below = dome_z(gx, gy) - material
    # the letters stand to the surface; the field is cut at most 2.8 mm below it
    letters = rg.from_loops(loops, "letters")
    inside = rg.contains_points(rg.offset(letters, -0.05), np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape)
    assert np.abs(below[inside]).max() < 2e-3
    assert below.max() < 2.8 + 2e-3
    assert np.percentile(below[~inside], 90) > 1.0       # the face is textured, not left standing
    # the volume removed is what lies between the dome and the cut (not the air above the dome)
    analytic = np.sum(np.maximum(below, 0.0)) * hf.cell_x * hf.cell_y
    assert result.removed_volume_mm3 == pytest.approx(analytic, rel=2e-3)


def test_flat_surface_gives_the_flat_program():
    surface = se.Surface(np.array([[-120, -70, 0], [120, -70, 0], [120, 70, 0], [-120, 70, 0]], float),
                         np.array([[0, 1, 2], [0, 2, 3]]), "flat")
    job = se.plan(PLATE, LETTERS, surface)
    baked, _ = engrave.bake(engrave.plan(PLATE, LETTERS).program)
    for followed, flat_op in zip(job.baked.operations, baked.operations):
        # the followed path lies on the flat path's lines at the flat depths
        points = cutting(followed)
        assert np.max(np.abs(points[:, 2] - flat_depth_at(flat_op, points[:, :2], points[:, 2]))) < 1e-9


def test_macro_program_on_the_dome_cuts_what_the_baked_program_cuts(dome_job):
    text = post.milling_post("fanuc-macro").to_text(dome_job.macro)
    assert "G66.1 P7024" in text and "O7024" in text
    # on a machine with every usual axis: no argument may be an axis address (the old B1 C0.05 were)
    run = run_program(text, clock=tm.clock_16ms(64172), start=(0, 0, 100), axes="XYZABCUVW")
    # the macro cuts G01 moves only; every rapid is a main-program block, across the plate at the
    # clearance height, down only to above the surface under the ball
    by_macro = [m for m in run.moves if m.line != m.main_line]
    assert by_macro and all(m.kind == "feed" for m in by_macro)
    rapids = [m for m in run.moves if m.kind == "rapid"]
    assert rapids and all(m.line == m.main_line for m in rapids)
    for m in rapids:
        moved_xy = abs(m.end[0] - m.start[0]) > 1e-9 or abs(m.end[1] - m.start[1]) > 1e-9
        floor = 20.0 if moved_xy else float(ball_tip_on_sphere(m.x, m.y, 3.0)) + 1.0
        assert m.z >= floor - 1e-9, m
    main_lines = text.split("O7024 (")[0].splitlines()
    opened = [n for n, line in enumerate(main_lines) if line.startswith("G66.1 P7024 ")]
    closed = [n for n, line in enumerate(main_lines) if line == "G67"]
    assert len(opened) == len(closed) >= 3 and all(a < b for a, b in zip(opened, closed))
    assert all(b < a for a, b in zip(opened[1:], closed[:-1]))          # balanced, never nested
    for a, b in zip(opened, closed):
        assert " E1 " in main_lines[a]
        assert all(" R" in line and "G" not in line for line in main_lines[a + 1:b])
    digits = tm.model_digits(tm.seed_state(int(64172 // 16) * 16))
    baked_flat, depths = engrave.bake(dome_job.result.program, digits=digits)
    ops = [se.follow(op, dome_job.surface, None)[0] for op in baked_flat.operations]
    baked_run = run_program(post.milling_post("fanuc").to_text(Program("x", ops)), start=(0, 0, 100))
    a, b = tm.path_points(run.moves), tm.path_points(baked_run.moves)
    assert a.shape == b.shape and np.max(np.abs(a - b)) < 1.5e-3
    # the depths the controller cut below the ball resting on the dome follow -2.0 +/- 0.2 k
    band_starts = text.splitlines().index("(OPERATION 2: BAND FINISHING)") + 1     # the roughing: before it
    rough = [m for m in run.moves if m.kind == "feed" and m.z is not None and m.z < 0 and m.main_line < band_starts]
    xyz = np.array([[m.x, m.y, m.z] for m in rough], float)
    depth = xyz[:, 2] - ball_tip_on_sphere(xyz[:, 0], xyz[:, 1], 3.0)
    assert depth.min() > -2.8 - 3e-3 and depth.max() < -1.2 + 3e-3
    levels = {round(-2.0 + 0.2 * k, 1) for k in range(-4, 5)}
    assert set(np.round(depths, 1)) <= levels and len(set(np.round(depths, 1))) >= 7


@pytest.mark.parametrize("name, control", [("fanuc", "fanuc-mill"), ("fanuc-macro", "fanuc-mill"),
                                           ("linuxcnc", "linuxcnc"), ("grbl", "grbl")])
def test_every_post_writes_the_dome_job_legally(dome_job, name, control):
    writer = post.milling_post(name)
    text = writer.to_text(dome_job.macro if writer.needs_texture else dome_job.baked)
    assert not controller_rules.check(text, control)
    if name == "linuxcnc" and rs274.available():
        kinds, points, _ = rs274.motion_endpoints(rs274.run(text))
        feeds = points[[i for i, k in enumerate(kinds) if k == "feed"]]
        want = dome_job.baked.operations
        want_feeds = np.vstack([op.xyz[op.kind == FEED] for op in want])
        assert len(feeds) == len(want_feeds)
        assert np.max(np.abs(feeds - want_feeds)) < 1e-3


def test_a_surface_that_misses_the_plate_is_refused():
    small = se.Surface(*se.dome(-50, -20, 50, 20, -20), "Small Dome")
    with pytest.raises(se.EngraveError, match="Small Dome.*does not cover the plate"):
        se.plan(PLATE, LETTERS, small)


def test_a_surface_above_the_clearance_plane_is_refused():
    v, f = se.dome(-101, -51, 101, 51, -20)
    v[:, 2] += 19.0
    with pytest.raises(se.EngraveError, match="rises to Z"):
        se.plan(PLATE, LETTERS, se.Surface(v, f, "high"))


def test_progress_rises_to_one_and_stopping_it_stops_the_plan(dome_job):
    assert PROGRESS[-1] == 1.0 and len(PROGRESS) > 20
    assert all(b >= a - 1e-12 for a, b in zip(PROGRESS, PROGRESS[1:]))

    class Stop(Exception):
        pass

    calls = []

    def stop_half_way(fraction, text):
        calls.append(fraction)
        if fraction > 0.5:
            raise Stop

    with time_limit(60), pytest.raises(Stop):
        se.plan(PLATE, LETTERS, dome_job.surface, progress=stop_half_way)
    assert max(calls) < 0.7          # it stopped where it was asked to, not at the end


@pytest.mark.parametrize("vertices, faces, message", [
    (np.zeros((0, 3)), np.zeros((0, 3), int), "vertices must be"),
    (np.array([[0, 0, 0], [1, 0, 0], [0, 1, np.nan]]), np.array([[0, 1, 2]]), "non-finite"),
    (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]]), np.array([[0, 1, 7]]), "refers to vertex 7"),
])
def test_a_broken_surface_mesh_is_refused_by_name(vertices, faces, message):
    with pytest.raises(se.EngraveError, match=f"surface 'Bad': .*{message}"):
        se.Surface(vertices, faces, "Bad")


def ridged_surface():
    """A flat plate top with a narrow raised ridge across it (a cosine bump 1.5 mm high, 5 mm wide,
    along Y at X = -80): a tool placed by the depth under its tip alone would cut into its flanks."""
    from kezuri.toolpath.operations.carve.carve_samples import heightmap_solid

    x, y = np.linspace(-101, 101, 809), np.linspace(-51, 51, 103)
    gx, _ = np.meshgrid(x, y, indexing="ij")
    bump = np.where(np.abs(gx + 80) < 2.5, 0.75 * (1 + np.cos(np.pi * (gx + 80) / 2.5)), 0.0)
    return heightmap_solid(x, y, bump - 1.5, -20.0)


def test_a_raised_ridge_beside_the_cut_is_not_gouged():
    surface = se.Surface(*ridged_surface(), "ridge")
    with time_limit(120):
        job = se.plan(PLATE, LETTERS, surface, plate_thickness=20)
    limits = se.simulation_limits(surface, PLATE, LETTERS[0][1], job.result.program, -2.0, -20.0)
    stock = se.plate_stock(surface, PLATE, 20.0)
    window = (-90, -50, -70, 50)      # the ridge and the field beside it
    result = simulate(job.baked, stock, cell=0.1, **limits)
    assert not result.findings_of("gouge")
    # the same depths measured under the tip alone (z = surface under the tip + depth) do gouge
    # the ridge's flanks: the check is not blind to it
    baked_flat, _ = engrave.bake(job.result.program)
    naive_ops = []
    for op in baked_flat.operations:
        followed, _ = se.follow(op, surface, None)
        xyz = followed.xyz.copy()
        cutting = xyz[:, 2] < op.clearance_z - 1e-9
        point = surface.heights(xyz[cutting, :2])
        contact = surface.cutter(op.tool).points(xyz[cutting, :2])
        xyz[cutting, 2] += point - contact
        naive_ops.append(followed.replace(xyz=xyz))
    naive = simulate(Program("naive", naive_ops), stock, cell=0.1, **limits)
    gouges = naive.findings_of("gouge")
    assert gouges and gouges[0].depth_mm > 0.05
    x, y = gouges[0].xy
    assert window[0] <= x <= window[2]


def test_the_letter_guard_lifts_a_tool_over_a_letter_to_its_top():
    """A path planned straight through a letter (the planner never does this) is lifted by the
    drop onto the letters' solid: beside the letter the ball rests on its top edge,
    z = -(r - sqrt(r^2 - d^2)) at a distance d from the edge; over the letter on its top, z = 0."""
    from kezuri.toolpath.ir.program import PathBuilder, Tool, Operation

    plane = se.Surface(np.array([[-60, -60, 0], [60, -60, 0], [60, 60, 0], [-60, 60, 0]], float),
                       np.array([[0, 1, 2], [0, 2, 3]]), "plane")
    square = [np.array([[-10, -10], [10, -10], [10, 10], [-10, 10]], float)]
    guard_mesh = se.letters_solid(plane, square, -30.0)
    ball = Tool(2, "ball", 6.0)
    builder = PathBuilder(20.0, 1000.0, 300.0, 2.0)
    builder.plunge(-30.0, 0.0, -2.0)
    builder.line(30.0, 0.0, -2.0)
    builder.retract()
    arrays = builder.arrays()
    op = Operation(name="through", tool=ball, spindle_rpm=6000, **arrays)
    followed, lifted = se.follow(op, plane, se.DropCutter(*guard_mesh, ball))
    assert lifted
    cut = followed.xyz[(followed.kind == FEED) & (np.abs(followed.xyz[:, 1]) < 1e-9)
                       & (followed.xyz[:, 2] < 1.0)]
    edge = 10.0 - engrave.KEEP_MARGIN
    d = np.abs(cut[:, 0]) - edge
    expected = np.where(d <= 0, 0.0, np.where(d < 3.0, -(3.0 - np.sqrt(np.maximum(9.0 - d * d, 0.0))), -2.0))
    expected = np.maximum(expected, -2.0)
    assert np.max(np.abs(cut[:, 2] - expected)) < 1e-6


def test_a_surface_with_a_small_hole_under_the_path_is_refused_by_name():
    """A hole between the coverage check's 2 mm grid points, in the band beside the letter I where
    the 1 mm flat end runs (X -47): the tool path finds it and names it."""
    vertices, faces = se.dome(-101, -51, 101, 51, -20, cell=0.5)
    centres = vertices[faces].mean(axis=1)
    top = vertices[faces][:, :, 2].min(axis=1) > -19            # the top faces
    hole = top & (np.abs(centres[:, 0] + 47.0) < 0.9) & (np.abs(centres[:, 1] - 1.0) < 0.9)
    assert hole.sum() >= 2
    surface = se.Surface(vertices, faces[~hole], "Holey")
    with time_limit(120), pytest.raises(se.EngraveError, match="Holey.*hole under the"):
        se.plan(PLATE, LETTERS, surface)
