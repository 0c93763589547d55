"""The machine profile in the shell: Machine & Stock's Machine menu and settings (and batch's
``--machine`` with its overrides) -> the :class:`toolpath.ir.machine.MachineProfile` a program is written
for and checked against.  Machine = Post's Machine gives the chosen post's own preset; picking a
preset fills the settings, which are then the user's (each checked against its range in
:mod:`.limits`)."""
from __future__ import annotations

from .. import post as posts
from ..toolpath.ir import machine as machines
from .limits import check_group

POST_MACHINE = "POST"      # the Machine menu's first item: the chosen post's own default machine
# Machine & Stock's settings -> the profile's fields (toolpath.ir.machine.MachineProfile)
PROFILE_FIELDS = {"z_reach": "clearance_max", "clearance_height": "clearance_z", "retract": "retract",
                  "machine_top_z": "machine_top_z", "tool_change": "tool_change", "m6_lifts_z": "m6_retracts",
                  "max_spindle": "max_spindle_rpm", "max_feed": "max_feed", "rapid_rate": "rapid_rate"}


def fill_machine(props, name: str) -> None:
    """Machine & Stock's settings from the preset ``name`` (what picking it in the menu does)."""
    profile = machines.preset(name)
    props.travel_x, props.travel_y, props.travel_z = profile.travel
    for setting, field_name in PROFILE_FIELDS.items():
        setattr(props, setting, getattr(profile, field_name))


def scene_machine(props, families, post_name: str):
    """The machine profile a program for ``post_name`` is written for: the post's own machine
    (Machine = Post's Machine), or the picked preset with Machine & Stock's settings, each checked
    against its range (:mod:`.limits`) and the preset's family against the post's."""
    post_class = posts.find(families, post_name)
    if props.preset == POST_MACHINE:
        profile = posts.registry.default_machine(post_class)
        return None if profile is None else profile.replace(rapid_rate=float(props.rapid_rate), arcs=bool(props.arcs))
    check_group(props, "machine")
    base = machines.preset(props.preset)
    if base.family != post_class.family:
        raise machines.MachineError(
            f"Machine & Stock: Machine {base.label!r} is a {base.family} machine and the {post_name} post writes "
            f"{post_class.family} programs; pick a {post_class.family} machine or Post's Machine")
    if props.clearance_height > props.z_reach + 1e-9:
        raise machines.MachineError(
            f"Machine & Stock: Clearance Height = {props.clearance_height:g} mm is above Z Reach = "
            f"{props.z_reach:g} mm")
    changes = {field_name: getattr(props, setting) for setting, field_name in PROFILE_FIELDS.items()}
    changes["m6_retracts"] = bool(changes["m6_retracts"])
    changes["arcs"] = bool(props.arcs)
    return base.replace(travel=(float(props.travel_x), float(props.travel_y), float(props.travel_z)), **changes)


def machine_arguments(parser) -> None:
    """Batch's machine options (Machine & Stock's Machine menu and settings)."""
    from .batchio import number
    from .limits import RANGES
    table = RANGES["machine"]
    parser.add_argument("--machine", choices=list(machines.PRESETS),
                        help="the machine preset (default: the post's own machine)")
    parser.add_argument("--clearance-max", type=number("--clearance-max", limit=table["z_reach"]),
                        help="how high above the work zero the tool reaches (mm; Machine & Stock > Z Reach)")
    parser.add_argument("--clearance-height", type=number("--clearance-height", limit=table["clearance_height"]),
                        help="the frames' safe height above the work zero (mm)")
    parser.add_argument("--travel", nargs=3, metavar=("X", "Y", "Z"),
                        type=number("--travel", limit=table["travel_x"]), help="axis travel (mm)")
    parser.add_argument("--retract", choices=machines.RETRACTS, help="how the frames lift Z")
    parser.add_argument("--tool-change", choices=machines.TOOL_CHANGES, help="a changer (atc) or by hand (manual)")
    no_arcs_argument(parser)


def no_arcs_argument(parser) -> None:
    """Batch's ``--no-arcs`` (Machine & Stock > Arcs (G2/G3) off)."""
    parser.add_argument("--no-arcs", action="store_true",
                        help="milling posts write every move as planned: no polyline fitted as G2/G3 arcs")


def batch_machine(args, scene, families, post_name: str):
    """Batch, before any work: ``--machine`` and its overrides into the scene's Machine & Stock
    (an override alone starts from the post's own machine), then the profile for ``post_name``."""
    from .batchio import set_exactly
    props = scene.kezuri.machine
    if getattr(args, "no_arcs", False):
        props.arcs = False
    overrides = {("z_reach", "--clearance-max"): args.clearance_max,
                 ("clearance_height", "--clearance-height"): args.clearance_height,
                 ("retract", "--retract"): args.retract, ("tool_change", "--tool-change"): args.tool_change}
    given = {key: value for key, value in overrides.items() if value is not None}
    if args.machine is not None or given or args.travel is not None:
        name = args.machine or posts.registry.default_machine(posts.find(families, post_name)).name
        props.preset = name
        fill_machine(props, name)       # the menu's update does it in Blender; done here whatever the build
        for (setting, option), value in given.items():
            set_exactly(props, setting, value, option)
        if args.travel is not None:
            for axis, value in zip("xyz", args.travel):
                set_exactly(props, f"travel_{axis}", value, "--travel")
    return scene_machine(props, families, post_name)
