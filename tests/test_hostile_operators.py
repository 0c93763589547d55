"""Hostile values through bpy: every operator of every workflow, with each number it reads set to
a value that means nothing (below or above its range, NaN, infinite), must end CANCELLED with an
ERROR report naming the setting (its panel label), the value and the range; no traceback, no file
written, no object added, and the scene's settings left as they were.

Blender clamps a property at its hard limits without a word, so the settings carry only soft
limits and the operators check the values against one table (operators/limits.py), the one
batch's options use too.  The bad values here are computed from the table's bounds (just past
each bound, far past it, NaN, inf) and Hypothesis adds arbitrary ones; each case runs under a
time limit."""
import contextlib
import io
import math
import os

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from test_hostile import time_limit  # noqa: E402

from kezuri.operators import limits, properties, samples  # noqa: E402
from kezuri.operators.workflows import WORKFLOWS  # noqa: E402

CASE_SECONDS = 60
COUNT = {"cases": 0}

# What each operator reads: scene groups (scene.kezuri.<group>), "pocket" (the pocket objects'
# settings) and "self:<group>" (its own redo-panel properties, ranged like that group's).  Every
# operator of the workflow table must be listed here or in READS_NO_NUMBERS.
READS = {
    "kezuri.engrave_generate": ("machine", "engrave"),
    "kezuri.engrave_export": ("machine", "engrave"),
    "kezuri.rotary_generate": ("machine", "rotary", "pocket"),
    "kezuri.rotary_export": ("machine", "rotary", "pocket"),
    "kezuri.export_stepnc": ("stepnc", "pocket:depth"),
    "kezuri.turnmill_classify": ("turnmill:sample_spacing",),
    "kezuri.turnmill_generate": ("turnmill",),
    "kezuri.turnmill_export": ("turnmill",),
    "kezuri.carve_generate": ("machine", "carve"),
    "kezuri.carve_export": ("machine", "carve"),
    "kezuri.unfold_quad": ("self:sheet", "sheet:corners"),
    "kezuri.sheet_export": ("sheet:corners,divisions,tool_diameter,thickness,pitch,station",),
    "kezuri.add_elbow": ("self:sheet", "sheet:tool_diameter,thickness,pitch,station"),
    "kezuri.elbow_export": ("sheet:elbow_diameter,elbow_radius,elbow_angle,elbow_pieces,tool_diameter,thickness,pitch,"
                            "station",),
    "kezuri.simulate": ("simulation",),
}
READS_NO_NUMBERS = {"kezuri.mark_pocket", "kezuri.import_stepnc", "kezuri.stepnc_generate", "kezuri.stepnc_export",
                    "kezuri.workingstep_move", "kezuri.quad_from_selection", "kezuri.import_cdl",
                    "kezuri.carve_sample"}
EXPORTS = {"kezuri.engrave_export": ".nc", "kezuri.rotary_export": ".ngc", "kezuri.export_stepnc": ".stp",
           "kezuri.turnmill_export": ".ngc", "kezuri.carve_export": ".nc", "kezuri.sheet_export": ".nc",
           "kezuri.elbow_export": ".dxf"}
SHEET_OWN = {"kezuri.unfold_quad": ("divisions", "tool_diameter", "thickness", "pitch", "station"),
             "kezuri.add_elbow": ("elbow_diameter", "elbow_radius", "elbow_angle", "elbow_pieces")}


def operators_in_table() -> list:
    found = [cls.bl_idname for w in WORKFLOWS for cls in w.classes if issubclass(cls, bpy.types.Operator)]
    return found + ["kezuri.simulate"]


def setting_names(entry: str, idname: str) -> list:
    """(group, property) pairs one READS entry stands for."""
    if entry.startswith("self:"):
        return [("self", name) for name in SHEET_OWN[idname]]
    group, _, names = entry.partition(":")
    return [(group, name) for name in (names.split(",") if names else limits.RANGES[group])]


