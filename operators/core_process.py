"""Runs one call of the pure core in a separate Python process (see ``common.ProcessJob``).

    python core_process.py PACKAGE_NAME PACKAGE_DIR CALL_FILE RESULT_FILE

CALL_FILE holds the pickled ``(module, function, kwargs)``; ``module`` is relative to the
package (e.g. "toolpath.simulate").  Progress goes to stdout as ``progress <fraction>`` lines;
the pickled ``("ok", value)`` or ``("error", exception or traceback text)`` goes to RESULT_FILE.

The package is imported under the same name as in Blender (e.g. ``bl_ext.user_default.kezuri``)
so pickled core objects mean the same classes on both sides; its parent packages are empty
stand-ins, because the real ones import bpy, which this process neither has nor needs.
"""
import importlib
import importlib.util
import os
import pickle
import sys
import traceback
import types


def import_package(name: str, folder: str):
    parts = name.split(".")
    for depth in range(1, len(parts)):
        parent = ".".join(parts[:depth])
        if parent not in sys.modules:
            stand_in = types.ModuleType(parent)
            stand_in.__path__ = []
            sys.modules[parent] = stand_in
    spec = importlib.util.spec_from_file_location(name, os.path.join(folder, "__init__.py"),
                                                  submodule_search_locations=[folder])
    package = importlib.util.module_from_spec(spec)
    sys.modules[name] = package
    spec.loader.exec_module(package)


def progress(fraction: float, text: str = ""):
    print(f"progress {float(fraction):.4f}", flush=True)


def main(package: str, folder: str, call_file: str, result_file: str) -> int:
    import_package(package, folder)
    with open(call_file, "rb") as stream:
        module, function, kwargs = pickle.load(stream)
    try:
        work = getattr(importlib.import_module(f"{package}.{module}"), function)
        outcome = ("ok", work(progress=progress, **kwargs))
    except Exception as error:  # noqa: BLE001 - every failure goes back to the parent
        error_module = type(error).__module__
        outcome = ("error", error if error_module.startswith(package) else traceback.format_exc())
    try:
        data = pickle.dumps(outcome)
    except Exception:  # noqa: BLE001 - an exception that cannot be pickled goes back as text
        data = pickle.dumps(("error", "".join(traceback.format_exception_only(outcome[1]))
                             if outcome[0] == "error" else traceback.format_exc()))
    with open(result_file, "wb") as stream:
        stream.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
