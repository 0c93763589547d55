"""Posts: Program (the IR) -> controller text.  Only this package writes NC.

Every module of the package is imported here, so every post class in it registers itself
(:mod:`.registry`); lookups by name and by machine family go through the registry.
"""
from __future__ import annotations

import importlib
import pkgutil

from . import registry
from .gcode import GcodePost, PostError
from .output import write_atomic
from .registry import (FAMILIES, ControllerLimits, Post, UnknownPostError, choices, create, enum_items, extension,
                       find, posts)

for _module in pkgutil.iter_modules(__path__):
    importlib.import_module(f"{__name__}.{_module.name}")


def milling_post(name: str, work_offset: str | None = None, machine=None) -> GcodePost:
    """A 3-axis milling post by name (``fanuc``, ``fanuc-macro``, ``linuxcnc``, ``grbl`` ...), for
    ``machine`` (a :class:`toolpath.ir.machine.MachineProfile`; None: the post's own default machine)."""
    return create("milling", name, work_offset=work_offset, **({} if machine is None else {"machine": machine}))


def rotary_post(name: str, work_offset: str | None = None, max_table_rpm: float | None = None, machine=None):
    """A C-X-Z rotary-table post by its choice word (``linuxcnc``, ``fanuc`` ...)."""
    options = {"work_offset": work_offset, **({} if machine is None else {"machine": machine})}
    if max_table_rpm is not None:
        options["max_table_rpm"] = max_table_rpm
    return create("cxz", name, **options)


__all__ = ["FAMILIES", "ControllerLimits", "Post", "UnknownPostError", "GcodePost", "PostError", "choices", "create",
           "enum_items", "extension", "find", "posts", "registry", "milling_post", "rotary_post", "write_atomic"]
