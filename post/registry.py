"""The post registry: every post class declares what it is, and nothing else lists posts.

A post is one file in ``post/``.  Its class says who it is for, and the registry reads that:

    class HaasPost(FanucPost):
        name = "haas"                    # unique; written in the program header
        label = "Haas (NGC)"             # what the panel shows
        label_ja = "Haas (NGC)"          # the same in Japanese (the translation table reads it)
        description = "Haas mill control, Fanuc-compatible ISO 6983"
        description_ja = "..."
        family = "milling"               # which machines (and so which workflows) it serves
        extension = ".nc"
        order = 40                       # place in the panel's list
        limits = ControllerLimits(...)   # the control's word ranges, citing its manual

Defining the class registers it (``__init_subclass__``); ``post/__init__.py`` imports every module
of the package, so a new file needs no other edit: the panel's enums, batch's ``--post`` choices,
export file names and the preferences all ask the registry.  Classes without a ``label`` of their
own (shared writers such as :class:`GcodePost`) are not posts a user can pick.

``choice`` is what a user types for the post within its family (``batch.py rotary --post fanuc``
picks the C-X-Z Fanuc post); it defaults to ``name``.
"""
from __future__ import annotations

import zlib
from dataclasses import dataclass

from ..toolpath.ir.program import default_machine as family_machine
from ..toolpath.ir.errors import InputError

# Machine families: the kind of machine a post's program runs on.
FAMILIES = {
    "milling": "3-axis milling machine or router (X Y Z)",
    "cxz": "rotary table turning the part on C, tool moving in X and Z",
    "xzc": "turn-mill centre (X Z C, driven tools on the turret)",
    "punch": "turret punch press",
    "cldata": "APT cutter-location data for a post-processor",
}


class PostError(InputError):
    """A program the chosen controller cannot run (the message says why and what to change)."""


class UnknownPostError(PostError):
    """A post name that no registered post has (the message lists those that exist)."""


@dataclass(frozen=True)
class ControllerLimits:
    """What the control accepts, per word (inclusive ranges, mm and mm/min), and where it is written.

    ``None`` means the control sets no limit we know of.  ``source`` cites the manual (or manuals)
    the numbers come from.  The posts check the words they write against these
    (:meth:`check_word`); ``tool_change``, ``program_start`` and ``program_end`` describe the
    sequences the post writes, for the header of the file and for the reader.
    """

    feed_per_minute: tuple | None = None        # F under G94 (mm/min)
    inverse_time_feed: tuple | None = None      # F under G93 (1/min)
    feed_per_rev: tuple | None = None           # F under G95 (mm/rev)
    spindle_rpm: tuple | None = None            # S
    tool_number: tuple | None = None            # T
    length_offset: tuple | None = None          # H (tool length offset number)
    sequence_number: tuple | None = None        # N
    program_number: tuple | None = None         # O
    coordinate: float | None = None             # largest |X|, |Y|, |Z| the word format holds (mm)
    resolution: float = 0.001                   # least input increment (mm)
    decimal_point: bool = False                 # every axis and F word needs a decimal point
    inverse_time_every_block: bool = True       # G93: every G1/G2/G3 block carries its own F
    tool_changer: bool = True                   # M06 changes the tool
    tool_change: tuple = ()                     # the safe sequence before the cutting starts
    program_start: tuple = ()
    program_end: tuple = ()
    source: str = ""
    max_line_length: int | None = None          # characters a line may hold (None: no limit we know of)
    line_length_source: str = ""                # where that number comes from
    arc_end_tolerance: float | None = None      # mm: the most an arc's start and end radii may differ before the
                                                # control alarms (None: the post writes no fitted arcs)
    arc_source: str = ""                        # where that number comes from

    def check_word(self, word: str, value: float, where: str) -> None:
        """Raise :class:`PostError` when ``value`` of ``word`` (a field name above) is outside the
        control's range; ``where`` names the operation and move for the message."""
        bounds = getattr(self, word)
        if bounds is None:
            return
        low, high = (-bounds, bounds) if word == "coordinate" else bounds
        if not low <= value <= high:
            raise PostError(f"{where}: {WORD_NAMES[word]} {value:.10g} is outside the {low:.10g}..{high:.10g} the "
                            f"control accepts ({self.source.split(':')[0]})")


