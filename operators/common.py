"""What every Kezuri operator shares: error reporting and progress."""
from __future__ import annotations

import sys
import traceback


def user_errors():
    """Exception types whose message is meant for the user (no traceback): every input error of
    the core and the shell, and file-system errors (a missing file, a folder not writable)."""
    from ..toolpath.errors import InputError
    return (InputError, OSError)


def run_reported(operator, work):
    """Run ``work()`` for an operator; turn any failure into a report and CANCELLED.

    Input errors are shown as they are; anything else is a bug: a short message in the
    status bar and the traceback in the system console, never an exception out of execute().
    """
    from bpy.app.translations import pgettext_rpt
    try:
        return work()
    except user_errors() as error:
        operator.report({"ERROR"}, pgettext_rpt(str(error)))
    except Exception as error:  # noqa: BLE001 - the last line of defence of the UI
        traceback.print_exc(file=sys.stderr)
        operator.report({"ERROR"}, f"Kezuri internal error ({type(error).__name__}): {error}; "
                                   "details in the system console")
    return {"CANCELLED"}


class Progress:
    """Progress in the UI (window manager cursor) or as a text bar in batch mode."""

    def __init__(self, context=None, label: str = ""):
        import bpy

        self.wm = context.window_manager if (context is not None and not bpy.app.background) else None
        self.label = label
        self.last = -1
        if self.wm is not None:
            self.wm.progress_begin(0, 100)

    def __call__(self, fraction: float, text: str = ""):
        percent = int(max(0.0, min(1.0, fraction)) * 100)
        if self.wm is not None:
            self.wm.progress_update(percent)
        elif percent // 10 != self.last // 10:
            bar = "#" * (percent // 5)
            print(f"\r{self.label:<10} [{bar:<20}] {percent:3d}% {text:<30}", end="", file=sys.stderr, flush=True)
            if percent >= 100:
                print(file=sys.stderr)
        self.last = percent

    def end(self):
        if self.wm is not None:
            self.wm.progress_end()
