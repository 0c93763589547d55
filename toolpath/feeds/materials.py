"""Materials: the chip load per tooth and the surface speed each published chart gives, by tool
diameter and tool material (carbide, HSS), each row naming its source.

A chart's chip loads are kept as the chart prints them (inches per tooth at a cutter diameter in
inches, a low and a high value) and read in mm (:meth:`ChipChart.band_mm`): between two of its
diameters the band is interpolated linearly; above its largest diameter the largest row holds;
below its smallest the smallest row's band is scaled by the diameter (a smaller cutter takes a
proportionally thinner chip; the result says so).  Surface speeds are kept in surface feet per
minute as the charts print them and read in m/min.

The router-bit charts give one chip-load range for carbide router bits; no chart of HSS router
bits in wood or plastic was found, so an HSS tool reads the same chip-load chart (chip load is a
matter of the cutter's flutes and diameter) and differs by its surface speed (the HSS table), as
the rows' ``source`` say.  Drills are fed per revolution, not per tooth: :data:`DRILL_FEED` (inches
per revolution by drill diameter, one chart for every material, its lower half for the harder
ones) and each material's drill surface speed (``drill_speed``, HSS and carbide).  A V-bit or engraver cuts with its tip: its band is the chart's smallest
row (a 1/8 in cutter), its recommended chip load the V-groove chart's where one is published.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..ir.errors import InputError

MM_PER_INCH = 25.4
M_PER_FOOT = 0.3048
TOOL_MATERIALS = ("carbide", "hss")


class MaterialError(InputError):
    """A material, tool material or diameter the tables cannot answer for."""


# ----- the published sources ----------------------------------------------------------------------------

AST = ("AST Tooling, Speeds and Feeds - Spiral Router Bits, Recommended Feeds & Speeds for Solid Carbide "
       "Router Bits (chip load range by tool diameter, cut depth = 1 x D), "
       "https://www.asttooling.com/pages/speeds-and-feeds-charts")
HIT = ("HIT Tooling Parameter Sheet, End Mills CLPT, Aluminum (6061), "
       "https://cdn.shopify.com/s/files/1/0612/0733/files/HIT_Tooling_Parameter_Sheet.pdf")
ITI = ("ITI Carbide Cutting Tools catalog 14, Speeds and Feeds for Carbide Endmills, Brass / Soft Bronze "
       "(feed per tooth for end mills up to 1/4 in and up to 1/2 in), "
       "https://cdn.shopify.com/s/files/1/0612/0733/files/Internal_Tool_Parameters.pdf")
AMANA_V = ("Amana Tool, Carbide Tipped V-Groove Router Bits speed chart v2 (18,000 rpm), "
           "https://cdn.shopify.com/s/files/1/1558/5651/files/Carbide-Tipped-V-Groove-Speed-Chart-v2.pdf")
AMANA_PLASTIC = ("Amana Tool, Spektra Solid Carbide Plastic Cutting Spiral Single O Flute Router Bits speed chart "
                 "v13 (SFM 500 - 1,200), "
                 "https://cdn.shopify.com/s/files/1/1558/5651/files/Spektra-Plastic-O-Flute-Speed-Chart-v13.pdf")
GRIZZLY = ("Grizzly G0619 manual, Cutting Speeds for High Speed Steel (HSS) Cutting Tools (after Machinery's "
           "Handbook; 'for carbide cutting tools, double the cutting speed'), "
           "https://manualshive.com/en/manual/grizzly/g0619/2266130?page=26")
TORBIDE = ("Torbide Tooling, Feeds & Speeds, Copper / Yellow Brass, High Lead Brass, Red Brass (carbide end "
           "mills, SFM 800 - 1500), http://torbidetooling.com/feeds-speeds?chapter=0")
NAVY = ("US Navy training manual (Engine Mechanics), Holding the Work: feed rates for drilling in thousandths of "
        "an inch per revolution (ipr) by drill diameter; cutting speeds for high-speed steel twist drills, 'carbide "
        "may be run at two to three times these speeds', "
        "https://enginemechanics.tpub.com/14345/Holding-The-Work-93.html")
BESTDRILL = ("bestdrillbit.com, Defining Drilling Speed, Drilling Speed (HSS, for carbide up the speeds by 2 to 3 "
             "times): wood 300-400 sfm, "
             "https://bestdrillbit.com/drilling-reference-guide/defining-drilling-speed/")
MACHINISTPOST = ("MachinistPost, Speeds and Feeds, SFM (HSS) for drilling: Plastics (nylon, HDPE) 150-250, "
                 "https://machinistpost.com/blog/speeds-and-feeds.php")
CARBIDE_DRILL = "carbide: the HSS drill speed doubled (the low end of the Navy manual's 'two to three times')"
HSS_CHIP = "no HSS chart found: the carbide chart's chip loads (chip load follows the cutter's size and flutes)"


@dataclass(frozen=True)
class ChipChart:
    """Chip load per tooth by cutter diameter: ``rows`` of (diameter, low, high), all in inches as
    the chart prints them; ``source``: the chart."""

    rows: tuple
    source: str
    up_to: bool = False         # the chart's rows are "up to" a diameter: a cutter takes the first row it fits

    def band_mm(self, diameter_mm: float) -> tuple:
        """(low, high, note) in mm per tooth for a cutter of ``diameter_mm``; ``note`` says how
        the band was read when the diameter is not one of the chart's rows ("" when it is)."""
        d = diameter_mm / MM_PER_INCH
        rows = sorted(self.rows)
        first, last = rows[0], rows[-1]
        if self.up_to:
            row = next((r for r in rows if d <= r[0] + 1e-12), last)
            note = (f"the chart's row up to {row[0] * MM_PER_INCH:.3g} mm" if d <= row[0] + 1e-12 else
                    f"above the chart's largest diameter ({last[0] * MM_PER_INCH:.3g} mm): its band used")
            return row[1] * MM_PER_INCH, row[2] * MM_PER_INCH, note
        if d < first[0]:
            scale = d / first[0]
            return (first[1] * scale * MM_PER_INCH, first[2] * scale * MM_PER_INCH,
                    f"below the chart's smallest diameter ({first[0] * MM_PER_INCH:.3g} mm): its band scaled by "
                    f"{diameter_mm:g} / {first[0] * MM_PER_INCH:.3g}")
        if d > last[0]:
            return (last[1] * MM_PER_INCH, last[2] * MM_PER_INCH,
                    f"above the chart's largest diameter ({last[0] * MM_PER_INCH:.3g} mm): its band used")
        for (d0, lo0, hi0), (d1, lo1, hi1) in zip(rows, rows[1:]):
            if d0 <= d <= d1:
                t = 0.0 if d1 == d0 else (d - d0) / (d1 - d0)
                exact = math.isclose(d, d0) or math.isclose(d, d1)
                return ((lo0 + t * (lo1 - lo0)) * MM_PER_INCH, (hi0 + t * (hi1 - hi0)) * MM_PER_INCH,
                        "" if exact else f"interpolated between the chart's {d0 * MM_PER_INCH:.3g} and "
                                         f"{d1 * MM_PER_INCH:.3g} mm rows")
        return first[1] * MM_PER_INCH, first[2] * MM_PER_INCH, ""     # one row: d equals it

    def tip_band_mm(self) -> tuple:
        """The band of the chart's smallest row (a V-bit's or engraver's cutting tip), in mm."""
        d, lo, hi = min(self.rows)
        return lo * MM_PER_INCH, hi * MM_PER_INCH


