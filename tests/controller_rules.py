"""An independent reader of NC text: would this control alarm on the program?

Written again from the controls' manuals, not from the posts (it imports nothing of ``post/``,
and none of the ranges in ``post/registry.py`` or the posts' profiles), as ``macrob.py`` is
independent of the macro post.  ``check(text, control)`` returns the violations, each
``(rule, line number, message)``; an empty list means the program passes.

Controls and where their rules come from:

* ``fanuc-mill``, ``fanuc-cxz``: Fanuc 0i / 16 / 18 -M operator's manuals (B-62764EN and the 0i
  editions): ``%`` frame and ``O`` number 1..9999, N 1..99999, IS-B metric (8 digits, 3 decimals,
  |value| <= 99999.999), a decimal point on every axis word (``X1`` is 1 micron), F per minute
  0.001..240000, G93 inverse time F 0.001..9999.999 with a decimal point on every G01/G02/G03
  block, S up to 5 digits, T up to 4 digits, H 0..99, program end M30 (or M02).
* ``linuxcnc``, ``linuxcnc-cxz``, ``turnmill-linuxcnc``: LinuxCNC G-code manual: G93 needs an F
  word on every G1/G2/G3 block, F > 0, T >= 0, H >= 0, S >= 0, N 0..99999; the program ends with
  M2/M30; ``%`` lines come as a pair or not at all.
* ``grbl``: Grbl v1.1 commands: no M6 and no G43 H (only G43.1), N up to 9999999, G93 supported,
  F > 0, a line of at most 79 characters once spaces and comments are dropped (protocol.h
  LINE_BUFFER_SIZE 80; protocol.c stores at most LINE_BUFFER_SIZE - 1 characters, error:11 beyond),
  no ``%``; ends with M2/M30.

Line length (the raw line, comments and all): LinuxCNC reads a line into LINELEN = 255 bytes
(rs274ngc; its G-code overview: "a maximum (currently 256) to the number of characters allowed on a
line"), and a line that fills the buffer with its newline and end mark is "Command too long", so 252
characters; the Fanuc manuals read (B-62764EN, B-63684EN 13.) give no longest block, and the Fanuc
controls are held to the same 252 (a choice, said so, not a manual's figure).  Grbl's serial buffer
holds 128 bytes (serial.h RX_BUFFER_SIZE), so a sender counting characters can stream a line of at
most 127 characters and its newline.
* ``turnmill-xzc``: Fanuc 0i-T style: the same word formats as the Fanuc mill, T = 2-digit station +
  2-digit offset, the turret homed (``G28 U0. W0.``) with the driven tool stopped before indexing.
* ``amada-04p``: the Amada 04P turret punch: N000..N999 (3 digits), every value with exactly two
  decimals, T three digits, the program opens with ``N000 G92`` and ends with ``G50`` (or M30).
  Where the hits fall (worked out from the G72 / G69 / G79 words here, as the Amada ARIES 245
  (04PA) programming manual defines sheet coordinates: from the sheet's lower-left corner, first
  quadrant): at X, Y >= 0, within the sheet and outside the clamps' dead zones when the caller
  gives them (as numbers), and no hit punched twice.

Fanuc macro modal call (Custom Macro B, G66.1 ... G67): the pairs balanced, never nested; the call
made in G01 only, and cancelled (G67) before any rapid or retract (G00), reference return (G28,
G53), spindle stop, tool change, stop or program end (M00 M01 M02 M05 M06 M30): every block
under G66.1 is handed to the macro, which should then have to tell a rapid from a cut.

Where the tool is when XY moves (rule ``safe-z``; milling and C-X-Z controls).  After the program
start and after every tool load the controller does not know where the tool tip is above the work:
at the start it is wherever the operator left it (on a hobby router, touching the plate top after
Z was zeroed there); an ``M00``/``M01`` pause lets the operator change the bit, jog and re-zero
(Grbl v1.1 "Commands": M0 program pause, no M6; LinuxCNC "M-Codes": M0/M1 pause, and M6 with
``hal_manualtoolchange`` stops and waits for the operator, while Z moves only if the INI's
``TOOL_CHANGE_QUILL_UP`` asks for it, [EMCIO] section of the INI reference).  So after these, any
X, Y or C motion before Z has been raised is a violation: raised means a return to a machine
position with Z (``G28``/``G30`` Z, FANUC 0i-MF operator's manual B-64604EN "Reference position
return"; LinuxCNC and Grbl ``G28``/``G30``), a machine-coordinate move with Z (``G53 ... Z``, LinuxCNC
"G53 Move in Machine Coordinates", Grbl v1.1 G53 on a homed machine), or an absolute rapid to a Z of
at least ``clearance`` above the work zero (the caller's, e.g. the machine's clearance height).
One exception, the Fanuc changer: an ``M06`` with Z still at the reference position it was sent
to (``G28 Z0.`` and no Z move since) leaves Z there, at the top (B-64604EN: the reference position is
where a machining centre changes tools).  At the program end the same: after the last feed move,
an X/Y/C move before Z is raised is a violation.

Canned drilling cycles (milling controls but Grbl, which has none: Grbl v1.1 "Commands" lists no
G80-G89): G81 drilling, G82 drilling with a dwell, G83 peck drilling, modal until G80 (or a G00-G03)
cancels them (LinuxCNC G-code reference "G80-G89 Canned Cycles"; Fanuc 0i-M operator's manual,
canned cycles); while one is in force each block with X/Y drills a hole there.  The cycle block
needs Z (the bottom) and R (the R plane) above it; G82 needs P (LinuxCNC: seconds; Fanuc: the dwell
in milliseconds, written without a decimal point as G04 P); G83 needs Q > 0 (the peck; on a Fanuc
with a decimal point, as the axis words: ``Q3`` is 3 microns); G81-G83
with G91 are refused as anywhere.  Where the tool is after a hole (rule ``safe-z``): with G98 at
the initial level (the Z the cycle started from, or R if R is higher), with G99 at the R plane; a
hole drilled counts as a feed move.

Arcs (rule ``arc``; G02/G03 in the XY plane, G17, the centre as I/J offsets from the start): the
block needs I or J and a known start point, and the start's and the end's distances from the centre
may differ by no more than the control accepts.  LinuxCNC (G-Codes, "G2, G3 Arc", center format:
an error when they differ "by more than (.05 inch/.5 mm) OR ((.0005 inch/.005mm) AND .1% of
radius)"), and Grbl the same (grbl/gcode.c v1.1: STATUS_GCODE_INVALID_TARGET, ``error:33``, when
delta_r > 0.005 and delta_r > 0.001 r, or delta_r > 0.5 mm).  Fanuc (0i-MF B-64604EN alarm PS0020
OVER TOLERANCE OF RADIUS: the difference exceeds parameter No. 3410, the machine builder's
setting): held here to 0.001 mm, the least nonzero value the parameter holds in IS-B, so a program
that passes runs whatever the builder set.

Tool changes (milling controls with a changer): the spindle stopped (M05), for Fanuc Z sent to the
change position (``G91 G28 Z0.``) and back to G90, the length offset cancelled (G49), never a change
to the tool already in the spindle, and the offset re-applied (G43 H) before the first cut.  Every
feed move needs the spindle (or the driven tool) running.
"""
from __future__ import annotations

