"""View3D > Sidebar > CAM: the machine panel and one panel per workflow."""
from __future__ import annotations

import bpy

from .workflows import simulated


class KezuriPanel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "CAM"


def property_subpanel(idname: str, label: str, parent: str, group: str, names: tuple):
    """A sub-panel, closed at first, listing ``names`` of ``scene.kezuri.<group>``."""
    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        props = getattr(context.scene.kezuri, group)
        for name in names:
            layout.prop(props, name)
    return type(idname, (KezuriPanel, bpy.types.Panel), {"bl_idname": idname, "bl_label": label, "bl_parent_id": parent,
                                                          "bl_options": {"DEFAULT_CLOSED"}, "draw": draw})


class KEZURI_PT_machine(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_machine"
    bl_label = "Machine & Stock"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        settings = context.scene.kezuri
        layout.prop(settings.machine, "post")
        layout.prop(settings.machine, "work_offset")
        layout.prop(settings.machine, "rapid_rate")
        layout.prop(settings.machine, "output_dir")
        layout.separator()
        layout.prop(settings.stock, "plate")
        layout.prop(settings.stock, "origin")


class KEZURI_PT_engrave(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_engrave"
    bl_label = "Engrave"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        props = context.scene.kezuri.engrave
        layout.prop(props, "letters")
        layout.prop(props, "letters_collection")
        layout.prop(props, "surface")
        row = layout.row(align=True)
        row.scale_y = 1.4
        row.operator("kezuri.engrave_generate", icon="MOD_NOISE")
        layout.operator("kezuri.engrave_export", icon="EXPORT")


class KEZURI_PT_engrave_texture(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_engrave_texture"
    bl_label = "Gouge Texture (Roughing)"
    bl_parent_id = "KEZURI_PT_engrave"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        props = context.scene.kezuri.engrave
        layout.menu("KEZURI_MT_library_tools", icon="TOOL_SETTINGS")
        for name in ("rough_diameter", "rough_tool_number", "stepover", "raster_angle", "letter_clearance",
                     "base_depth", "quantum", "amplitude", "spacing", "motion", "spacing_jitter", "seed"):
            layout.prop(props, name)


class KEZURI_PT_rotary(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_rotary"
    bl_label = "Rotary Pockets"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        scene = context.scene
        pockets = [o for o in scene.objects if o.kezuri_pocket.enabled]
        layout.label(text=f"Block: the stock object; {len(pockets)} pocket(s)", icon="INFO")
        obj = context.active_object
        if obj is not None and obj.type in {"MESH", "CURVE"} and obj != scene.kezuri.stock.plate:
            box = layout.box()
            box.prop(obj.kezuri_pocket, "enabled", text=f"{obj.name} is a pocket")
            if obj.kezuri_pocket.enabled:
                for name in ("depth", "wall_angle", "bottom"):
                    box.prop(obj.kezuri_pocket, name)
                if obj.kezuri_pocket.bottom == "sphere":
                    box.prop(obj.kezuri_pocket, "sphere_radius")
        layout.operator("kezuri.mark_pocket", icon="ADD")
        row = layout.row(align=True)
        row.scale_y = 1.4
        row.operator("kezuri.rotary_generate", icon="DRIVER_ROTATIONAL_DIFFERENCE")
        layout.prop(scene.kezuri.rotary, "post")
        layout.operator("kezuri.rotary_export", icon="EXPORT")


class KEZURI_PT_stepnc(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_stepnc"
    bl_label = "STEP-NC Workplan"

    def draw(self, context):
        layout = self.layout
        props = context.scene.kezuri.stepnc
        layout.operator("kezuri.import_stepnc", icon="IMPORT")
        if props.filepath:
            layout.label(text=bpy.path.basename(props.filepath), icon="FILE")
        row = layout.row()
        row.template_list("KEZURI_UL_workingsteps", "", props, "steps", props, "active_step", rows=5)
        column = row.column(align=True)
        column.operator("kezuri.workingstep_move", icon="TRIA_UP", text="").direction = "UP"
        column.operator("kezuri.workingstep_move", icon="TRIA_DOWN", text="").direction = "DOWN"
        row = layout.row(align=True)
        row.scale_y = 1.4
        row.operator("kezuri.stepnc_generate", icon="SEQ_STRIP_DUPLICATE")
        layout.operator("kezuri.stepnc_export", icon="EXPORT")


class KEZURI_PT_stepnc_write(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_stepnc_write"
    bl_label = "Write Pockets as ISO 14649"
    bl_parent_id = "KEZURI_PT_stepnc"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        props = context.scene.kezuri.stepnc
        layout.label(text="Pockets: outline objects marked as pockets, on the stock")
        for name in ("tool_diameter", "tool_number", "flute_length", "feed", "spindle_rpm"):
            layout.prop(props, name)
        layout.operator("kezuri.export_stepnc", icon="EXPORT")


class KEZURI_PT_turnmill(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_turnmill"
    bl_label = "Turn-Mill"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        props = context.scene.kezuri.turnmill
        for name in ("part", "selected_only", "stock_radius", "stock_z_min", "stock_z_max", "engine"):
            layout.prop(props, name)
        row = layout.row(align=True)
        row.operator("kezuri.turnmill_classify", icon="SHADING_RENDERED")
        row = layout.row(align=True)
        row.scale_y = 1.4
        row.operator("kezuri.turnmill_generate", icon="MOD_SCREW")
        layout.operator("kezuri.turnmill_export", icon="EXPORT")


class KEZURI_PT_carve(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_carve"
    bl_label = "Carve"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        props = context.scene.kezuri.carve
        layout.prop(props, "design")
        row = layout.row(align=True)
        row.operator("kezuri.carve_sample", text="Wave Relief", icon="MESH_GRID").sample = "wave"
        row.operator("kezuri.carve_sample", text="Domed Plate", icon="MESH_UVSPHERE").sample = "dome"
        row.operator("kezuri.carve_sample", text="Steep Ridge", icon="MESH_CONE").sample = "ridge"
        for name in ("stock_above", "scallop", "raster_angle", "finish_diameter", "rough"):
            layout.prop(props, name)
        row = layout.row(align=True)
        row.scale_y = 1.4
        row.operator("kezuri.carve_generate", icon="MOD_DISPLACE")
        layout.operator("kezuri.carve_export", icon="EXPORT")


class KEZURI_PT_sheet(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_sheet"
    bl_label = "Sheet Metal"

    def draw(self, context):
        layout = self.layout
        sheet = context.scene.kezuri.sheet
        layout.label(text="Twisted quad corners (mm)")
        grid = layout.column(align=True)
        for corner in range(4):
            row = grid.row(align=True)
            row.label(text=f"P{corner + 1}")
            for axis in range(3):
                row.prop(sheet, "corners", index=3 * corner + axis, text="XYZ"[axis])
        row = layout.row(align=True)
        row.operator("kezuri.quad_from_selection", icon="FACESEL")
        row.operator("kezuri.import_cdl", text="CDL", icon="IMPORT")
        layout.use_property_split = True
        for name in ("divisions", "direction", "tool_diameter", "thickness", "pitch", "station"):
            layout.prop(sheet, name)
        row = layout.row(align=True)
        row.scale_y = 1.4
        row.operator("kezuri.unfold_quad", icon="MOD_UVPROJECT")
        layout.operator("kezuri.sheet_export", icon="EXPORT")


class KEZURI_PT_sheet_elbow(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_sheet_elbow"
    bl_label = "Pipe Elbow"
    bl_parent_id = "KEZURI_PT_sheet"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        sheet = context.scene.kezuri.sheet
        for name in ("elbow_diameter", "elbow_radius", "elbow_angle", "elbow_pieces"):
            layout.prop(sheet, name)
        layout.operator("kezuri.add_elbow", icon="MESH_CYLINDER")
        layout.operator("kezuri.elbow_export", icon="EXPORT")


class KEZURI_PT_simulate(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_simulate"
    bl_label = "Simulate & Check"

    def draw(self, context):
        layout = self.layout
        props = context.scene.kezuri.simulation
        layout.use_property_split = True
        layout.prop(props, "engine")
        if props.engine == "heightfield":
            layout.prop(props, "cell")
        layout.prop(props, "colour_by")
        layout.use_property_split = False
        row = layout.row(align=True)
        for workflow in simulated():
            row.operator("kezuri.simulate", text=workflow.short_label).workflow = workflow.key
        if len(props.findings):
            box = layout.box()
            box.label(text=f"{len(props.findings)} finding(s)", icon="ERROR")
            for index, finding in enumerate(props.findings[:20]):
                row = box.row(align=True)
                row.label(text=finding.message)
                row.operator("kezuri.frame_finding", text="", icon="ZOOM_SELECTED").index = index
            blocking = sum(1 for f in props.findings if f.blocking)
            if blocking:
                box.prop(props, "allow_findings", text=f"Write despite these {blocking} finding(s)")
        else:
            layout.label(text="No findings", icon="CHECKMARK")


KEZURI_PT_engrave_finish = property_subpanel(
    "KEZURI_PT_engrave_finish", "Band & Burr Finishing", "KEZURI_PT_engrave", "engrave",
    ("finish_diameter", "finish_tool_number", "band_width", "band_depth", "band_stepover"))
KEZURI_PT_engrave_feeds = property_subpanel(
    "KEZURI_PT_engrave_feeds", "Feeds & Heights", "KEZURI_PT_engrave", "engrave",
    ("rough_rpm", "rough_feed", "finish_rpm", "finish_feed", "plunge_feed", "clearance_z", "safe_z", "show_rapids"))
KEZURI_PT_rotary_settings = property_subpanel(
    "KEZURI_PT_rotary_settings", "Bit, Feeds & Pitch", "KEZURI_PT_rotary", "rotary",
    ("tool_diameter", "tool_number", "flute_length", "spindle_rpm", "cutting_speed", "plunge_speed", "spacing",
     "stepover", "step_down", "allowance", "wall_stepover", "max_table_rpm"))
KEZURI_PT_turnmill_settings = property_subpanel(
    "KEZURI_PT_turnmill_settings", "Tool & Tolerance", "KEZURI_PT_turnmill", "turnmill",
    ("tool_diameter", "tolerance", "sample_spacing", "feed", "spindle_rpm"))
KEZURI_PT_carve_roughing = property_subpanel(
    "KEZURI_PT_carve_roughing", "Roughing", "KEZURI_PT_carve", "carve",
    ("rough_diameter", "rough_tool_number", "allowance", "step_down", "rough_stepover"))
KEZURI_PT_carve_settings = property_subpanel(
    "KEZURI_PT_carve_settings", "Finishing, Feeds & Heights", "KEZURI_PT_carve", "carve",
    ("finish_tool_number", "max_slope", "steep_cleanup", "sample_spacing", "rough_rpm", "finish_rpm", "rough_feed", "finish_feed",
     "plunge_feed", "clearance", "safe_z", "show_rapids"))

CLASSES = (KEZURI_PT_machine, KEZURI_PT_engrave, KEZURI_PT_engrave_texture, KEZURI_PT_engrave_finish,
           KEZURI_PT_engrave_feeds, KEZURI_PT_rotary, KEZURI_PT_rotary_settings, KEZURI_PT_stepnc,
           KEZURI_PT_stepnc_write, KEZURI_PT_turnmill, KEZURI_PT_turnmill_settings, KEZURI_PT_carve,
           KEZURI_PT_carve_roughing, KEZURI_PT_carve_settings, KEZURI_PT_sheet,
           KEZURI_PT_sheet_elbow, KEZURI_PT_simulate)
