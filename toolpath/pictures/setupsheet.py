"""The setup sheet: one self-contained HTML page per job, for the person at the machine.

It says what to clamp and where the work zero is, which tools to load (number, kind, diameter,
stick-out), the operations in order with their tool, spindle, feeds and time, the total time, what
the export gate found, and the program file's name and size.  Pictures are inline (base64 PNG data
URIs), the style is inline and prints on A4; there are no scripts and no links to anything outside
the file, so it can be mailed, archived or printed as it is.  Every text is HTML-escaped; the file
is UTF-8 (Japanese job names and messages come out as written).

:class:`SetupSheet` is the input; :func:`setup_sheet` turns it into the HTML text;
:func:`sheet_from` fills one from a :class:`~toolpath.ir.program.Program` and a batch run's report.
Lengths are shown in mm as the program has them, times as h:mm:ss.

Language: the sheet's own words are English templates (``{}`` for each value) put through a
``translate(template, *values)`` function the caller gives (the shell's ``translations.sheet_text``
for Japanese); without one they are English as written.  Names, numbers and codes (T2, G54, file
names) are shown as they are; only the ``<html lang>`` and the words change.
"""
from __future__ import annotations

import base64
import math
from dataclasses import dataclass, field
from html import escape

from ..ir.errors import InputError

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
GATE_STATUSES = ("passed", "refused", "written despite findings", "not run")
LANGUAGES = ("en", "ja")        # the languages a sheet can be written in (batch --language, a job's [setup])
DASH = "\u2014"


class SetupSheetError(InputError):
    """A setup sheet's input that cannot be shown (a picture that is not a PNG, an unknown gate status)."""


@dataclass(frozen=True)
class SheetTool:
    number: int
    kind: str
    diameter: float | None
    corner_radius: float | None = None
    flute_length: float | None = None
    stick_out: float | None = None      # how far the tool stands out of the holder (None: not known)
    description: str = ""
    chip_loads: tuple = ()              # the chip loads (mm a tooth; a drill's (mm, "revolution")): report.json's ``feeds``


@dataclass(frozen=True)
class SheetOperation:
    name: str
    tool_number: int | None
    spindle_rpm: float | None
    feed: float | None                  # mm/min
    plunge_feed: float | None           # mm/min
    cycle_time_s: float | None
    moves: int | None


@dataclass(frozen=True)
class SheetProgram:
    """A program file the job wrote (or read): its name, its size in bytes and in lines."""

    name: str
    size_bytes: int
    lines: int


@dataclass(frozen=True)
class SheetPicture:
    caption: str
    png: bytes

    def __post_init__(self):
        if not isinstance(self.png, (bytes, bytearray)) or not bytes(self.png).startswith(PNG_SIGNATURE):
            raise SetupSheetError(f"setup sheet picture {self.caption!r}: not a PNG image")


@dataclass(frozen=True)
class SetupSheet:
    """What one setup sheet shows.  ``stock``: :func:`stock_entry`'s dict (or None when not known);
    ``gate_status``: one of :data:`GATE_STATUSES`; sequences are kept as tuples."""

    job_name: str
    machine_label: str = ""
    post_label: str = ""
    work_offset: str = ""
    stock: dict | None = None
    work_zero: str = ""
    tools: tuple = ()
    operations: tuple = ()
    total_time_s: float | None = None
    gate_status: str = "not run"
    gate_findings: tuple = ()
    programs: tuple = ()
    pictures: tuple = ()
    notes: tuple = field(default=())

    def __post_init__(self):
        if self.gate_status not in GATE_STATUSES:
            raise SetupSheetError(f"setup sheet gate status {self.gate_status!r}: one of {', '.join(GATE_STATUSES)}")
        for name in ("tools", "operations", "gate_findings", "programs", "pictures", "notes"):
            object.__setattr__(self, name, tuple(getattr(self, name)))
        pictures = tuple(p if isinstance(p, SheetPicture) else SheetPicture(*p) for p in self.pictures)
        object.__setattr__(self, "pictures", pictures)

    def shown_total_s(self) -> float | None:
        """The total time: as given, else the operations' times added."""
        if self.total_time_s is not None:
            return self.total_time_s
        times = [op.cycle_time_s for op in self.operations if op.cycle_time_s is not None]
        return sum(times) if times else None


def english(text: str, *values, context: str = "") -> str:
    """A sheet text in English: the template with its values put in (the default ``translate``).
    ``context`` tells apart one English word of two meanings (a tool kind "drill", an operation
    "drill"), as Blender's translation contexts do."""
    return text.format(*values) if values else text