def cases() -> list:
    """(operator, group, property) for every number every operator reads."""
    return [(idname, group, name) for idname, entries in READS.items() for entry in entries
            for group, name in setting_names(entry, idname)]


def bad_values(limit: limits.Range) -> list:
    """Just past each bound, far past it, and the non-numbers (floats only)."""
    values = []
    if limit.integer:
        if limit.lo is not None:
            values += [int(limit.lo) - 1, -2**31]
        if limit.hi is not None and limit.hi < 2**31 - 1:
            values += [int(limit.hi) + 1, 2**31 - 1]
        return values
    if limit.lo is not None:
        values += [limit.lo if limit.lo_open else limit.lo - max(1e-3, 0.01 * abs(limit.lo)),
                   limit.lo - 1e6]
    if limit.hi is not None:
        values += [limit.hi + max(1e-3, 0.01 * abs(limit.hi)), limit.hi + 1e6]
    return values + [math.nan, math.inf, -math.inf]


# ----- the scenes the operators would succeed on ---------------------------------------------

def workflow_scene(idname: str, tmp_path):
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    scene.kezuri.simulation.property_unset("cell")
    for group in ("machine", "engrave", "rotary", "stepnc", "turnmill", "carve", "sheet"):
        props = getattr(scene.kezuri, group)
        for name in limits.RANGES[group]:
            props.property_unset(name)
    if idname.startswith("kezuri.engrave") or idname == "kezuri.simulate":
        samples.name_plate(scene)
    elif idname.startswith("kezuri.rotary") or idname == "kezuri.export_stepnc":
        samples.rotary_block(scene)
    elif idname.startswith("kezuri.turnmill"):
        samples.turnmill_part(scene)
    elif idname.startswith("kezuri.carve"):
        from kezuri.operators import carve
        carve.add_sample(scene, "wave")
    return scene


def group_of(scene, group: str):
    if group == "pocket":
        return [o.kezuri_pocket for o in scene.objects if o.kezuri_pocket.enabled]
    return [getattr(scene.kezuri, group)]


def label_of(group: str, name: str) -> str:
    rna = properties.KezuriSheet.bl_rna if group == "self" else {
        "pocket": properties.KezuriPocket.bl_rna}.get(group) or getattr(bpy.context.scene.kezuri, group).bl_rna
    return rna.properties[name].name


def snapshot(scene) -> dict:
    values = {}
    for group in limits.RANGES:
        for index, props in enumerate(group_of(scene, group)):
            for name in limits.RANGES[group]:
                value = getattr(props, name)
                values[(group, index, name)] = repr(tuple(value) if hasattr(value, "__len__") else value)
    return values


def call(idname: str, scene, tmp_path, own: dict) -> tuple:
    """(raised message or None, result, stderr) of the operator run as a script runs it."""
    module, name = idname.split(".")
    operator = getattr(getattr(bpy.ops, module), name)
    kwargs = dict(own)
    if idname in EXPORTS:
        kwargs["filepath"] = str(tmp_path / f"job{EXPORTS[idname]}")
    if idname == "kezuri.simulate":
        kwargs["workflow"] = "ENGRAVE"
    stderr = io.StringIO()
    COUNT["cases"] += 1
    with time_limit(CASE_SECONDS), contextlib.redirect_stderr(stderr):
        try:
            result = operator(**kwargs)
        except RuntimeError as error:
            return str(error), {"CANCELLED"}, stderr.getvalue()
    return None, result, stderr.getvalue()


