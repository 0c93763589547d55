"""Feeds and speeds: spindle speed, feed, plunge feed, step-down and step-over for one tool in one
material for one operation kind, on one machine, each shown with the chip load it gives and where
its numbers come from; and the check of given values (a user's override, or what a planned
program runs at) against the material's safe band.

* spindle: the material's surface speed for the tool material (the middle of the chart's band) at
  the tool's diameter, ``rpm = v / (pi d)``, capped by the machine's fastest spindle;
* feed: ``rpm x flutes x chip load`` (the middle of the chart's band at the diameter), capped by
  the machine's fastest feed; the chip load shown is the one the feed then gives;
* plunge feed: the feed divided by the flutes (Amana Tool's "Ramp Down = Feed Rate / # of
  flutes"); a drill plunges at its feed;
* a drill (tool kind ``drill``) is fed per revolution, not per tooth: spindle from the material's
  drill surface speed, feed = feed per revolution (the drilling chart's middle at the diameter, its
  low end in the harder materials) x rpm, plunge = feed; its band is the chart's feed per revolution
  (:data:`.materials.DRILL_FEED`).  An end mill milling a hole (helix) keeps the router chart;
* step-down and step-over: per operation kind, as fractions of the diameter (:data:`OPERATIONS`).

The safe band is the chart's chip-load band at the diameter (:mod:`.materials`).  A chip load below
it rubs (heat, burning, a dull tool), above it overloads the tool (breakage); a spindle speed or
feed beyond the machine profile is flagged too.  Every flag carries its number and the band.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..ir.errors import InputError
from . import materials as mt

TOOL_KINDS = ("flat", "ball", "bull", "vbit", "drill", "engraver")
TIPPED = ("vbit", "engraver")          # cut with their tip: the chart's smallest row
DEFAULT_FLUTES = 2                     # the router-bit charts' tools (2-flute) when a tool does not say
# Router bits and end mills: 1 (O-flute, single-flute plastic bits) to 8 flutes is what the makers sell for
# routers and small mills; the charts' chip loads are per tooth, so any count is read the same way.  20
# is the tool library's bound (a flute count a library file may hold, e.g. a face mill's inserts) and the
# calculator's: one constant, so a tool the library holds is one the calculator takes.
MAX_FLUTES = 20
FEED_PER_REV = "revolution"             # what a drill's chip load is counted per (a router bit's: "tooth")
AMANA_RAMP = ("Amana Tool chart notes: 'To find Ramp Down: Feed Rate IPM / # of flutes', "
              "https://cdn.shopify.com/s/files/1/1558/5651/files/Solid-Carbide-Spiral-Plunge-Solid-Wood-v5.pdf")
AMANA_DOC = ("Amana Tool chart notes: 'Depth of Cut: 1 x D use recommended chip load; 2 x D reduce chip load by "
             "25%; 3 x D reduce by 50%', "
             "https://cdn.shopify.com/s/files/1/1558/5651/files/Solid-Carbide-Spiral-Plunge-Solid-Wood-v5.pdf")
HIT_WIDTHS = ("HITCARB 4 Flute Speeds/Feeds, Application table: slotting ADOC 50% of D, RDOC 100%; roughing RDOC "
              "25% - 40% of D, https://cdn.shopify.com/s/files/1/0961/5830/files/HITCARB_4_Flute_Speeds_Feeds.pdf")
PAPER = ("the gouge-texture paper (seed 000): 6 mm ball end mill, zigzag stepover 3 mm (0.5 x D), S6000; "
         "/work/shared/SPEC.md W1")
SCALLOP_MM = 0.05


@dataclass(frozen=True)
class Rule:
    """An operation kind's step-down and step-over as fractions of the diameter (None: the
    geometry decides, e.g. a V-carve's depth), and where they come from."""

    step_down: float | None
    step_over: float | None
    source: str
    scallop: bool = False       # step-over from the scallop a ball leaves (SCALLOP_MM), not a fraction