# ----- numbers as the sheet writes them -----------------------------------------------------------

def hms(seconds: float | None) -> str:
    """Seconds as h:mm:ss (rounded to the second); a dash when not known."""
    if seconds is None or not math.isfinite(seconds):
        return DASH
    whole = int(round(seconds))
    return f"{whole // 3600}:{whole // 60 % 60:02d}:{whole % 60:02d}"


def mm(value: float | None) -> str:
    """A length as the program has it (up to 4 decimals, no trailing zeros); a dash when not known."""
    if value is None or not math.isfinite(value):
        return DASH
    text = f"{value:.4f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def rate(value: float | None) -> str:
    """A feed (mm/min) or a spindle speed (rpm), to a tenth; a dash when not known."""
    if value is None or not math.isfinite(value):
        return DASH
    return f"{value:.1f}".rstrip("0").rstrip(".")


def chip_text(values, translate=english) -> str:
    """The chip loads a tool runs at (mm, 4 decimals), each once and each with what it is per: "/tooth",
    or "/rev" for a value given as (value, "revolution") (a drill's feed per revolution); a dash when
    not checked.  The column's header says only "(mm)": a tool's cells say per what."""
    def text(v):
        if isinstance(v, tuple):
            return None if _number(v[0]) is None else translate("{}/rev", f"{float(v[0]):.4f}")
        return None if _number(v) is None else translate("{}/tooth", f"{float(v):.4f}")
    shown = list(dict.fromkeys(t for t in map(text, values) if t is not None))
    return ", ".join(shown) if shown else DASH


# ----- stock and work zero -----------------------------------------------------------------------

def _mm6(value) -> float:
    return round(float(value), 6)


def stock_entry(stock) -> dict | None:
    """A stock as plain numbers (mm, to 6 decimals) for the sheet and report.json: a box (``x0``..``z1``;
    a curved plate's box with ``"surface": True``), a cylinder about Z (``radius``, ``height``,
    ``z_top``; a turn-mill bar's ``z_min``/``z_max`` read as one), a dict as it is, or None."""
    if stock is None or isinstance(stock, dict):
        return stock
    if all(hasattr(stock, name) for name in ("x0", "y0", "z0", "x1", "y1", "z1")):
        entry = {"kind": "box", **{name: _mm6(getattr(stock, name)) for name in ("x0", "y0", "z0", "x1", "y1", "z1")}}
        surface = getattr(stock, "surface", None)
        if surface is not None and len(surface):
            entry["surface"] = True
        return entry
    if all(hasattr(stock, name) for name in ("radius", "height", "z_top")):
        return {"kind": "cylinder", "radius": _mm6(stock.radius), "height": _mm6(stock.height),
                "z_top": _mm6(stock.z_top)}
    if all(hasattr(stock, name) for name in ("radius", "z_min", "z_max")):
        return {"kind": "cylinder", "radius": _mm6(stock.radius), "height": _mm6(stock.z_max - stock.z_min),
                "z_top": _mm6(stock.z_max)}
    raise SetupSheetError(f"setup sheet: a stock of type {type(stock).__name__} is neither a box nor a cylinder")


def describe_stock(stock: dict | None, translate=english) -> str:
    if not stock:
        return DASH
    kind = stock.get("kind")
    if kind == "box":
        x0, y0, z0, x1, y1, z1 = (stock[k] for k in ("x0", "y0", "z0", "x1", "y1", "z1"))
        text = translate("block {} \u00d7 {} \u00d7 {} mm (X {} \u2026 {}, Y {} \u2026 {}, Z {} \u2026 {})",
                         mm(x1 - x0), mm(y1 - y0), mm(z1 - z0), mm(x0), mm(x1), mm(y0), mm(y1), mm(z0), mm(z1))
        return translate("{}; its top is a curved surface", text) if stock.get("surface") else text
    if kind == "cylinder":
        top = stock["z_top"]
        return translate("round \u00d8{} \u00d7 {} mm, axis along Z (Z {} \u2026 {})", mm(2 * stock["radius"]),
                         mm(stock["height"]), mm(top - stock["height"]), mm(top))
    if kind == "sheet":
        size = " \u00d7 ".join(mm(v) for v in stock["size"])
        thickness = stock.get("thickness")
        return (translate("sheet {} mm", size) if thickness is None
                else translate("sheet {} mm, {} mm thick", size, mm(thickness)))
    return DASH


