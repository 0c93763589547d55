"""Scene properties: machine, stock and one settings group per workflow (``scene.kezuri``).

Defaults are the source papers' values; every length is in millimetres whatever the scene
units (a CNC user thinks in the machine's units, and G-code coming out 1000x too large is the
commonest complaint about Blender CAM add-ons).

The numbers' ranges are in :mod:`.limits` (one table for the panel and batch): :func:`ranged`
turns them into soft limits and drops the hard ones, so a bad value set from Python stays what
it is and is refused by name when the job reads it, instead of being clamped into another job.
"""
import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty, FloatVectorProperty,
                       IntProperty, PointerProperty, StringProperty)

from .. import post as posts
from ..toolpath.feeds import materials as feed_materials
from ..toolpath.ir import machine as machine_presets
from ..toolpath.operations.sheetmetal import nibbling
from . import jobrows, limits, machines, pathview
from .jobrows import KezuriJobList

_ENUM_ITEMS: dict = {}   # Blender reads dynamic enum strings after the callback returns: keep them alive


def post_items(families, texture: bool | None = None, first: tuple = ()):
    """A dynamic ``items`` callback listing the registered posts of ``families`` (see
    ``post.registry``): a post added to ``post/`` shows up without an edit here."""
    def items(self, context):
        found = posts.enum_items(families, texture=texture, first=first)
        return _ENUM_ITEMS.setdefault(repr(found), found)
    return items


def post_number(choice: str) -> int:
    """The enum value of a post (a dynamic enum's default is a number)."""
    return posts.registry.enum_number(choice)


DEFAULT_POST = ("DEFAULT", "Preferences Default", "The default post of the extension preferences")

MATERIAL_ITEMS = [("NONE", "None", "No material: the feeds are not checked")] + [
    (m.key, m.label, m.examples) for m in feed_materials.MATERIALS.values()]
WORK_OFFSET_ITEMS = [(f"G{n}", f"G{n}", f"Work coordinate system G{n}") for n in range(54, 60)]

ORIGIN_ITEMS = [
    ("CENTER", "Top centre", "Work zero at the centre of the plate's top face (as the paper programs it)"),
    ("CORNER", "Top front-left corner", "Work zero at the front-left corner of the plate's top face"),
]


def _mesh_poll(self, obj):
    return obj.type == "MESH"


def _outline_poll(self, obj):
    return obj.type in {"MESH", "CURVE", "FONT"}


def mm(name, default, description, minimum=None, maximum=None, soft_min=None, soft_max=None):
    """A length in millimetres (shown as a plain number: the NC is in mm whatever the scene)."""
    options = {"name": name, "default": default, "description": description + " (mm)", "precision": 3,
               "step": 10}
    for key, value in (("min", minimum), ("max", maximum), ("soft_min", soft_min), ("soft_max", soft_max)):
        if value is not None:
            options[key] = value
    return FloatProperty(**options)


def ranged(settings: dict, group: str) -> dict:
    """``settings`` (name -> property definition) with the ranges of ``limits.RANGES[group]`` as
    soft limits and no hard ones."""
    table = limits.RANGES[group]
    result = {}
    for name, prop in settings.items():
        if name in table:
            keywords = {k: v for k, v in prop.keywords.items() if k not in ("min", "max", "soft_min", "soft_max")}
            prop = prop.function(**keywords, **limits.soft_limits(table[name]))
        result[name] = prop
    return result


def limited(cls, group: str):
    """Apply :func:`ranged` to a property group class's annotations (before registration)."""
    cls.__annotations__ = ranged(dict(cls.__annotations__), group)
    return cls



# The menu's names where a preset's label does not fit the sidebar (toolpath/ir/machine.py keeps the full one)
MACHINE_MENU_NAMES = {"linuxcnc-manual": "LinuxCNC, Manual Change", "linuxcnc-atc": "LinuxCNC, Tool Changer",
                      "wood-lathe-cxz": "Wood Lathe C-X-Z (Fanuc)", "wood-lathe-cxz-linuxcnc": "Wood Lathe C-X-Z (LinuxCNC)"}


