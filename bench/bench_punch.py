"""W5: the turret-punch simulation (core only): a 60-piece pipe elbow of 400 mm diameter, every
piece's program punched out of its blank, and one program at the 20,000-hit limit.

Before the hits of a line were united in closed form (toolpath/punch.py ``_chain``) every hit was a
polygon of its own in the union: on 2026-11-27 the elbow took 48 s
(and batch punched every piece twice)."""
from __future__ import annotations

from timing import best_of


def elbow_programs(diameter: float = 400.0, pieces: int = 60, punch_diameter: float = 10.0,
                   pitch: float = 2.0) -> list:
    """(NC text, flat pattern) of every piece, as the elbow export writes them."""
    from kezuri.post import amada_punch
    from kezuri.toolpath import unfold

    elbow = unfold.unfold_elbow(90.0, 3000.0, diameter, pieces)
    return [(amada_punch.to_text(unfold.compensate_outline(piece.outline, punch_diameter), station=302,
                                 pitch=pitch, thickness=1.6), piece.outline) for piece in elbow.pieces]


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
    from kezuri.toolpath import punch

    programs = elbow_programs()
    hits = sum(len(punch.read_amada(text).hits) for text, _ in programs)

    def elbow():
        for text, outline in programs:
            punch.simulate_punching(text, punch_diameter=10.0, pattern=outline)

    square = square_program()
    square_hits = len(punch.read_amada(square).hits)
    return [
        {"name": "punch: 60-piece elbow, 400 mm pipe, every piece punched", "seconds": best_of(3, elbow),
         "target_s": 5.0, "notes": f"{len(programs)} programs, {hits} hits; before (every hit its own polygon): 48 s"},
        {"name": f"punch: one program of {square_hits} hits on 4 lines", "seconds":
         best_of(3, lambda: punch.simulate_punching(square, punch_diameter=5.0)), "target_s": 5.0,
         "notes": "the hit limit is 20,000 a program"},
    ]
