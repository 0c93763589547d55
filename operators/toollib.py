"""The CAM tab's Tool Library panel: the user's tool library file (:mod:`.toolstore`) as a list to
pick from, add to, remove from and edit, and its import and export.

The rows live on the window manager (not in the .blend: the library is the user's, shared by every
file).  Edits to a row are written by Save, which checks every row first (a row that is no tool is
an error naming it; nothing is written); Add, Remove and Import write the rows at once (edits
included, checked the same way), and Export writes the rows as shown.
"""
from __future__ import annotations

import bpy
from bpy.props import BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from ..toolpath.ir.errors import InputError
from ..toolpath.tooling import formats, store
from ..toolpath.tooling.library import KINDS, LibraryTool, ToolLibrary, ToolLibraryError
from . import toolstore
from .translations import translate_message

KIND_ITEMS = [("flat", "Flat End Mill", "Square end mill"), ("ball", "Ball End Mill", "Ball-nose end mill"),
              ("bull", "Bull Nose", "End mill with a corner radius"), ("vbit", "V-Bit", "Engraving V-bit"),
              ("drill", "Drill", "Twist drill"), ("engraver", "Engraver", "Pointed engraving cutter")]
MATERIAL_ITEMS = [("carbide", "Carbide", "Solid carbide"), ("hss", "HSS", "High-speed steel")]
FORMAT_ITEMS = [("AUTO", "From Extension", "The format the file name's extension says"),
                ("kezuri", "Kezuri (.toml)", "Kezuri's own tool library file"),
                ("tbl", "LinuxCNC (.tbl)", "A LinuxCNC tool table"),
                ("fusion", "Fusion 360 (.json)", "A Fusion 360 tool library"),
                ("freecad", "FreeCAD (.fctl)", "A FreeCAD tool library and its tool bit files")]
UNIT_ITEMS = [("mm", "Millimetres", "The tool table is in millimetres"),
              ("inch", "Inches", "The tool table is in inches")]
ANGLED = ("vbit", "engraver", "drill")
SLOT_LABELS = {"rough": "Use for Roughing", "finish": "Use for Finishing", "tool": "Use for the Job"}
ROW_SLOT_LABELS = {"tool": "Use for the Row", "rest": "Use for Rest Machining", "drill": "Use as the Drill",
                   "mill": "Use for Helix Milling", "spot": "Use for Spotting", "clear": "Use for Clearing"}
assert tuple(item[0] for item in KIND_ITEMS) == KINDS


def length(name: str, description: str):
    # soft limits only: a hard one would change a typed value without a word (Save checks it)
    return FloatProperty(name=name, description=description, default=0.0, soft_min=0.0, soft_max=500.0,
                         precision=3)


class KezuriToolRow(bpy.types.PropertyGroup):
    number: IntProperty(name="Number", default=1, soft_min=1, soft_max=999, description="Tool number, the T word")
    kind: EnumProperty(name="Type", items=KIND_ITEMS, default="flat")
    diameter: length("Diameter", "Cutting diameter (mm)")
    corner_radius: length("Corner Radius", "Bull nose corner radius (mm)")
    angle: FloatProperty(name="Angle", default=90.0, soft_min=1.0, soft_max=179.0,
                         description="V-bit or engraver: included angle; drill: point angle (degrees)")
    flutes: IntProperty(name="Flutes", default=2, soft_min=1, soft_max=20, description="Number of flutes")
    flute_length: length("Flute Length", "Cutting length (mm)")
    stick_out: length("Stick-Out", "How far the tool stands out of the holder (mm); 0: not measured")
    holder_diameter: length("Holder Diameter", "The holder's (collet nut's) diameter (mm); 0: not known")
    material: EnumProperty(name="Material", items=MATERIAL_ITEMS, default="carbide")
    vendor: StringProperty(name="Vendor", description="Who makes the tool")
    product_id: StringProperty(name="Product ID", description="The maker's product number")


class KezuriToolLibraryState(bpy.types.PropertyGroup):
    tools: CollectionProperty(type=KezuriToolRow)
    index: IntProperty(default=0)
    loaded: BoolProperty(default=False)
    error: StringProperty()


def state(context):
    return context.window_manager.kezuri_tool_library