def _machine_items():
    from ..toolpath.ir import machine
    return [("POST", "Post's Machine", "The machine the chosen post's program assumes (its own preset)")] + [
        (p.name, MACHINE_MENU_NAMES.get(p.name, p.label), p.description) for p in machine.PRESETS.values()]


MACHINE_ITEMS = _machine_items()
RETRACT_ITEMS = [
    ("reference", "Reference Return", "Fanuc G91 G28 Z0.: Z to the reference position (machine coordinates)"),
    ("machine", "Machine Z (G53)", "G53 G00 Z to Machine Top Z: needs a homed machine"),
    ("clearance", "Clearance Height", "G00 Z to the clearance height above the work zero (a machine not homed)"),
]
TOOL_CHANGE_ITEMS = [("atc", "Tool Changer", "M06 changes the tool"),
                     ("manual", "Manual", "The operator changes the tool at a pause (M00, or an M6 that asks)")]


def _fill_machine(self, context):
    if self.preset != "POST":
        machines.fill_machine(self, self.preset)


class KezuriMachine(bpy.types.PropertyGroup):
    post: EnumProperty(name="Post", items=post_items("milling", first=(DEFAULT_POST,)), default=0,
                       description="Controller the NC program is written for")
    work_offset: EnumProperty(name="Work Offset", items=WORK_OFFSET_ITEMS, default="G54",
                              description="Work coordinate system selected at the program start")
    rapid_rate: FloatProperty(name="Rapid Rate", default=5000.0, min=1.0,
                              description="Rapid traverse speed used for cycle-time estimates (mm/min)")
    output_dir: StringProperty(name="Output Folder", subtype="DIR_PATH", default="",
                               description="Folder for exported NC programs (empty: the preferences' folder)")
    preset: EnumProperty(name="Machine", items=MACHINE_ITEMS, default="POST", update=_fill_machine,
                         description="The machine the programs are written for: travel, how high Z reaches, how "
                                     "the frames lift Z, the tool change (picking one fills the settings below)")
    travel_x: mm("Travel X", 600.0, "How far the X axis travels")
    travel_y: mm("Travel Y", 400.0, "How far the Y axis travels (0: no Y axis)")
    travel_z: mm("Travel Z", 150.0, "How far the Z axis travels")
    z_reach: mm("Z Reach", 80.0, "How high above the work zero the tool can be lifted")
    clearance_height: mm("Clearance Height", 20.0, "Where the frames lift Z to on a machine without a "
                                                   "machine-coordinate retract, above the work zero")
    retract: EnumProperty(name="Retract", items=RETRACT_ITEMS, default="machine",
                          description="How Z is lifted at the start, around tool changes and at the end")
    machine_top_z: mm("Machine Top Z", 0.0, "Machine-coordinate Z of the top of travel (G53)")
    tool_change: EnumProperty(name="Tool Change", items=TOOL_CHANGE_ITEMS, default="manual",
                              description="How a tool gets into the spindle")
    m6_lifts_z: BoolProperty(name="M6 Lifts Z", default=False,
                             description="The changer's M6 lifts Z by itself (LinuxCNC TOOL_CHANGE_QUILL_UP)")
    max_spindle: FloatProperty(name="Max Spindle", default=24000.0, description="Fastest spindle speed (rpm)")
    max_feed: FloatProperty(name="Max Feed", default=6000.0, description="Fastest cutting feed (mm/min)")
    orient_spindle: BoolProperty(name="Orient Spindle (M19)", default=False,
                                 description="Fanuc posts: M19 before each tool change, for a changer that needs "
                                             "the spindle keys aligned (a post without it refuses the export)")
    arcs: BoolProperty(name="Arcs (G2/G3)", default=True,
                       description="Milling posts write polylines that follow circles as G2/G3 arcs (within 0.01 mm, "
                                   "within the control's arc end check); off: every move as planned")