import re

WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")
COMMENT = re.compile(r"\([^)]*\)")

FANUC_AXES = "XYZCUWIJKR"
CONTROLS = {
    # feed_min, feed_max (G94), g93 max, s max, t max, h max, n max, coordinate max, decimals, decimal point
    "fanuc-mill": dict(f94=(0.001, 240000.0), f93=(0.001, 9999.999), s=99999, t=9999, h=99, n=(1, 99999),
                       coord=99999.999, decimals=3, point=True, frame="fanuc", changer="fanuc", line=252),
    "fanuc-cxz": dict(f94=(0.001, 240000.0), f93=(0.001, 9999.999), s=99999, t=9999, h=99, n=(1, 99999),
                      coord=99999.999, decimals=3, point=True, frame="fanuc", changer="fanuc", line=252),
    "linuxcnc": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 99999), coord=None,
                     decimals=None, point=False, frame="linuxcnc", changer="linuxcnc", line=252),
    "linuxcnc-cxz": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 99999), coord=None,
                         decimals=None, point=False, frame="linuxcnc", changer="linuxcnc", line=252),
    "turnmill-linuxcnc": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 99999), coord=None,
                              decimals=None, point=False, frame="linuxcnc", changer="linuxcnc", line=252),
    "grbl": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 9999999), coord=None,
                 decimals=None, point=False, frame="grbl", changer="none", stripped_line=79,
                 line=127),
    "turnmill-xzc": dict(f94=(0.001, 240000.0), f93=(0.001, 9999.999), s=99999, t=9999, h=None, n=(1, 99999),
                         coord=99999.999, decimals=3, point=True, frame="fanuc", changer="turret"),
}
EXCLUSIVE_MIN = {"linuxcnc", "linuxcnc-cxz", "turnmill-linuxcnc", "grbl"}   # F must be > 0
SAFE_Z_CONTROLS = {"fanuc-mill", "fanuc-cxz", "linuxcnc", "linuxcnc-cxz", "grbl"}   # rule "safe-z"
DEFAULT_CLEARANCE = 10.0      # mm above the work zero: the least absolute G00 Z counted as a raise


