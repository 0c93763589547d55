"""What a posted program asks of the control that stores and runs it, against the machine profile.

Read from the program's text after posting, so it holds for every post alike:

* **Size**: a control that keeps its programs in memory (a Fanuc 0i: 512 kB of part program
  storage, :attr:`toolpath.ir.machine.MachineProfile.memory_kb`) cannot load a larger one; it must be
  run from a memory card or DNC, or split.  The size is the text's bytes (one per character, the
  end of block one), in kB of 1024 bytes.
* **Block time**: a control reads and plans each block in a fixed time (``block_ms``: 7.5 ms for
  the 0i-T preset); a block that takes less starves it, and the machine slows or stutters.  An
  inverse-time block (G93) states its time in its F word, F = 1 / minutes, so each one is timed
  from the text: minutes = 1 / F.  (Per-minute blocks would need their lengths; the planners that
  write G93 are the ones that make such short blocks, the C-axis moves.)

:func:`program_findings` returns the findings as sentences naming both numbers; the exports add
them to their report, print them in batch and show them in the panel.
"""
from __future__ import annotations

import re

WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")
COMMENT = re.compile(r"\([^)]*\)|;.*$")
MOTION = {"0", "00", "1", "01", "2", "02", "3", "03"}


def program_kb(text: str) -> float:
    """The program's size in kB (1024 bytes), as the control stores it: one byte a character."""
    return len(text.encode("ascii", "replace")) / 1024.0


def inverse_time_blocks(text: str) -> list:
    """(line number, minutes) of every cutting block under G93, from its F word (1 / minutes)."""
    found, inverse, motion = [], False, None
    for number, line in enumerate(text.splitlines(), start=1):
        bare = COMMENT.sub("", line).upper()
        words = WORD.findall(bare)
        for letter, value in words:
            if letter == "G":
                code = value.lstrip("+")
                if code in ("93", "93."):
                    inverse = True
                elif code in ("94", "94.", "95", "98", "99"):
                    inverse = False
                elif code in MOTION:
                    motion = int(float(code))
        letters = dict((letter, value) for letter, value in words if letter not in "GM")
        moves = any(axis in letters for axis in "XYZABCUVW")
        if inverse and moves and motion in (1, 2, 3) and "F" in letters and float(letters["F"]) > 0:
            found.append((number, 1.0 / float(letters["F"])))
    return found


def short_blocks(text: str, block_ms: float) -> list:
    """Line numbers of the G93 blocks that take less than ``block_ms`` milliseconds."""
    return [number for number, minutes in inverse_time_blocks(text) if minutes * 60000.0 < block_ms]


def program_findings(text: str, profile, what: str = "the program") -> list:
    """Sentences for what the machine of ``profile`` cannot take of ``text``: a size past its
    program memory, blocks shorter than its block processing time (an empty list: none, or no
    profile)."""
    if profile is None:
        return []
    found = []
    if profile.memory_kb is not None:
        size = program_kb(text)
        if size > profile.memory_kb:
            found.append(f"{what} is {size:,.1f} kB, larger than the {profile.memory_kb:g} kB program memory of "
                         f"{profile.label}: run it from a memory card or DNC, or split it")
    if profile.block_ms is not None:
        short = short_blocks(text, profile.block_ms)
        if short:
            found.append(f"{what} has {len(short):,} inverse-time blocks shorter than the {profile.block_ms:g} ms "
                         f"{profile.label} takes to process a block (first on line {short[0]}): the feed drops there")
    return found
