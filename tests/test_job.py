"""The job model (toolpath/job.py) in the core: operations planned in order over one stock, one
program, fingerprints and the cache, the design layers the gate checks the whole job against.
Expected values come from the geometry given here (a plate, two letters as squares, holes)."""
import dataclasses

import numpy as np
import pytest

from kezuri.toolpath import job as jobs
from kezuri.toolpath import simulate
from kezuri.toolpath.ir import machine as machines
from kezuri.toolpath.ir.program import Tool
from kezuri.toolpath.operations.drill import drill
from kezuri.toolpath.operations.drill.kind import DrillGeometry
from kezuri.toolpath.operations.engrave import engrave
from kezuri.toolpath.operations.engrave.kind import EngraveGeometry


def square(cx, cy, half):
    return np.array([[cx - half, cy - half], [cx + half, cy - half], [cx + half, cy + half], [cx - half, cy + half]])


PLATE = (square(0, 0, 40) * [1.5, 1.0],)          # 120 x 80 mm, top at Z = 0
LETTERS = (("Letters", (square(-20, 0, 10), square(20, 0, 10))),)
HOLES = ((-50.0, -30.0), (50.0, -30.0), (50.0, 30.0), (-50.0, 30.0))


def engraving(seed=7):
    settings = dataclasses.replace(engrave.EngraveSettings(), texture=dataclasses.replace(
        engrave.EngraveSettings().texture, seed=seed))
    return jobs.JobOperation("engrave", "plate", settings, EngraveGeometry(PLATE, 10.0, LETTERS))


def drilling(holes=HOLES, depth=6.0, number=4):
    settings = drill.DrillSettings(tool=Tool(number, "drill", 4.0, flute_length=30.0), depth=depth, peck=2.0)
    return jobs.JobOperation("drill", "holes", settings, DrillGeometry(holes))


def setup(**changes):
    return jobs.Setup(name="plate", post="linuxcnc", **changes)


def test_the_kinds_are_found_by_walking_the_operations_folder():
    found = jobs.kinds()
    assert {"engrave", "carve", "drill"} <= set(found)
    assert found["drill"].families == ("milling",)


def test_one_program_in_the_job_order_with_every_tool():
    planned = jobs.plan_job(jobs.Job(setup(), (engraving(), drilling())))
    program = planned.program()
    names = [op.name for op in program.operations]
    assert names == ["roughing (gouge texture)", "band finishing", "burr contour", "drill"]
    assert [t.number for t in program.tools()] == [2, 3, 4]
    # the drill goes to 6 mm below the top at the four centres and nowhere else
    op = program.operations[-1]
    deepest = op.xyz[op.kind != 0]
    assert np.isclose(deepest[:, 2].min(), -6.0)
    bottoms = deepest[np.isclose(deepest[:, 2], -6.0)][:, :2]
    assert sorted(map(tuple, np.round(bottoms, 9))) == sorted(HOLES)
    # pecks of at most 2 mm: each feed move goes down by 2 mm or less
    feeds = np.flatnonzero(op.kind == 1)
    starts = op.start_points()[feeds]
    assert np.all(starts[:, 2] - op.xyz[feeds, 2] <= 2.0 + 0.5 + 2.0 + 1e-9)   # first peck from the 2 mm gap
    assert np.all(np.diff(op.xyz[feeds, 2][op.xyz[feeds, 2] < 0]) != 0)
    # the macro variant writes the engraving's untextured roughing, the rest as cut
    macro = planned.program(macro=True)
    assert macro.operations[0].texture is not None and program.operations[0].texture is None
    assert macro.operations[-1] is program.operations[-1]


def test_the_cache_replans_the_changed_operation_and_those_after_it():
    cache = {}
    first = jobs.plan_job(jobs.Job(setup(), (engraving(), drilling())), cache)
    assert first.replanned() == ["plate", "holes"]
    again = jobs.plan_job(jobs.Job(setup(), (engraving(), drilling())), cache)
    assert again.replanned() == []
    assert again.parts[0] is first.parts[0]
    deeper = jobs.plan_job(jobs.Job(setup(), (engraving(), drilling(depth=8.0))), cache)
    assert deeper.replanned() == ["holes"]
    reseeded = jobs.plan_job(jobs.Job(setup(), (engraving(seed=8), drilling(depth=8.0))), cache)
    assert reseeded.replanned() == ["plate", "holes"]       # the drilling starts from another stock
    moved = jobs.plan_job(jobs.Job(setup(), (engraving(seed=8), drilling(HOLES[:3], 8.0))), cache)
    assert moved.replanned() == ["holes"]
    other_setup = jobs.plan_job(jobs.Job(setup(work_offset="G55"), (engraving(seed=8), drilling(HOLES[:3], 8.0))),
                                cache)
    assert other_setup.replanned() == ["plate", "holes"]