CYCLES = (81, 82, 83)        # the canned drilling cycles read here (G80 cancels)


def cycle_words(letters: dict, gnum: list, frame: str) -> list:
    """What a block starting a canned cycle lacks or has wrong (messages)."""
    code = [int(g) for g in gnum if g in CYCLES][0]
    wrong = [f"G{code} needs {w}" for w in "ZR" if w not in letters]
    if not wrong and float(letters["R"]) <= float(letters["Z"]):
        wrong.append(f"G{code}: R{letters['R']} is not above the bottom Z{letters['Z']}")
    if code == 82:
        if "P" not in letters:
            wrong.append("G82 needs the dwell P")
        elif frame == "fanuc" and "." in letters["P"]:
            wrong.append(f"G82 P{letters['P']}: Fanuc's dwell is milliseconds without a decimal point")
    if code == 83 and not ("Q" in letters and float(letters["Q"]) > 0):
        wrong.append("G83 needs the peck Q > 0")
    elif code == 83 and frame == "fanuc" and "." not in letters["Q"]:
        wrong.append(f"G83 Q{letters['Q']}: Fanuc reads a Q without a point in microns")
    return wrong


def _blocks(text: str):
    """(line number, stripped line, words [(letter, text)]) for every line."""
    for number, line in enumerate(text.splitlines(), start=1):
        bare = COMMENT.sub("", line).strip()
        yield number, line, bare, WORD.findall(bare.upper())


def check(text: str, control: str, clearance: float = DEFAULT_CLEARANCE) -> list:
    """The violations of ``text`` on ``control``; ``clearance``: the lowest absolute ``G00 Z`` (mm
    above the work zero) that counts as lifting the tool clear of the work (rule ``safe-z``)."""
    if control == "amada-04p":
        return check_punch(text)
    found = check_blocks(text, control)
    found += check_arcs(text, control)
    if control in SAFE_Z_CONTROLS:
        found += check_safe_z(text, control, clearance)
    return sorted(found, key=lambda violation: violation[1])


def check_safe_z(text: str, control: str, clearance: float) -> list:
    """Rule ``safe-z`` (see the module's docstring): X/Y/C motion while Z is unknown (after the
    start, a tool load or a pause) or, after the last feed move, not yet raised."""
    found = []
    unknown, low, distance, motion, at_reference = True, False, 90, None, False
    reason = "the program start"
    after_last_feed = []          # XY moves with the tool not raised since the last feed move
    cycle, level, z_now, r_plane = None, 98, float("inf"), None     # canned cycle state; Z (inf: unknown/top)
    for number, raw, bare, words in _blocks(text):
        if not bare or bare == "%" or re.match(r"^O\d+", bare):
            continue              # the frame and the program number (subprograms follow M30)
        letters = dict((letter, value) for letter, value in reversed(words))
        gnum = [float(value) for letter, value in words if letter == "G"]
        ms = [int(float(value)) for letter, value in words if letter == "M"]
        for g in gnum:
            if g in (98, 99):
                level = int(g)
            if g in (0, 1, 2, 3, 80):
                cycle = None
        started = [int(g) for g in gnum if g in CYCLES]
        if started:
            cycle, cycle_from = started[0], z_now
        if cycle is not None:
            if "R" in letters:
                r_plane = float(letters["R"])
            if started or any(a in letters for a in "XY"):      # a hole drilled
                if unknown:
                    found.append(("safe-z", number, f"canned cycle after {reason} before Z is raised: {bare!r}"))
                    unknown = False
                top = max(cycle_from, r_plane) if level == 98 else r_plane
                z_now = top
                after_last_feed = []
                low = not (z_now >= clearance - 1e-9)
            continue
        for g in gnum:
            if g in (90, 91):
                distance = int(g)
            if g in (0, 1, 2, 3):
                motion = int(g)
        machine_move = any(g in (28, 30, 53) for g in gnum)
        raised = False
        if machine_move and "Z" in letters:
            raised = True
        elif "Z" in letters and motion == 0 and distance == 90 and float(letters["Z"]) >= clearance - 1e-9:
            raised = True
        xy = [axis for axis in "XYC" if axis in letters]
        if raised:
            unknown, low = False, False
        if machine_move and "Z" in letters:
            z_now = float("inf")
        elif "Z" in letters and distance == 90:
            z_now = float(letters["Z"])
        if xy and (motion is not None or machine_move):
            if unknown:
                found.append(("safe-z", number, f"{'/'.join(xy)} move after {reason} before Z is raised "
                                                f"(G28/G30 Z, G53 Z, or G00 Z{clearance:g} or higher first): {bare!r}"))
                unknown = False           # one finding per start or load
            elif low and not raised:
                after_last_feed.append((number, bare))
        if "Z" in letters and not raised and not machine_move:
            low = True
        if motion in (1, 2, 3) and any(a in letters for a in "XYZC") and not machine_move:
            low, after_last_feed = True, []
        # Where M06 leaves Z: at the reference position on a Fanuc changer if it was sent there.
        if any(g == 28 for g in gnum) and "Z" in letters:
            at_reference = True
        elif "Z" in letters:
            at_reference = False
        if 6 in ms and not (control.startswith("fanuc") and at_reference):
            unknown, reason = True, f"the tool load (M06, line {number})"
        if 0 in ms or 1 in ms:
            unknown, reason = True, f"the pause (M0{0 if 0 in ms else 1}, line {number})"
        if any(m in (2, 30) for m in ms):
            for line, block in after_last_feed:
                found.append(("safe-z", line, f"X/Y/C move at the program end before Z is raised: {block!r}"))
            break
    return found


