"""What every Kezuri operator shares: error reporting and progress."""
from __future__ import annotations

import sys
import traceback

from .translations import translate_message


def user_errors():
    """Exception types whose message is meant for the user (no traceback): every input error of
    the core and the shell, and file-system errors (a missing file, a folder not writable)."""
    from ..toolpath.ir.errors import InputError
    return (InputError, OSError)


def blender_path(path: str) -> str:
    """An operator's file path as the file system knows it: Blender's ``//`` (relative to the saved
    .blend) resolved; before, ``//job.nc`` was taken as ``/job.nc`` in the file-system root.  An
    empty path, or ``//`` in a .blend never saved, is refused."""
    import bpy

    from .convert import SceneInputError
    if not path.strip():
        raise SceneInputError("no file given: the file path is empty")
    if path.startswith("//"):
        if not bpy.data.filepath:
            raise SceneInputError(f"{path}: a path relative to the .blend file ('//') needs the .blend saved first")
        return bpy.path.abspath(path)
    return path


def run_reported(operator, work):
    """Run ``work()`` for an operator; turn any failure into a report and CANCELLED.

    Input errors are shown as they are; anything else is a bug: a short message in the
    status bar and the traceback in the system console, never an exception out of execute().
    """
    try:
        if isinstance(getattr(operator, "filepath", None), str):    # import and export operators
            operator.filepath = blender_path(operator.filepath)
        return work()
    except user_errors() as error:
        operator.report({"ERROR"}, translate_message(str(error)))
    except Exception as error:  # noqa: BLE001 - the last line of defence of the UI
        traceback.print_exc(file=sys.stderr)
        operator.report({"ERROR"}, translate_message(f"Kezuri internal error ({type(error).__name__}): {error}; "
                                   "details in the system console"))
    return {"CANCELLED"}


