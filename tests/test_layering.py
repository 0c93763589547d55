"""The layering rules, checked on the source: posts read only the IR, the core never imports Blender."""
import ast
import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# What a post may take from toolpath/: names of the IR module (toolpath/ir/program.py: the Program and
# all a post needs with it), and of the kinematics and errors modules (DESIGN.md: posts import only the
# IR, kinematics and errors).  A module reached is "ir.program.FEED": its module path comes first.
POST_MAY_IMPORT = ("ir.program.", "ir.kinematics.", "ir.errors.")
BLENDER = {"bpy", "bmesh", "mathutils", "gpu", "blf"}


def python_files(folder):
    for directory, _, names in os.walk(os.path.join(ROOT, folder)):
        for name in sorted(names):
            if name.endswith(".py"):
                yield os.path.relpath(os.path.join(directory, name), ROOT)


def imports(path):
    """(module, level, names) of every import statement in the file; ``import a.b`` gives ("a.b", 0, [])."""
    with open(os.path.join(ROOT, path), encoding="utf-8") as stream:
        tree = ast.parse(stream.read(), path)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, 0, []
        elif isinstance(node, ast.ImportFrom):
            yield node.module or "", node.level, [alias.name for alias in node.names]


def toolpath_modules_of_post(module, level, names):
    """The toolpath modules (dotted, below toolpath/) a post/*.py import statement reaches (post/ sits
    beside toolpath/)."""
    parts = module.split(".") if module else []
    if level == 2 and parts[:1] == ["toolpath"]:
        below = parts[1:]
    elif level == 0 and parts[:2] == ["kezuri", "toolpath"]:
        below = parts[2:]
    elif level == 2 and not parts:
        return ["toolpath"] if "toolpath" in names else []     # from .. import toolpath: the whole core
    else:
        return []
    return [".".join(below + [n]) for n in names] if below else list(names)


def test_the_checks_see_the_import_forms():
    assert toolpath_modules_of_post("toolpath.operations.turnmill", 2, ["turnmill"]) == ["operations.turnmill.turnmill"]
    assert toolpath_modules_of_post("toolpath", 2, ["ir"]) == ["ir"]
    assert toolpath_modules_of_post("toolpath.ir.program", 2, ["Tool"]) == ["ir.program.Tool"]
    assert toolpath_modules_of_post("", 2, ["toolpath"]) == ["toolpath"]
    assert toolpath_modules_of_post("kezuri.toolpath.operations.engrave", 0, ["engrave"]) == ["operations.engrave.engrave"]
    assert toolpath_modules_of_post("gcode", 1, ["GcodePost"]) == []


@pytest.mark.parametrize("path", list(python_files("post")))
def test_posts_import_only_the_ir_kinematics_and_errors(path):
    reached = {m for statement in imports(path) for m in toolpath_modules_of_post(*statement)}
    outside = sorted(m for m in reached if not m.startswith(POST_MAY_IMPORT))
    assert not outside, f"{path} imports toolpath modules other than the IR, kinematics and errors: {outside}"


def defined_names(path: str) -> set:
    """The names a module defines at its top level (classes, functions, assignments), not those it imports."""
    tree = ast.parse(open(path, encoding="utf-8").read())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                names |= {n.id for n in ast.walk(target) if isinstance(n, ast.Name)}
    return names


@pytest.mark.parametrize("path", list(python_files("post")))
def test_what_a_post_takes_from_the_core_is_defined_there_not_passed_on(path):
    """A name re-exported by the IR module (defined in another of the core's modules) would let a
    post reach that module after all: every name a post imports is defined where it imports it."""
    for module, level, names in imports(path):
        for reached in toolpath_modules_of_post(module, level, names):
            parts = reached.split(".")
            if parts[0] != "ir" or len(parts) < 3:
                continue
            source = os.path.join(ROOT, "toolpath", "ir", parts[1] + ".py")
            assert parts[2] in defined_names(source), f"{path}: {parts[2]} is not defined in toolpath/ir/{parts[1]}.py"


def test_the_posts_rule_refuses_the_ir_package_and_its_other_modules():
    for module, names in (("toolpath.ir.punch", ["PunchProgram"]), ("toolpath.ir", ["machine"]),
                          ("toolpath.ir", ["Program"]), ("toolpath.ir", ["kinematics"]),
                          ("toolpath.ir.arcfit", ["fit_program"]), ("toolpath.ir.programs", ["X"])):
        reached = toolpath_modules_of_post(module, 2, names)
        assert not any(m.startswith(POST_MAY_IMPORT) for m in reached), reached
    for module, names in (("toolpath.ir.program", ["FEED"]), ("toolpath.ir.kinematics", ["block_minutes"]),
                          ("toolpath.ir.errors", ["InputError"])):
        assert all(m.startswith(POST_MAY_IMPORT) for m in toolpath_modules_of_post(module, 2, names))


@pytest.mark.parametrize("path", list(python_files("toolpath")) + list(python_files("post")))
def test_the_core_and_the_posts_never_import_blender(path):
    for module, level, _ in imports(path):
        assert not (level == 0 and module.split(".")[0] in BLENDER), f"{path} imports {module}"


def test_kinematics_imports_nothing_of_the_project():
    """program.py imports kinematics, so kinematics must not import the IR (or anything else of ours)."""
    assert [m for m, level, _ in imports("toolpath/ir/kinematics.py") if level > 0] == []


def reached_packages(path):
    """The toolpath packages (dotted, below toolpath/) a toolpath module's imports reach."""
    package = os.path.dirname(path).replace(os.sep, ".").split(".")[1:]      # below toolpath/
    for module, level, names in imports(path):
        if level == 0:
            parts = module.split(".")
            if parts[:2] == ["kezuri", "toolpath"]:
                yield ".".join(parts[2:])
            continue
        base = package[:len(package) - (level - 1)] if level > 1 else package
        yield ".".join(base + (module.split(".") if module else []))


@pytest.mark.parametrize("path", list(python_files("toolpath/ir")))
def test_the_ir_imports_only_the_ir(path):
    """The IR is what the posts read: it knows no engine, simulation or operation kind (a workflow's
    type or error in it would make every post depend on that workflow)."""
    outside = sorted(m for m in reached_packages(path) if m.split(".")[0] != "ir")
    assert not outside, f"{path} imports {outside}"


@pytest.mark.parametrize("path", list(python_files("toolpath/engines")))
def test_the_engines_import_no_operation_kind(path):
    """The engines are shared by the operation kinds: their errors and types are their own."""
    kinds = sorted(m for m in reached_packages(path) if m.split(".")[0] == "operations")
    assert not kinds, f"{path} imports {kinds}"


def test_the_import_reader_resolves_relative_imports():
    assert list(reached_packages("toolpath/ir/arcfit.py")) == ["ir", "ir.errors", "ir.moves"]   # from . import arcfit_kernel
    assert "operations.turnmill.errors" in reached_packages("toolpath/operations/turnmill/turnjoin.py")
    assert "engines.meshdata" in reached_packages("toolpath/engines/meshrays.py")
