"""Fanuc machining centres (ISO 6983 with Custom Macro B).

Two modes for a textured engraving:

* baked (``FanucPost``): the texture depths were drawn by the add-on and are written
  literally, so the program cuts exactly what the preview shows;
* controller macro (``FanucMacroPost``): the paper's method.  The roughing path is written
  untextured; ``G66.1 P7023`` is in force only over the cutting (each run of raster blocks:
  G01 at constant Z), ``G67`` comes before every retract, plunge and repositioning rapid, which
  are ordinary blocks.  Program O7023 draws a digit 0..9 for every gouge and applies the depth
  rule on the controller, so each run of the program cuts a different texture.

Macro arguments.  Fanuc Custom Macro B passes a call's address words as local variables by
argument specification I (A B C I J K D E F H M Q R S T U V W X Y Z -> #1..#26 with
A #1, B #2, C #3, I #4, J #5, K #6, D #7, E #8, F #9, H #11, M #13, Q #17, R #18, ...; G, L, N,
O and P cannot be arguments) or II (A B C once, I J K up to ten times); the control tells them
apart by the letters used and a later one wins where both name one variable (FANUC Series
16i/18i operator's manual, 16. Custom macro, "Argument specification", B-63684EN/01 p. 278;
the 0i/16i/18i-M manuals have the same tables).  The macros here take X Y Z (the move's own end
point, by design), F, and for O7024 E, Q and R, letters that are not axis addresses on any usual
machine, each once (so both specifications read them alike).

Where the digits come from.  The paper took the last decimal digit of the millisecond clock
``#3001``.  On the paper's control that clock counts in 16 ms steps, so its last digit is always
even and only digits 0 2 4 6 8 (five of the nine depths) ever occur.  O7023 instead keeps a
pseudo-random generator in common variable ``#115``: the Lehmer (multiplicative congruential)
generator ``x <- 2987 x mod 32749``.  32749 is prime and 2987 a primitive root of it, so the
sequence runs through every value 1..32748 before repeating, and the digit ``FIX[10 x / 32749]``
takes each value 0..9 with frequency 1/10 to within 1/3275 over a period.  The control computes
with about 8 significant digits, so the constants are chosen to keep everything exact: the
product 2987 x is at most 2987 * 32748 = 97 818 276 < 10^8, an integer the control holds exactly;
the remainder is taken as ``p - 32749 FIX[p / 32749]`` and brought back into 0..32748 by one
addition or subtraction if the division rounded across an integer.  ``#115`` is vacant after
power-on (or holds something that is not a state 1..32748); the first gouge then seeds it once
from the clock, ``FIX[frac(#3001 / 32749) * 32748] + 1`` (the clock's 16 ms granularity does not
matter: 16 k mod 32749 reaches every residue).  Later runs continue the sequence, so each run
still cuts a different texture.  Depth rule as in :mod:`..toolpath.operations.engrave.engrave`: digit 0 and 5 both
give the base depth, so the base occurs 2/10 of the time and each other depth 1/10.

O7023 follows the published macro with its two defects fixed: ``IF[#28GT5]`` sent d = 5 to
the shallow branch (depth -1.0, outside the stated range), here ``GE``; and
``IF[#24+#25]EQ#0]`` had unbalanced brackets and tested a sum (0, never vacant), here each
word is tested for vacancy on its own.  Beyond the paper, one loop with a signed step serves
both X directions, a move with both X and Y is split with Y interpolated along it, and the
macro no longer tells rapids and arcs from cuts by ``#4001``: the main program calls it on
cutting blocks only, and a call that is not one (a Z word, no X or Y) raises a macro alarm.
"""
from __future__ import annotations

import numpy as np

from ..toolpath.ir.program import GougeTexture, MoveKind

from .gcode import GcodePost, PostError, fmt
from .registry import ControllerLimits

RAPID, FEED = int(MoveKind.RAPID), int(MoveKind.FEED)     # the IR's move kinds

