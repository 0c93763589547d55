"""Load the repository root as the package ``kezuri`` (as Blender loads the extension), so
the tests import exactly what users run: ``kezuri.toolpath``, ``kezuri.post``, ``kezuri.operators``."""
import importlib.util
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
if HERE not in sys.path:
    sys.path.insert(0, HERE)
pytest_plugins = ["blender_helpers"]    # the empty_scene fixture
if "kezuri" not in sys.modules:
    spec = importlib.util.spec_from_file_location("kezuri", os.path.join(ROOT, "__init__.py"),
                                                  submodule_search_locations=[ROOT])
    package = importlib.util.module_from_spec(spec)
    sys.modules["kezuri"] = package
    spec.loader.exec_module(package)