def fill_rows(rows, library: ToolLibrary) -> None:
    rows.clear()
    for tool in library:
        row = rows.add()
        row.name = tool.name
        for key in ("number", "kind", "diameter", "corner_radius", "flutes", "flute_length", "material", "vendor",
                    "product_id"):
            setattr(row, key, getattr(tool, key))
        row.angle = tool.angle if tool.angle is not None else 90.0
        row.stick_out = tool.stick_out or 0.0
        row.holder_diameter = tool.holder_diameter or 0.0


def shown(value: float) -> float:
    """A length or angle as a row holds it (a float32 property) and gives it back (6 digits)."""
    import numpy as np

    return float(f"{float(np.float32(value)):.6g}")


def as_shown(tool: LibraryTool) -> LibraryTool:
    """The tool as its row gives it back: each number through :func:`shown`."""
    changes = {key: shown(getattr(tool, key)) for key in ("diameter", "corner_radius", "angle", "flute_length",
                                                          "stick_out", "holder_diameter")
               if getattr(tool, key) is not None}
    return tool.replace(**changes)


def tool_of_row(row) -> LibraryTool:
    """The row as a library tool (float32 properties read back as the decimals typed)."""
    def mm(value):
        return shown(value)

    fields = dict(number=row.number, kind=row.kind, diameter=mm(row.diameter), flutes=row.flutes,
                  flute_length=mm(row.flute_length), material=row.material, vendor=row.vendor,
                  product_id=row.product_id, name=row.name,
                  stick_out=mm(row.stick_out) if row.stick_out > 0 else None,
                  holder_diameter=mm(row.holder_diameter) if row.holder_diameter > 0 else None)
    if row.kind == "bull":
        fields["corner_radius"] = mm(row.corner_radius)
    if row.kind in ANGLED:
        fields["angle"] = mm(row.angle)
    return LibraryTool(**fields)


def shown_library(context) -> ToolLibrary:
    """The library as the panel shows it (its rows, edits not yet saved included), else the file's.
    A row not edited gives the file's tool, its numbers as the file has them (a row holds 6 digits)."""
    tools = state(context)
    saved = toolstore.load()
    if not tools.loaded:
        return saved
    found = []
    for row in tools.tools:
        tool, before = tool_of_row(row), saved.find(row.number)
        found.append(before if before is not None and as_shown(before) == tool else tool)
    return ToolLibrary(found, [f"row {i + 1}" for i in range(len(found))])


def reload(context) -> ToolLibrary:
    library = toolstore.load()
    tools = state(context)
    fill_rows(tools.tools, library)
    tools.index = min(tools.index, len(tools.tools) - 1) if len(tools.tools) else 0
    tools.loaded, tools.error = True, ""
    return library


class ToolLibraryOperator:
    bl_options = {"REGISTER"}

    def run(self, context) -> str | None:
        raise NotImplementedError

    def execute(self, context):
        try:
            message = self.run(context)
        except (InputError, OSError) as error:
            state(context).error = str(error)
            self.report({"ERROR"}, translate_message(str(error)))
            return {"CANCELLED"}
        if message:
            self.report({"INFO"}, translate_message(message))
        return {"FINISHED"}


class KEZURI_OT_toollib_load(ToolLibraryOperator, bpy.types.Operator):
    """Read the tool library file (edits not saved are dropped)"""

    bl_idname = "kezuri.toollib_load"
    bl_label = "Load Tool Library"

    def run(self, context):
        return f"Tool library: {len(reload(context))} tools from {toolstore.library_path()}"


class KEZURI_OT_toollib_save(ToolLibraryOperator, bpy.types.Operator):
    """Check every row and write the tool library file (the file before is kept as a backup)"""

    bl_idname = "kezuri.toollib_save"
    bl_label = "Save Tool Library"

    def run(self, context):
        path = toolstore.save(shown_library(context))
        reload(context)
        return f"Saved the tool library to {path}"


class KEZURI_OT_toollib_add(ToolLibraryOperator, bpy.types.Operator):
    """Add a 6 mm flat end mill under the next free number, and save"""

    bl_idname = "kezuri.toollib_add"
    bl_label = "Add Library Tool"

    def run(self, context):
        library = shown_library(context)
        number = max(library.numbers(), default=0) + 1
        toolstore.save(library.with_tool(LibraryTool(number, "flat", 6.0, name=f"Tool {number}")))
        reload(context)
        state(context).index = [row.number for row in state(context).tools].index(number)
        return None