# Fanuc 0i / 16 / 18 -M (machining centre), metric input, increment system IS-B (0.001 mm).
FANUC_MILL_SOURCE = (
    "FANUC Series 16/18/160/180-MODEL C for Machining Center, Operator's Manual B-62764EN: "
    "5 Feed functions (inverse time feed G93: F 0.001..9999.999, every block; feed per minute); "
    "Program configuration (O number 1..9999, % frame, N 1..99999, M30); Tool function (T, M06); "
    "Tool length offset G43/G44/G49 (H offset numbers); Increment system IS-B (8 digits, 0.001 mm); "
    "decimal point programming (X1 means 0.001 mm without a point).  FANUC Series 0i-MD/0i-MF "
    "operator's manuals keep the same formats")
FANUC_MILL_LIMITS = ControllerLimits(
    feed_per_minute=(0.001, 240000.0), inverse_time_feed=(0.001, 9999.999), spindle_rpm=(0, 99999),
    tool_number=(0, 9999), length_offset=(0, 99), sequence_number=(1, 99999), program_number=(1, 9999),
    coordinate=99999.999, resolution=0.001, decimal_point=True, inverse_time_every_block=True, tool_changer=True,
    tool_change=("M05", "G91 G28 Z0.", "G90", "G49", "[M19]", "T.. M06", "S.. M03", "G43 Z.. H.."),
    program_start=("%", "O....", "G21 G17 G40 G49 G80 G90"), program_end=("M05", "G91 G28 Z0.", "M30", "%"),
    source=FANUC_MILL_SOURCE, max_line_length=252,
    line_length_source=("B-62764EN and the 16i/18i manual B-63684EN (13. Program configuration) state no longest block; "
                        "they count a comment's characters in its block (TV check).  252 characters, the longest line "
                        "LinuxCNC reads, is our choice for Fanuc, not a limit from its manuals"),
    arc_end_tolerance=0.001,
    arc_source=("FANUC Series 0i-MODEL F operator's manual B-64604EN, alarm PS0020 OVER TOLERANCE OF RADIUS: in circular "
                "interpolation (G02/G03) the start point's and the end point's distances from the centre differ by "
                "more than parameter No. 3410 (the machine builder's setting, in IS-B units of 0.001 "
                "mm).  0.001 mm, the least nonzero value it holds, so the arcs pass whatever the builder set"))

MACRO_PROGRAM = 7023
SURFACE_MACRO_PROGRAM = 7024     # the same texture on a curved plate (surface_macro_program)
# O7023's pseudo-random generator (see the module docstring): x <- LCG_MULTIPLIER * x mod LCG_MODULUS
# in common variable #LCG_STATE_VAR.
LCG_MODULUS = 32749
LCG_MULTIPLIER = 2987
LCG_STATE_VAR = 115