ARC_RULES = {"fanuc-mill": "fanuc", "fanuc-cxz": "fanuc", "linuxcnc": "linuxcnc", "linuxcnc-cxz": "linuxcnc",
             "turnmill-linuxcnc": "linuxcnc", "grbl": "linuxcnc"}
FANUC_RADIUS_TOLERANCE = 0.001      # mm: parameter 3410 at its least nonzero IS-B value (see the docstring)


def arc_radius_error(rule: str, start_r: float, end_r: float) -> bool:
    """Whether the control alarms on an arc whose start and end radii are these (mm)."""
    delta = abs(end_r - start_r)
    if rule == "fanuc":
        return delta > FANUC_RADIUS_TOLERANCE + 1e-9
    return delta > 0.5 or (delta > 0.005 and delta > 0.001 * start_r)


def arc_blocks(text: str) -> list:
    """(line number, clockwise, start xy, end xy, centre xy or None) of every G02/G03 block in the
    XY plane, read from the words (absolute coordinates, I/J from the start); start None where the
    program has not yet put X and Y anywhere."""
    found = []
    x = y = None
    motion, plane = None, 17
    for number, raw, bare, words in _blocks(text):
        letters = dict((letter, value) for letter, value in reversed(words))
        gnum = [float(value) for letter, value in words if letter == "G"]
        for g in gnum:
            if g in (0, 1, 2, 3):
                motion = int(g)
            if g in (17, 18, 19):
                plane = int(g)
        if any(g in (28, 30, 53, 91) for g in gnum):      # machine moves (Z only in our programs) and G91 G28
            continue
        new_x = float(letters["X"]) if "X" in letters else x
        new_y = float(letters["Y"]) if "Y" in letters else y
        if motion in (2, 3) and plane == 17 and any(a in letters for a in "XYZ"):
            centre = None
            if ("I" in letters or "J" in letters) and x is not None and y is not None:
                centre = (x + float(letters.get("I", "0")), y + float(letters.get("J", "0")))
            found.append((number, motion == 2, None if x is None or y is None else (x, y), (new_x, new_y), centre,
                          "I" in letters or "J" in letters, bare))
        x, y = new_x, new_y
    return found


def check_arcs(text: str, control: str) -> list:
    """Rule ``arc`` (see the module's docstring)."""
    import math
    rule = ARC_RULES.get(control)
    if rule is None:
        return []
    found = []
    for number, _, start, end, centre, has_centre, bare in arc_blocks(text):
        if not has_centre:
            found.append(("arc", number, f"arc without I or J (centre format expected): {bare!r}"))
        elif start is None or end[0] is None or end[1] is None:
            found.append(("arc", number, f"arc from a point the program has not set: {bare!r}"))
        else:
            start_r = math.hypot(start[0] - centre[0], start[1] - centre[1])
            end_r = math.hypot(end[0] - centre[0], end[1] - centre[1])
            if arc_radius_error(rule, start_r, end_r):
                found.append(("arc", number, f"the arc's start radius {start_r:.4f} and end radius {end_r:.4f} differ "
                                             f"by {abs(end_r - start_r):.4f} mm, more than the control accepts: {bare!r}"))
    return found