@dataclass(frozen=True)
class SurfaceSpeed:
    """Surface speed band in surface feet per minute as the chart prints it; ``source``: the chart."""

    low_sfm: float
    high_sfm: float
    source: str

    @property
    def band_m_min(self) -> tuple:
        return self.low_sfm * M_PER_FOOT, self.high_sfm * M_PER_FOOT

    @property
    def target_m_min(self) -> float:
        """The middle of the band (m/min): where the calculator aims."""
        return (self.low_sfm + self.high_sfm) / 2 * M_PER_FOOT


@dataclass(frozen=True)
class Material:
    key: str
    label: str
    examples: str
    chip: ChipChart                     # carbide router bits / end mills
    speed: dict                         # tool material -> SurfaceSpeed
    vbit_chip_in: float | None = None   # the V-groove chart's chip load (inches per tooth), where published
    hss_chip: ChipChart | None = None   # an HSS chart of its own, where one is published
    drill_speed: dict | None = None     # tool material -> SurfaceSpeed of a twist drill (None: none published)

    def chart(self, tool_material: str) -> ChipChart:
        if tool_material == "hss" and self.hss_chip is not None:
            return self.hss_chip
        return self.chip

    def chip_source(self, tool_material: str) -> str:
        if tool_material == "hss" and self.hss_chip is None:
            return f"{self.chip.source} ({HSS_CHIP})"
        return self.chart(tool_material).source