PLACE_TOLERANCE = 0.001   # mm: the least increment a control reads; a zero this close is on the face


def _place(value: float, low: float, high: float, names: tuple, beyond: tuple, translate=english) -> str:
    """Where ``value`` lies on low..high: at one end, the middle, how far in from the low end, or
    how far beyond an end (``beyond``: the words for below low and above high); each phrase is one
    template of its own (e.g. "{} mm left of the left side"), so a language may order it its way."""
    if abs(value - low) <= PLACE_TOLERANCE:
        return translate(names[0])
    if abs(value - high) <= PLACE_TOLERANCE:
        return translate(names[2])
    if abs(value - (low + high) / 2) <= PLACE_TOLERANCE:
        return translate(names[1])
    if value < low:
        return translate("{} mm " + beyond[0] + " the " + names[0], mm(low - value))
    if value > high:
        return translate("{} mm " + beyond[1] + " the " + names[2], mm(value - high))
    return translate("{} mm from the " + names[0], mm(value - low))


def _end(value: float, low: float, high: float) -> str | None:
    """"low" or "high" when ``value`` is at that end of low..high, "middle" in the middle, else None."""
    for name, at in (("low", low), ("high", high), ("middle", (low + high) / 2)):
        if abs(value - at) <= PLACE_TOLERANCE:
            return name
    return None


def work_zero_text(stock: dict | None, work_offset: str = "", translate=english) -> str:
    """Where the program's zero sits on the stock, in words (from the stock's numbers)."""
    where = f"{work_offset}: " if work_offset else ""
    if not stock:
        return where + DASH
    kind = stock.get("kind")
    if kind == "box":
        x = _end(0.0, stock["x0"], stock["x1"])
        y = _end(0.0, stock["y0"], stock["y1"])
        z = _end(0.0, stock["z0"], stock["z1"])
        if x == y == "middle":
            xy = translate("X0 Y0 at the centre of the stock")
        elif x in ("low", "high") and y in ("low", "high"):
            xy = translate(f"X0 Y0 at the {('front', 'back')[y == 'high']}-{('left', 'right')[x == 'high']} "
                           "corner of the stock")
        else:
            xy = translate("X0 at the stock's {}, Y0 at its {}",
                           _place(0.0, stock["x0"], stock["x1"], ("left side", "middle", "right side"),
                                  ("left of", "right of"), translate),
                           _place(0.0, stock["y0"], stock["y1"], ("front", "middle", "back"), ("in front of", "behind"),
                                  translate))
        if z in ("low", "high"):
            zero = translate("Z0 on the stock top" if z == "high" else "Z0 on the stock bottom")
        else:
            zero = translate("Z0 {}", _place(0.0, stock["z0"], stock["z1"], ("bottom", "middle", "top"), ("below", "above"),
                                             translate))
        return where + translate("{}; {}", xy, zero)
    if kind == "cylinder":
        top, bottom = stock["z_top"], stock["z_top"] - stock["height"]
        z = _end(0.0, bottom, top)
        if z in ("low", "high"):
            zero = translate("Z0 on the top end face" if z == "high" else "Z0 on the bottom end")
        else:
            zero = translate("Z0 {}", _place(0.0, bottom, top, ("bottom end", "middle", "top end face"), ("below", "above"),
                                             translate))
        return where + translate("{}; {}", translate("X0 Y0 on the axis of rotation"), zero)
    if kind == "sheet":
        return where + translate(stock.get("origin") or "the punch's sheet origin (see the program header)")
    return where + DASH


# ----- the page ------------------------------------------------------------------------------------

