"""Blender's interface switched to Japanese for the length of a ``with`` block (the add-on's
translations registered), and back to what it was."""
import contextlib

import bpy


@contextlib.contextmanager
def japanese_interface():
    from kezuri.operators import translations

    translations.register()
    view = bpy.context.preferences.view
    saved = view.language, view.use_translate_interface
    try:
        view.language = "ja_JP"
        view.use_translate_interface = True
        yield
    finally:
        view.language, view.use_translate_interface = saved