class FanucPost(GcodePost):
    name = "fanuc"
    label = "Fanuc (baked texture)"
    label_ja = "FANUC（テクスチャをベイク）"
    description = "Fanuc machining centre, ISO 6983; texture depths written literally"
    description_ja = "FANUCのマシニングセンタ（ISO 6983）。刀跡の深さを数値のまま書き出します"
    family = "milling"
    order = 10
    extension = ".nc"
    decimals = 3
    program_number = "O0001"
    limits = FANUC_MILL_LIMITS

    default_machine = "fanuc-vmc"
    states_machine = True
    # Fanuc 0i-M operator's manual, canned cycles: G98/G99 return to the initial level / the R point,
    # G81 drilling, G82 with a dwell P at the bottom (as G04 P: milliseconds, no decimal point), G83
    # peck drilling with Q the cut per peck (positive, incremental), Z and R absolute under G90, G80
    # cancel; the hole positions follow as X Y blocks while the cycle is modal.
    canned_cycles = True

    def dwell_word(self, seconds):
        return f"P{int(round(seconds * 1000))}"
    # The frames: G91 G28 Z0. (reference return), G90 G53 Z.. (machine coordinates) or G00 Z.. (the
    # clearance height); the tool change itself is always at the reference position.  A machining
    # centre's M06 runs the changer, so a manual change is refused rather than written as M06.
    retracts = ("reference", "machine", "clearance")
    tool_changes = ("atc",)

    def __init__(self, work_offset: str | None = None, orient_spindle: bool = False, machine=None):
        super().__init__(work_offset, machine)
        self.orient_spindle = orient_spindle     # M19 before M06, for changers that need the keys aligned

    def lift(self):
        if self.machine.retract == "machine":
            return [f"G90 G53 Z{self.n(self.machine.machine_top_z)}"]
        return super().lift()

    def after_load(self, op, first):
        """Nothing: the change was made at the reference position (G91 G28 Z0. before M06), where
        the changer leaves Z (FANUC 0i-MF operator's manual B-64604EN, reference position return:
        the reference position is where the tool is changed)."""
        return []

    def length_offset(self, op):
        return [f"G43 Z{self.n(op.safe_z)} H{op.tool.number:02d}", f"Z{self.n(op.clearance_z)}"]

    def tool_change(self, op, first):
        """Spindle stopped, Z at the tool-change position (machine zero by G28 through the
        incremental zero move), length offset cancelled, optionally the spindle oriented, then the
        change; the spindle and the new offset follow before the first cut."""
        return ["M05", "G91 G28 Z0.", "G90", "G49", *(["M19"] if self.orient_spindle else []),
                f"T{op.tool.number:02d} M06"]

    def ending(self, program):
        if self.machine.retract == "reference":
            return ["M05", "G91 G28 Z0.", "G28 X0. Y0.", "G90", "M30"]
        return ["M05", *self.lift(), "M30"]