class KezuriStock(bpy.types.PropertyGroup):
    plate: PointerProperty(name="Plate", type=bpy.types.Object, poll=_mesh_poll,
                           description="The stock: a mesh whose top face is machined")
    origin: EnumProperty(name="Work Zero", items=ORIGIN_ITEMS, default="CENTER",
                         description="Where the program's X0 Y0 Z0 is on the plate")
    material: EnumProperty(name="Material", items=MATERIAL_ITEMS, default="NONE",
                           description="What the stock is: each operation's spindle speed and feed are checked "
                                       "against its tool's chip-load band in it before export (None: not checked)")


class KezuriEngrave(bpy.types.PropertyGroup):
    letters: PointerProperty(name="Letters", type=bpy.types.Object, poll=_outline_poll,
                             description="Text, curve or mesh object with the lettering to leave standing")
    letters_collection: PointerProperty(name="More Letters", type=bpy.types.Collection,
                                        description="Optional: every Text, curve or mesh in this collection "
                                                    "is lettering too")
    surface: PointerProperty(name="Plate Surface", type=bpy.types.Object, poll=_mesh_poll,
                             description="Optional: a mesh whose top is the plate's curved top (a dome, a "
                                         "cylinder, a sculpted board), spanning the whole plate outline; the "
                                         "toolpaths follow it.  Empty: the flat top of the plate")
    # Roughing with the gouge texture
    rough_diameter: mm("Ball Diameter", 6.0, "Roughing ball end mill diameter", minimum=0.1)
    rough_tool_number: IntProperty(name="Ball Tool No.", default=2, min=0, max=999)
    stepover: mm("Stepover", 3.0, "Distance between zigzag rows", minimum=0.0)
    raster_angle: FloatProperty(name="Raster Angle", default=0.0, min=-180, max=180,
                                description="Direction of the zigzag rows from the X axis (degrees); the "
                                            "controller macro needs 0")
    letter_clearance: mm("Letter Clearance", 4.0, "How far the ball's centre keeps from the letters",
                         minimum=0.0)
    base_depth: mm("Base Depth", -2.0, "Depth the random gouges vary around", maximum=0.0)
    quantum: mm("Depth Step", 0.2, "Gouge depths are multiples of this", minimum=0.001)
    amplitude: mm("Amplitude", 0.8, "Largest gouge depth above or below the base depth", minimum=0.0)
    spacing: mm("Gouge Spacing", 20.0, "A new random depth every this much travel along a row", minimum=0.1)
    motion: EnumProperty(name="Gouge Motion", default="ramp",
                         items=[("ramp", "Ramp", "Straight lines from one depth to the next (the paper)"),
                                ("scoop", "Scoop", "Dive to the depth, then push up, like a hand gouge")])
    spacing_jitter: FloatProperty(name="Spacing Jitter", default=0.0, min=0.0, max=0.5, subtype="FACTOR",
                                  description="Vary each gouge length by up to this fraction (baked only)")
    seed: IntProperty(name="Seed", default=0, min=0,
                      description="Random seed of the baked texture: same seed, same program")
    # Band finishing and burr contour
    finish_diameter: mm("Flat Diameter", 1.0, "Band finishing flat end mill diameter", minimum=0.05)
    finish_tool_number: IntProperty(name="Flat Tool No.", default=3, min=0, max=999)
    band_width: mm("Band Width", 4.0, "Width of the flat band cut around every letter", minimum=0.0)
    band_depth: mm("Band Depth", -2.0, "Depth of the band around the letters", maximum=0.0)
    band_stepover: mm("Band Stepover", 0.5, "Distance between the band's contour passes", minimum=0.0)
    band_step_down: mm("Band Step Down", 1.0, "Deepest cut of one level of the band: at most the flat end mill's "
                       "diameter", minimum=0.0)
    band_ramp_angle: FloatProperty(name="Band Ramp Angle", default=3.0, min=0.0, max=45.0,
                                   description="Each level of the band is entered on a ramp along the ring at this "
                                               "angle (degrees); the flat end mill never plunges straight down")
    # Feeds and heights
    rough_rpm: FloatProperty(name="Ball Spindle", default=6000.0, min=0.0, description="Spindle speed (rpm)")
    finish_rpm: FloatProperty(name="Flat Spindle", default=12000.0, min=0.0, description="Spindle speed (rpm)")
    rough_feed: FloatProperty(name="Ball Feed", default=1200.0, min=0.0, description="Cutting feed (mm/min)")
    finish_feed: FloatProperty(name="Flat Feed", default=600.0, min=0.0, description="Cutting feed (mm/min)")
    plunge_feed: FloatProperty(name="Plunge Feed", default=300.0, min=0.0, description="Plunge feed (mm/min)")
    clearance_z: mm("Clearance Plane", 20.0, "Height of rapid moves between cuts", minimum=0.0)
    safe_z: mm("Safe Z", 0.0, "Height where each operation starts and ends; 0: the machine's clearance height "
                              "(tool changes and the program end lift Z as the machine profile says)", minimum=0.0)
    # the last Generate's characters too fine for the band finishing tool (JSON, operators/engrave.py)
    too_fine: StringProperty(name="Too Fine", options={"HIDDEN"})


