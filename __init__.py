"""Kezuri CAM (削り): toolpaths, carved-stock previews and NC programs for craftspeople.

The repository root is the Blender extension.  ``toolpath/`` and ``post/`` are the pure core
(numpy, manifold3d, trimesh); ``operators/`` is the Blender shell.  bpy is imported only when
Blender registers the extension, so the core can be used and tested without Blender.
"""


def register():
    from . import operators
    operators.register()


def unregister():
    from . import operators
    operators.unregister()