class KEZURI_OT_toollib_remove(ToolLibraryOperator, bpy.types.Operator):
    """Remove the selected tool from the library, and save"""

    bl_idname = "kezuri.toollib_remove"
    bl_label = "Remove Library Tool"

    @classmethod
    def poll(cls, context):
        tools = state(context)
        if not (0 <= tools.index < len(tools.tools)):
            cls.poll_message_set("Select a tool in the library first")
            return False
        return True

    def run(self, context):
        tools = state(context)
        toolstore.save(shown_library(context).without(tools.tools[tools.index].number))
        reload(context)
        return None


class KEZURI_OT_toollib_import(ToolLibraryOperator, bpy.types.Operator):
    """Merge a tool file (Kezuri .toml, LinuxCNC .tbl, Fusion 360 .json, FreeCAD .fctl) into the library"""

    bl_idname = "kezuri.toollib_import"
    bl_label = "Import Tools"

    filepath: StringProperty(subtype="FILE_PATH")
    filter_glob: StringProperty(default="*.toml;*.tbl;*.json;*.tools;*.fctl", options={"HIDDEN"})
    file_format: EnumProperty(name="Format", items=FORMAT_ITEMS, default="AUTO")
    units: EnumProperty(name="Table Units", items=UNIT_ITEMS, default="mm",
                        description="A LinuxCNC tool table's units (the table does not say)")
    replace: BoolProperty(name="Replace Same Numbers", default=False,
                          description="Tools of the file replace the library's tools of the same number")

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def run(self, context):
        from .common import blender_path

        path = blender_path(self.filepath)
        incoming, notes = formats.read_import(path, None if self.file_format == "AUTO" else self.file_format,
                                            self.units)
        merged, added, replaced = shown_library(context).merged(incoming, self.replace, source=path)
        toolstore.save(merged)
        reload(context)
        for note in notes:
            self.report({"WARNING"}, translate_message(note))
        return f"Imported {len(added)} new and {len(replaced)} replaced tools from {path}"


class KEZURI_OT_toollib_export(ToolLibraryOperator, bpy.types.Operator):
    """Write the tool library to a file (Kezuri .toml, LinuxCNC .tbl, Fusion 360 .json, FreeCAD .fctl)"""

    bl_idname = "kezuri.toollib_export"
    bl_label = "Export Tools"

    filepath: StringProperty(subtype="FILE_PATH")
    file_format: EnumProperty(name="Format", items=FORMAT_ITEMS, default="AUTO")
    units: EnumProperty(name="Table Units", items=UNIT_ITEMS, default="mm",
                        description="A LinuxCNC tool table's units")

    def invoke(self, context, event):
        if not self.filepath:
            self.filepath = "tools.tbl"
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def run(self, context):
        from .common import blender_path

        path = blender_path(self.filepath)
        library = shown_library(context)
        fmt = formats.format_of(path, None if self.file_format == "AUTO" else self.file_format)
        for name, text in formats.files_for(path, library, fmt, self.units):
            store.write_export(name, text)
        return f"Exported {len(library)} tools to {path}"


PANEL_GROUPS = ("engrave", "carve", "rotary")      # kinds whose panel settings a library tool can fill


def panel_kind(context) -> str | None:
    """The picked job's kind when its panel takes tools from the library."""
    from .workflows import workflow_of

    kind = workflow_of(context.scene.kezuri.job).kind
    return kind if kind in PANEL_GROUPS else None


def row_kind(context) -> str | None:
    """The kind of the job list's selected row when its panel group takes tools from the library
    (profile, pocket, drill, chamfer, V-carve)."""
    from . import jobrows
    from .jobtools import SLOTS

    row = jobrows.active_row(context.scene)
    if row is None or row.kind in PANEL_GROUPS or row.kind not in SLOTS:
        return None
    return row.kind if jobrows.group_of(context.scene, row.kind) is not None else None


class KEZURI_OT_toollib_use(ToolLibraryOperator, bpy.types.Operator):
    """Put the selected library tool on the picked job (its number, diameter and flute length)"""

    bl_idname = "kezuri.toollib_use"
    bl_label = "Use Library Tool"
    bl_options = {"REGISTER", "UNDO"}

    slot: StringProperty(name="Slot", options={"HIDDEN"})
    row: BoolProperty(name="Row", default=False, options={"HIDDEN"},
                      description="Put it on the job list's selected row, not on the picked workflow's panel")

    def run(self, context):
        from . import jobrows, jobtools

        kind, tools = (row_kind(context) if self.row else panel_kind(context)), state(context)
        if kind is None or not 0 <= tools.index < len(tools.tools):
            raise ToolLibraryError("Select a tool in the library first")
        number = tools.tools[tools.index].number
        values = jobtools.tool_settings({"tools": {self.slot: number}}, kind, {}, "Tool Library",
                                        lambda: shown_library(context))
        group = getattr(context.scene.kezuri, kind)
        for key, value in values.items():
            setattr(group, key, value)
        if self.row:
            jobrows.read_back(context.scene)        # the row keeps what its panel shows
        return None