def check_blocks(text: str, control: str) -> list:
    """Every rule but ``safe-z``: frame, words, ranges, modes, spindle, tool changes."""
    rules = CONTROLS[control]
    found = []

    def bad(rule, line, message):
        found.append((rule, line, message))

    lines = text.splitlines()
    frame = rules["frame"]
    if frame == "fanuc":
        if not lines or lines[0].strip() != "%" or lines[-1].strip() != "%":
            bad("frame", 1, "a Fanuc program starts and ends with a % line")
        program = re.match(r"^O(\d{1,4})\b", lines[1]) if len(lines) > 1 else None
        if program is None or not 1 <= int(program.group(1)) <= 9999:
            bad("frame", 2, "the line after % is the program number O1..O9999")
    elif frame == "linuxcnc":
        percent = [i for i, line in enumerate(lines) if line.strip() == "%"]
        if percent and (len(percent) != 2 or percent[0] != 0 or percent[1] != len(lines) - 1):
            bad("frame", 1, "% lines must be the first and the last line, both or neither")
    elif frame == "grbl" and any(line.strip().startswith("%") for line in lines):
        bad("frame", 1, "Grbl does not take % lines")

    feed_mode, motion, spindle, tool, offset, at_change, ended = 94, None, False, None, False, False, False
    need_offset, in_sub, cycle = False, False, None
    modal_call = None                       # line of the G66.1 in force (Fanuc)
    for number, raw, bare, words in _blocks(text):
        if rules.get("line") is not None and len(raw) > rules["line"]:
            bad("length", number, f"a line of {len(raw)} characters, more than the {rules['line']} the control reads")
        if not bare or bare == "%":
            continue
        if ended:
            # After M30: only subprograms (O.... .. M99); macro statements are the macro checker's.
            if re.match(r"^O\d+", bare):
                in_sub = True
                continue
            if not in_sub:
                bad("frame", number, f"block after the program end: {bare!r}")
            if re.search(r"\bM99\b", bare):
                in_sub = False
            continue
        if "#" in bare or "[" in bare:
            bad("word", number, f"macro expression in the main program: {bare!r}")
            continue
        if rules.get("stripped_line") is not None and len(re.sub(r"\s", "", bare)) > rules["stripped_line"]:
            bad("length", number, f"a Grbl line holds at most {rules['stripped_line']} characters without spaces "
                                  "and comments")
        letters = {}
        for letter, value in words:
            if letter in letters and letter not in "GM":
                bad("word", number, f"word {letter} twice in one block")
            letters.setdefault(letter, value)
        gs = [value for letter, value in words if letter == "G"]
        ms = [int(float(value)) for letter, value in words if letter == "M"]
        gnum = [float(g) for g in gs]
        # --- word formats and ranges --------------------------------------------------------
        for letter, value in words:
            if letter in FANUC_AXES:
                if rules["point"] and "." not in value:
                    bad("decimal", number, f"{letter}{value}: Fanuc reads a number without a point in microns")
                if rules["decimals"] is not None and "." in value and len(value.split(".")[1]) > rules["decimals"]:
                    bad("word", number, f"{letter}{value} has more than {rules['decimals']} decimals")
                if rules["coord"] is not None and abs(float(value)) > rules["coord"]:
                    bad("range", number, f"{letter}{value} is beyond +-{rules['coord']}")
        if "N" in letters:
            low, high = rules["n"]
            if not (low <= float(letters["N"]) <= high and "." not in letters["N"]):
                bad("range", number, f"N{letters['N']} outside {low}..{high}")
        if "S" in letters and not 0 <= float(letters["S"]) <= (rules["s"] if rules["s"] is not None else 1e99):
            bad("range", number, f"S{letters['S']} outside 0..{rules['s']}")
        if "T" in letters and not 0 <= float(letters["T"]) <= (rules["t"] if rules["t"] is not None else 1e99):
            bad("range", number, f"T{letters['T']} outside 0..{rules['t']}")
        if "H" in letters and not 0 <= float(letters["H"]) <= (rules["h"] if rules["h"] is not None else 1e99):
            bad("range", number, f"H{letters['H']} outside 0..{rules['h']}")
        # --- macro modal call (Fanuc G66.1 ... G67) -------------------------------------------
        if frame == "fanuc":
            if 66.1 in gnum:
                if modal_call is not None:
                    bad("modalcall", number, f"G66.1 while the G66.1 of line {modal_call} is in force")
                if motion != 1 or any(g in (0, 2, 3) for g in gnum):
                    bad("modalcall", number, "G66.1 made outside G01: the macro would be handed a rapid or an arc")
                modal_call = number
            elif 67 in gnum:
                if modal_call is None:
                    bad("modalcall", number, "G67 without a G66.1 in force")
                modal_call = None
            elif modal_call is not None:
                stops = [f"M{m:02d}" for m in ms if m in (0, 1, 2, 5, 6, 30)]
                moves_g = [f"G{g:g}" for g in gnum if g in (0, 28, 53)]
                if stops or moves_g or motion == 0:
                    what = " ".join(moves_g + stops) or "a G00 move"
                    bad("modalcall", number, f"{what} with the G66.1 of line {modal_call} in force (G67 first)")
        # --- modes ---------------------------------------------------------------------------
        for g in gnum:
            if g in (93, 94, 95):
                feed_mode = int(g)
            if g == 98 and control == "turnmill-xzc":
                feed_mode = 94
            if g in (0, 1, 2, 3):
                motion = int(g)
                cycle = None
            if g == 80:
                cycle, motion = None, 80
            if g in CYCLES:
                if control == "grbl":
                    bad("cycle", number, f"Grbl has no canned cycle G{g:g}")
                cycle = int(g)
                for message in cycle_words(letters, gnum, frame):
                    bad("cycle", number, message)
        if any(g == 28 for g in gnum) and "Z" in letters and float(letters["Z"]) == 0:
            at_change = True
        elif "Z" in letters:
            at_change = False
        if "F" in letters:
            f = float(letters["F"])
            low, high = rules["f93"] if feed_mode == 93 else rules["f94"]
            if (f <= low if control in EXCLUSIVE_MIN else f < low) or (high is not None and f > high):
                bad("feed", number, f"F{letters['F']} outside {low}..{high} under G{feed_mode}")
            if feed_mode == 93 and rules["point"] and "." not in letters["F"]:
                bad("decimal", number, f"F{letters['F']} under G93 needs a decimal point")
        moves = any(a in letters for a in "XYZCUW")
        cutting = moves and (motion in (1, 2, 3) or cycle is not None) and not any(g in (28, 53) for g in gnum)
        if moves and motion == 80 and cycle is None and not any(g in (28, 30, 53) for g in gnum):
            bad("word", number, f"axis words with no motion mode in force (after G80): {bare!r}")
        if cutting and feed_mode == 93 and "F" not in letters:
            bad("g93", number, "G93: every G1/G2/G3 block carries its own F")
        # --- spindle ---------------------------------------------------------------------------
        for m in ms:
            if m in (3, 4) or m in (133, 134):
                speed = float(letters.get("S", letters.get("P", "1")))
                spindle = speed > 0
            if m in (5, 135):
                spindle = False
        if control == "grbl":
            if 6 in ms:
                bad("toolchange", number, "Grbl has no tool changer (M6)")
            if any(g == 43 for g in gnum):
                bad("toolchange", number, "Grbl has no G43 H (only G43.1)")
            if 0 in ms and spindle:
                bad("toolchange", number, "M00 pause for a tool change with the spindle running")
        # --- tool change ---------------------------------------------------------------------------
        if rules["changer"] in ("fanuc", "linuxcnc") and 6 in ms:
            new = letters.get("T")
            if spindle:
                bad("toolchange", number, "M06 with the spindle running (M05 first)")
            if offset:
                bad("toolchange", number, "M06 with the length offset active (G49 first)")
            if rules["changer"] == "fanuc" and not at_change:
                bad("toolchange", number, "M06 with Z not at the change position (G91 G28 Z0. first)")
            if new is not None and tool is not None and int(float(new)) == tool:
                bad("toolchange", number, f"change to T{new}, the tool already in the spindle")
            if new is not None:
                tool = int(float(new))
            need_offset = True
        if rules["changer"] == "turret" and "T" in letters:
            if spindle:
                bad("toolchange", number, "turret indexed with the driven tool running")
            if not at_change:
                bad("toolchange", number, "turret indexed without the G28 U0. W0. home return")
        if rules["changer"] == "turret" and any(g == 28 for g in gnum) and "U" in letters and "W" in letters:
            at_change = True
        elif rules["changer"] == "turret" and moves and not any(g == 28 for g in gnum):
            at_change = False
        if any(g == 49 for g in gnum):
            offset = False
        if any(g == 43 for g in gnum):
            if "H" in letters:
                offset = True
                if tool is not None and int(float(letters["H"])) != tool:
                    bad("toolchange", number, f"G43 H{letters['H']} is not the offset of T{tool}")
                need_offset = False
        if any(g == 91 for g in gnum) and not any(g == 28 for g in gnum):
            bad("word", number, "G91 outside the reference return: the program is absolute")
        if cutting:
            if not spindle:
                bad("spindle", number, "feed move with the spindle stopped")
            if need_offset:
                bad("toolchange", number, "feed move before the length offset of the new tool (G43 H)")
        if any(m in (2, 30) for m in ms):
            ended = True
    if not ended:
        bad("frame", len(lines), "no program end (M30 or M02)")
    if modal_call is not None:
        bad("modalcall", len(lines), f"the G66.1 of line {modal_call} is never cancelled (G67)")
    return found