# Shared by the Sheet Metal panel (scene settings) and the operators' redo panels.
UNFOLD_SETTINGS = ranged({
    "divisions": IntProperty(name="Divisions N", default=5, min=1, max=500,
                             description="Every edge of the quad is divided into N equal parts"),
    "direction": EnumProperty(name="Strips", default="horizontal", items=[
        ("horizontal", "Horizontal (YR)", "Strips joining edges L1 and L3"),
        ("vertical", "Vertical (TR)", "Strips joining edges L2 and L4")]),
    "tool_diameter": mm("Tool Diameter", 10.0, "Punch diameter: the cut contour is offset by its radius",
                        minimum=0.5),
    "thickness": mm("Sheet Thickness", 1.6, "Sheet thickness; above 3.2 mm the punching line G79 is used",
                    minimum=0.01),
    "pitch": mm("Nibbling Pitch", 2.0, "Distance between punch hits (Q word)", minimum=0.1),
    "station": IntProperty(name="Station", default=302, min=1, max=999, description="Turret station (T word)"),
}, "sheet")
ELBOW_SETTINGS = ranged({
    "elbow_diameter": mm("Pipe Diameter", 100.0, "Neutral diameter of the pipe", minimum=0.1),
    "elbow_radius": mm("Bend Radius", 150.0, "Radius of the elbow's centre line", minimum=0.1),
    "elbow_angle": FloatProperty(name="Bend Angle", default=90.0, min=1.0, max=180.0,
                                 description="Angle the elbow turns the pipe through (degrees)"),
    "elbow_pieces": IntProperty(name="Pieces", default=5, min=2, max=60,
                                description="Pieces in all, the two half pieces at the ends included"),
}, "sheet")


def copies(settings: dict) -> dict:
    """Fresh property definitions for another class (an operator's redo panel): Blender binds a
    definition to the class it is registered with, so two classes cannot share one."""
    return {name: prop.function(**prop.keywords) for name, prop in settings.items()}


