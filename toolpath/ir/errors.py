"""The one base class of every error that means "this input cannot be used".

Each workflow raises its own subclass with a message that names the object, line or value at
fault; the Blender shell and batch.py show exactly these to the user, and treat anything else
as a bug (with its traceback).  A ValueError, so plain Python callers can catch it as one.
"""


class InputError(ValueError):
    """Bad input: the message says what is wrong and where."""


class ProgramError(InputError):
    """A tool or a move that cannot be machined (no feed, NaN, a tool that does not exist)."""


# mm: 100 m, further than any machine reaches.  A part, plate, design or coordinate beyond it is
# a slip (other units, a mistyped exponent, a wrong unit scale) and is refused, never worked on.
MAX_REACH_MM = 1.0e5
