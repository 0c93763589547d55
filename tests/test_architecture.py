"""The shape of the code, checked: the core never imports bpy, no module takes another's private names,
our modules import each other without a circle (function-level imports included), the core keeps no
module state between calls, and no module grows past one screenful of purposes."""
import ast
import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_LINES = 800
# Flat data, not logic: the translation table may be longer.
LONG_DATA = {"operators/translations.py"}


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


@pytest.mark.parametrize("path", sources("toolpath") + sources("post"))
def test_the_core_never_imports_blender(path):
    modules = {module.split(".")[0] for level, module, _ in imports_of(path) if level == 0}
    assert not modules & {"bpy", "mathutils", "bmesh", "bpy_extras"}, path


OURS = ("toolpath", "post", "operators")


def module_of(path: str) -> str:
    """The module a file is, as a repository path without .py; a package is its folder."""
    name = path[:-3]
    return name[:-len("/__init__")] if name.endswith("/__init__") else name


MODULES = {module_of(p) for folder in OURS for p in sources(folder)}


def private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def reached(path: str, node) -> list:
    """What an import statement of ``path`` takes from our modules: (module, name) pairs, name None
    where the statement takes the module itself (``from . import stock`` gives ("...simulate/stock",
    None)).  A package is reached only for the names it defines or re-exports, not for its
    submodules: importing ``simulate.api`` does not make an edge to ``simulate/__init__``."""
    if isinstance(node, ast.Import):
        found = []
        for alias in node.names:
            parts = alias.name.split(".")
            if parts[0] in OURS:
                found.append(("/".join(parts), None))
        return found
    if node.level:
        base = module_of(path).split("/") if path.endswith("__init__.py") else path[:-3].split("/")[:-1]
        base = base[:len(base) - (node.level - 1)]
    else:
        base = []
    parts = base + (node.module.split(".") if node.module else [])
    target = "/".join(parts)
    if parts and target not in MODULES:
        return []                                   # not ours (numpy, manifold3d ...)
    found = []
    for alias in node.names:
        inner = "/".join(parts + [alias.name])
        if inner in MODULES:
            found.append((inner, None))
        elif parts:
            found.append((target, alias.name))
    return found


def parsed(path: str):
    with open(os.path.join(ROOT, path), encoding="utf-8") as stream:
        return ast.parse(stream.read(), path)


def private_uses(path: str, source: str | None = None) -> list:
    """Private names of another of our modules that ``path`` (or ``source`` read as that file) uses:
    ``from .stock import _grid``, or ``stock._grid`` / ``simulate.checks._mesh_top`` through a name
    bound to one of our modules (function-level imports included)."""
    tree = parsed(path) if source is None else ast.parse(source, path)
    own = module_of(path)
    found = []
    bound = {}                               # local name -> our module it stands for
    for node in ast.walk(tree):
        if not isinstance(node, (ast.Import, ast.ImportFrom)):
            continue
        for (module, name), alias in zip(reached(path, node), node.names):
            if name is not None and private(name) and module != own:
                found.append(f"{path}:{node.lineno} imports {name} from {module}")
            if name is None:
                if isinstance(node, ast.Import):
                    bound[alias.asname or alias.name.split(".")[0]] = alias.asname and module or alias.name.split(".")[0]
                else:
                    bound[alias.asname or alias.name] = module

    def module_named(expr):
        if isinstance(expr, ast.Name):
            return bound.get(expr.id)
        if isinstance(expr, ast.Attribute):
            outer = module_named(expr.value)
            if outer is not None and outer + "/" + expr.attr in MODULES:
                return outer + "/" + expr.attr
        return None

    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and private(node.attr):
            module = module_named(node.value)
            if module is not None and module != own:
                found.append(f"{path}:{node.lineno} uses {module}.{node.attr}")
    return found


def import_graph(folders) -> dict:
    """Module -> the modules of ours it imports (at any level of the file)."""
    graph = {}
    for folder in folders:
        for path in sources(folder):
            module = module_of(path)
            graph.setdefault(module, set())
            for node in ast.walk(parsed(path)):
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    graph[module] |= {target for target, _ in reached(path, node) if target != module}
    return graph


def circle(graph: dict):
    """One import circle of the graph as a list of modules (first == last), or None."""
    state = {}

    def visit(node, trail):
        state[node] = "open"
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                return trail[trail.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt, trail + [nxt])
                if found:
                    return found
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node, [node])
            if found:
                return found
    return None


