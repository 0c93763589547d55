"""View3D > Sidebar > CAM: the job picker, Machine & Stock, the job list (the scene's operations as
one job, :mod:`.joblist`), the picked workflow's panels and Simulate & Check.

The job (``scene.kezuri.job``, one entry per workflow of the table with panels) decides which
workflow panels show: a panel with ``job = "ENGRAVE"`` shows only while Engraving is picked
(its sub-panels follow their parent).  Every text fits the sidebar's default width in English
and Japanese (tests/test_sidebar_fit.py measures it); what does not fit goes into tooltips.
"""
from __future__ import annotations

import bpy

from ..toolpath.feeds.operationfeeds import KINDS as FEEDS_KINDS
from .translations import iface
from .workflows import workflow_of


class KezuriPanel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "CAM"
    job = ""          # the workflow key whose panels these are ("": every job)

    @classmethod
    def poll(cls, context):
        return not cls.job or context.scene.kezuri.job == cls.job


class KEZURI_PT_job(KezuriPanel, bpy.types.Panel):
    # the job picker at the top of the tab (a comment: a docstring would be a tooltip)
    bl_idname = "KEZURI_PT_job"
    bl_label = "Job"
    bl_options = {"HIDE_HEADER"}

    def draw(self, context):
        settings = context.scene.kezuri
        self.layout.prop(settings, "job", text="", icon="TOOL_SETTINGS")
        if workflow_of(settings.job).simulation is not None:     # a job with toolpaths in the viewport
            self.layout.prop(settings, "show_rapids")


NAME_SHARE = 0.5    # of the panel's width, for a setting's name (Blender's split gives it 0.4 less a column)

# Short names of the simulation's finding kinds (the full message is the button's tooltip).
FINDING_KINDS = {"gouge": "Gouge", "rapid_in_material": "Rapid in stock", "plunge": "Plunge",
                 "spindle_stopped": "Spindle stopped", "travel": "Travel limit"}


def field(layout, data, name: str, text: str | None = None, wide: bool = False):
    """One setting on one line: its name right-aligned in the left half, the value in the right
    half (the value's tooltip has the full description).  A check box takes the whole line; a
    ``wide`` one (a menu of long names) has its name above and the whole line below."""
    prop = data.bl_rna.properties[name]
    if prop.type == "BOOLEAN":
        layout.prop(data, name, text=text)
        return
    if wide:
        column = layout.column(align=True)
        column.label(text=prop.name if text is None else text)
        column.prop(data, name, text="")
        return
    split = layout.split(factor=NAME_SHARE, align=True)
    label = split.row()
    label.alignment = "RIGHT"
    label.label(text=prop.name if text is None else text)
    split.prop(data, name, text="")


def fields(layout, data, names):
    for name in names:
        field(layout, data, name)


def big_button(layout, idname: str, icon: str, text: str | None = None):
    row = layout.row(align=True)
    row.scale_y = 1.4
    return row.operator(idname, icon=icon) if text is None else row.operator(idname, icon=icon, text=text)


def property_subpanel(idname: str, label: str, parent: str, group: str, names: tuple):
    """A sub-panel, closed at first, listing ``names`` of ``scene.kezuri.<group>`` (shown with its
    parent, so with the parent's job)."""
    def draw(self, context):
        fields(self.layout, getattr(context.scene.kezuri, group), names)
    return type(idname, (KezuriPanel, bpy.types.Panel), {"bl_idname": idname, "bl_label": label, "bl_parent_id": parent,
                                                          "bl_options": {"DEFAULT_CLOSED"}, "draw": draw})