_PUNCH = machine_presets.preset("amada-04p")
# Where the part goes on the turret punch's sheet, and the micro-joints that keep it there
# (defaults: the Amada 04P preset of toolpath/ir/machine.py).
SHEET_SETUP = ranged({
    "sheet_origin": FloatVectorProperty(name="G92 Origin", size=2, default=_PUNCH.sheet_origin, precision=2,
                                        description="The program origin the control is told (G92 X Y, mm)"),
    "sheet_size": FloatVectorProperty(name="Sheet", size=2, default=_PUNCH.sheet_max, precision=1,
                                      description="The sheet the part is placed on, X along the clamped edge (mm)"),
    "clamps": StringProperty(name="Clamps", default=", ".join(f"{c.x:g}" for c in _PUNCH.clamps),
                             description="Clamp centres along the sheet's clamped edge, X from the sheet's corner "
                                         "(mm, separated by commas)"),
    "clamp_width": mm("Clamp Width", _PUNCH.clamps[0].width, "Width of each clamp's dead zone along X"),
    "clamp_depth": mm("Clamp Depth", _PUNCH.clamps[0].depth, "Depth of each clamp's dead zone into the sheet"),
    "joints": IntProperty(name="Micro-Joints", default=nibbling.DEFAULT_JOINTS, min=0, max=nibbling.MAX_JOINTS,
                          description="Webs left uncut on the part's outline so it stays in the sheet (0: the part "
                                      "falls free at the last hits)"),
    "joint_width": mm("Joint Width", nibbling.DEFAULT_JOINT_WIDTH, "Width of the web each micro-joint leaves"),
}, "sheet")


# The paper's test quad: P1 (0,0,0), P2 (0,30,100), P3 (100,50,100), P4 (100,40,0).
PAPER_CORNERS = (0.0, 0.0, 0.0, 0.0, 30.0, 100.0, 100.0, 50.0, 100.0, 100.0, 40.0, 0.0)


class KezuriSheet(bpy.types.PropertyGroup):
    __annotations__ = ranged({
        "corners": FloatVectorProperty(name="Corners", size=12, default=PAPER_CORNERS,
                                       description="P1..P4 of the twisted quad, x y z each (mm)"),
        **UNFOLD_SETTINGS, **ELBOW_SETTINGS, **SHEET_SETUP,
    }, "sheet")


class KezuriPocket(bpy.types.PropertyGroup):
    """A rotary-table pocket, on the object that outlines it."""

    enabled: BoolProperty(name="Rotary Pocket", default=False,
                          description="This closed curve or mesh outlines a pocket on the rotating table")
    depth: mm("Depth", 10.0, "Depth of the pocket below the block's top", minimum=0.01)
    wall_angle: FloatProperty(name="Wall Angle", default=0.0, min=0.0, max=75.0,
                              description="Wall slope from vertical (degrees); 0 = vertical wall")
    bottom: EnumProperty(name="Bottom", default="flat", items=[
        ("flat", "Flat", "A flat floor, cleared by one spiral"),
        ("sphere", "Spherical Bowl", "A concave spherical bowl, cut by a spiral on the sphere")])
    sphere_radius: mm("Sphere Radius", 25.0, "Radius of the spherical bowl", minimum=0.1)


class KezuriRotary(bpy.types.PropertyGroup):
    tool_diameter: mm("Bit Diameter", 6.0, "Ball-nose (pencil) bit diameter", minimum=0.1)
    tool_number: IntProperty(name="Bit Tool No.", default=1, min=0, max=999)
    flute_length: mm("Flute Length", 25.0, "Cutting length of the bit: pockets may not be deeper", minimum=0.1)
    spindle_rpm: FloatProperty(name="Spindle", default=18000.0, min=0.0, description="Router speed (rpm)")
    cutting_speed: FloatProperty(name="Cutting Speed", default=1500.0, min=1.0,
                                 description="Feed along the path on the wood (mm/min); written as "
                                             "inverse-time G93 feeds")
    plunge_speed: FloatProperty(name="Plunge Speed", default=300.0, min=1.0, description="mm/min")
    spacing: mm("Point Spacing", 1.0, "Distance between path points (the paper's alpha)", minimum=0.01)
    stepover: mm("Helix Pitch", 1.0, "Pitch of the floor and bowl spirals (the paper's P)", minimum=0.01)
    step_down: mm("Step-Down", 3.0, "Deepest roughing layer", minimum=0.01)
    allowance: mm("Allowance", 0.5, "Stock roughing leaves for finishing", minimum=0.0)
    wall_stepover: mm("Wall Stepover", 0.5, "Wall finishing pitch along the wall", minimum=0.01)
    max_table_rpm: FloatProperty(name="Table Speed Limit", default=60.0, min=0.1,
                                 description="Fastest the face plate turns (rpm), for feeds and times")
    post: EnumProperty(name="Post", items=post_items("cxz"), default=post_number("linuxcnc"))


