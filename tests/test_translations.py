"""The Japanese (ja_JP) translation covers every label, tooltip and fixed message of the extension.

The English strings are collected at run time from the registered classes (labels, operator
tooltips, property names and descriptions, enum items) and from the operators' source (fixed
texts of layout.label / layout.operator, poll messages, reports and raised errors), so a new
property or operator without a translation fails here.
"""
import ast
import os
import re
from collections import Counter

import pytest

bpy = pytest.importorskip("bpy")

import kezuri  # noqa: E402  (loaded by conftest from the repository root)
from kezuri import operators  # noqa: E402
from kezuri.operators import preferences, properties, translations  # noqa: E402
from blender_language import japanese_interface  # noqa: E402

JA = translations.TRANSLATIONS["ja_JP"]
DEFAULT = bpy.app.translations.contexts.default            # "*"
OPERATOR = bpy.app.translations.contexts.operator_default  # "Operator"

# English that is a code, an abbreviation or a product/format name: kept as it is in Japanese.
CODE_ONLY = {
    "G54", "G55", "G56", "G57", "G58", "G59",
    "LinuxCNC", "GRBL", "Fanuc", "mm/min",
    "CADKEY CDL (.cdl)", "ISO 14649 STEP-NC (.stp, .p21)", "ISO 14649 STEP-NC (.stp)",
    "Blender BVH", "trimesh", "LinuxCNC X-Z-C",
}
JAPANESE = re.compile(r"[\u3040-\u30ff\u3400-\u4dbf\u4e00-\u9fff\uff66-\uff9f]")   # kana or kanji
PLACEHOLDER = re.compile(r"\{[^{}]*\}|%(?:\.\d+)?[sdifr]")


@pytest.fixture(scope="module", autouse=True)
def registered():
    if not hasattr(bpy.types.Scene, "kezuri"):
        kezuri.register()
    translations.register()
    yield


def ui_classes():
    from kezuri.operators.workflows import settings_groups
    groups = [cls for _, cls in settings_groups()]        # the router kinds' settings (scene.kezuri.<kind>)
    return list(dict.fromkeys([*operators.CLASSES, *properties.CLASSES, *preferences.CLASSES, *groups]))


def own_property_names(cls) -> set:
    """Properties the extension defines (not Blender's, nor bpy_extras' ExportHelper.filepath)."""
    names = set()
    for klass in cls.__mro__:
        if klass.__module__.startswith(kezuri.__name__ + "."):
            names |= set(vars(klass).get("__annotations__", {}))
    return names


def inherited_property_pointers(cls) -> set:
    """Blender's own properties of the base types (PropertyGroup.name, Operator.bl_options ...)."""
    pointers = set()
    for base in cls.__mro__[1:]:
        try:
            pointers |= {p.as_pointer() for p in base.bl_rna.properties}
        except (AttributeError, TypeError):
            pass
    return pointers


def operator_rna(cls):
    """The registered operator type: its name is bl_label, its description the docstring."""
    module, name = cls.bl_idname.split(".")
    return getattr(getattr(bpy.ops, module), name).get_rna_type()


def ui_strings() -> list:
    """(context, English, where) for every UI string of the registered classes."""
    found = []

    def add(context, text, where):
        if text and text.strip():
            found.append((context, text, where))

    for cls in ui_classes():
        where = cls.__name__
        if issubclass(cls, bpy.types.Operator):
            rna = operator_rna(cls)
            assert rna.name == cls.bl_label
            add(OPERATOR, rna.name, f"{where}.bl_label")
            add(DEFAULT, rna.name, f"{where}.bl_label")
            add(DEFAULT, rna.description, f"{where} docstring")
            props = rna.properties
        else:
            if issubclass(cls, (bpy.types.Panel, bpy.types.Menu)):
                add(DEFAULT, getattr(cls, "bl_label", ""), f"{where}.bl_label")
                add(DEFAULT, vars(cls).get("bl_description") or vars(cls).get("__doc__"), f"{where} docstring")
            props = cls.bl_rna.properties
        own, inherited = own_property_names(cls), inherited_property_pointers(cls)
        for prop in props:
            if prop.identifier == "rna_type" or prop.is_hidden or prop.identifier not in own \
                    or prop.as_pointer() in inherited:
                continue
            if prop.name != prop.identifier:         # Blender names an unnamed property by its identifier
                add(DEFAULT, prop.name, f"{where}.{prop.identifier} name")
            add(DEFAULT, prop.description, f"{where}.{prop.identifier} description")
            if prop.type == "ENUM":
                for item in prop.enum_items:
                    add(DEFAULT, item.name, f"{where}.{prop.identifier}[{item.identifier}] name")
                    add(DEFAULT, item.description, f"{where}.{prop.identifier}[{item.identifier}] description")
    return found