# Feed per revolution (inches) of a twist drill by its diameter (inches), the rows "up to" a diameter:
# No. 80 to 1/8 in, 1/8 to 1/4 in, 1/4 to 1/2 in, 1/2 to 1 in (the manual's "greater than 1 inch",
# 0.015 - 0.025, is not kept: a larger drill reads the 1 in row, the slower)
DRILL_FEED = ChipChart(((0.125, 0.001, 0.002), (0.25, 0.002, 0.004), (0.5, 0.004, 0.007), (1.0, 0.007, 0.015)),
                       NAVY + ": feed per revolution", up_to=True)
HARD_DRILLING = ("aluminium", "brass")      # "use the lower feed rate ... for the harder materials" (NAVY)


def drill_speeds(low_sfm: float, high_sfm: float, source: str) -> dict:
    """A twist drill's surface speeds: HSS as the chart gives them, carbide doubled (:data:`CARBIDE_DRILL`)."""
    return {"hss": SurfaceSpeed(low_sfm, high_sfm, source),
            "carbide": SurfaceSpeed(2 * low_sfm, 2 * high_sfm, f"{source}; {CARBIDE_DRILL}")}


def _wood_speeds() -> dict:
    # Grizzly / Machinery's Handbook: wood 300-500 sfm with HSS; carbide doubles it
    return {"hss": SurfaceSpeed(300, 500, GRIZZLY + ": wood 300 - 500 sfm"),
            "carbide": SurfaceSpeed(600, 1000, GRIZZLY + ": wood 300 - 500 sfm, doubled for carbide")}


def _plastic_speeds() -> dict:
    return {"hss": SurfaceSpeed(300, 800, GRIZZLY + ": plastics 300 - 800 sfm"),
            "carbide": SurfaceSpeed(500, 1200, AMANA_PLASTIC)}


