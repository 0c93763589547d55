"""ISO 14649 (STEP-NC) support.  So far: the ISO 10303-21 (Part 21) reader and writer."""
from .part21 import (  # noqa: F401
    DERIVED, UNKNOWN, UNSET, ComplexInstance, Derived, Entity, Enum, Instance, Part21Error,
    Part21File, Part21Writer, Ref, Typed, Unset, format_real, format_string, format_value,
    iter_refs, make_header, parse_part21, read_part21, write_part21,
)
