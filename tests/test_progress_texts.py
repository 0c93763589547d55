"""The stage texts a stepped operator shows in the status bar ("Export Engraving NC: 40%  checking")
come out in Japanese: every text the work passes as progress text, in operators/ and in the core
it runs (toolpath/), is found in the source (by AST) and has a Japanese entry, fixed or a template;
the status line puts it through translate_message."""
import ast
import os
import re

import pytest

bpy = pytest.importorskip("bpy")

from kezuri import operators  # noqa: E402
from kezuri.operators import common, translations  # noqa: E402

JA = translations.TRANSLATIONS["ja_JP"]
JAPANESE = re.compile(r"[\u3040-\u30ff\u3400-\u4dbf\u4e00-\u9fff]")
ROOT = os.path.dirname(os.path.dirname(operators.__file__))
REPORTERS = {"progress", "report"}      # what the work calls as progress(fraction, text)


def _calls(function):
    """The progress calls inside ``function`` (nested functions and lambdas included)."""
    for node in ast.walk(function):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in REPORTERS \
                and len(node.args) >= 2:
            yield node


def _texts(node, assigned: dict) -> list:
    """("fixed", text) / ("template", english with {}) of a progress text node; a name assigned
    a string in the function is followed; ``text or "planning"`` gives its constant."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [("fixed", node.value)] if node.value else []
    if isinstance(node, ast.JoinedStr):
        return [("template", "".join(v.value if isinstance(v, ast.Constant) else "{}" for v in node.values))]
    if isinstance(node, ast.BoolOp):
        return [t for value in node.values for t in _texts(value, assigned)]
    if isinstance(node, ast.Name) and node.id in assigned:
        return [t for value in assigned[node.id] for t in _texts(value, assigned)]
    return []


def progress_texts() -> dict:
    """{(kind, text): where} of every progress text in operators/ and toolpath/: literal texts,
    f-strings, names assigned them, and the constants passed to a function that hands one of its
    parameters on as progress text (``export_work("unfolding", ...)``)."""
    found, passes, trees = {}, {}, []
    for top in ("operators", "toolpath"):
        for base, _, names in sorted(os.walk(os.path.join(ROOT, top))):
            for filename in sorted(n for n in names if n.endswith(".py") and n != "translations.py"):
                where = os.path.relpath(os.path.join(base, filename), ROOT)
                with open(os.path.join(base, filename), encoding="utf-8") as stream:
                    trees.append((where, ast.parse(stream.read(), filename)))
    for where, tree in trees:
        for function in ast.walk(tree):
            if not isinstance(function, (ast.FunctionDef, ast.Lambda)):
                continue
            assigned = {}
            for node in ast.walk(function):
                if isinstance(node, ast.Assign) and isinstance(node.value, (ast.Constant, ast.JoinedStr)):
                    for target in node.targets:
                        if isinstance(target, ast.Name):
                            assigned.setdefault(target.id, []).append(node.value)
            parameters = [a.arg for a in function.args.args]
            for call in _calls(function):
                text = call.args[1]
                for entry in _texts(text, assigned):
                    found.setdefault(entry, f"{where}:{call.lineno}")
                if isinstance(function, ast.FunctionDef) and isinstance(text, ast.Name) and text.id in parameters:
                    passes[function.name] = parameters.index(text.id)
    for where, tree in trees:
        for call in ast.walk(tree):
            if isinstance(call, ast.Call) and isinstance(call.func, ast.Name) and call.func.id in passes \
                    and len(call.args) > passes[call.func.id]:
                for entry in _texts(call.args[passes[call.func.id]], {}):
                    found.setdefault(entry, f"{where}:{call.lineno}")
    return found


def test_the_collector_finds_the_stages_of_every_stepped_export():
    found = progress_texts()
    fixed = {text for kind, text in found if kind == "fixed"}
    templates = {text for kind, text in found if kind == "template"}
    # the NC exports (exporting.py), the Sheet and Elbow exports (export_work's first stage), the kinds' work
    assert {"planning", "checking", "writing", "unfolding", "punching"} <= fixed
    assert {"roughing", "steep cleanup", "band finishing", "burr contour", "radial layers", "reading"} <= fixed
    assert {"pocket {}", "workingstep #{}", "following the surface: {}", "casting {} rays"} <= templates
    assert found[("fixed", "unfolding")].startswith("operators/sheetmetal.py")
    assert len(found) >= 25


def test_every_progress_text_has_a_japanese_entry():
    missing = []
    for (kind, text), where in sorted(progress_texts().items()):
        if kind == "fixed":
            japanese = JA.get(("*", text))
        else:
            japanese = translations.MESSAGE_TEMPLATES.get(text) and \
                translations.japanese_message(text.format(*[f"V{i}x" for i in range(text.count("{}"))]))
        if not japanese or not JAPANESE.search(japanese):
            missing.append(f"{where}: {text!r}")
    assert not missing, f"{len(missing)} progress texts without ja_JP:\n" + "\n".join(missing)


@pytest.mark.parametrize("english, japanese", [
    ("following the surface: band finishing", "曲面に沿わせています：帯仕上げ"),     # the operation's name too
    ("following the surface: roughing (gouge texture)", "曲面に沿わせています：荒加工（彫刻刀跡）"),
    ("pocket Pocket.001", "ポケット Pocket.001"),                                   # a name stays as typed
    ("workingstep #42", "ワーキングステップ #42"),
])
def test_a_stage_built_with_values_comes_out_whole_in_japanese(english, japanese):
    assert translations.japanese_message(english) == japanese


def test_the_turret_directions_rays_are_the_two_fixed_texts():
    from kezuri.toolpath.operations.turnmill.turnreach import DIRECTIONS
    for direction in DIRECTIONS:              # f"casting {DIRECTIONS[half]} rays": each whole, not a word left
        assert JAPANESE.search(JA[("*", f"casting {direction} rays")]) and direction not in \
            JA[("*", f"casting {direction} rays")]


def test_the_status_line_puts_the_stage_through_the_translation():
    """In English (this bpy has no Japanese interface, see test_translations) the line shows the
    stage as the work reports it; an empty stage leaves no lookup of "" (gettext's header)."""
    assert not translations.reports_in_japanese()
    assert common.status_line("Export Engraving NC", 0.4, "checking") == \
        "Export Engraving NC: 40%  checking   (Esc to cancel)"
    assert common.status_line("Simulate", 0.0, "") == "Simulate: 0%     (Esc to cancel)"
    source = ast.parse(open(common.__file__, encoding="utf-8").read())
    status = next(n for n in ast.walk(source) if isinstance(n, ast.FunctionDef) and n.name == "status_line")
    assert any(isinstance(n, ast.Call) and getattr(n.func, "id", "") == "translate_message"
               for n in ast.walk(status))