def refused_by_name(idname, group, name, value, tmp_path):
    scene = workflow_scene(idname, tmp_path)
    own = {}
    if group == "self":
        own[name] = value
        label, shown = label_of(group, name), value
    else:
        targets = group_of(scene, group)
        assert targets, (idname, group)
        for props in targets:
            if name == "corners":
                corners = list(props.corners)
                corners[4] = value
                props.corners = corners
                shown = props.corners[4]
            else:
                setattr(props, name, value)
                shown = getattr(props, name)
        label = label_of(group, name)
    assert not limits.RANGES["sheet" if group == "self" else group][name].allows(shown), (name, value, shown)
    if abs(shown) >= limits.FLOAT_MAX:          # Blender holds inf as the largest float: named as inf
        shown = math.copysign(math.inf, shown)
    objects = set(bpy.data.objects.keys())
    before = snapshot(scene)
    message, result, stderr = call(idname, scene, tmp_path, own)
    assert result == {"CANCELLED"}, (idname, name, value, result)
    assert message is not None, (idname, name, value, "no ERROR report")
    assert "Traceback" not in stderr and "internal error" not in message, message
    assert label in message and "outside the allowed range" in message, (idname, name, message)
    assert f"= {shown:g}" in message, (shown, message)          # the value, as the setting holds it
    assert list(tmp_path.iterdir()) == [], list(tmp_path.iterdir())
    assert set(bpy.data.objects.keys()) == objects
    assert snapshot(scene) == before                              # the redo panel's values not taken


CASES = cases()


@pytest.fixture(scope="module", autouse=True)
def registered():
    import kezuri
    if not hasattr(bpy.types.Scene, "kezuri"):
        kezuri.register()
    yield


def test_every_operator_of_the_workflow_table_is_covered():
    known = set(READS) | READS_NO_NUMBERS
    missing = [idname for idname in operators_in_table() if idname not in known]
    assert not missing, f"say which numbers these operators read: {missing}"
    assert not set(READS) - set(operators_in_table())


def test_every_number_of_the_settings_has_a_range_and_no_hard_limit():
    """A hard limit would clamp a bad value into a good one before anyone could refuse it."""
    scene = bpy.context.scene
    for group in limits.RANGES:
        rna = properties.KezuriPocket.bl_rna if group == "pocket" else getattr(scene.kezuri, group).bl_rna
        numbers = {p.identifier for p in rna.properties if p.type in {"FLOAT", "INT"} and p.identifier != "active_step"}
        assert numbers == set(limits.RANGES[group]), (group, numbers ^ set(limits.RANGES[group]))
        for name, limit in limits.RANGES[group].items():
            prop = rna.properties[name]
            floor = -2**31 if prop.type == "INT" else -limits.FLOAT_MAX
            assert prop.hard_min <= floor and prop.hard_max >= -floor - 1, (group, name)
            default = prop.default_array if getattr(prop, "is_array", False) else prop.default
            for item in (default if hasattr(default, "__len__") else [default]):
                assert limit.allows(item), (group, name, item)     # the defaults mean something


def test_the_redo_panels_are_as_free_as_the_scene():
    for idname, names in SHEET_OWN.items():
        module, name = idname.split(".")
        rna = getattr(getattr(bpy.ops, module), name).get_rna_type()
        for prop_name in names:
            prop = rna.properties[prop_name]
            floor = -2**31 if prop.type == "INT" else -limits.FLOAT_MAX
            assert prop.hard_min <= floor and prop.hard_max >= -floor - 1, (idname, prop_name)


@pytest.mark.parametrize("idname, group, name", CASES, ids=[f"{i} {g}.{n}" for i, g, n in CASES])
def test_bad_values_are_refused_by_name(idname, group, name, tmp_path):
    limit = limits.RANGES["sheet" if group == "self" else group][name]
    for value in bad_values(limit):
        for leftover in tmp_path.iterdir():
            leftover.unlink()
        refused_by_name(idname, group, name, value, tmp_path)


HYPOTHESIS_CASES = [c for c in CASES if c[0] in {"kezuri.engrave_export", "kezuri.rotary_generate",
                                                 "kezuri.carve_export", "kezuri.add_elbow", "kezuri.sheet_export",
                                                 "kezuri.simulate", "kezuri.turnmill_generate"}]