WORD_NAMES = {"feed_per_minute": "feed F (mm/min)", "inverse_time_feed": "inverse-time feed F (G93, 1/min)",
              "feed_per_rev": "feed F (mm/rev)", "spindle_rpm": "spindle speed S", "tool_number": "tool number T",
              "length_offset": "length offset H", "sequence_number": "sequence number N",
              "program_number": "program number O", "coordinate": "coordinate"}


class Post:
    """Mixed into every post class: the declarations the registry reads."""

    name: str = ""
    choice: str = ""
    label: str = ""
    label_ja: str = ""
    description: str = ""
    description_ja: str = ""
    family: str = ""
    extension: str = ".nc"
    order: int = 100
    needs_texture: bool = False       # writes only programs that carry a gouge texture (the macro post)
    default_machine: str = ""         # the machine preset (toolpath.ir.machine) a user who picks only the post
                                      # gets; empty: the family's (machine.DEFAULT_FOR_FAMILY)
    limits: ControllerLimits = ControllerLimits()

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "label" in cls.__dict__:
            register(cls)


_POSTS: dict = {}


def key_of(cls) -> str:
    return cls.choice or cls.name


def register(cls) -> type:
    """Add a post class (called for every subclass of :class:`Post` that declares a label)."""
    problems = [what for what, ok in (("a name", bool(cls.name)), ("a known family", cls.family in FAMILIES),
                                      ("an extension starting with '.'", cls.extension.startswith(".")))
                if not ok]
    if problems:
        raise TypeError(f"post class {cls.__qualname__} needs {', '.join(problems)}")
    for other in _POSTS.values():
        same_class = (other.__module__, other.__qualname__) == (cls.__module__, cls.__qualname__)  # a reload
        if other is not cls and not same_class and (
                other.name == cls.name or (other.family == cls.family and key_of(other) == key_of(cls))):
            raise TypeError(f"post {cls.name!r} ({cls.family}, {key_of(cls)!r}) is already registered "
                            f"by {other.__module__}.{other.__qualname__}")
    _POSTS[cls.name] = cls
    return cls


def unregister(cls) -> None:
    if _POSTS.get(cls.name) is cls:
        del _POSTS[cls.name]


def posts(families=None, *, texture: bool | None = None) -> list:
    """Registered post classes, in the panel's order; ``families``: one family or several;
    ``texture=False`` leaves out posts that need a gouge texture."""
    if isinstance(families, str):
        families = (families,)
    found = [cls for cls in _POSTS.values() if families is None or cls.family in families]
    if texture is False:
        found = [cls for cls in found if not cls.needs_texture]
    return sorted(found, key=lambda cls: (tuple(families or ()).index(cls.family) if families else 0, cls.order,
                                          cls.name))


def choices(families, *, texture: bool | None = None) -> list:
    """What a user may type for ``--post`` in these families."""
    return [key_of(cls) for cls in posts(families, texture=texture)]


def find(families, choice: str, *, texture: bool | None = None):
    """The post class a user means by ``choice`` (its choice word or its unique name)."""
    candidates = posts(families, texture=texture)
    for cls in candidates:
        if choice in (key_of(cls), cls.name):
            return cls
    names = ", ".join(key_of(cls) for cls in candidates)
    raise UnknownPostError(f"unknown post {choice!r}; choose one of {names}")


def default_machine(cls):
    """The machine profile a post's program assumes when the user picks only the post (None for a
    family without machines, e.g. CL data)."""
    return family_machine(cls.family, cls.default_machine)


def create(families, choice: str, **options):
    """An instance of the post ``choice`` of ``families``, built with ``options``."""
    return find(families, choice)(**options)


def extension(families, choice: str) -> str:
    return find(families, choice).extension


def enum_number(choice: str) -> int:
    """A stable number for a post in a Blender enum: saved files keep pointing at the same post
    when posts are added or reordered (Blender stores dynamic enum values as numbers)."""
    return zlib.crc32(choice.encode()) & 0x3FFFFFFF or 1


def enum_items(families, *, texture: bool | None = None, first: tuple = ()) -> list:
    """Blender enum items ``(identifier, label, description, icon, number)`` for these families;
    ``first``: extra items ``(identifier, label, description)`` put before the posts (number 0..)."""
    items = [(identifier, label, description, "NONE", number)
             for number, (identifier, label, description) in enumerate(first)]
    items += [(key_of(cls), cls.label, cls.description, "NONE", enum_number(key_of(cls)))
              for cls in posts(families, texture=texture)]
    return items
