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
  F > 0, a line of at most 80 characters once spaces and comments are dropped (protocol.h),
  no ``%``; ends with M2/M30.
* ``turnmill-xzc``: Fanuc 0i-T style: the same word formats as the Fanuc mill, T = 2-digit station +
  2-digit offset, the turret homed (``G28 U0. W0.``) with the driven tool stopped before indexing.
* ``amada-04p``: the Amada 04P turret punch: N000..N999 (3 digits), every value with exactly two
  decimals, T three digits, the program opens with ``N000 G92`` and ends with ``G50`` (or M30).

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
                       coord=99999.999, decimals=3, point=True, frame="fanuc", changer="fanuc"),
    "fanuc-cxz": dict(f94=(0.001, 240000.0), f93=(0.001, 9999.999), s=99999, t=9999, h=99, n=(1, 99999),
                      coord=99999.999, decimals=3, point=True, frame="fanuc", changer="fanuc"),
    "linuxcnc": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 99999), coord=None,
                     decimals=None, point=False, frame="linuxcnc", changer="linuxcnc"),
    "linuxcnc-cxz": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 99999), coord=None,
                         decimals=None, point=False, frame="linuxcnc", changer="linuxcnc"),
    "turnmill-linuxcnc": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 99999), coord=None,
                              decimals=None, point=False, frame="linuxcnc", changer="linuxcnc"),
    "grbl": dict(f94=(0.0, None), f93=(0.0, None), s=None, t=None, h=None, n=(0, 9999999), coord=None,
                 decimals=None, point=False, frame="grbl", changer="none"),
    "turnmill-xzc": dict(f94=(0.001, 240000.0), f93=(0.001, 9999.999), s=99999, t=9999, h=None, n=(1, 99999),
                         coord=99999.999, decimals=3, point=True, frame="fanuc", changer="turret"),
}
EXCLUSIVE_MIN = {"linuxcnc", "linuxcnc-cxz", "turnmill-linuxcnc", "grbl"}   # F must be > 0


def _blocks(text: str):
    """(line number, stripped line, words [(letter, text)]) for every line."""
    for number, line in enumerate(text.splitlines(), start=1):
        bare = COMMENT.sub("", line).strip()
        yield number, line, bare, WORD.findall(bare.upper())


def check(text: str, control: str) -> list:
    if control == "amada-04p":
        return check_punch(text)
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
    need_offset, in_sub = False, False
    for number, raw, bare, words in _blocks(text):
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
        if control == "grbl" and len(re.sub(r"\s", "", bare)) > 80:
            bad("word", number, "a Grbl line holds at most 80 characters")
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
        # --- modes ---------------------------------------------------------------------------
        for g in gnum:
            if g in (93, 94, 95):
                feed_mode = int(g)
            if g == 98 and control == "turnmill-xzc":
                feed_mode = 94
            if g in (0, 1, 2, 3):
                motion = int(g)
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
        cutting = moves and motion in (1, 2, 3) and not any(g in (28, 53) for g in gnum)
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
    return found


def check_punch(text: str) -> list:
    found = []
    lines = [line.strip() for line in text.splitlines() if line.strip()]
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