class Progress:
    """Progress in the UI (window manager cursor) or as a text bar in batch mode."""

    line_open = False       # batch: a bar is on stderr's last line, not ended (a message starts a new one)
    checkpoint = None       # batch: called at every update; raises to stop the run (a signal whose stop was lost)

    def __init__(self, context=None, label: str = ""):
        import bpy

        self.wm = context.window_manager if (context is not None and not bpy.app.background) else None
        self.label = label
        self.last = -1
        if self.wm is not None:
            self.wm.progress_begin(0, 100)

    def __call__(self, fraction: float, text: str = ""):
        if self.wm is None and Progress.checkpoint is not None:
            Progress.checkpoint()
        percent = int(max(0.0, min(1.0, fraction)) * 100)
        if self.wm is not None:
            self.wm.progress_update(percent)
        elif percent // 10 != self.last // 10:
            bar = "#" * (percent // 5)
            print(f"\r{self.label:<10} [{bar:<20}] {percent:3d}% {text:<30}", end="", file=sys.stderr, flush=True)
            Progress.line_open = True
            if percent >= 100:
                print(file=sys.stderr)
                Progress.line_open = False
        self.last = percent

    def end(self):
        if self.wm is not None:
            self.wm.progress_end()


class JobCancelled(Exception):
    """Raised inside a stepped job's work when the user pressed Esc."""


class SteppedJob:
    """Run ``compute(progress)`` a step at a time from Blender's main thread.

    The work runs on a worker thread, but only while the main thread waits for it in
    :meth:`step`: at its next progress call after ``step_seconds`` the worker parks and hands
    control back.  So the two threads never run Python at the same time, the work needs no
    locking, and native code that holds the GIL (manifold3d) cannot freeze the UI for longer
    than one step.  ``compute`` must not touch Blender data: read the scene before, write it
    after (:class:`SteppedOperator` does both on the main thread)."""

    def __init__(self, compute, step_seconds: float = 0.08):
        import threading

        self.compute = compute
        self.step_seconds = step_seconds
        self.fraction, self.text = 0.0, ""
        self.done = False
        self.cancelled = False
        self._result = self._error = None
        self._resume = threading.Event()
        self._parked = threading.Event()
        self._thread = threading.Thread(target=self._work, name="kezuri-job", daemon=True)
        self._step_started = 0.0
        self._started = False

    def _progress(self, fraction: float, text: str = ""):
        import time

        self.fraction, self.text = float(fraction), text or self.text
        if self.cancelled:
            raise JobCancelled()
        if time.perf_counter() - self._step_started >= self.step_seconds:
            self._park()
            if self.cancelled:
                raise JobCancelled()

    def _park(self):
        import time

        self._resume.clear()
        self._parked.set()
        self._resume.wait()
        self._step_started = time.perf_counter()

    def _work(self):
        import time

        self._resume.wait()
        self._step_started = time.perf_counter()
        try:
            self._result = self.compute(self._progress)
        except JobCancelled:
            pass
        except BaseException as error:  # noqa: BLE001 - handed to the main thread by result()
            self._error = error
        finally:
            self.done = True
            self._parked.set()

    def step(self) -> bool:
        """Let the work run for about one step; True once it has finished (or failed)."""
        if self.done:
            return True
        self._parked.clear()
        if not self._started:
            self._started = True
            self._thread.start()
        self._resume.set()
        self._parked.wait()
        return self.done

    def cancel(self):
        """Stop the work at its next progress call and wait for the worker to end."""
        self.cancelled = True
        if self._started and not self.done:
            while not self.step():
                pass
        self.done = True

    def result(self):
        """The work's return value; its exception is raised here, on the calling thread."""
        if self._error is not None:
            raise self._error
        return self._result


class SteppedOperator:
    """Mix-in for operators whose work takes long (texture jobs, classification, simulation).

    Subclasses define ``prepare(context)`` (main thread: read the scene, return a
    ``compute(progress)`` callable that touches no Blender data, or a :class:`CoreCall` to run
    in a separate process) and ``finish(context, result)``
    (main thread: add the result to the scene, report, return the operator's result set).
    Invoked from the UI the work runs in steps from a timer with a progress bar and Esc to
    cancel; nothing is added to the scene before it has finished, so a cancelled job leaves
    nothing behind.  Run from a script or in background mode, ``execute`` does it all at once.
    """

    progress_label = "Kezuri"
    _timer = None
    _job = None
    running = set()      # bl_idnames of the stepped jobs now running (one of each at a time)

    def execute(self, context):
        def work():
            compute = self.prepare(context)
            progress = Progress(context, self.progress_label)
            try:
                result = compute(progress)
            finally:
                progress.end()
            return self.finish(context, result)
        return run_reported(self, work)

    def invoke(self, context, event):
        return self.start_stepped(context)

    def start_stepped(self, context):
        """From the UI: the work in steps from a timer, Esc to cancel (returns RUNNING_MODAL); in
        background mode or without a window: :meth:`execute`, all at once."""
        import bpy

        if bpy.app.background or context.window is None:
            return SteppedOperator.execute(self, context)
        if self.bl_idname in SteppedOperator.running:
            self.report({"WARNING"},
                        translate_message("This job is already running: wait for it or press Esc to cancel it"))
            return {"CANCELLED"}

        def start():
            compute = self.prepare(context)
            self._job = ProcessJob(compute) if isinstance(compute, CoreCall) else SteppedJob(compute)
            wm = context.window_manager
            self._timer = wm.event_timer_add(0.02, window=context.window)
            wm.modal_handler_add(self)
            wm.progress_begin(0, 100)
            SteppedOperator.running.add(self.bl_idname)
            self._status(context)
            return {"RUNNING_MODAL"}
        return run_reported(self, start)

    def modal(self, context, event):
        if event.type == "ESC" and event.value == "PRESS":
            self._job.cancel()
            self._end(context)
            self.report({"INFO"}, translate_message("Cancelled: the scene is as it was"))
            return {"CANCELLED"}
        if event.type != "TIMER":      # (Blender's Event does not say whose timer fired: any will do)
            return {"PASS_THROUGH"}
        if not self._job.step():
            context.window_manager.progress_update(int(self._job.fraction * 100))
            self._status(context)
            return {"RUNNING_MODAL"}
        self._end(context)
        job = self._job
        return run_reported(self, lambda: self.finish(context, job.result()))

    def _status(self, context):
        if context.workspace is not None:
            context.workspace.status_text_set(status_line(self.bl_label, self._job.fraction, self._job.text))

    def _end(self, context):
        wm = context.window_manager
        if self._timer is not None:
            wm.event_timer_remove(self._timer)
            self._timer = None
        wm.progress_end()
        if context.workspace is not None:
            context.workspace.status_text_set(None)
        SteppedOperator.running.discard(self.bl_idname)


def status_line(label: str, fraction: float, text: str) -> str:
    """The status bar's line of a stepped job: its operator's label, the percent done and the
    stage its work reports ("planning", "checking" ...), each in the interface language."""
    from bpy.app.translations import pgettext_iface as iface

    stage = translate_message(text) if text else ""
    return f"{iface(label)}: {int(fraction * 100)}%  {stage}   ({iface('Esc to cancel')})"


class CoreCall:
    """A call of a pure-core function (``module`` relative to the package, e.g.
    "toolpath.simulate") with picklable keyword arguments; ``then`` turns its result into what
    the operator finishes with.  Called directly it runs here; :class:`ProcessJob` runs it in a
    separate process instead, for native work that holds Python's GIL (manifold3d booleans),
    which no thread of Blender's could interrupt."""

    def __init__(self, module: str, function: str, kwargs: dict, then=None):
        self.module, self.function, self.kwargs = module, function, kwargs
        self.then = then if then is not None else (lambda result: result)

    def __call__(self, progress=None):
        import importlib

        work = getattr(importlib.import_module(f"{package_name()}.{self.module}"), self.function)
        return self.then(work(progress=progress, **self.kwargs))


def package_name() -> str:
    return __package__.rsplit(".", 1)[0]


class ProcessJob:
    """A :class:`CoreCall` in a child Python process, with :class:`SteppedJob`'s interface:
    ``step()`` only looks at the child's progress (the UI never waits for the work), ``cancel()``
    ends the child, ``result()`` unpickles what it sent back (its input errors are raised
    here as they are)."""

    def __init__(self, call: CoreCall):
        import os
        import pickle
        import subprocess
        import sys
        import tempfile
        import threading

        self.call = call
        self.fraction, self.text = 0.0, ""
        self.done = self.cancelled = False
        self._folder = tempfile.mkdtemp(prefix="kezuri-job-")
        call_file = os.path.join(self._folder, "call.pickle")
        self._result_file = os.path.join(self._folder, "result.pickle")
        with open(call_file, "wb") as stream:
            pickle.dump((call.module, call.function, call.kwargs), stream)
        package_dir = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
        # sys.executable is Blender's own bundled Python (since 2.91); under the bpy wheel, the venv's.
        self._process = subprocess.Popen(
            [sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "core_process.py"),
             package_name(), package_dir, call_file, self._result_file],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        self._stderr = []
        threading.Thread(target=self._read_progress, daemon=True).start()
        threading.Thread(target=lambda: self._stderr.extend(self._process.stderr), daemon=True).start()

    def _read_progress(self):
        for line in self._process.stdout:
            if line.startswith("progress "):
                self.fraction = float(line.split()[1])

    def step(self) -> bool:
        if not self.done and self._process.poll() is not None:
            self.done = True
        return self.done

    def cancel(self):
        self.cancelled = True
        if self._process.poll() is None:
            self._process.terminate()
            self._process.wait()
        self.done = True
        self._clean()

    def result(self):
        import os
        import pickle

        self._process.wait()
        try:
            if self.cancelled:
                return None
            if not os.path.isfile(self._result_file):
                raise RuntimeError(f"the Kezuri worker process ended with status {self._process.returncode}: "
                                   + "".join(self._stderr)[-2000:])
            with open(self._result_file, "rb") as stream:
                status, value = pickle.load(stream)
        finally:
            self._clean()
        if status == "error":
            raise value if isinstance(value, BaseException) else RuntimeError(value)
        return self.call.then(value)

    def _clean(self):
        import shutil

        shutil.rmtree(self._folder, ignore_errors=True)