def _punch_hits(text: str) -> list:
    """(line number, x, y) of every hit of an 04P program, worked out here from the words: a G69 /
    G79 line from the last G72 point, I long at J degrees from +X, its hits evenly spaced from
    its start to its end (both included), as few as keep them at most Q apart, offset P/2 to the
    left of travel (P > 0 left, < 0 right, 0 the line is the punch centre)."""
    import math
    hits, point = [], None
    for number, line in enumerate(text.splitlines(), start=1):
        bare = COMMENT.sub("", line).strip().upper()
        words = dict(WORD.findall(re.sub(r"^N\d+\s*", "", bare)))
        if re.search(r"\bG72\b", bare) and "X" in words and "Y" in words:
            point = (float(words["X"]), float(words["Y"]))
        elif re.search(r"\bG(69|79)\b", bare) and point is not None and all(w in words for w in "IJQ"):
            length, angle, pitch = float(words["I"]), math.radians(float(words["J"])), float(words["Q"])
            offset = float(words.get("P", "0")) / 2
            steps = max(0, math.ceil(length / pitch - 1e-9)) if pitch > 0 else 0
            ux, uy = math.cos(angle), math.sin(angle)
            for k in range(steps + 1):
                t = length * k / steps if steps else 0.0
                hits.append((number, point[0] + ux * t - uy * offset, point[1] + uy * t + ux * offset))
    return hits