STYLE = """
@page { size: A4; margin: 12mm; }
html { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
body { font-family: "Noto Sans CJK JP", "Hiragino Sans", "Yu Gothic", "Meiryo", "DejaVu Sans", Arial, sans-serif;
       font-size: 10pt; color: #111; max-width: 186mm; margin: 0 auto; }
h1 { font-size: 15pt; margin: 0 0 2mm 0; }
h2 { font-size: 11.5pt; margin: 5mm 0 1.5mm 0; border-bottom: 0.4mm solid #333; break-after: avoid;
     page-break-after: avoid; }
table { border-collapse: collapse; width: 100%; }
thead { display: table-header-group; }
tfoot { display: table-row-group; }
tr, figure, img, .gate { break-inside: avoid; page-break-inside: avoid; }
th, td { border: 0.25mm solid #888; padding: 1mm 1.5mm; text-align: left; vertical-align: top; }
th { background: #eee; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tfoot td { font-weight: bold; }
dl { display: grid; grid-template-columns: max-content 1fr; gap: 0.8mm 4mm; margin: 0; }
dt { font-weight: bold; }
dd { margin: 0; }
.gate { padding: 2mm 3mm; border: 0.5mm solid; }
.gate-passed { border-color: #2a7a2a; background: #eef7ee; }
.gate-refused { border-color: #b00; background: #fbeaea; }
.gate-override { border-color: #c07000; background: #fdf3e3; }
.gate-none { border-color: #888; background: #f3f3f3; }
figure { margin: 3mm 0; }
figure img { display: block; max-width: 100%; max-height: 240mm; width: auto; height: auto; margin: 0 auto; }
figcaption { font-size: 9pt; color: #444; text-align: center; }
@media print { body { max-width: none; } a { color: inherit; text-decoration: none; } }
"""

GATE_CLASSES = {"passed": "gate-passed", "refused": "gate-refused", "written despite findings": "gate-override",
                "not run": "gate-none"}
GATE_WORDS = {"passed": "Passed: the simulation found nothing that stops the program.",
              "refused": "Refused: the program was not written.",
              "written despite findings": "Written despite findings: the override was given knowingly.",
              "not run": "Not run: the export gate did not check this program."}


def _text(value) -> str:
    return escape(str(value), quote=True)


def _row(cells, numeric=()) -> str:
    return "<tr>" + "".join(f'<td class="n">{_text(c)}</td>' if i in numeric else f"<td>{_text(c)}</td>"
                            for i, c in enumerate(cells)) + "</tr>"


def _head(names, numeric=()) -> str:
    return "<thead><tr>" + "".join(f'<th class="n">{_text(n)}</th>' if i in numeric else f"<th>{_text(n)}</th>"
                                   for i, n in enumerate(names)) + "</tr></thead>"


def _tools_table(tools, say) -> str:
    if not tools:
        return f"<p>{_text(say('No tools in this job.'))}</p>"
    numeric = (0, 2, 3, 4, 5, 6)
    rows = [_row((f"T{t.number}", say(t.kind, context="tool kind"), mm(t.diameter), mm(t.corner_radius), mm(t.flute_length),
                  mm(t.stick_out), chip_text(t.chip_loads, say), t.description), numeric) for t in tools]
    return ('<table id="tools">' + _head([say(h) for h in ("Tool", "Kind", "Diameter (mm)", "Corner R (mm)",
                                                          "Flute length (mm)", "Stick-out (mm)", "Chip load (mm)",
                                                          "Description")], numeric)
            + "<tbody>" + "".join(rows) + "</tbody></table>")


def _operations_table(sheet: SetupSheet, say) -> str:
    if not sheet.operations:
        return f"<p>{_text(say('No operations in this report.'))}</p>"
    numeric = (0, 3, 4, 5, 6, 7)
    rows = [_row((index, say(op.name), DASH if op.tool_number is None else f"T{op.tool_number}", rate(op.spindle_rpm),
                  rate(op.feed), rate(op.plunge_feed), DASH if op.moves is None else op.moves, hms(op.cycle_time_s)),
                 numeric) for index, op in enumerate(sheet.operations, start=1)]
    total = (f'<tfoot><tr id="total"><td colspan="7">{_text(say("Total"))}</td>'
             f'<td class="n">{_text(hms(sheet.shown_total_s()))}</td></tr></tfoot>')
    return ('<table id="operations">' + _head([say(h) for h in ("#", "Operation", "Tool", "Spindle (rpm)",
                                                               "Feed (mm/min)", "Plunge (mm/min)", "Moves",
                                                               "Time (h:mm:ss)")], numeric)
            + "<tbody>" + "".join(rows) + "</tbody>" + total + "</table>")


def _programs_table(programs, say) -> str:
    if not programs:
        return f"<p>{_text(say('No program file.'))}</p>"
    numeric = (1, 2)
    rows = [_row((p.name, f"{p.size_bytes:,}", f"{p.lines:,}"), numeric) for p in programs]
    return ('<table id="programs">' + _head([say(h) for h in ("File", "Size (bytes)", "Lines")], numeric)
            + "<tbody>" + "".join(rows) + "</tbody></table>")