OPERATIONS = {
    "engrave": Rule(1.0, 0.5, f"step-over {PAPER}; step-down {AMANA_DOC}"),
    "carve": Rule(0.5, None, f"step-down {HIT_WIDTHS}; step-over: the width a {SCALLOP_MM:g} mm scallop allows "
                             "a ball of the diameter, 2 sqrt(h (D - h)) (geometry)", scallop=True),
    "profile": Rule(1.0, None, f"step-down {AMANA_DOC}; a profile cuts its own width (no step-over)"),
    "pocket": Rule(0.5, 0.4, f"step-down and step-over {HIT_WIDTHS} (the upper roughing width)"),
    "drill": Rule(1.0, None, f"peck depth one diameter, {AMANA_DOC}"),
    "chamfer": Rule(None, None, "one pass at the depth the chamfer's width gives (geometry)"),
    "vcarve": Rule(None, None, "the depth the V-bit's angle and the letter's width give (geometry)"),
}


class FeedsError(InputError):
    """A value the calculator cannot work with, named as given."""


@dataclass(frozen=True)
class Flag:
    kind: str               # rubbing, overload, spindle above machine, spindle below machine, feed above machine
    message: str
    value: float
    band: tuple             # (low, high) the value was held against

    def as_dict(self) -> dict:
        return {"kind": self.kind, "message": self.message, "value": _r(self.value), "band": [_r(v) for v in self.band]}


@dataclass(frozen=True)
class Feeds:
    """What the calculator gives (or what it found of given values): every length in mm, feeds in
    mm/min; ``chip_load`` the chip the feed gives at the spindle speed, ``band`` the safe band."""

    material: str
    tool_kind: str
    diameter: float
    flutes: int
    tool_material: str
    operation: str
    rpm: float
    feed: float
    plunge_feed: float
    step_down: float | None
    step_over: float | None
    chip_load: float
    band: tuple
    surface_speed: float                # m/min at the spindle speed
    flags: tuple = ()
    notes: tuple = ()
    sources: dict = field(default_factory=dict)
    per: str = "tooth"                  # the chip load's unit: per tooth, or per revolution (a drill)

    def as_dict(self) -> dict:
        return {"material": self.material, "tool": {"kind": self.tool_kind, "diameter_mm": self.diameter,
                                                   "flutes": self.flutes, "material": self.tool_material},
                "operation": self.operation, "spindle_rpm": _r(self.rpm), "feed_mm_min": _r(self.feed),
                "plunge_feed_mm_min": _r(self.plunge_feed), "step_down_mm": _r(self.step_down),
                "step_over_mm": _r(self.step_over), "chip_load_mm": _r(self.chip_load, 4), "chip_load_per": self.per,
                "band_mm": [_r(v, 4) for v in self.band], "surface_speed_m_min": _r(self.surface_speed),
                "flags": [f.as_dict() for f in self.flags], "notes": list(self.notes), "sources": dict(self.sources)}


def _r(value, digits: int = 3):
    return None if value is None else round(float(value), digits)


# ----- input ------------------------------------------------------------------------------------------------