@pytest.mark.parametrize("idname, group, name", HYPOTHESIS_CASES, ids=[f"{i} {g}.{n}" for i, g, n in HYPOTHESIS_CASES])
@settings(max_examples=4, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(data=st.data())
def test_arbitrary_values_outside_the_range_are_refused(idname, group, name, data, tmp_path):
    limit = limits.RANGES["sheet" if group == "self" else group][name]
    if limit.integer:
        values = st.integers(-2**31, 2**31 - 1)
    else:
        values = st.floats(width=32)
    value = data.draw(values.filter(lambda v: not limit.allows(v) and not limit.allows(float(np.float32(v)))))
    for leftover in tmp_path.iterdir():
        leftover.unlink()
    refused_by_name(idname, group, name, value, tmp_path)


def test_the_suite_counts_its_cases():
    """Counted when the whole module runs: the README states the number of cases."""
    if COUNT["cases"] < len(CASES):
        pytest.skip("run with the whole module to count")
    print(f"\n{COUNT['cases']} hostile operator calls")
    assert COUNT["cases"] >= 150, COUNT


@pytest.mark.parametrize("idname", ["kezuri.engrave_generate", "kezuri.engrave_export", "kezuri.rotary_generate",
                                    "kezuri.simulate"])
def test_a_unit_scale_that_puts_the_plate_past_100_m_is_refused_by_name(idname, tmp_path):
    """Blender lets Unit Scale go to 1e9 m per unit; the sample plate then lies 1e14 mm out and
    Clipper raised "RuntimeError: Values exceed permitted range" (an internal error)."""
    scene = workflow_scene(idname, tmp_path)
    scene.unit_settings.scale_length = 1e9
    objects = set(bpy.data.objects.keys())
    message, result, stderr = call(idname, scene, tmp_path, {})
    assert result == {"CANCELLED"} and message is not None, (idname, result)
    assert "Traceback" not in stderr and "internal error" not in message, message
    assert "unit scale of 1e+09 m per unit" in message and "reaches" in message, message
    assert list(tmp_path.iterdir()) == [] and set(bpy.data.objects.keys()) == objects


@pytest.mark.parametrize("idname", ["kezuri.engrave_export", "kezuri.sheet_export", "kezuri.elbow_export"])
def test_blender_relative_and_empty_export_paths(idname, tmp_path):
    """'//name' is relative to the .blend in Blender: it was taken as '/name', so an export went to
    the file-system root (or failed there for a user without the right); an empty path wrote
    '.nc', '.dxf', '.svg' (or '-1.nc' ...) into the working folder."""
    name = "kezuri-hostile-relative"
    with contextlib.redirect_stdout(io.StringIO()):
        bpy.ops.wm.read_homefile(use_empty=True)        # a .blend never saved (an earlier test may have saved one)
    assert bpy.data.filepath == ""
    scene = workflow_scene(idname, tmp_path)
    suffix = EXPORTS[idname]
    module, op_name = idname.split(".")
    operator = getattr(getattr(bpy.ops, module), op_name)
    stray = [f"/{name}{end}" for end in (".nc", ".dxf", ".svg", *(f"-{k}.nc" for k in range(1, 61)))]
    try:
        for path, said in ((f"//{name}{suffix}", "needs the .blend saved first"), ("", "the file path is empty")):
            with time_limit(CASE_SECONDS), contextlib.redirect_stderr(io.StringIO()):
                with pytest.raises(RuntimeError, match=said):
                    operator(filepath=path)
            assert not any(os.path.exists(p) for p in stray)
        blend = tmp_path / "saved" / "job.blend"
        blend.parent.mkdir()
        bpy.ops.wm.save_as_mainfile(filepath=str(blend))
        scene = bpy.context.scene
        with time_limit(CASE_SECONDS), contextlib.redirect_stderr(io.StringIO()):
            assert operator(filepath=f"//out/{name}{suffix}") == {"FINISHED"}
        assert (blend.parent / "out" / f"{name}{suffix}").exists() or \
            (blend.parent / "out" / f"{name}-1.nc").exists()
        assert not any(os.path.exists(p) for p in stray)
    finally:
        for p in stray:
            if os.path.exists(p):
                os.remove(p)