def _gate(sheet: SetupSheet, say) -> str:
    findings = "".join(f"<li>{_text(say(f))}</li>" for f in sheet.gate_findings)
    return (f'<div class="gate {GATE_CLASSES[sheet.gate_status]}" id="gate" data-status="{_text(sheet.gate_status)}">'
            f"<strong>{_text(say(GATE_WORDS[sheet.gate_status]))}</strong>"
            + (f"<ul>{findings}</ul>" if findings else "") + "</div>")


def _pictures(pictures, say) -> str:
    return "".join(f'<figure><img alt="{_text(say(p.caption))}" src="data:image/png;base64,'
                   f'{base64.b64encode(bytes(p.png)).decode("ascii")}"><figcaption>{_text(say(p.caption))}</figcaption>'
                   "</figure>" for p in pictures)


def setup_sheet(sheet: SetupSheet, language: str = "en", translate=None) -> str:
    """The setup sheet as one HTML document (a str; write it as UTF-8).  ``language``: one of
    :data:`LANGUAGES`, the page's ``lang``; ``translate(text, *values, context="")``: the sheet's words, the
    gate's findings, the notes and the operation names in that language (default: English)."""
    if language not in LANGUAGES:
        raise SetupSheetError(f"setup sheet language {language!r}: one of {', '.join(LANGUAGES)}")
    say = translate or english
    work_zero = (work_zero_text(sheet.stock, sheet.work_offset, say)
                 if sheet.work_zero == work_zero_text(sheet.stock, sheet.work_offset)
                 else sheet.work_zero and say(sheet.work_zero))
    facts = (("Machine", sheet.machine_label or DASH), ("Post", sheet.post_label or DASH),
             ("Work offset", sheet.work_offset or DASH), ("Stock", describe_stock(sheet.stock, say)),
             ("Work zero", work_zero or DASH), ("Total time", hms(sheet.shown_total_s())))
    setup = ("<dl id=\"setup\">" + "".join(f"<dt>{_text(say(k))}</dt><dd>{_text(v)}</dd>" for k, v in facts)
             + "</dl>")
    notes = (f"<h2>{_text(say('Notes'))}</h2><ul id=\"notes\">" + "".join(f"<li>{_text(say(n))}</li>" for n in sheet.notes)
             + "</ul>" if sheet.notes else "")
    pictures = f"<h2>{_text(say('Pictures'))}</h2>{_pictures(sheet.pictures, say)}" if sheet.pictures else ""
    title = _text(say("Setup sheet: {}", sheet.job_name))
    heading = {name: f"<h2>{_text(say(name))}</h2>" for name in ("Setup", "Tools", "Operations", "Export gate",
                                                                "Program")}
    return ("<!DOCTYPE html>\n"
            f'<html lang="{language}"><head><meta charset="utf-8">'
            '<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{title}</title><style>{STYLE}</style></head>\n<body>"
            f'<h1 id="job">{title}</h1>'
            f"{heading['Setup']}{setup}"
            f"{heading['Tools']}{_tools_table(sheet.tools, say)}"
            f"{heading['Operations']}{_operations_table(sheet, say)}"
            f"{heading['Export gate']}{_gate(sheet, say)}"
            f"{heading['Program']}{_programs_table(sheet.programs, say)}"
            f"{notes}{pictures}</body></html>\n")


# ----- filling one from a program and a report --------------------------------------------------

def program_file(name: str, data: bytes) -> SheetProgram:
    """A program file's entry from its bytes (lines: the newlines, plus a last line without one)."""
    lines = data.count(b"\n") + (1 if data and not data.endswith(b"\n") else 0)
    return SheetProgram(name, len(data), lines)


def gate_status(gate: dict | None) -> tuple:
    """(status, finding messages) of a report's ``gate`` entry (None: the gate did not run)."""
    if gate is None:
        return "not run", ()
    findings = tuple(str(f.get("message", f)) if isinstance(f, dict) else str(f) for f in gate.get("findings", ()))
    if not findings:
        return "passed", ()
    return ("written despite findings" if gate.get("overridden") else "refused"), findings


def _number(value) -> float | None:
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def _from_program(program) -> tuple:
    tools = tuple(SheetTool(t.number, t.kind, float(t.diameter), float(t.corner_radius), float(t.flute_length), None,
                            t.describe()) for t in program.tools())
    operations = []
    for op in program.operations:
        feed, plunge = op.feeds()
        operations.append(SheetOperation(op.name, op.tool.number, float(op.spindle_rpm), feed, plunge,
                                         float(op.cycle_time(program.rapid_rate)), len(op)))
    return tools, tuple(operations), float(program.cycle_time())