def positive(value, what: str) -> float:
    """``value`` as a positive finite number; anything else is refused naming ``what``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise FeedsError(f"{what} = {value!r}: must be a positive number")
    return float(value)


def tool_kind(value) -> str:
    if isinstance(value, str) and value.strip().lower() in TOOL_KINDS:
        return value.strip().lower()
    raise FeedsError(f"unknown tool kind {value!r}: the kinds are {', '.join(TOOL_KINDS)}")


def flute_count(value) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= MAX_FLUTES:
        raise FeedsError(f"flutes = {value!r}: must be a whole number 1..{MAX_FLUTES}")
    return value


def operation_kind(value) -> str:
    if isinstance(value, str) and value.strip().lower() in OPERATIONS:
        return value.strip().lower()
    raise FeedsError(f"unknown operation kind {value!r}: the kinds are {', '.join(OPERATIONS)}")


# ----- the band and the flags --------------------------------------------------------------------------------

def band(material, kind: str, diameter: float, tool_material: str = "carbide") -> tuple:
    """(low, high, recommended, note, source): the safe chip-load band (mm per tooth) of a tool of
    ``kind`` and ``diameter`` in the material, and the chip load the calculator aims at."""
    m = material if isinstance(material, mt.Material) else mt.material(material)
    kind, diameter = tool_kind(kind), positive(diameter, "tool diameter")
    if kind == "drill":
        low, high, note = mt.DRILL_FEED.band_mm(diameter)
        aim = low if m.key in mt.HARD_DRILLING else (low + high) / 2
        note = f"feed per revolution ({note})" if note else "feed per revolution"
        if m.key in mt.HARD_DRILLING:
            note += "; the chart's low end in a harder material"
        return low, high, aim, note, mt.DRILL_FEED.source
    chart = m.chart(mt.tool_material(tool_material))
    source = m.chip_source(tool_material)
    if kind in TIPPED:
        low, high = chart.tip_band_mm()
        note = "a V-bit cuts with its tip: the chart's smallest row"
        if m.vbit_chip_in is not None:
            return low, high, m.vbit_chip_in * mt.MM_PER_INCH, note + "; recommended: the V-groove chart's", \
                f"{source}; recommended {mt.AMANA_V}"
        return low, high, (low + high) / 2, note, source
    low, high, note = chart.band_mm(diameter)
    return low, high, (low + high) / 2, note, source


def teeth(kind: str, flutes: int) -> int:
    """What a feed is divided by besides the rpm to give the chip the band holds: a drill's feed is
    per revolution (1), a router bit's per tooth (its flutes)."""
    return 1 if kind == "drill" else flutes


def flags_for(rpm: float, feed: float, flutes: int, low: float, high: float, machine=None, per: str = "tooth") -> tuple:
    """The flags of running at ``rpm`` and ``feed`` with ``flutes`` against the band and the machine;
    ``per``: "tooth" (``flutes`` cut) or :data:`FEED_PER_REV` (a drill: the feed per revolution)."""
    found = []
    chip = feed / (rpm * flutes)
    what = "feed per revolution" if per == FEED_PER_REV else "chip load"
    unit = "mm per revolution" if per == FEED_PER_REV else "mm per tooth"
    if chip < low - 1e-12:
        found.append(Flag("rubbing", f"{what} {chip:.4f} {unit} is below the safe band {low:.4f} - "
                                     f"{high:.4f} mm: the tool rubs (heat, burning, a dull edge); raise the feed "
                                     f"or lower the spindle speed", chip, (low, high)))
    elif chip > high + 1e-12:
        found.append(Flag("overload", f"{what} {chip:.4f} {unit} is above the safe band {low:.4f} - "
                                      f"{high:.4f} mm: the tool is overloaded (breakage risk); lower the feed or "
                                      f"raise the spindle speed", chip, (low, high)))
    if machine is not None:
        top, bottom = float(machine.max_spindle_rpm), float(machine.min_spindle_rpm)
        if rpm > top + 1e-9:
            found.append(Flag("spindle above machine", f"spindle {rpm:g} rpm is beyond the machine "
                                                       f"{machine.label!r}: {bottom:g} - {top:g} rpm", rpm, (bottom, top)))
        elif rpm < bottom - 1e-9:
            found.append(Flag("spindle below machine", f"spindle {rpm:g} rpm is below the machine "
                                                       f"{machine.label!r}: {bottom:g} - {top:g} rpm", rpm, (bottom, top)))
        if feed > float(machine.max_feed) + 1e-9:
            found.append(Flag("feed above machine", f"feed {feed:g} mm/min is beyond the machine {machine.label!r}: "
                                                    f"0 - {float(machine.max_feed):g} mm/min", feed,
                              (0.0, float(machine.max_feed))))
    return tuple(found)


# ----- the calculator ---------------------------------------------------------------------------------------