class KEZURI_PT_machine(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_machine"
    bl_label = "Machine & Stock"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.kezuri
        field(layout, settings.machine, "post", wide=True)
        field(layout, settings.machine, "preset", wide=True)
        if settings.machine.preset != "POST":       # the picked preset's settings, the user's to change
            fields(layout, settings.machine, ("travel_x", "travel_y", "travel_z", "z_reach", "clearance_height"))
            field(layout, settings.machine, "retract", wide=True)
            fields(layout, settings.machine, ("machine_top_z", "tool_change", "m6_lifts_z", "max_spindle", "max_feed"))
        fields(layout, settings.machine, ("work_offset", "rapid_rate", "output_dir", "orient_spindle", "arcs"))
        layout.separator()
        field(layout, settings.stock, "plate")
        field(layout, settings.stock, "origin", wide=True)
        field(layout, settings.stock, "material", wide=True)


class KEZURI_PT_engrave(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_engrave"
    job = "ENGRAVE"
    bl_label = "Engrave"

    def draw(self, context):
        layout = self.layout
        fields(layout, context.scene.kezuri.engrave, ("letters", "letters_collection", "surface"))
        big_button(layout, "kezuri.engrave_generate", "MOD_NOISE")
        layout.operator("kezuri.engrave_export", icon="EXPORT")
        from .engrave import too_fine_lines
        lines = too_fine_lines(context.scene.kezuri.engrave)     # characters the band's tool cannot resolve
        if lines:
            box = layout.box()
            for line in lines:
                box.label(text=line, icon="ERROR", translate=False)


class KEZURI_PT_engrave_texture(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_engrave_texture"
    bl_label = "Gouge Texture (Roughing)"
    bl_parent_id = "KEZURI_PT_engrave"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.menu("KEZURI_MT_library_tools", icon="TOOL_SETTINGS")
        fields(layout, context.scene.kezuri.engrave,
               ("rough_diameter", "rough_tool_number", "stepover", "raster_angle", "letter_clearance", "base_depth",
                "quantum", "amplitude", "spacing", "motion", "spacing_jitter", "seed"))


class KEZURI_PT_rotary(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_rotary"
    job = "ROTARY"
    bl_label = "Rotary Pockets"

    def draw(self, context):
        layout = self.layout
        scene = context.scene
        pockets = [o for o in scene.objects if o.kezuri_pocket.enabled]
        layout.label(text=f"{iface('Pockets')}: {len(pockets)}", icon="INFO", translate=False)
        obj = context.active_object
        if obj is not None and obj.type in {"MESH", "CURVE"} and obj != scene.kezuri.stock.plate:
            box = layout.box()
            box.label(text=obj.name, icon="OBJECT_DATA", translate=False)
            box.prop(obj.kezuri_pocket, "enabled")
            if obj.kezuri_pocket.enabled:
                fields(box, obj.kezuri_pocket, ("depth", "wall_angle", "bottom"))
                if obj.kezuri_pocket.bottom == "sphere":
                    field(box, obj.kezuri_pocket, "sphere_radius")
        layout.operator("kezuri.mark_pocket", icon="ADD")
        big_button(layout, "kezuri.rotary_generate", "DRIVER_ROTATIONAL_DIFFERENCE")
        field(layout, scene.kezuri.rotary, "post", wide=True)
        layout.operator("kezuri.rotary_export", icon="EXPORT")


class KEZURI_PT_stepnc(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_stepnc"
    job = "STEPNC"
    bl_label = "STEP-NC Workplan"

    def draw(self, context):
        layout = self.layout
        props = context.scene.kezuri.stepnc
        layout.operator("kezuri.import_stepnc", icon="IMPORT")
        if props.filepath:
            layout.label(text=bpy.path.basename(props.filepath), icon="FILE", translate=False)
        # the list the whole width (its rows need it), the order buttons below it
        layout.template_list("KEZURI_UL_workingsteps", "", props, "steps", props, "active_step", rows=5)
        row = layout.row(align=True)
        row.operator("kezuri.workingstep_move", icon="TRIA_UP", text="").direction = "UP"
        row.operator("kezuri.workingstep_move", icon="TRIA_DOWN", text="").direction = "DOWN"
        big_button(layout, "kezuri.stepnc_generate", "SEQ_STRIP_DUPLICATE")
        layout.operator("kezuri.stepnc_export", icon="EXPORT")


class KEZURI_PT_stepnc_write(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_stepnc_write"
    bl_label = "Write Pockets as ISO 14649"
    bl_parent_id = "KEZURI_PT_stepnc"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.label(text="Pockets: objects marked as pockets", icon="INFO")
        fields(layout, context.scene.kezuri.stepnc, ("tool_diameter", "tool_number", "flute_length", "feed",
                                                     "spindle_rpm"))
        layout.operator("kezuri.export_stepnc", icon="EXPORT")


class KEZURI_PT_turnmill(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_turnmill"
    job = "TURNMILL"
    bl_label = "Turn-Mill"

    def draw(self, context):
        layout = self.layout
        fields(layout, context.scene.kezuri.turnmill,
               ("part", "selected_only", "stock_radius", "stock_z_min", "stock_z_max", "engine"))
        layout.operator("kezuri.turnmill_classify", icon="SHADING_RENDERED")
        big_button(layout, "kezuri.turnmill_generate", "MOD_SCREW")
        layout.operator("kezuri.turnmill_export", icon="EXPORT")


class KEZURI_PT_carve(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_carve"
    job = "CARVE"
    bl_label = "Carve"

    def draw(self, context):
        layout = self.layout
        props = context.scene.kezuri.carve
        field(layout, props, "design")
        samples = layout.column(align=True)        # three sample buttons do not fit side by side
        samples.operator("kezuri.carve_sample", text="Wave Relief", icon="MESH_GRID").sample = "wave"
        samples.operator("kezuri.carve_sample", text="Domed Plate", icon="MESH_UVSPHERE").sample = "dome"
        samples.operator("kezuri.carve_sample", text="Steep Ridge", icon="MESH_CONE").sample = "ridge"
        fields(layout, props, ("stock_above", "scallop", "raster_angle", "finish_diameter", "rough"))
        big_button(layout, "kezuri.carve_generate", "MOD_DISPLACE")
        layout.operator("kezuri.carve_export", icon="EXPORT")


class KEZURI_PT_sheet(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_sheet"
    job = "SHEET"
    bl_label = "Sheet Metal"

    def draw(self, context):
        layout = self.layout
        sheet = context.scene.kezuri.sheet
        layout.label(text="Quad corners (mm)")
        grid = layout.column(align=True)
        header = grid.row(align=True)
        for text in ("", "X", "Y", "Z"):
            header.label(text=text, translate=False)
        for corner in range(4):
            row = grid.row(align=True)
            row.label(text=f"P{corner + 1}", translate=False)
            for axis in range(3):
                row.prop(sheet, "corners", index=3 * corner + axis, text="")
        layout.operator("kezuri.quad_from_selection", text="From Selected Face", icon="FACESEL")
        layout.operator("kezuri.import_cdl", text="Import CDL", icon="IMPORT")
        fields(layout, sheet, ("divisions", "direction", "tool_diameter", "thickness", "pitch", "station"))
        big_button(layout, "kezuri.unfold_quad", "MOD_UVPROJECT")
        layout.operator("kezuri.sheet_export", icon="EXPORT")


class KEZURI_PT_sheet_elbow(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_sheet_elbow"
    bl_label = "Pipe Elbow"
    bl_parent_id = "KEZURI_PT_sheet"

    def draw(self, context):
        layout = self.layout
        fields(layout, context.scene.kezuri.sheet, ("elbow_diameter", "elbow_radius", "elbow_angle", "elbow_pieces"))
        layout.operator("kezuri.add_elbow", icon="MESH_CYLINDER")
        layout.operator("kezuri.elbow_export", icon="EXPORT")


class KEZURI_PT_sheet_setup(KezuriPanel, bpy.types.Panel):
    # where the part goes on the turret punch's sheet, the clamps, the micro-joints
    bl_idname = "KEZURI_PT_sheet_setup"
    bl_label = "Sheet, Clamps & Joints"
    bl_parent_id = "KEZURI_PT_sheet"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        sheet = context.scene.kezuri.sheet
        for name in ("sheet_size", "sheet_origin"):          # X and Y side by side under the name
            column = layout.column(align=True)
            column.label(text=sheet.bl_rna.properties[name].name)
            row = column.row(align=True)
            for index in range(2):
                row.prop(sheet, name, index=index, text="")
        field(layout, sheet, "clamps", wide=True)
        fields(layout, sheet, ("clamp_width", "clamp_depth", "joints", "joint_width"))


class KEZURI_PT_simulate(KezuriPanel, bpy.types.Panel):
    bl_idname = "KEZURI_PT_simulate"
    bl_label = "Simulate & Check"

    @classmethod
    def poll(cls, context):
        return workflow_of(context.scene.kezuri.job).simulation is not None

    def draw(self, context):
        layout = self.layout
        props = context.scene.kezuri.simulation
        field(layout, props, "engine")
        if props.engine == "heightfield":
            field(layout, props, "cell")
        field(layout, props, "colour_by")
        big_button(layout, "kezuri.simulate", "MOD_BOOLEAN").workflow = context.scene.kezuri.job
        if len(props.findings):
            box = layout.box()
            box.label(text=f"{iface('Findings')}: {len(props.findings)}", icon="ERROR", translate=False)
            for index, finding in enumerate(props.findings[:20]):
                # the short kind and move on the button, the whole message in its tooltip
                text = f"{iface(FINDING_KINDS.get(finding.kind, finding.kind))} · {finding.move}"
                box.operator("kezuri.frame_finding", text=text, icon="ZOOM_SELECTED", translate=False).index = index
            blocking = sum(1 for f in props.findings if f.blocking)
            if blocking:
                box.prop(props, "allow_findings")
        else:
            layout.label(text="No findings", icon="CHECKMARK")


class KEZURI_PT_joblist(KezuriPanel, bpy.types.Panel):
    # the scene's operations as one job (operators/joblist.py): the list, the selected one below
    bl_idname = "KEZURI_PT_joblist"
    bl_label = "Job"

    def draw(self, context):
        from .joblist import STATE_ICONS, kind_items

        layout = self.layout
        listed = context.scene.kezuri.job_list
        layout.template_list("KEZURI_UL_job", "", listed, "rows", listed, "active", rows=4)
        row = layout.row(align=True)
        row.menu("KEZURI_MT_job_add", icon="ADD", text="")
        row.operator("kezuri.job_duplicate", icon="DUPLICATE", text="")
        row.operator("kezuri.job_remove", icon="REMOVE", text="")
        row.operator("kezuri.job_move", icon="TRIA_UP", text="").direction = "UP"
        row.operator("kezuri.job_move", icon="TRIA_DOWN", text="").direction = "DOWN"
        row.operator("kezuri.job_load", icon="FILEBROWSER", text="")
        row.operator("kezuri.job_save", icon="FILE_TICK", text="")
        row.operator("kezuri.import_design", icon="IMPORT", text="")     # an SVG / DXF drawing as curves
        selected = listed.rows[listed.active] if 0 <= listed.active < len(listed.rows) else None
        if selected is not None:
            box = layout.box()
            label = next((label for key, label, _ in kind_items() if key == selected.kind), selected.kind)
            box.label(text=f"{iface(label)}: {selected.name}", icon=STATE_ICONS.get(selected.state, "DOT"),
                      translate=False)
            for item in selected.objects:
                field(box, item, "object", text=iface(item.slot.capitalize()))
            if getattr(context.scene.kezuri, selected.kind, None) is None:     # no panel of its own: as in the file
                box.prop(selected, "settings", text="")
                box.prop(selected, "extra", text="")
            elif _has_settings_panels(selected.kind):     # its settings below; holes, tabs as in the file
                field(box, selected, "extra")
            if selected.kind in FEEDS_KINDS:             # the calculator's feeds for the stock's material
                box.operator("kezuri.job_suggest_feeds", icon="AUTO")
        big_button(layout, "kezuri.job_generate", "FILE_REFRESH")
        column = layout.column(align=True)
        column.operator("kezuri.job_simulate", icon="MOD_BOOLEAN", text="Simulate Job").upto = False
        column.operator("kezuri.job_simulate", icon="TRIA_DOWN_BAR", text="Simulate up to Selected").upto = True
        layout.operator("kezuri.job_export", icon="EXPORT")
        field(layout, context.scene.kezuri, "show_rapids")


def joblist_subpanels(classes) -> tuple:
    """The settings sub-panels of each job kind's workflow panel, again under the Job panel, shown
    while a row of that kind is selected (they draw the kind's group, which holds the row's settings)."""
    from .joblist import adapters

    made = []
    for kind, workflow in adapters().items():
        mains = {cls.bl_idname for cls in classes if cls.job == workflow.key and not getattr(cls, "bl_parent_id", "")}
        for cls in classes:
            if getattr(cls, "bl_parent_id", "") in mains:
                idname = "KEZURI_PT_joblist_" + cls.bl_idname.removeprefix("KEZURI_PT_")
                poll = classmethod(_kind_poll(kind))
                made.append(type(idname, (KezuriPanel, bpy.types.Panel),
                                 {"bl_idname": idname, "bl_label": cls.bl_label, "bl_parent_id": "KEZURI_PT_joblist",
                                  "bl_options": {"DEFAULT_CLOSED"}, "draw": cls.draw, "poll": poll}))
    return tuple(made)


def kind_settings_subpanels() -> tuple:
    """The settings sub-panels of the operation kinds whose settings are panel properties
    (``Workflow.settings_panels``: profile, pocket, drill, chamfer), under the Job panel, shown while
    a row of that kind is selected; they draw ``scene.kezuri.<kind>``, which holds the row's settings."""
    from .joblist import adapters

    made = []
    for kind, workflow in adapters().items():
        for index, (label, names) in enumerate(workflow.settings_panels):
            idname = f"KEZURI_PT_joblist_{kind}_{index}"
            made.append(type(idname, (KezuriPanel, bpy.types.Panel),
                             {"bl_idname": idname, "bl_label": label, "bl_parent_id": "KEZURI_PT_joblist",
                              "bl_options": set() if index == 0 else {"DEFAULT_CLOSED"},
                              "draw": _settings_drawer(kind, names), "poll": classmethod(_kind_poll(kind))}))
    return tuple(made)


def _settings_drawer(kind: str, names: tuple):
    def draw(self, context):
        fields(self.layout, getattr(context.scene.kezuri, kind), names)
    return draw


def _has_settings_panels(kind: str) -> bool:
    from .joblist import adapters
    return bool(getattr(adapters().get(kind), "settings_panels", ()))


def _kind_poll(kind: str):
    def poll(cls, context):
        return _selected_kind(context) == kind
    return poll


def _selected_kind(context) -> str:
    listed = context.scene.kezuri.job_list
    return listed.rows[listed.active].kind if 0 <= listed.active < len(listed.rows) else ""


KEZURI_PT_engrave_finish = property_subpanel(
    "KEZURI_PT_engrave_finish", "Band & Burr Finishing", "KEZURI_PT_engrave", "engrave",
    ("finish_diameter", "finish_tool_number", "band_width", "band_depth", "band_stepover", "band_step_down",
     "band_ramp_angle"))
KEZURI_PT_engrave_feeds = property_subpanel(
    "KEZURI_PT_engrave_feeds", "Feeds & Heights", "KEZURI_PT_engrave", "engrave",
    ("rough_rpm", "rough_feed", "finish_rpm", "finish_feed", "plunge_feed", "clearance_z", "safe_z"))
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
    ("finish_tool_number", "max_slope", "steep_cleanup", "wall_pass", "sample_spacing", "rough_rpm", "finish_rpm", "rough_feed",
     "finish_feed", "plunge_feed", "clearance", "safe_z"))

WORKFLOW_PANELS = (KEZURI_PT_engrave, KEZURI_PT_engrave_texture, KEZURI_PT_engrave_finish,
           KEZURI_PT_engrave_feeds, KEZURI_PT_rotary, KEZURI_PT_rotary_settings, KEZURI_PT_stepnc,
           KEZURI_PT_stepnc_write, KEZURI_PT_turnmill, KEZURI_PT_turnmill_settings, KEZURI_PT_carve,
           KEZURI_PT_carve_roughing, KEZURI_PT_carve_settings, KEZURI_PT_sheet,
           KEZURI_PT_sheet_setup, KEZURI_PT_sheet_elbow, KEZURI_PT_simulate)
# Machine & Stock on top, the job list below it, then the picked workflow's panels
CLASSES = (KEZURI_PT_job, KEZURI_PT_machine, KEZURI_PT_joblist, *joblist_subpanels(WORKFLOW_PANELS),
           *kind_settings_subpanels(), *WORKFLOW_PANELS)