def check_punch(text: str, sheet=None, clamp_zones=(), punch_radius: float = 0.0, same_hit: float = 0.05) -> list:
    """The 04P's word and frame rules, and what an operator checks of where the hits fall: every
    hit at X, Y >= 0 (the sheet's corner is the origin), within ``sheet`` (X, Y) when given, its
    disc (``punch_radius``) clear of every clamp's dead zone (x0, y0, x1, y1) in ``clamp_zones``,
    and no hit punched twice (two hit centres closer than ``same_hit`` mm)."""
    found = []
    lines = [COMMENT.sub("", line).strip() for line in text.splitlines()]
    lines = [line for line in lines if line]
    if not lines or not re.match(r"^N000 G92 X\S+ Y\S+$", lines[0]):
        found.append(("frame", 1, "an 04P program opens with N000 G92 X.. Y.."))
    if not lines or lines[-1] not in ("G50", "M30"):
        found.append(("frame", len(lines), "an 04P program ends with G50 (or M30)"))
    sequence = -1
    for number, line in enumerate(lines, start=1):
        for letter, value in WORD.findall(line):
            if letter == "N":
                if not re.fullmatch(r"\d{3}", value) or int(value) <= sequence:
                    found.append(("range", number, f"N{value}: sequence numbers are N000..N999, rising"))
                sequence = int(value) if value.isdigit() else sequence
            elif letter == "T":
                if not re.fullmatch(r"\d{3}", value) or int(value) < 1:
                    found.append(("range", number, f"T{value}: a turret station is three digits, 001..999"))
            elif letter in "XYIJPQD":
                if not re.fullmatch(r"-?\d+\.\d{2}", value):
                    found.append(("decimal", number, f"{letter}{value}: 04P values carry exactly two decimals"))
                elif abs(float(value)) > 9999.99:
                    found.append(("range", number, f"{letter}{value} beyond 9999.99"))
        if re.search(r"\bG(69|79)\b", line) and not all(re.search(rf"\b{w}", line) for w in "IJPQT"):
            found.append(("word", number, "a G69/G79 line needs I J P Q T"))
        if re.search(r"\bG79\b", line) and "D" not in line:
            found.append(("word", number, "a G79 punching line needs D (thickness)"))
    hits = _punch_hits(text)
    for number, x, y in hits:
        if x < 0 or y < 0:
            found.append(("sheet", number, f"a hit at X{x:.2f} Y{y:.2f}: off the sheet (its corner is X0 Y0)"))
        elif sheet is not None and (x > sheet[0] or y > sheet[1]):
            found.append(("sheet", number, f"a hit at X{x:.2f} Y{y:.2f}: beyond the {sheet[0]:g} x {sheet[1]:g} sheet"))
        for index, (x0, y0, x1, y1) in enumerate(clamp_zones, start=1):
            if x0 - punch_radius < x < x1 + punch_radius and y0 - punch_radius < y < y1 + punch_radius:
                found.append(("clamp", number, f"a hit at X{x:.2f} Y{y:.2f} strikes clamp {index}'s dead zone"))
    ordered = sorted(hits, key=lambda h: (h[1], h[2]))
    for i, (number, x, y) in enumerate(ordered):
        for other, x2, y2 in ordered[i + 1:]:
            if x2 - x >= same_hit:
                break
            if abs(y2 - y) < same_hit and (x2 - x) ** 2 + (y2 - y) ** 2 < same_hit ** 2:
                found.append(("double hit", max(number, other), f"X{x:.2f} Y{y:.2f} is punched twice "
                                                                 f"(lines {min(number, other)} and {max(number, other)})"))
    return found