class FanucMacroPost(FanucPost):
    name = "fanuc-macro"
    label = "Fanuc (controller macro)"
    label_ja = "FANUC（制御装置マクロ）"
    description = "Fanuc Custom Macro B: G66.1 P7023 draws the depths on the controller (seeded from #3001)"
    description_ja = "FANUCカスタムマクロB：G66.1 P7023 が制御装置上でクロック #3001 を種に深さを乱数で決めます"
    order = 11
    needs_texture = True

    def check(self, program):
        textured = [op for op in program.operations if op.texture is not None]
        if not textured:
            raise PostError("the controller-macro post needs an operation with a gouge texture; "
                            "use the baked Fanuc post for this program")
        for op in textured:
            texture = op.texture
            if not isinstance(texture, GougeTexture):
                raise PostError(f"operation {op.name!r}: the macro post knows only the gouge texture")
            if abs(texture.raster_angle) > 1e-9:
                raise PostError(f"operation {op.name!r}: O7023 splits X moves only; set the raster angle "
                                "to 0 or use the baked Fanuc post")
            if texture.motion != "ramp" or texture.spacing_jitter:
                raise PostError(f"operation {op.name!r}: scoop motion and spacing jitter exist only in "
                                "baked programs; use the baked Fanuc post")
        if len({(op.texture.base_depth, op.texture.quantum, op.texture.amplitude, op.texture.spacing)
                for op in textured}) > 1:
            raise PostError("all textured operations must share one texture: O7023 is one program")
        untextured = [op for op in program.operations if op.texture is None]
        super().check(program.__class__(program.name, untextured))

    def operation_moves(self, op):
        if op.texture is None:
            return super().operation_moves(op)
        if op.texture_marks is not None:
            return self.marked_moves(op)
        return self.confined_moves(op)

    def confined_moves(self, op) -> list:
        """The flat roughing with the macro confined to cutting.

        A raster block is a feed move at constant Z (the moves :func:`..toolpath.operations.engrave.engrave.apply_texture`
        textures or cuts at the current depth: rows, stepovers, short moves).  Each run of raster
        blocks is written between ``G66.1 P7023`` (on the run's first block, so the call that
        block makes carries its move) and ``G67``; every other move (rapid, retract, plunge,
        approach, arc) is an ordinary block outside the modal call, so O7023 never sees a rapid
        and needs no ``#4001``.  The macro leaves Z at the last gouge's depth, so the block after
        a run states its Z (and its G code and F) again."""
        starts = op.start_points()
        raster = (op.kind == FEED) & (np.abs(op.xyz[:, 2] - starts[:, 2]) <= 1e-9)
        lines, mode, after_run = [], None, False
        for lo, hi, is_run in _segments(raster):
            part = op.replace(kind=op.kind[lo:hi], xyz=op.xyz[lo:hi], feed=op.feed[lo:hi],
                              center=op.center[lo:hi], rotary={}, start=starts[lo], texture=None,
                              texture_marks=None, links=None)
            start = starts[lo].copy()
            if after_run:
                start[2] = np.nan            # the Z word of the next block is written whatever it reads
            block = self.moves(part, start)
            if not block:
                continue
            if is_run:
                first = block[0].removeprefix("G01 ")      # G66.1 is the only G code of its block
                if mode != "G01":
                    lines.append("G01")      # the modal call is made in G01 only
                lines += [f"G66.1 P{MACRO_PROGRAM} {first}", *block[1:], "G67"]
                mode, after_run = "G01", True
            else:
                lines += block
                codes = [line[:3] for line in block if line[:3] in ("G00", "G01", "G02", "G03")]
                mode, after_run = (codes[-1] if codes else mode), False
        return lines

    def marked_moves(self, op) -> list:
        """The surface-following roughing for O7024.  A marked block (one of a row, ``texture_marks``
        not NaN) gives X, Y and Z (the surface) in full, R its ramp position (0..1), Q1 where a new
        gouge starts and E1 on the first block of a run; each run of marked blocks is written
        between ``G66.1 P7024`` (on its first block) and ``G67``.  Other blocks (rapids, retracts,
        plunges) are ordinary blocks outside the modal call; the one after a run states its G code,
        Z and F again (the macro left Z below the programmed surface)."""
        lines, mode, feed_word, in_run = [], None, None, False
        last = {axis: self.n(value) for axis, value in zip("XYZ", op.start)}
        for kind, xyz, f, (new, fraction) in zip(op.kind.tolist(), op.xyz.tolist(), op.feed.tolist(),
                                                   op.texture_marks.tolist()):
            code = "G00" if kind == RAPID else "G01"
            axes = [(axis, self.n(value)) for axis, value in zip("XYZ", xyz)]
            marked = fraction == fraction      # not NaN
            if in_run and not marked:
                lines.append("G67")
                in_run, mode, feed_word, last["Z"] = False, None, None, None
            motion = [f"{axis}{text}" for axis, text in axes if marked or text != last[axis]]
            if not motion:
                continue
            if marked:
                words = motion + (["E1"] if not in_run else []) + (["Q1"] if new else []) + [f"R{fmt(fraction, 4)}"]
            else:
                words = ([code] if code != mode else []) + motion
            if kind != RAPID and (fmt(f, 1) != feed_word or (marked and not in_run)):
                feed_word = fmt(f, 1)
                words.append(f"F{feed_word}")
            if marked and not in_run:
                if mode != "G01":
                    lines.append("G01")          # the modal call is made in G01 only
                words = [f"G66.1 P{SURFACE_MACRO_PROGRAM}"] + words
                in_run = True
            lines.append(" ".join(words))
            mode = code
            last.update(axes)
        if in_run:
            lines.append("G67")
        return lines

    def header(self, program):
        surface = any(op.texture_marks is not None for op in program.operations)
        number = SURFACE_MACRO_PROGRAM if surface else MACRO_PROGRAM
        return super().header(program) + [
            f"(GOUGE TEXTURE: RANDOM DEPTHS DRAWN ON THE CONTROLLER BY O{number}: LEHMER GENERATOR "
            f"X = {LCG_MULTIPLIER} X MOD {LCG_MODULUS} IN #{LCG_STATE_VAR}, SEEDED ONCE FROM CLOCK #3001)",
            "(G66.1 ONLY ON THE G01 RASTER BLOCKS; G67 BEFORE EVERY RAPID, RETRACT AND PLUNGE)"]

    def to_text(self, program):
        main = super().to_text(program)
        texture = next(op.texture for op in program.operations if op.texture is not None)
        if any(op.texture_marks is not None for op in program.operations):
            return main[:-2] + surface_macro_program(texture, self.decimals) + "%\n"
        return main[:-2] + macro_program(texture, self.decimals) + "%\n"


