"""Load the repository root as the package ``kezuri`` (as Blender loads the extension), so
the tests import exactly what users run: ``kezuri.toolpath``, ``kezuri.post``, ``kezuri.operators``."""
import importlib.util
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
for path in (HERE, ROOT):  # ROOT: transitional, until every test imports through ``kezuri``
    if path not in sys.path:
        sys.path.insert(0, path)
if "kezuri" not in sys.modules:
    spec = importlib.util.spec_from_file_location("kezuri", os.path.join(ROOT, "__init__.py"),
                                                  submodule_search_locations=[ROOT])
    package = importlib.util.module_from_spec(spec)
    sys.modules["kezuri"] = package
    spec.loader.exec_module(package)