def check_turret_frames(text: str, control: str, radius: float, end_z: float) -> list:
    """The lathe's frame rule (``turnmill-xzc``, ``turnmill-linuxcnc``): away from the cut, the
    tool never enters the bar's envelope (radius ``radius``, end face at ``end_z``; X words are
    diameters on the Fanuc control, radii on LinuxCNC).

    A rapid (G00) is positioned axis by axis at each axis's own rate unless the machine builder set
    linear positioning (Fanuc B-63944EN 4.1 "Positioning (G00)": non-linear interpolation type
    positioning, bit LRP of parameter No. 1401), so its path may be any dog-leg inside the box its
    end points span; the home return ``G28 U0. W0.`` goes from where the tool is straight to the
    reference position (the intermediate point U0 W0 is the current one), which is outside the
    bar in both X and Z.  So:

    * from the program start, and after every turret index (T) or driven-tool stop (M135 / M05),
      until the first feed move: every move's box must lie outside the bar (all its X at or beyond
      the radius, or all its Z at or above the end face);
    * every home return starts outside the bar (X beyond the radius or Z above the end face);
    * at the program end the tool is home or outside the bar.
    Returns ``(rule, line, message)`` for each violation, as :func:`check`."""
    scale = 0.5 if control == "turnmill-xzc" else 1.0
    inf = float("inf")
    x, z, motion, approach = inf, inf, 0, True
    found = []

    def outside(x0, z0, x1=None, z1=None) -> bool:
        x1 = x0 if x1 is None else x1
        z1 = z0 if z1 is None else z1
        return min(x0, x1) >= radius - 1e-9 or min(z0, z1) >= end_z - 1e-9

    for number, raw, bare, words in _blocks(text):
        if not bare or bare == "%":
            continue
        letters = dict((letter, value) for letter, value in words if letter not in "GM")
        gnum = [float(value) for letter, value in words if letter == "G"]
        ms = [int(float(value)) for letter, value in words if letter == "M"]
        for g in gnum:
            if g in (0, 1, 2, 3):
                motion = int(g)
        if 28 in gnum:
            if not outside(x, z):
                found.append(("frame", number, f"home return from X{x / scale:g} Z{z:g}, inside the bar "
                                               f"(radius {radius:g}, end face Z{end_z:g}): retract first"))
            x, z, approach = inf, inf, True
            continue
        if "T" in letters or any(m in (5, 135) for m in ms):
            approach = True
        if any(axis in letters for axis in "XZ"):
            nx = float(letters["X"]) * scale if "X" in letters else x
            nz = float(letters["Z"]) if "Z" in letters else z
            if motion == 0 and approach and not outside(x, z, nx, nz):
                found.append(("frame", number, f"rapid into the bar's envelope before the first cut after a start "
                                               f"or tool change: to X{nx / scale:g} Z{nz:g} (radius {radius:g}, end "
                                               f"face Z{end_z:g})"))
            if motion in (1, 2, 3):
                approach = False
            x, z = nx, nz
        if any(m in (2, 30) for m in ms) and not outside(x, z):
            found.append(("frame", number, f"program ends with the tool at X{x / scale:g} Z{z:g}, inside the bar"))
    return found