class KEZURI_UL_library(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index=0, flt_flag=0):
        split = layout.split(factor=0.22, align=True)
        split.label(text=f"T{item.number}", translate=False)
        rest = split.split(factor=0.4, align=True)
        rest.label(text=f"Ø{item.diameter:.4g}", translate=False)
        rest.prop(item, "name", text="", emboss=False)


def draw_library(layout, context) -> None:
    from .panels import field, fields

    tools = state(context)
    if not tools.loaded:
        if tools.error:
            layout.label(text="The library file cannot be read", icon="ERROR")
        layout.operator("kezuri.toollib_load", icon="FILE_REFRESH")
        return
    row = layout.row()
    row.template_list("KEZURI_UL_library", "", tools, "tools", tools, "index", rows=4)
    column = row.column(align=True)
    column.operator("kezuri.toollib_add", icon="ADD", text="")
    column.operator("kezuri.toollib_remove", icon="REMOVE", text="")
    column.operator("kezuri.toollib_load", icon="FILE_REFRESH", text="")
    row = layout.row(align=True)
    row.operator("kezuri.toollib_save", icon="FILE_TICK", text="Save")
    row.operator("kezuri.toollib_import", icon="IMPORT", text="Import")
    row.operator("kezuri.toollib_export", icon="EXPORT", text="Export")
    if not 0 <= tools.index < len(tools.tools):
        return
    tool = tools.tools[tools.index]
    field(layout, tool, "kind", wide=True)
    fields(layout, tool, ("number", "diameter"))
    if tool.kind == "bull":
        field(layout, tool, "corner_radius")
    if tool.kind in ANGLED:
        field(layout, tool, "angle")
    fields(layout, tool, ("flutes", "flute_length", "stick_out", "holder_diameter", "material", "vendor",
                          "product_id"))
    kind = panel_kind(context)
    if kind is not None:
        from .jobtools import SLOTS

        column = layout.column(align=True)
        for slot, (*_, kinds, _angled) in SLOTS[kind].items():
            if tool.kind in kinds:
                column.operator("kezuri.toollib_use", text=SLOT_LABELS[slot], icon="TOOL_SETTINGS").slot = slot
    kind = row_kind(context)
    if kind is not None:
        from .jobtools import SLOTS

        column = layout.column(align=True)
        for slot, (*_, kinds, _angled) in SLOTS[kind].items():
            if tool.kind in kinds:
                button = column.operator("kezuri.toollib_use", text=ROW_SLOT_LABELS[slot], icon="TOOL_SETTINGS")
                button.slot, button.row = slot, True


class KEZURI_PT_toollib(bpy.types.Panel):
    # the user's tool library (a comment: a docstring would be a tooltip)
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "CAM"
    bl_idname = "KEZURI_PT_toollib"
    bl_label = "Tool Library"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        draw_library(self.layout, context)


CLASSES = (KezuriToolRow, KezuriToolLibraryState, KEZURI_OT_toollib_load, KEZURI_OT_toollib_save,
           KEZURI_OT_toollib_add, KEZURI_OT_toollib_remove, KEZURI_OT_toollib_import, KEZURI_OT_toollib_export,
           KEZURI_OT_toollib_use,
           KEZURI_UL_library, KEZURI_PT_toollib)


def load_when_ready():
    """Read the library once Blender's window is up (a timer: registering cannot touch data)."""
    try:
        reload(bpy.context)
    except (InputError, OSError) as error:
        state(bpy.context).error = str(error)
    return None


def register_properties():
    bpy.types.WindowManager.kezuri_tool_library = bpy.props.PointerProperty(type=KezuriToolLibraryState)


def unregister_properties():
    if hasattr(bpy.types.WindowManager, "kezuri_tool_library"):
        del bpy.types.WindowManager.kezuri_tool_library
