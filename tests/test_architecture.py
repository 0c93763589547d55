"""The shape of the code, checked: the core never imports bpy, posts import only the IR, the shell's
modules import each other without a circle, and no module grows past one screenful of purposes."""
import ast
import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_LINES = 800
# Flat data, not logic: the translation table and the ISO 14649 entity model may be longer.
LONG_DATA = {"operators/translations.py", "toolpath/operations/stepnc/model.py"}


def sources(folder: str) -> list:
    found = []
    for base, _, files in os.walk(os.path.join(ROOT, folder)):
        found += [os.path.relpath(os.path.join(base, f), ROOT) for f in files if f.endswith(".py")]
    return sorted(found)


def imports_of(path: str) -> list:
    """Every import in the file, function-level ones included, as (level, module, names)."""
    with open(os.path.join(ROOT, path), encoding="utf-8") as stream:
        tree = ast.parse(stream.read(), path)
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(0, alias.name, ()) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            found.append((node.level, node.module or "", tuple(alias.name for alias in node.names)))
    return found


def resolved(path: str, level: int, module: str, names: tuple) -> list:
    """Repository paths (without .py) a relative import of ``path`` reaches."""
    if level == 0:
        return []
    base = os.path.dirname(path).split(os.sep)
    base = base[:len(base) - (level - 1)] if level > 1 else base
    target = base + (module.split(".") if module else [])
    return ["/".join(target + [name]) for name in names] + ["/".join(target)]


@pytest.mark.parametrize("path", sources("toolpath") + sources("post"))
def test_the_core_never_imports_blender(path):
    modules = {module.split(".")[0] for level, module, _ in imports_of(path) if level == 0}
    assert not modules & {"bpy", "mathutils", "bmesh", "bpy_extras"}, path


def test_the_shell_has_no_import_circle():
    modules = {p[:-3] for p in sources("operators")}
    graph = {m: set() for m in modules}
    for module in modules:
        for level, name, names in imports_of(module + ".py"):
            for target in resolved(module + ".py", level, name, names):
                target = target[:-len("/__init__")] if target.endswith("/__init__") else target
                if target in modules and target != module and target != "operators/__init__":
                    graph[module].add(target)
    graph.pop("operators/__init__", None)
    state = {}

    def visit(node, trail):
        state[node] = "open"
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                raise AssertionError("import circle: " + " -> ".join(trail[trail.index(nxt):] + [nxt]))
            if nxt not in state:
                visit(nxt, trail + [nxt])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])


@pytest.mark.parametrize("path", sources("toolpath") + sources("post") + sources("operators") + ["batch.py"])
def test_no_module_is_over_800_lines(path):
    if path in LONG_DATA:
        return
    with open(os.path.join(ROOT, path), encoding="utf-8") as stream:
        lines = sum(1 for _ in stream)
    assert lines <= MAX_LINES, f"{path} has {lines} lines"
