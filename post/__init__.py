"""Posts: Program (the IR) -> controller text.  Only this package writes NC."""
from __future__ import annotations

from .fanuc import FanucMacroPost, FanucPost
from .gcode import GcodePost, PostError
from .grbl import GrblPost
from .linuxcnc import LinuxCNCPost
from .output import write_atomic
from .rotary_cxz import ROTARY_POSTS, rotary_post
from .turnmill_xzc import TurnMillLinuxCNCPost, TurnMillXZCPost

MILLING_POSTS = {"fanuc": FanucPost, "fanuc-macro": FanucMacroPost, "linuxcnc": LinuxCNCPost, "grbl": GrblPost}


def milling_post(name: str, work_offset: str | None = None) -> GcodePost:
    try:
        return MILLING_POSTS[name](work_offset)
    except KeyError:
        raise PostError(f"unknown post {name!r}; choose one of {', '.join(MILLING_POSTS)}") from None


__all__ = ["MILLING_POSTS", "milling_post", "ROTARY_POSTS", "rotary_post", "TurnMillXZCPost", "TurnMillLinuxCNCPost",
           "PostError", "write_atomic"]