def _from_report(entries: list) -> tuple:
    """Tools and operations from a report's ``operations`` (:meth:`Operation.summary` entries)."""
    tools, operations = {}, []
    for entry in entries:
        number = entry.get("tool_number")
        if number is not None and number not in tools:
            tools[number] = SheetTool(int(number), str(entry.get("tool_kind", DASH)),
                                      _number(entry.get("tool_diameter_mm")),
                                      _number(entry.get("tool_corner_radius_mm")),
                                      _number(entry.get("tool_flute_length_mm")), None, str(entry.get("tool", "")))
        moves = entry.get("moves")
        operations.append(SheetOperation(str(entry.get("name", DASH)), number, _number(entry.get("spindle_rpm")),
                                         _number(entry.get("feed_mm_min")), _number(entry.get("plunge_feed_mm_min")),
                                         _number(entry.get("cycle_time_s")), None if moves is None else int(moves)))
    return tuple(tools.values()), tuple(operations)


def _label(value, fallback) -> str:
    for candidate in (value, fallback):
        if candidate is None or candidate == "":
            continue
        if isinstance(candidate, dict):
            return str(candidate.get("label") or candidate.get("name") or "")
        if isinstance(candidate, str):
            return candidate
        return str(getattr(candidate, "label", "") or getattr(candidate, "name", "") or candidate)
    return ""


def sheet_from(program, report: dict | None = None, machine=None, post=None, pictures=(), *, stock=None,
               programs=(), job_name: str | None = None, stick_out: dict | None = None) -> SetupSheet:
    """A setup sheet from one ``program`` (a Program, or None for a job without one, such as a
    punched flat pattern) and a batch run's ``report`` (its ``gate``, ``operations``, ``machine``,
    ``post``, ``cycle_time_s``, ``warnings``; the gate's ``stock`` and ``work_offset``; a sheet
    job's ``sheet``).  What is given explicitly wins over the report: ``machine`` (a machine
    profile, its summary dict or a label), ``post`` (a label), ``pictures`` ((caption, PNG
    bytes) pairs), ``stock`` (a stock object or :func:`stock_entry` dict), ``programs``
    (:class:`SheetProgram`), ``stick_out`` ({tool number: mm})."""
    report = report or {}
    gate = report.get("gate")
    if program is not None:
        tools, operations, total = _from_program(program)
        offset = program.work_offset
    else:
        tools, operations = _from_report(report.get("operations") or [])
        total = _number(report.get("cycle_time_s"))
        if total is None and any(op.cycle_time_s is not None for op in operations):
            total = sum(op.cycle_time_s or 0.0 for op in operations)
        offset = (gate or {}).get("work_offset", "")
    if stick_out:
        tools = tuple(SheetTool(t.number, t.kind, t.diameter, t.corner_radius, t.flute_length,
                                stick_out.get(t.number, t.stick_out), t.description) for t in tools)
    chips = {}
    for entry in report.get("feeds") or ():       # the check before export: each operation's chip load
        if isinstance(entry, dict) and entry.get("checked") and entry.get("tool_number") is not None:
            value = entry.get("chip_load_mm")
            chips.setdefault(entry["tool_number"], []).append(
                (value, "revolution") if entry.get("chip_load_per") == "revolution" else value)
    if chips:
        tools = tuple(SheetTool(t.number, t.kind, t.diameter, t.corner_radius, t.flute_length, t.stick_out,
                                t.description, tuple(chips.get(t.number, ()))) for t in tools)
    if stock is None:
        stock = (gate or {}).get("stock")
        sheet_entry = report.get("sheet")
        if stock is None and isinstance(sheet_entry, dict) and sheet_entry.get("sheet_mm"):
            stock = {"kind": "sheet", "size": [float(v) for v in sheet_entry["sheet_mm"]]}
    stock = stock_entry(stock)
    status, findings = gate_status(gate)
    name = job_name or (program.name if program is not None else None) or (gate or {}).get("program") \
        or str(report.get("workflow", "job"))
    notes = tuple(str(w) for w in report.get("warnings") or () if isinstance(w, str))
    return SetupSheet(job_name=name, machine_label=_label(machine, report.get("machine")),
                      post_label=_label(post, report.get("post")), work_offset=offset or "", stock=stock,
                      work_zero=work_zero_text(stock, offset or ""), tools=tools, operations=operations,
                      total_time_s=total, gate_status=status, gate_findings=findings, programs=programs,
                      pictures=pictures, notes=notes)