class KezuriWorkingstep(bpy.types.PropertyGroup):
    """One MACHINING_WORKINGSTEP of the imported workplan, in the order it will be cut."""

    ident: IntProperty(name="Instance", description="Instance number (#id) in the Part 21 file")
    name: StringProperty(name="Name")
    feature: StringProperty(name="Feature")
    operation: StringProperty(name="Operation")
    feature_name: StringProperty(name="Feature Name", description="The feature's name in the file")
    step: StringProperty(name="Step", description="The operation in a word (rough, finish, drill ...)")
    tool: StringProperty(name="Tool", description="Tool number and diameter")
    enabled: BoolProperty(name="Cut", default=True, description="Include this workingstep in the NC program")


class KezuriStepNC(bpy.types.PropertyGroup):
    filepath: StringProperty(name="ISO 14649 File", subtype="FILE_PATH",
                             description="The imported Part 21 file; export converts it again")
    steps: CollectionProperty(type=KezuriWorkingstep)
    active_step: IntProperty(name="Active Workingstep", default=0)
    tool_diameter: mm("End Mill Diameter", 6.0, "Flat end mill for pockets written as ISO 14649", minimum=0.1)
    tool_number: IntProperty(name="End Mill Tool No.", default=1, min=0, max=999)
    flute_length: mm("Flute Length", 20.0, "Cutting length of the end mill", minimum=0.1)
    feed: FloatProperty(name="Feed", default=600.0, min=1.0, description="Cutting feed (mm/min)")
    spindle_rpm: FloatProperty(name="Spindle", default=10000.0, min=1.0, description="Spindle speed (rpm)")


class KezuriTurnMill(bpy.types.PropertyGroup):
    part: PointerProperty(name="Part", type=bpy.types.Object, poll=_mesh_poll,
                          description="The part: a mesh around the Z axis (the C axis)")
    selected_only: BoolProperty(name="Selected Faces Only", default=False,
                                description="Machine only the faces selected in Edit Mode (all faces still "
                                            "block the rays)")
    stock_radius: mm("Stock Radius", 42.5, "Radius of the round bar stock (85 mm chemical wood: 42.5)",
                     minimum=0.1)
    stock_z_min: mm("Stock Z Min", -60.0, "Chuck side of the stock")
    stock_z_max: mm("Stock Z Max", 0.0, "End face of the stock")
    tool_diameter: mm("Ball Diameter", 6.0, "Ball end mill on both turret stations", minimum=0.1)
    tolerance: mm("Chordal Tolerance", 0.01, "Point spacing and scallops follow this tolerance", minimum=0.0001)
    sample_spacing: mm("Ray Spacing", 2.0, "Distance between ray samples on each face", minimum=0.01)
    feed: FloatProperty(name="Feed", default=500.0, min=1.0, description="Cutting feed (mm/min)")
    spindle_rpm: FloatProperty(name="Spindle", default=4000.0, min=1.0, description="Driven tool speed (rpm)")
    engine: EnumProperty(name="Ray Engine", default="BVH", items=[
        ("BVH", "Blender BVH", "Blender's BVHTree"),
        ("TRIMESH", "trimesh", "trimesh (Embree when bundled), as in batch runs")])