def test_the_checks_see_what_they_look_for():
    """The checks on a made-up graph and on the import forms they must see."""
    assert circle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert circle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert reached("toolpath/simulate/api.py", ast.parse("from .stock import _grid, BoxStock").body[0]) == [
        ("toolpath/simulate/stock", "_grid"), ("toolpath/simulate/stock", "BoxStock")]
    assert reached("toolpath/simulate/__init__.py", ast.parse("from . import api").body[0]) == [
        ("toolpath/simulate/api", None)]
    assert reached("toolpath/operations/carve/carve.py", ast.parse("from ...simulate import checks").body[0]) == [
        ("toolpath/simulate/checks", None)]
    assert reached("toolpath/operations/carve/carve.py", ast.parse("from ... import simulate").body[0]) == [
        ("toolpath/simulate", None)]
    assert reached("post/fanuc.py", ast.parse("from ..toolpath.ir.program import Program").body[0]) == [
        ("toolpath/ir/program", "Program")]
    assert reached("operators/carve.py", ast.parse("from .. import toolpath").body[0]) == [("toolpath", None)]
    assert reached("toolpath/simulate/api.py", ast.parse("import numpy as np").body[0]) == []
    carve = "toolpath/operations/carve/carve.py"
    assert private_uses(carve, "def f():\n    from ...simulate.checks import _mesh_top\n")
    assert private_uses(carve, "from ...simulate import checks\nchecks._mesh_top(1)\n")
    assert private_uses(carve, "from ... import simulate\nsimulate.checks._mesh_top(1)\n")
    assert private_uses(carve, "from ...simulate import checks as c\nc._mesh_top(1)\n")
    assert not private_uses(carve, "from ...simulate.meshtop import mesh_top\n_x = 1\nmesh_top(_x)\n")
    assert not private_uses(carve, "import numpy as np\nnp._NoValue\n")       # not ours


@pytest.mark.parametrize("path", sources("toolpath") + sources("post") + sources("operators"))
def test_no_private_name_is_taken_from_another_module(path):
    """A helper two modules need is public in the module it belongs to; a module that needs another's
    internals belongs with it."""
    assert not private_uses(path), "\n".join(private_uses(path))


@pytest.mark.parametrize("folders", [("toolpath",), ("post", "toolpath"), ("operators", "toolpath", "post")])
def test_no_import_circle(folders):
    """No circle among our modules, function-level imports included (a circle hidden by importing inside
    a function is still a circle)."""
    found = circle(import_graph(folders))
    assert found is None, "import circle: " + " -> ".join(found)


MUTATORS = {"append", "extend", "insert", "pop", "popitem", "clear", "update", "setdefault", "add", "discard", "remove",
            "sort", "reverse", "__setitem__", "__delitem__"}
MUTABLE_CALLS = {"dict", "list", "set", "defaultdict", "OrderedDict", "deque", "Counter"}
CACHES = {"lru_cache", "cache"}


def _mutable(value) -> bool:
    if isinstance(value, (ast.List, ast.Dict, ast.Set, ast.ListComp, ast.DictComp, ast.SetComp)):
        return True
    return isinstance(value, ast.Call) and getattr(value.func, "id", getattr(value.func, "attr", None)) in MUTABLE_CALLS


def _stored(node) -> list:
    """The names a statement binds (assignment targets, loop variables, imports, definitions)."""
    if isinstance(node, ast.Name) and isinstance(node.ctx, (ast.Store, ast.Del)):
        return [node.id]
    if isinstance(node, ast.arg):
        return [node.arg]
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return [node.name]
    if isinstance(node, (ast.Import, ast.ImportFrom)):
        return [(alias.asname or alias.name).split(".")[0] for alias in node.names]
    return []