def _constant(node):
    """The string a node always evaluates to ("a" "b" and "a" + "b" included), else None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _constant(node.left), _constant(node.right)
        if left is not None and right is not None:
            return left + right
    return None


def source_messages() -> list:
    """(context, English, where) for the fixed texts in operators/*.py: layout texts, poll
    messages, reports and raised errors.  f-strings (names, numbers) cannot be translated whole
    and are left out."""
    found = []
    folder = os.path.dirname(operators.__file__)
    for filename in sorted(os.listdir(folder)):
        if not filename.endswith(".py") or filename == "translations.py":
            continue
        with open(os.path.join(folder, filename), encoding="utf-8") as stream:
            tree = ast.parse(stream.read(), filename)
        for node in ast.walk(tree):
            texts = []
            if isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call) and node.exc.args:
                texts.append((DEFAULT, node.exc.args[0]))
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
                keywords = {k.arg: k.value for k in node.keywords}
                if node.func.attr in {"report", "poll_message_set"} and node.args:
                    texts.append((DEFAULT, node.args[-1]))
                elif node.func.attr == "operator" and "text" in keywords:
                    texts.append((OPERATOR, keywords["text"]))     # looked up in the operator's context
                elif node.func.attr in {"label", "prop", "menu"} and "text" in keywords:
                    texts.append((DEFAULT, keywords["text"]))
            for context, arg in texts:
                text = _constant(_unwrapped(arg))
                if text:
                    found.append((context, text, f"operators/{filename}:{node.lineno}"))
    return found


def _unwrapped(node):
    """The message inside ``translate_message(...)``, or the node itself."""
    if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "translate_message" and node.args:
        return node.args[0]
    return node


def _template(node):
    """The English template of a message: an f-string with ``{}`` for each value (literal braces
    doubled, as str.format wants them); None when part of it is not literal."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value.replace("{", "{{").replace("}", "}}")
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value.replace("{", "{{").replace("}", "}}") if isinstance(v, ast.Constant) else "{}"
                       for v in node.values)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _template(node.left), _template(node.right)
        return None if left is None or right is None else left + right
    return None


def raised_messages():
    """(message node, where) for every message the core or the shell raises (``raise
    ...Error(...)``) or reports (``report(level, ...)``)."""
    root = os.path.dirname(os.path.dirname(operators.__file__))
    for top in ("toolpath", "post", "operators"):
        for folder, filename in sorted((os.path.relpath(base, root), name)
                                       for base, _, names in os.walk(os.path.join(root, top)) for name in names):
            if not filename.endswith(".py") or filename == "translations.py":
                continue
            with open(os.path.join(root, folder, filename), encoding="utf-8") as stream:
                tree = ast.parse(stream.read(), filename)
            for node in ast.walk(tree):
                message = None
                if isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call) and node.exc.args:
                    name = getattr(node.exc.func, "id", getattr(node.exc.func, "attr", ""))
                    if name.endswith("Error"):
                        message = node.exc.args[0]
                elif isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "report" and len(node.args) == 2:
                    message = _unwrapped(node.args[1])
                if message is not None:
                    yield message, f"{folder}/{filename}:{node.lineno}"


def formatted_messages() -> dict:
    """{English template: where} for every message built with an f-string that the core or the
    shell raises or reports."""
    found = {}
    for message, where in raised_messages():
        if isinstance(message, (ast.JoinedStr, ast.BinOp)):
            template = _template(message)
            if template is not None and "{}" in template:
                found.setdefault(template, where)
    return found


def _missing(strings):
    return sorted({f"{where}: ({context!r}, {text!r})" for context, text, where in strings
                   if (context, text) not in JA})


def test_the_collectors_find_the_known_strings():
    strings = {(c, t) for c, t, _ in ui_strings()}
    assert (OPERATOR, "Generate Engraving") in strings
    assert (DEFAULT, "Write the engraving NC program for the chosen controller") in strings
    assert (DEFAULT, "Stepover") in strings and (DEFAULT, "Distance between zigzag rows (mm)") in strings
    assert (DEFAULT, "Ball End Mill") in strings and (DEFAULT, "Machine & Stock") in strings
    assert (DEFAULT, "File Path") not in strings                 # ExportHelper's, Blender translates it
    assert (DEFAULT, "Unique name used in the code and scripting") not in strings
    assert len(strings) > 150
    messages = {(c, t) for c, t, _ in source_messages()}
    assert (DEFAULT, "Pick the plate (stock) object first") in messages
    assert (OPERATOR, "Import CDL") in messages


def test_every_ui_string_has_a_japanese_translation():
    missing = _missing(ui_strings())
    assert not missing, f"{len(missing)} UI strings without ja_JP translation:\n" + "\n".join(missing)


def test_every_operator_label_is_translated_in_both_contexts():
    for cls in ui_classes():
        if issubclass(cls, bpy.types.Operator):
            assert (OPERATOR, cls.bl_label) in JA, cls.__name__
            assert (DEFAULT, cls.bl_label) in JA, cls.__name__


def test_every_fixed_message_of_the_operators_is_translated():
    missing = _missing(source_messages())
    assert not missing, f"{len(missing)} fixed messages without ja_JP translation:\n" + "\n".join(missing)


def test_translations_are_japanese_and_keep_the_placeholders():
    assert set(translations.TRANSLATIONS) == {"ja_JP"}
    for (context, english), japanese in JA.items():
        assert context in {DEFAULT, OPERATOR}, (context, english)
        assert isinstance(japanese, str) and japanese.strip(), (context, english)
        if english not in CODE_ONLY:
            assert JAPANESE.search(japanese), f"no kana or kanji in the translation of {english!r}: {japanese!r}"
        assert Counter(PLACEHOLDER.findall(japanese)) == Counter(PLACEHOLDER.findall(english)), \
            f"placeholders differ: {english!r} -> {japanese!r}"
    english_keys = {english for _, english in JA}
    assert CODE_ONLY <= english_keys, f"stale allow-list entries: {sorted(CODE_ONLY - english_keys)}"


def test_translation_register_and_unregister_twice_cleanly():
    for _ in range(2):
        translations.unregister()
        kezuri.unregister()
        assert not hasattr(bpy.types.Scene, "kezuri")
        kezuri.register()
        translations.register()
        assert hasattr(bpy.types.Scene, "kezuri")
    translations.register()          # registering again (a reload) replaces, does not fail
    translations.unregister()
    translations.unregister()        # and unregistering what is not registered is harmless
    translations.register()


@pytest.mark.xfail(not bpy.app.build_options.international, strict=True,
                   reason="this bpy wheel is built without WITH_INTERNATIONAL: its only interface language is "
                          "'DEFAULT' (no locale files), so preferences.view.language cannot be set to ja_JP and "
                          "pgettext_iface returns the English")
def test_blender_shows_japanese_when_the_interface_language_is_japanese():
    with japanese_interface():
        assert bpy.app.translations.pgettext_iface("Machine & Stock") == "機械と素材"
        assert bpy.app.translations.pgettext_iface("Generate Engraving", OPERATOR) == "彫刻パスを生成"


def test_the_formatted_message_collector_finds_the_known_ones():
    found = formatted_messages()
    assert "stock radius must be > 0, got {}" in found                      # toolpath (a raise)
    assert "Wrote {}" in found                                              # operators (a report)
    assert "line {}: cannot read {}" in found                               # toolpath/operations/sheetmetal/punch.py
    assert "#{} DIRECTION: direction_ratios are all zero" in found         # toolpath/stepnc
    assert len(found) > 200


def test_every_formatted_message_has_a_japanese_template():
    missing = sorted(f"{where}: {template!r}" for template, where in formatted_messages().items()
                     if template not in translations.MESSAGE_TEMPLATES)
    assert not missing, f"{len(missing)} f-string messages without a ja_JP template:\n" + "\n".join(missing)


def test_every_fixed_error_message_is_translated():
    fixed = {(message.value, where) for message, where in raised_messages()
             if isinstance(message, ast.Constant) and isinstance(message.value, str)}
    assert "the NC file has no moves" in {text for text, _ in fixed}          # toolpath/simulate/ncread.py
    missing = sorted(f"{where}: {text!r}" for text, where in fixed if (DEFAULT, text) not in JA)
    assert not missing, f"{len(missing)} fixed error messages without ja_JP translation:\n" + "\n".join(missing)


def test_japanese_templates_use_every_value_once():
    for english, japanese in translations.MESSAGE_TEMPLATES.items():
        count = english.count("{}")
        assert sorted(int(i) for i in re.findall(r"\{(\d+)\}", japanese)) == list(range(count)), english
        assert JAPANESE.search(japanese), english


def sample_values(template: str) -> list:
    return [f"V{index}x" for index in range(template.count("{}"))]


@pytest.mark.parametrize("english", sorted(translations.MESSAGE_TEMPLATES))
def test_a_formatted_message_comes_out_in_japanese_with_its_values(english):
    values = sample_values(english)
    message = english.format(*values)
    japanese = translations.japanese_message(message)
    assert japanese is not None and JAPANESE.search(japanese), message
    for value in values:
        assert value in japanese, (message, japanese)


def test_real_error_messages_are_matched():
    from kezuri.toolpath.operations.sheetmetal import punch
    from kezuri.toolpath.operations.turnmill import turnmill
    with pytest.raises(turnmill.TurnMillError) as raised:
        turnmill.Stock(radius=-1.0, z_min=0.0, z_max=1.0)
    assert translations.japanese_message(str(raised.value)) == "素材の半径は0より大きくしてください（指定値 -1.0）"
    with pytest.raises(punch.PunchError) as raised:
        punch.read_amada("N001 G72 X0.00 Y0.00\nG69 I10.00 J0.00 P0.00 T302\nG50\n")
    assert translations.japanese_message(str(raised.value)) == \
        "2 行目：G69 には I, J, P, Q, T が必要です（'G69 I10.00 J0.00 P0.00 T302'）"


def test_english_stays_english():
    assert not translations.reports_in_japanese()          # the default interface language
    message = "stock radius must be > 0, got -1"
    assert translations.translate_message(message) == message
    assert translations.translate_message("no template looks like this {x}") == "no template looks like this {x}"


def test_range_messages_name_the_panel_and_the_label_as_the_japanese_panel_shows_them():
    """A value outside its range is refused naming the panel and the property: in Japanese with
    the panel's and the label's Japanese words (as the user sees them), not the English ones."""
    from kezuri.operators import limits
    scene = bpy.context.scene
    every_group = set(limits.GROUP_NAMES.values())
    assert all((DEFAULT, name) in JA for name in every_group), every_group
    label = scene.kezuri.sheet.bl_rna.properties["thickness"].name
    message = limits.problem("sheet", "thickness", label, -1.0)
    japanese = translations.japanese_message(message)
    assert japanese.startswith(JA[(DEFAULT, "Sheet Metal")] + "：" + JA[(DEFAULT, label)] + " = -1 "), japanese
    assert label not in japanese and "Sheet Metal" not in japanese
    # an array's element and a library tool's place keep their index and name
    corners = scene.kezuri.sheet.bl_rna.properties["corners"].name
    message = limits.problem("sheet", "corners", corners, (0.0, 0.0, float("nan")) + (0.0,) * 9)
    japanese = translations.japanese_message(message)
    assert JA[(DEFAULT, corners)] + " [3] = nan" in japanese, japanese
    message = limits.problem("", "diameter", "Diameter", -2.0, "Tool Library 'T7 ball'", limits.LIBRARY["diameter"])
    japanese = translations.japanese_message(message)
    assert japanese.startswith(JA[(DEFAULT, "Tool Library")] + " 'T7 ball'：" + JA[(DEFAULT, "Diameter")]), japanese


# A measurement put into a message with no format (str of a float) shows Blender's single
# precision or the arithmetic's last bits: "outside the 140.00000664964318 x 90.00000427477062 mm
# board", "stepover 0.30000001192092896 mm".  Every message the core or the shell raises or reports
# formats such a value (:g, :.3f ...); exempt are values shown as given after "got" (the refused
# input), !r (a value quoted as given), CONSTANTS written in the code, and these, which are not floats:
NOT_MEASUREMENTS = {"feed_line",          # ncread: a line number
                    "area",               # picture: a pixel rectangle (ints)
                    "levels",             # pocket: a count
                    "size", "scale",      # convert: already formatted text
                    "lengths",            # sheetmetal: already formatted text
                    "height",             # picture: "got {width} x {height}" pixels as given
                    "overlap"}            # stepnc motion: a ratio or None, shown as the file gives it
MEASUREMENT = re.compile(r"depth|diameter|size|radius|thickness|width|height|stepover|spacing|tolerance|length|"
                         r"pitch|angle|scale|allowance|clearance|feed|rpm|overlap|distance|gap|reach|travel|area|"
                         r"top|bottom|level|cell|margin|slope|^[xyz]$|_[xyz]$", re.I)


def test_no_message_shows_a_measurement_unformatted():
    bare = []
    for message, where in raised_messages():
        if not isinstance(message, ast.JoinedStr):
            continue
        before = ""
        for part in message.values:
            if isinstance(part, ast.Constant):
                before = str(part.value)
                continue
            value = part.value
            last = value.attr if isinstance(value, ast.Attribute) else getattr(value, "id", None)
            if (part.format_spec is None and part.conversion != ord("r") and last and MEASUREMENT.search(last)
                    and not last.isupper() and last not in NOT_MEASUREMENTS and not before.rstrip().endswith("got")):
                bare.append(f"{where}: {{{ast.unparse(value)}}}")
            before = ""
    assert not bare, "measurements shown unformatted (give them :g or a precision):\n" + "\n".join(bare)


def warning_messages() -> dict:
    """{English template: where} of every warning or note built with an f-string and added to a
    list of warnings or notes (``warnings.append(f"...")``, ``notes.insert(0, f"...")``): the panel
    reports them (translate_message) as it reports errors."""
    root = os.path.dirname(os.path.dirname(operators.__file__))
    found = {}
    for top in ("toolpath", "post", "operators"):
        for base, _, names in sorted(os.walk(os.path.join(root, top))):
            for filename in sorted(names):
                if not filename.endswith(".py") or filename == "translations.py":
                    continue
                with open(os.path.join(base, filename), encoding="utf-8") as stream:
                    tree = ast.parse(stream.read(), filename)
                for node in ast.walk(tree):
                    if not (isinstance(node, ast.Call) and getattr(node.func, "attr", "") in {"append", "insert"}
                            and node.args):
                        continue
                    target = ast.unparse(node.func.value)
                    if "warning" not in target and "notes" not in target:
                        continue
                    message = node.args[-1]
                    if isinstance(message, (ast.JoinedStr, ast.BinOp)):
                        template = _template(message)
                        if template is not None and "{}" in template:
                            found.setdefault(template, f"{os.path.relpath(base, root)}/{filename}:{node.lineno}")
    return found


def test_every_formatted_warning_has_a_japanese_template():
    found = warning_messages()
    assert "through feature #{} '{}' ends at Z {}, {} mm above that stock bottom: it does not go through" in found
    missing = sorted(f"{where}: {template!r}" for template, where in found.items()
                     if template not in translations.MESSAGE_TEMPLATES)
    assert not missing, f"{len(missing)} f-string warnings without a ja_JP template:\n" + "\n".join(missing)


def test_a_quoted_name_holding_the_templates_next_words_is_kept_whole():
    """An operation named 'roughing (gouge texture)' before ' (T2 ...)': the name was cut at its own
    ' (' and the Japanese read 'roughing（gouge texture)' (T2 ...）."""
    message = ("feeds: operation 'roughing (gouge texture)' (T2 6 mm ball end mill (roughing ball)) in hardwood: "
               "chip load 0.1000 mm per tooth is below the safe band 0.1186 - 0.1694 mm: the tool rubs (heat, "
               "burning, a dull edge); raise the feed or lower the spindle speed")
    japanese = translations.japanese_message(message)
    assert japanese.startswith("送り：工程 'roughing (gouge texture)'（T2 6 mm ball end mill (roughing ball)）、材料 hardwood：")
    # a name with a quote escaped inside it, and a plain (unquoted) value, as before
    assert translations.japanese_message("job file {}: no such file".replace("{}", "'a (b)\\'s.toml'")) == \
        "ジョブファイル 'a (b)\\'s.toml'：ファイルがありません"