def _segments(mask: np.ndarray):
    """(start, end, value) of the runs of equal values of a boolean array."""
    if not len(mask):
        return
    edges = np.flatnonzero(mask[1:] != mask[:-1]) + 1
    bounds = [0, *edges.tolist(), len(mask)]
    for lo, hi in zip(bounds[:-1], bounds[1:]):
        yield lo, hi, bool(mask[lo])


def _texture_lines(texture, n) -> list:
    return [f"#110={n(texture.base_depth)} (BASE DEPTH)",
            f"#111={n(texture.quantum)} (DEPTH QUANTUM)",
            f"#112={n(texture.amplitude)} (AMPLITUDE)",
            f"#113={n(texture.spacing)} (GOUGE SPACING ALONG X)"]


def _seed_lines() -> list:
    """Seed the generator in #115 from the clock when it holds no state (labels N7, N8)."""
    m, x = LCG_MODULUS, f"#{LCG_STATE_VAR}"
    return [f"IF[{x}LT1]GOTO7 (GENERATOR STATE VACANT OR INVALID: SEED IT)",
            f"IF[{x}GE{m}]GOTO7",
            f"IF[{x}EQFIX[{x}]]GOTO8",
            "N7",
            f"#30=#3001/{m} (SEED ONCE FROM THE MILLISECOND CLOCK)",
            f"{x}=FIX[[#30-FIX[#30]]*{m - 1}]+1",
            "N8"]


def _draw_lines() -> list:
    """Step the generator, take a digit 0..9 and put its depth in #114 (labels N3, N4)."""
    m, a, x = LCG_MODULUS, LCG_MULTIPLIER, f"#{LCG_STATE_VAR}"
    return [f"#29={a}*{x} (NEXT STATE: {a}*X MOD {m}, EXACT BELOW 1E8)",
            f"#30=FIX[#29/{m}]",
            f"{x}=#29-#30*{m}",
            f"IF[{x}LT0]THEN{x}={x}+{m}",
            f"IF[{x}GE{m}]THEN{x}={x}-{m}",
            f"#28=FIX[{x}*10/{m}] (DIGIT 0..9)",
            "IF[#28GE5]GOTO3",
            "#114=#110+#111*ROUND[#28*#112/[4*#111]] (0..4: SHALLOWER)",
            "GOTO4",
            "N3",
            "#114=#110-#111*ROUND[[#28-5]*#112/[4*#111]] (5..9: DEEPER)",
            "N4"]


def surface_macro_program(texture: GougeTexture, decimals: int = 3) -> str:
    """Program O7024: the gouge texture on a curved plate (``Operation.texture_marks``).

    Called by ``G66.1 P7024`` on the blocks of a row only (:meth:`FanucMacroPost.marked_moves`).
    The roughing path follows the surface (Z: the tool touching it) and is split where a new
    gouge begins.  Arguments (specification I): X Y Z the block's end point on the surface
    (#24 #25 #26), F (#9), R (#18) how far along the gouge's ramp (0..1) the block ends, Q1
    (#17) a new depth is drawn as the block starts, E1 (#8) the block begins a run (the depth
    starts from the base).  R, Q and E are not axis addresses on any usual machine (the old B
    and C were, on a machine with a B or C axis).  The block is cut to
    Z + #117 + (#114 - #117) * R: the depth ramps from the last gouge's (#117) to the new one
    (#114) below the surface.  A call without Z or R is not a row block: macro alarm 3002.
    """
    n = lambda value: fmt(value, decimals)  # noqa: E731
    lines = [
        f"O{SURFACE_MACRO_PROGRAM} (KEZURI GOUGE TEXTURE ON A SURFACE)",
        "IF[#26EQ#0]GOTO90 (NO Z: NOT A ROW BLOCK)",
        "IF[#18EQ#0]GOTO90 (NO RAMP POSITION R)",
        *_texture_lines(texture, n),
        "IF[#8NE1]GOTO1",
        "#114=#110 (E1: A RUN STARTS AT THE BASE DEPTH)",
        "#117=#114",
        "N1",
        "IF[#114EQ#0]GOTO90 (NO DEPTH YET: THE RUN LACKS ITS E1)",
        "IF[#17NE1]GOTO5 (NO Q1: THE SAME GOUGE)",
        "#117=#114 (THE DEPTH WHERE THIS GOUGE STARTS)",
        *_seed_lines(),
        *_draw_lines(),
        "N5",
        "G01X#24Y#25Z[#26+#117+[#114-#117]*#18]F#9",
        "GOTO30",
        "N90",
        "#3000=2 (NOT A ROW BLOCK)",
        "N30",
        "M99",
    ]
    return "\n".join(lines) + "\n"


