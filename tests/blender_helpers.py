"""What the Blender-shell tests share: a registered Kezuri with a clean millimetre scene, a
recording stand-in for UILayout, and batch.py run as a separate process."""
import os
import subprocess
import sys
import types

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture
def empty_scene():
    """Kezuri registered, every object removed, Kezuri settings at their defaults, units mm."""
    bpy = pytest.importorskip("bpy")
    import kezuri
    from kezuri.operators import samples
    if not hasattr(bpy.types.Scene, "kezuri"):
        kezuri.register()
    scene = bpy.context.scene
    samples.clear_scene(scene)
    samples.set_millimetres(scene)
    return scene


class RecordingLayout:
    """Stands in for UILayout (background mode cannot draw): records what a panel shows."""

    def __init__(self):
        self.props, self.operators = [], []
        self.use_property_split = False
        self.scale_y = 1.0

    def prop(self, data, name, **_):
        assert hasattr(data, name), name
        self.props.append(name)

    def operator(self, idname, **_):
        self.operators.append(idname)
        return types.SimpleNamespace()      # the operator's properties, which panels may set

    def template_list(self, list_type, list_id, data, name, active_data, active_name, **_):
        assert hasattr(data, name) and hasattr(active_data, active_name), (name, active_name)
        self.props.append(name)

    def row(self, **_):
        return self

    column = box = split = row

    def menu(self, idname, **_):
        self.operators.append(idname)

    def separator(self, **_):
        pass

    def label(self, **_):
        pass


def draw_panel(panel, context) -> RecordingLayout:
    """Run a panel's draw() against a RecordingLayout (background mode cannot draw)."""
    holder = types.SimpleNamespace(layout=RecordingLayout())
    panel.draw(holder, context)
    return holder.layout


def run_batch(*args, timeout: int = 900) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, os.path.join(ROOT, "batch.py"), *args], capture_output=True, text=True,
                          timeout=timeout, cwd=ROOT)
