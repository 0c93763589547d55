"""Batch: one line when numba compiles one of our kernels (the first run after an install, or
after its cache was cleared), instead of seconds of silence.

An interactive Blender compiles the kernels ahead in a child process (``operators.start_warmup``);
a batch run compiles what it needs on first use.  numba reports every compile it starts through
its event API (``numba.core.event``, event "numba:compile"; a kernel found in its on-disk cache
is loaded without one).  The listener is put in when numba is imported, so a run that needs no
kernel (unfold, elbow) does not import numba for it.
"""
from __future__ import annotations

import importlib.abc
import importlib.util
import sys

MESSAGE = ("compiling the numba kernels (first run after an install only, about 2-5 s; "
           "later runs load them from numba's cache)")
PACKAGE = "kezuri."         # our kernels' modules; numba's own compiles (its helpers) are not announced


def say_when_compiling(say) -> None:
    """Call ``say`` with :data:`MESSAGE` (in the interface language) once, when numba starts compiling the first kernel of ours in this
    process; nothing when every kernel comes from the cache."""
    if _NOTICE["put"]:          # once a process (batch.main may run several times in one)
        return
    _NOTICE["put"] = True
    if "numba" in sys.modules:
        _listen(say)
        return
    try:
        found = importlib.util.find_spec("numba") is not None
    except (ImportError, ValueError):
        found = False
    if found:
        sys.meta_path.insert(0, _AfterImport("numba", lambda: _listen(say)))


_NOTICE = {"put": False}


def _listen(say) -> None:
    try:
        from numba.core import event
    except (ImportError, OSError, RuntimeError):    # no usable numba (as compiled.kernel_module): nothing compiles
        return

    class Notice(event.Listener):
        def __init__(self):
            self.said = False

        def on_start(self, ev):
            function = getattr(ev.data.get("dispatcher"), "py_func", None)
            if not self.said and getattr(function, "__module__", "").startswith(PACKAGE):
                self.said = True
                from .translations import translate_message
                say(translate_message(MESSAGE))

        def on_end(self, ev):
            pass

    event.register("numba:compile", Notice())


class _AfterImport(importlib.abc.MetaPathFinder):
    """Runs ``then`` right after the module ``name`` has been imported (once; then steps aside)."""

    def __init__(self, name: str, then):
        self.name, self.then = name, then

    def find_spec(self, fullname, path, target=None):
        if fullname != self.name:
            return None
        sys.meta_path.remove(self)
        spec = importlib.util.find_spec(fullname)
        if spec is None or spec.loader is None:
            return spec
        execute, then = spec.loader.exec_module, self.then

        def exec_module(module):
            execute(module)
            then()

        spec.loader.exec_module = exec_module
        return spec
