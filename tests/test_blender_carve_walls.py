"""The wall pass in Blender: the panel's setting reaches the core, Generate on the walled block
sample shows the wall pass's toolpath, and turning it off leaves the walls with a warning."""
import pytest

bpy = pytest.importorskip("bpy")

from kezuri.operators import carve as shell  # noqa: E402
from kezuri.operators import panels  # noqa: E402
from blender_helpers import draw_panel  # noqa: E402


def test_the_wall_pass_setting_is_on_the_panel_and_reaches_the_core(empty_scene):
    assert bpy.ops.kezuri.carve_sample(sample="block") == {"FINISHED"}
    props = empty_scene.kezuri.carve
    assert props.wall_pass is True              # on by default
    assert "wall_pass" in draw_panel(panels.KEZURI_PT_carve_settings, bpy.context).props
    props.rough = False
    assert bpy.ops.kezuri.carve_generate() == {"FINISHED"}
    names = {o.name for o in bpy.data.collections["Kezuri"].objects}
    assert "Kezuri Carve wall pass" in names and "Kezuri Carve steep cleanup" not in names
    props.wall_pass = False
    assert shell.settings_from(props).wall_pass is False
    job = shell.run_carve(empty_scene, bpy.context.evaluated_depsgraph_get())
    assert [op.name for op in job.result.program.operations] == ["finishing"]
    assert any("Wall Pass is off" in w for w in job.result.warnings)
