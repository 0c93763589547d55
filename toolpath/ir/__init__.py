"""The IR: what the core hands to the posts.

:mod:`.program` is the Program and its Operations and all a post takes from the core, with
:mod:`.kinematics` (machine <-> part for rotary axes) and :mod:`.errors`; the other modules are
the IR's own parts (move kinds, tools, cycles, the gouge texture, machine profiles, the punch
program, the arc filter).
"""