MATERIALS = {m.key: m for m in (
    Material("softwood", "Softwood", "pine, spruce, cedar, Japanese cedar (sugi), cypress (hinoki)",
             ChipChart(((0.125, 0.003, 0.005), (0.25, 0.006, 0.008), (0.375, 0.015, 0.017), (0.5, 0.019, 0.021)),
                       AST + ": Softwood"),
             _wood_speeds(), vbit_chip_in=0.0024, drill_speed=drill_speeds(300, 400, BESTDRILL)),
    Material("hardwood", "Hardwood",
             "Japanese magnolia (hoonoki: the gouge-texture paper's name plate), oak, maple, walnut, cherry, beech",
             ChipChart(((0.125, 0.002, 0.004), (0.25, 0.005, 0.007), (0.375, 0.013, 0.015), (0.5, 0.017, 0.019)),
                       AST + ": Hardwood"),
             _wood_speeds(), vbit_chip_in=0.0024, drill_speed=drill_speeds(300, 400, BESTDRILL)),
    Material("mdf", "MDF", "medium-density fibreboard, particle board",
             ChipChart(((0.125, 0.004, 0.007), (0.25, 0.012, 0.015), (0.375, 0.017, 0.019), (0.5, 0.020, 0.025)),
                       AST + ": MDF / Particle Board"),
             _wood_speeds(), vbit_chip_in=0.0048, drill_speed=drill_speeds(300, 400, BESTDRILL)),
    Material("plywood", "Plywood", "birch, lauan and softwood plywood",
             ChipChart(((0.125, 0.003, 0.005), (0.25, 0.006, 0.009), (0.375, 0.015, 0.018), (0.5, 0.018, 0.021)),
                       AST + ": Plywood"),
             _wood_speeds(), vbit_chip_in=0.0024, drill_speed=drill_speeds(300, 400, BESTDRILL)),
    Material("acrylic", "Acrylic", "cast acrylic (PMMA), polycarbonate: the chart's hard plastics",
             ChipChart(((0.125, 0.002, 0.004), (0.25, 0.005, 0.008), (0.375, 0.008, 0.010), (0.5, 0.010, 0.013)),
                       AST + ": Hard Plastic"),
             _plastic_speeds(), vbit_chip_in=0.0024, drill_speed=drill_speeds(150, 250, MACHINISTPOST)),
    Material("hdpe", "HDPE", "HDPE, UHMW, polypropylene: the chart's soft plastics",
             ChipChart(((0.125, 0.003, 0.005), (0.25, 0.006, 0.009), (0.375, 0.009, 0.011), (0.5, 0.011, 0.014)),
                       AST + ": Soft Plastic"),
             _plastic_speeds(), vbit_chip_in=0.0024, drill_speed=drill_speeds(150, 250, MACHINISTPOST)),
    Material("aluminium", "Aluminium", "6061 and similar wrought alloys",
             ChipChart(((0.125, 0.0005, 0.0012), (0.1875, 0.0008, 0.0018), (0.25, 0.001, 0.0022),
                        (0.375, 0.0015, 0.0035), (0.5, 0.002, 0.0045)), HIT),
             {"hss": SurfaceSpeed(300, 300, GRIZZLY + ": aluminum & alloys 300 sfm"),
              "carbide": SurfaceSpeed(800, 2200, HIT + ": 800 - 2200 sfm")},
             drill_speed=drill_speeds(200, 300, NAVY + ": aluminum 200-300 fpm")),
    Material("brass", "Brass", "yellow brass, free-cutting brass, soft bronze",
             ChipChart(((0.25, 0.0005, 0.002), (0.5, 0.002, 0.003)), ITI, up_to=True),
             {"hss": SurfaceSpeed(150, 150, GRIZZLY + ": brass & bronze 150 sfm"),
              "carbide": SurfaceSpeed(800, 1500, TORBIDE)},
             drill_speed=drill_speeds(200, 300, NAVY + ": brass 200-300 fpm")),
)}
# The gouge-texture paper's name plate is Japanese magnolia (hoonoki), a hardwood.
PAPER_MATERIAL = "hardwood"


ALIASES = {"aluminum": "aluminium"}       # the American spelling


def material(key) -> Material:
    """The material called ``key``; an unknown one is refused listing those there are."""
    if isinstance(key, str) and ALIASES.get(key.strip().lower(), key.strip().lower()) in MATERIALS:
        return MATERIALS[ALIASES.get(key.strip().lower(), key.strip().lower())]
    raise MaterialError(f"unknown material {key!r}: the materials are {', '.join(MATERIALS)}")


def tool_material(value) -> str:
    if isinstance(value, str) and value.strip().lower() in TOOL_MATERIALS:
        return value.strip().lower()
    raise MaterialError(f"unknown tool material {value!r}: the tool materials are {', '.join(TOOL_MATERIALS)}")


def table() -> list:
    """Every material's chart rows and speeds as plain values (the README's table, report.json)."""
    rows = []
    for m in MATERIALS.values():
        rows.append({"material": m.key, "label": m.label, "examples": m.examples,
                     "chip_load_in": [list(row) for row in m.chip.rows], "chip_source": m.chip.source,
                     "surface_speed_sfm": {k: [s.low_sfm, s.high_sfm] for k, s in m.speed.items()},
                     "speed_source": {k: s.source for k, s in m.speed.items()},
                     "vbit_chip_in": m.vbit_chip_in,
                     "drill_feed_in_per_rev": [list(row) for row in DRILL_FEED.rows], "drill_feed_source": DRILL_FEED.source,
                     "drill_speed_sfm": {k: [s.low_sfm, s.high_sfm] for k, s in (m.drill_speed or {}).items()},
                     "drill_speed_source": {k: s.source for k, s in (m.drill_speed or {}).items()}})
    return rows
