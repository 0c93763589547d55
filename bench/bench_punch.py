"""W5: the turret-punch simulation (core only): a 60-piece pipe elbow of 400 mm diameter, every
piece's program punched out of its blank, and one program at the 20,000-hit limit.

Before the hits of a line were united in closed form (toolpath/operations/sheetmetal/punch.py ``_chain``) every hit was a
polygon of its own in the union: on 2026-11-27 the elbow took 48 s
(and batch punched every piece twice).  Since issue 26 each piece is placed on the sheet with two
micro-joints, and the simulation also releases the part at its joints (one more boolean a piece).
Since issue 32 a program lying along X is punched turned a quarter (the booleans sweep along Y):
the elbow's pieces, 1257 mm along X, took 6.1 s CPU before (495f8bd, same run, load 3-4: 1.7 s)."""
from __future__ import annotations

from timing import best_of


def elbow_programs(diameter: float = 400.0, pieces: int = 60, punch_diameter: float = 10.0,
                   pitch: float = 2.0) -> list:
    """(NC text, flat pattern, micro-joints) of every piece, as the elbow export writes them: each
    placed on the Amada 04P preset's sheet clear of the clamps, nibbled with merged lines, each hit
    once, and two micro-joints."""
    from kezuri.post import amada_punch
    from kezuri.toolpath.ir import machine
    from kezuri.toolpath.operations.sheetmetal import nibbling, placement, unfold

    # the 400 mm pipe's pattern is 1257 mm round: a 2500 x 1250 sheet (the 1270 mm preset's is too narrow)
    profile = machine.preset("amada-04p").replace(sheet_max=(2500.0, 1250.0))
    elbow = unfold.unfold_elbow(90.0, 3000.0, diameter, pieces)
    out = []
    for piece in elbow.pieces:
        outline = piece.outline - piece.outline.min(axis=0)
        contour = unfold.compensate_outline(outline, punch_diameter)
        where = placement.place(contour, punch_diameter, profile)
        lines = nibbling.nibble(contour, pitch, punch_diameter).moved(where.offset)
        text = amada_punch.AmadaPunchPost().to_text(placement.program(where, lines, 302, 1.6, profile))
        out.append((text, outline + where.offset, lines.joints))
    return out


def square_program(side: float = 499.0, pitch: float = 0.1) -> str:
    """Four nibbling lines round a square, 4 x 4991 hits."""
    lines = ["N000 G92 X1000.00 Y1040.00", "N001 G72 X0.00 Y0.00"]
    for index, angle in enumerate((0.0, 90.0, 180.0, -90.0)):
        if index:
            corner = [(side, 0.0), (side, side), (0.0, side)][index - 1]
            lines.append(f"N{index + 1:03d} G72 X{corner[0]:.2f} Y{corner[1]:.2f}")
        lines.append(f"G69 I{side:.2f} J{angle:.2f} P0.00 Q{pitch:.2f} T302")
    return "\n".join(lines + ["G50"]) + "\n"


def run():
    from kezuri.toolpath.operations.sheetmetal import punch

    programs = elbow_programs()
    hits = sum(len(punch.read_amada(text).hits) for text, _, _ in programs)

    def elbow():
        for text, outline, joints in programs:
            result = punch.simulate_punching(text, punch_diameter=10.0, pattern=outline, joints=joints)
            assert result.held_by_joints

    square = square_program()
    square_hits = len(punch.read_amada(square).hits)
    return [
        {"name": "punch: 60-piece elbow, 400 mm pipe, every piece punched", "seconds": best_of(3, elbow),
         "target_s": 5.0, "notes": f"{len(programs)} programs, {hits} hits; before (every hit its own polygon): 48 s; "
                  "before the quarter turn: 6.1 s CPU at load 3-4 (1.7 s the same run)"},
        {"name": f"punch: one program of {square_hits} hits on 4 lines", "seconds":
         best_of(3, lambda: punch.simulate_punching(square, punch_diameter=5.0)), "target_s": 5.0,
         "notes": "the hit limit is 20,000 a program"},
    ]