def macro_program(texture: GougeTexture, decimals: int = 3) -> str:
    """Program O7023, called by ``G66.1 P7023`` on the raster blocks only (G01 at constant Z:
    :meth:`FanucMacroPost.confined_moves`).

    Arguments: #24/#25 = X/Y of the calling block, #9 = F.  A Y-only block is a stepover, cut at
    the current depth; an X move of the gouge spacing or less is cut at the current depth; a
    longer one is cut in pieces, a new depth at every spacing.  Every block it writes is G01: it
    is never called on a rapid, an arc or a move with Z (those are ordinary blocks after G67), so
    it reads no ``#4001`` (which modal state a macro called by G66.1 sees there is not what the
    manual's "modal information up to the preceding block" settles).  A call with Z, or with
    neither X nor Y, is not a raster block: macro alarm 3001 rather than a guess.  Commons
    #110..#114 hold the texture settings and the drawn depth, #115 the state of the digit
    generator (kept between calls and runs; seeded from #3001 when vacant).
    """
    n = lambda value: fmt(value, decimals)  # noqa: E731
    assert LCG_MULTIPLIER * (LCG_MODULUS - 1) < 10**8, "the generator's product must stay exact in 8 digits"
    lines = [
        f"O{MACRO_PROGRAM} (KEZURI GOUGE TEXTURE)",
        "IF[#26NE#0]GOTO90 (A Z WORD: NOT A RASTER BLOCK)",
        "IF[#24NE#0]GOTO1",
        "IF[#25EQ#0]GOTO90 (NEITHER X NOR Y)",
        "G01Y#25F#9 (Y ONLY: STEPOVER AT THE CURRENT DEPTH)",
        "GOTO30",
        "N1",
        *_texture_lines(texture, n),
        "#15=#5001 (X BEFORE THE BLOCK)",
        "#17=#5002 (Y BEFORE THE BLOCK)",
        "#6=#24-#15",
        "IF[ABS[#6]LE#113]GOTO10 (SHORT MOVE: AT THE CURRENT DEPTH)",
        "#8=1",
        "IF[#6GT0]GOTO2",
        "#8=-1",
        "N2",
        "#16=#15+#8*#113",
        *_seed_lines(),
        "WHILE[[#24-#16]*#8GE0]DO1",
        *_draw_lines(),
        "IF[#25EQ#0]GOTO5",
        "#33=#17+[#25-#17]*[#16-#15]/#6",
        "G01X#16Y#33Z#114F#9",
        "GOTO6",
        "N5",
        "G01X#16Z#114F#9",
        "N6",
        "#16=#16+#8*#113",
        "END1",
        "N10",
        "G01X#24Y#25F#9 (THE REST OF THE MOVE AT THE LAST DEPTH)",
        "GOTO30",
        "N90",
        "#3000=1 (NOT A RASTER BLOCK)",
        "N30",
        "M99",
    ]
    return "\n".join(lines) + "\n"
