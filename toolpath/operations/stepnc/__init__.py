"""ISO 14649 (STEP-NC) to ISO 6983 G-code (W3).

part21    the ISO 10303-21 values and reader (part21_writer: the writer)
model     ISO 14649-10/-11 entities as a small typed model: the project and workplan; its parts in
          geometry, features and process (operations, tools, strategies); errors (the two troubles)
loaded    a file read into the model (reader; coordinates: a POLYLINE's points at once)
workplan  workplan -> Program (reorderable workingsteps); motion (approaches, layers, retracts),
          technology (speeds and feeds), inprocess (the material left, for approaches;
          inprocess_kernel: its compiled column lowering)
pockets   pockets -> Part 21
"""
from .errors import StepNcError  # noqa: F401
from .part21 import Part21Error, parse_part21, read_part21  # noqa: F401
from .part21_writer import write_part21  # noqa: F401
from .workplan import PocketSpec, load_workplan, nothing_to_machine, pockets_to_part21, to_program