def compute(kind, diameter, material, flutes=None, operation="profile", machine=None, tool_material="carbide",
            rpm=None, feed=None, plunge_feed=None) -> Feeds:
    """The feeds and speeds of a tool (``kind``, ``diameter`` mm, ``flutes``: None for
    :data:`DEFAULT_FLUTES`; ``tool_material``) in ``material`` for an ``operation`` kind on
    ``machine`` (a MachineProfile or None); ``rpm``, ``feed``, ``plunge_feed``: the user's
    overrides, kept as given and flagged where they leave the band or the machine."""
    m = material if isinstance(material, mt.Material) else mt.material(material)
    kind, diameter = tool_kind(kind), positive(diameter, "tool diameter")
    assumed = flutes is None
    flutes = DEFAULT_FLUTES if assumed else flute_count(flutes)
    tool_material, operation = mt.tool_material(tool_material), operation_kind(operation)
    low, high, aim, band_note, chip_source = band(m, kind, diameter, tool_material)
    drilling = kind == "drill"
    speed = m.drill_speed[tool_material] if drilling and m.drill_speed else m.speed[tool_material]
    per = FEED_PER_REV if drilling else "tooth"
    cut = teeth(kind, flutes)
    notes = [band_note] if band_note else []
    if assumed and not drilling:
        notes.append(f"flutes not given: {DEFAULT_FLUTES} assumed (the charts' router bits)")
    sources = {"chip_load": chip_source, "surface_speed": speed.source,
               "plunge_feed": "a drill plunges at its feed (feed per revolution x rpm)" if drilling else AMANA_RAMP,
               "steps": OPERATIONS[operation].source}
    if rpm is None:
        wanted = speed.target_m_min * 1000 / (math.pi * diameter)
        rpm = wanted
        if machine is not None and wanted > machine.max_spindle_rpm:
            rpm = float(machine.max_spindle_rpm)
            notes.append(f"spindle {wanted:.0f} rpm for {speed.target_m_min:.0f} m/min capped at the machine's "
                         f"{rpm:g} rpm")
        if machine is not None and rpm < machine.min_spindle_rpm:
            rpm = float(machine.min_spindle_rpm)
            notes.append(f"spindle raised to the machine's slowest, {rpm:g} rpm")
        rpm = float(round(rpm))
    else:
        rpm = positive(rpm, "spindle rpm")
        notes.append("spindle speed as given")
    if feed is None:
        wanted = rpm * cut * aim
        feed = wanted
        if machine is not None and wanted > machine.max_feed:
            feed = float(machine.max_feed)
            if drilling:
                notes.append(f"feed {wanted:.0f} mm/min capped at the machine's {feed:g} mm/min: feed per "
                             f"revolution {feed / (rpm * cut):.4f} mm")
            else:
                notes.append(f"feed {wanted:.0f} mm/min capped at the machine's {feed:g} mm/min: chip load per "
                             f"tooth {feed / (rpm * cut):.4f} mm")
        feed = float(round(feed))
    else:
        feed = positive(feed, "feed")
        notes.append("feed as given")
    if plunge_feed is None:
        plunge_feed = feed if kind == "drill" or operation == "drill" else float(round(feed / flutes))
    else:
        plunge_feed = positive(plunge_feed, "plunge feed")
    rule = OPERATIONS[operation]
    step_down = None if rule.step_down is None else rule.step_down * diameter
    if rule.scallop and kind == "ball":
        step_over = 2 * math.sqrt(SCALLOP_MM * (diameter - SCALLOP_MM)) if diameter > 2 * SCALLOP_MM else diameter / 2
    elif rule.scallop:
        step_over = 0.4 * diameter
        sources["steps"] += f"; a {kind} tool is not a ball: step-over {HIT_WIDTHS}"
    else:
        step_over = None if rule.step_over is None else rule.step_over * diameter
    return Feeds(m.key, kind, diameter, flutes, tool_material, operation, rpm, feed, plunge_feed, step_down,
                 step_over, feed / (rpm * cut), (low, high), math.pi * diameter * rpm / 1000,
                 flags_for(rpm, feed, cut, low, high, machine, per), tuple(notes), sources, per)


def check(kind, diameter, material, rpm, feed, flutes=None, tool_material="carbide", machine=None) -> Feeds:
    """What ``rpm`` and ``feed`` give for the tool in the material: the chip load, the band and
    the flags (a planned operation's values, or a user's)."""
    return compute(kind, diameter, material, flutes, "profile", machine, tool_material, rpm=rpm, feed=feed)