def hidden_state(source: str, name: str = "<source>") -> list:
    """Module state a run changes, found in the source: a functools cache on a function, a ``global``
    statement, a function that mutates a name bound at module level (``CACHE[key] = ...``,
    ``CACHE.append(...)``, ``del CACHE[k]``, ``THING.attr = ...``), and a mutable class attribute
    (shared by every instance).  Mutating the module's tables while it is imported is not state."""
    tree = ast.parse(source, name)
    found = []
    module_level, imported = set(), set()
    for statement in tree.body:
        for node in ast.walk(statement) if not isinstance(statement, (ast.FunctionDef, ast.ClassDef)) else [statement]:
            (imported if isinstance(node, (ast.Import, ast.ImportFrom)) else module_level).update(_stored(node))
    module_level -= imported
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            for decorator in node.decorator_list:
                target = decorator.func if isinstance(decorator, ast.Call) else decorator
                if getattr(target, "id", getattr(target, "attr", None)) in CACHES:
                    found.append(f"{name}:{node.lineno} {node.name} keeps a functools cache")
        if isinstance(node, ast.Global):
            found.append(f"{name}:{node.lineno} global {', '.join(node.names)}")
        if isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, (ast.Assign, ast.AnnAssign)) and item.value is not None and _mutable(item.value):
                    found.append(f"{name}:{item.lineno} class {node.name} holds a mutable class attribute")
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            continue
        local = {bound for inner in ast.walk(node) for bound in _stored(inner)} - {getattr(node, "name", None)}
        shared = module_level - local

        def changes(target) -> bool:
            """``NAME[...]`` / ``NAME.x`` of a module-level NAME, or ``module.NAME[...]`` / ``module.NAME.x``
            of an imported module's (the module functions called as ``np.sort(...)`` are not state)."""
            if not isinstance(target, (ast.Subscript, ast.Attribute)):
                return False
            if isinstance(target.value, ast.Name):
                return target.value.id in shared
            return isinstance(target.value, ast.Attribute) and isinstance(target.value.value, ast.Name) \
                and target.value.value.id in imported - local

        for inner in ast.walk(node):
            targets = []
            if isinstance(inner, ast.Assign):
                targets = inner.targets
            elif isinstance(inner, (ast.AugAssign, ast.AnnAssign)):
                targets = [inner.target]
            elif isinstance(inner, ast.Delete):
                targets = inner.targets
            elif isinstance(inner, ast.Call) and isinstance(inner.func, ast.Attribute) and inner.func.attr in MUTATORS:
                targets = [inner.func] if changes(inner.func) else []
                if targets:
                    found.append(f"{name}:{inner.lineno} {ast.unparse(inner.func)}(...) changes module state")
                continue
            for target in targets:
                for part in ast.walk(target) if isinstance(target, ast.Tuple) else [target]:
                    if changes(part):
                        found.append(f"{name}:{inner.lineno} {ast.unparse(part)}: module state changed at run time")
    return sorted(set(found))


def test_the_state_check_sees_a_module_cache():
    """The check on made-up modules: each way of keeping state between calls is seen, and what only
    looks like it is not."""
    assert hidden_state("_LAST = []\ndef f(x):\n    _LAST[:] = [x]\n")
    assert hidden_state("_SEEN = {}\ndef f(x):\n    return _SEEN.setdefault(x, len(_SEEN))\n")
    assert hidden_state("import functools\n@functools.lru_cache(maxsize=None)\ndef f(x):\n    return x\n")
    assert hidden_state("from functools import cache\n@cache\ndef f(x):\n    return x\n")
    assert hidden_state("N = 0\ndef f():\n    global N\n    N += 1\n")
    assert hidden_state("class C:\n    memo = {}\n")
    assert hidden_state("S = {}\ndef f(k):\n    del S[k]\n")
    assert hidden_state("from . import other\ndef f(k):\n    other.TABLE[k] = 1\n")
    assert hidden_state("from . import other\ndef f(k):\n    other.SEEN.add(k)\n")
    assert not hidden_state("import numpy as np\ndef f(a):\n    return np.sort(np.append(a, 1))\n")
    assert not hidden_state("TABLE = {}\nTABLE['a'] = 1\nfor k in 'bc':\n    TABLE[k] = 2\n")      # built on import
    assert not hidden_state("SHAPES = {}\ndef f(shapes):\n    SHAPES2 = {}\n    SHAPES2['a'] = 1\n    shapes.append(1)\n")
    assert not hidden_state("D = {}\ndef f(D):\n    D['a'] = 1\n")             # a parameter of the same name
    assert not hidden_state("import functools\nclass M:\n    @functools.cached_property\n    def tree(self):\n"
                            "        return 1\n")                                # a cache on the object: explicit


@pytest.mark.parametrize("path", sources("toolpath"))
def test_the_core_keeps_no_module_state(path):
    """The core is pure between calls: a cache is an object the caller owns and passes on (a
    :class:`meshrays.CheckedMesh`, the :class:`meshrays.Triangles` a plan builds once), never a
    module-level memo that makes one call depend on the one before."""
    with open(os.path.join(ROOT, path), encoding="utf-8") as stream:
        found = hidden_state(stream.read(), path)
    assert not found, "\n".join(found)


@pytest.mark.parametrize("path", sources("toolpath") + sources("post") + sources("operators") + ["batch.py"])
def test_no_module_is_over_800_lines(path):
    if path in LONG_DATA:
        return
    with open(os.path.join(ROOT, path), encoding="utf-8") as stream:
        lines = sum(1 for _ in stream)
    assert lines <= MAX_LINES, f"{path} has {lines} lines"