def test_one_number_one_tool_across_the_job():
    with pytest.raises(jobs.JobError, match=r"tool number 3 is the T3 1 mm flat end mill .* in 'band finishing' but the T3 4 mm drill .*in 'drill'"):
        jobs.plan_job(jobs.Job(setup(), (engraving(), drilling(number=3)))).program()


def test_refusals_name_the_operation():
    with pytest.raises(jobs.JobError, match="two operations are named 'plate'"):
        jobs.plan_job(jobs.Job(setup(), (engraving(), dataclasses.replace(drilling(), name="plate"))))
    with pytest.raises(jobs.JobError, match="unknown operation kind 'waterjet'"):
        jobs.plan_job(jobs.Job(setup(), (dataclasses.replace(drilling(), kind="waterjet"),)))
    with pytest.raises(jobs.JobError, match="operation 'holes': settings must be DrillSettings"):
        jobs.plan_job(jobs.Job(setup(), (dataclasses.replace(drilling(), settings=engrave.EngraveSettings()),)))
    lathe = machines.preset("wood-lathe-cxz")
    with pytest.raises(jobs.JobError, match=r"'plate' \(Engraving\) runs on milling machines, not on the job's cxz"):
        jobs.plan_job(jobs.Job(setup(machine=lathe), (engraving(),)))
    with pytest.raises(jobs.JobError, match="no operation switched on"):
        jobs.plan_job(jobs.Job(setup(), (dataclasses.replace(drilling(), enabled=False),)))


def test_a_switched_off_operation_is_left_out():
    planned = jobs.plan_job(jobs.Job(setup(), (engraving(), dataclasses.replace(drilling(), enabled=False))))
    assert [op.name for op in planned.program().operations][-1] == "burr contour"


def test_design_layers_laid_in_order():
    planned = jobs.plan_job(jobs.Job(setup(), (engraving(), drilling())))
    design = planned.design_limits()["design"]
    floor = engrave.simulation_limits([l for _, ls in LETTERS for l in ls], planned.parts[0].result.result.program,
                                      engrave.EngraveSettings().band_depth)["design"]
    x = np.array([[-50.0, 0.0, -20.0, 30.0]])
    y = np.array([[-30.0, 30.0, 0.0, -30.0]])
    z = design(x, y)
    # a hole centre: the drill's floor (6 mm, less 0.01); the plate's field: the engraving's floor;
    # inside a letter: the plate's top; outside the plate: the engraving's layer does not speak
    assert z[0, 0] == pytest.approx(-6.01)
    assert z[0, 1] == pytest.approx(floor)
    assert z[0, 2] == pytest.approx(0.0)
    assert z[0, 3] == pytest.approx(floor)
    outside = design(np.array([[70.0]]), np.array([[0.0]]))
    assert outside[0, 0] == -np.inf


def simulated(holes):
    planned = jobs.plan_job(jobs.Job(setup(), (engraving(), drilling(holes))))
    program, stock, limits = planned.simulation()
    return simulate.simulate(program, stock, cell=0.25, **limits)


def test_the_gate_over_the_whole_job_passes_holes_in_the_field_and_finds_one_in_a_letter():
    clean = simulated(HOLES)
    assert [f for f in clean.findings if f.kind == "gouge"] == []
    bad = simulated(HOLES + ((20.0, 0.0),))         # the centre of the second letter
    gouges = [f for f in bad.findings if f.kind == "gouge"]
    assert len(gouges) == 1 and gouges[0].operation == 3 and gouges[0].message.startswith("drill:")
    assert abs(gouges[0].xy[0] - 20.0) < 2 and abs(gouges[0].xy[1]) < 2
    # the area gouged is the 4 mm drill's disc, pi * 2^2 = 12.6 mm^2, within the 0.25 mm cells' rim
    area = float(gouges[0].message.split("; ")[1].split(" mm^2")[0])
    assert abs(area - np.pi * 4) < 2 * np.pi * 2 * 0.25


def test_fingerprints_see_arrays_change_in_place():
    op = drilling()
    key = jobs.fingerprint(setup(), op)
    assert jobs.fingerprint(setup(), drilling()) == key
    assert jobs.fingerprint(setup(), drilling(), before="x") != key
    plate = PLATE[0].copy()
    plate[0, 0] += 1e-9
    moved = dataclasses.replace(engraving(), geometry=EngraveGeometry((plate,), 10.0, LETTERS))
    assert jobs.fingerprint(setup(), moved) != jobs.fingerprint(setup(), engraving())