class KezuriCarve(bpy.types.PropertyGroup):
    design: PointerProperty(name="Design", type=bpy.types.Object, poll=_mesh_poll,
                            description="The surface to carve: a mesh in work coordinates, its top at the stock top")
    stock_above: mm("Stock Above", 0.0, "How far the stock's top stands above the design's highest point",
                    minimum=0.0)
    rough: BoolProperty(name="Roughing", default=True,
                        description="Rough in Z levels with the flat end mill before finishing")
    rough_diameter: mm("Roughing Diameter", 6.0, "Flat end mill for roughing", minimum=0.1)
    rough_tool_number: IntProperty(name="Roughing Tool No.", default=1, min=0, max=999,
                                   description="Tool number of the roughing end mill")
    allowance: mm("Allowance", 0.5, "Stock roughing leaves on the design", minimum=0.0)
    step_down: mm("Step Down", 3.0, "Depth between roughing levels", minimum=0.01)
    rough_stepover: mm("Roughing Stepover", 2.4, "Distance between roughing passes", minimum=0.01)
    finish_diameter: mm("Ball Diameter", 3.0, "Ball end mill for finishing", minimum=0.1)
    finish_tool_number: IntProperty(name="Ball Tool Number", default=2, min=0, max=999,
                                    description="Tool number of the finishing ball end mill")
    scallop: mm("Scallop Height", 0.02, "Height of the ridges the ball may leave between passes; the stepover "
                "follows from it", minimum=0.0001)
    raster_angle: FloatProperty(name="Raster Angle", default=0.0, min=-180.0, max=180.0,
                                description="Direction of the finishing passes, degrees from +X")
    max_slope: FloatProperty(name="Max Slope", default=60.0, min=0.0, max=89.0,
                             description="Faces steeper than this across the raster do not shrink its stepover: "
                                         "the Steep Cleanup and the Wall Pass finish them (degrees)")
    steep_cleanup: BoolProperty(name="Steep Cleanup", default=True,
                                description="Cut the faces steeper across the raster than Max Slope again, with a "
                                            "raster across the first, so the scallop there stays within the height "
                                            "asked")
    wall_pass: BoolProperty(name="Wall Pass", default=True,
                            description="Finish the walls no raster finishes (vertical, or steeper than Max Slope "
                                        "across both rasters) by waterlines, Z steps chosen from the scallop height")
    sample_spacing: mm("Point Spacing", 0.25, "Distance between points along a pass (refined where the surface "
                       "bends)", minimum=0.01)
    rough_rpm: FloatProperty(name="Roughing Spindle", default=16000.0, min=1.0,
                             description="Spindle speed for roughing (rpm)")
    finish_rpm: FloatProperty(name="Finishing Spindle", default=18000.0, min=1.0,
                              description="Spindle speed for finishing (rpm)")
    rough_feed: FloatProperty(name="Roughing Feed", default=1500.0, min=1.0, description="Roughing feed (mm/min)")
    finish_feed: FloatProperty(name="Finishing Feed", default=2000.0, min=1.0,
                               description="Finishing feed (mm/min)")
    plunge_feed: FloatProperty(name="Plunge Feed", default=400.0, min=1.0, description="Feed into the work (mm/min)")
    clearance: mm("Clearance", 5.0, "Height above the stock top for moves between cuts", minimum=0.1)
    safe_z: mm("Safe Z", 50.0, "Height above the stock top at the start and the end", minimum=0.1)


class KezuriFinding(bpy.types.PropertyGroup):
    kind: StringProperty(name="Kind")
    message: StringProperty(name="Message")
    blocking: BoolProperty(name="Blocks Export", default=False)
    signature: StringProperty(name="Signature", options={"HIDDEN"})
    operation: IntProperty(name="Operation")
    move: IntProperty(name="Move")
    location: FloatVectorProperty(name="Location", size=3, subtype="XYZ")


def show_colours(props, context=None):
    """Make the simulated stock show the colours the panel asks for (both are stored on it)."""
    from .simview import COLOUR_ATTRIBUTES, PREFIX
    for obj in bpy.data.objects:
        if obj.name.startswith(PREFIX) and obj.type == "MESH":
            attribute = obj.data.color_attributes.get(COLOUR_ATTRIBUTES[props.colour_by])
            if attribute is not None:
                obj.data.color_attributes.active_color = attribute


def acknowledge(props, context=None):
    """Ticking "Write Despite Findings" acknowledges exactly the blocking findings now listed."""
    props.acknowledged = ("\n".join(f.signature for f in props.findings if f.blocking)
                          if props.allow_findings else "")


class KezuriSimulation(bpy.types.PropertyGroup):
    engine: EnumProperty(name="Engine", default="heightfield", items=[
        ("heightfield", "Height Field", "Fast Z-map of the exact tool envelope (3-axis and C-X-Z jobs)"),
        ("manifold", "Exact Solid", "manifold3d booleans of the swept tools: exact, slower")])
    cell: mm("Cell Size", 0.1, "Height-field grid spacing", minimum=0.01)
    colour_by: EnumProperty(name="Colour", default="DEPTH", update=show_colours, items=[
        ("DEPTH", "Depth", "Light wood at the top, dark at the deepest cut"),
        ("OPERATION", "Operation", "Each operation's surface in its own colour")])
    findings: CollectionProperty(type=KezuriFinding)
    allow_findings: BoolProperty(name="Write Despite Findings", default=False, update=acknowledge,
                                 description="Export the program although the simulation found the faults listed "
                                             "above (only these: a different finding stops the export again)")
    acknowledged: StringProperty(name="Acknowledged Findings", options={"HIDDEN"})


class KezuriSettings(bpy.types.PropertyGroup):
    machine: PointerProperty(type=KezuriMachine)
    stock: PointerProperty(type=KezuriStock)
    engrave: PointerProperty(type=KezuriEngrave)
    sheet: PointerProperty(type=KezuriSheet)
    rotary: PointerProperty(type=KezuriRotary)
    stepnc: PointerProperty(type=KezuriStepNC)
    turnmill: PointerProperty(type=KezuriTurnMill)
    carve: PointerProperty(type=KezuriCarve)
    simulation: PointerProperty(type=KezuriSimulation)
    show_rapids: BoolProperty(name="Show Rapids", default=True, update=pathview.show_rapids,
                              description="Show the rapid moves in the preview")
    job_list: PointerProperty(type=KezuriJobList)       # the CAM tab's job list (operators/joblist.py)


for _cls, _group in ((KezuriMachine, "machine"), (KezuriEngrave, "engrave"), (KezuriPocket, "pocket"),
                     (KezuriRotary, "rotary"), (KezuriStepNC, "stepnc"), (KezuriTurnMill, "turnmill"),
                     (KezuriCarve, "carve"), (KezuriSimulation, "simulation")):
    limited(_cls, _group)

CLASSES = (KezuriMachine, KezuriStock, KezuriEngrave, KezuriSheet, KezuriPocket, KezuriRotary, KezuriWorkingstep,
           KezuriStepNC, KezuriTurnMill, KezuriCarve, KezuriFinding, KezuriSimulation, *jobrows.CLASSES,
           KezuriSettings)


_KIND_GROUPS: list = []     # the operation kinds' settings groups registered with KezuriSettings


def register(jobs: list, groups: list = ()):
    """``jobs``: the job picker's items, (key, label, description) per workflow with panels
    (:func:`.workflows.job_items`); ``groups``: (kind, PropertyGroup class) of the operation kinds
    whose settings have panel properties (:func:`.workflows.settings_groups`): ``scene.kezuri.<kind>``."""
    KezuriSettings.__annotations__["job"] = EnumProperty(
        name="Job", items=jobs, default=jobs[0][0],
        description="The job the CAM tab shows: its panels, and Machine & Stock")
    for kind, cls in groups:
        bpy.utils.register_class(cls)
        _KIND_GROUPS.append(cls)
        KezuriSettings.__annotations__[kind] = PointerProperty(type=cls)
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.kezuri = PointerProperty(type=KezuriSettings)
    bpy.types.Object.kezuri_pocket = PointerProperty(type=KezuriPocket)


def unregister():
    del bpy.types.Object.kezuri_pocket
    del bpy.types.Scene.kezuri
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    while _KIND_GROUPS:
        bpy.utils.unregister_class(_KIND_GROUPS.pop())
