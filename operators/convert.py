"""Scene <-> arrays.  The only place that converts Blender units to millimetres (and back).

Everything handed to the core is in millimetres in the work coordinate system; everything
shown in the viewport goes back through :class:`WorkFrame`.
"""
from __future__ import annotations

from dataclasses import dataclass

import bpy
import numpy as np

from ..toolpath.engines import meshdata, region
from ..toolpath.ir.errors import MAX_REACH_MM, InputError

COLLECTION = "Kezuri"


class SceneInputError(InputError):
    """The scene does not hold what the job needs; the message names the object."""


def typed(value):
    """A float setting as the user typed it.  Blender keeps floats in single precision (0.1 reads
    back as 0.10000000149011612); the shortest decimal that single precision rounds to the same
    number is the one typed, and the one messages should name.  Other values pass unchanged."""
    return float(str(np.float32(value))) if isinstance(value, float) else value


class Typed:
    """A property group's values read through :func:`typed` (for the settings a job reads)."""

    def __init__(self, props):
        self._props = props

    def __getattr__(self, name):
        return typed(getattr(self._props, name))


def mm_per_unit(scene) -> float:
    """Millimetres per Blender unit: ``scale_length`` says how many metres one unit is."""
    scale = scene.unit_settings.scale_length
    if not scale > 0:
        raise SceneInputError(f"scene unit scale must be positive, got {scale}")
    return scale * 1000.0


@dataclass(frozen=True)
class WorkFrame:
    """World (Blender units) <-> work coordinates (mm).  Work origin at ``origin_mm`` in world mm."""

    mm_per_unit: float
    origin_mm: tuple

    def to_work(self, world_points) -> np.ndarray:
        return np.asarray(world_points, float) * self.mm_per_unit - np.asarray(self.origin_mm)

    def to_world(self, work_points) -> np.ndarray:
        return (np.asarray(work_points, float) + np.asarray(self.origin_mm)) / self.mm_per_unit


def placed(co: np.ndarray, matrix) -> np.ndarray:
    """(n, 3) local points moved by a 4 x 4 object matrix, by explicit sums: a BLAS product
    would wake OpenBLAS's helper thread, which then spins on a core after every call."""
    m = np.asarray(matrix, float)
    co = np.asarray(co, float).reshape(-1, 3)
    return np.einsum("ij,kj->ik", co, m[:3, :3]) + m[:3, 3]


# A plate's top or a letter's plane tilted by less than this (degrees) is taken as level: over a
# 1 m plate it moves the top by 0.017 mm, and it is far above single precision's 1e-5 deg noise.
TILT_LIMIT_DEG = 0.001


def tilt_of(matrix) -> tuple:
    """How far the local XY plane of a 4 x 4 (or 3 x 3) object matrix is tilted out of the
    world's XY plane: (degrees, "X" / "Y" / "X and Y").  A turn about Z alone or a flip upside
    down (the plane stays level) is no tilt."""
    m = np.asarray(matrix, float)[:3, :3]
    normal = np.cross(m[:, 0], m[:, 1])
    length = float(np.linalg.norm(normal))
    if not length > 0:
        return 0.0, ""
    normal = normal / length
    degrees = float(np.degrees(np.arccos(min(1.0, abs(normal[2])))))
    largest = max(abs(normal[0]), abs(normal[1]))
    about_x, about_y = abs(normal[1]) >= 0.05 * largest, abs(normal[0]) >= 0.05 * largest
    axis = "X and Y" if about_x and about_y else "X" if about_x else "Y"
    return degrees, axis


def check_level(obj, what: str, matrix=None) -> None:
    """Refuse an object whose plane is tilted (an unapplied rotation about X or Y): the plate and
    the letters are read as seen from above, so a tilted top would be cut as if it were flat."""
    degrees, axis = tilt_of(obj.matrix_world if matrix is None else matrix)
    if not degrees > TILT_LIMIT_DEG:
        return
    if what == "plate":
        raise SceneInputError(f"plate {obj.name!r} is tilted {degrees:.3g} deg about {axis}: apply or clear its "
                              f"rotation (Ctrl-A)")
    if what == "collection instance":
        raise SceneInputError(f"collection instance {obj.name!r} is tilted {degrees:.3g} deg about {axis}: clear its "
                              f"rotation about X and Y")
    raise SceneInputError(f"object {obj.name!r} is tilted {degrees:.3g} deg about {axis} out of the plate's top: "
                          f"apply or clear its rotation (Ctrl-A)")


def evaluated_mesh_arrays(obj, depsgraph, matrix=None):
    """World-space vertices (Blender units), polygons and edges of the evaluated object
    (``matrix``: its world matrix when it is shown through an instance; default its own)."""
    evaluated = obj.evaluated_get(depsgraph)
    try:
        mesh = evaluated.to_mesh()
    except RuntimeError as error:
        raise SceneInputError(f"object {obj.name!r} cannot be turned into a mesh: {error}") from None
    if mesh is None:
        raise SceneInputError(f"object {obj.name!r} ({obj.type}) has no geometry")
    try:
        count = len(mesh.vertices)
        co = np.empty(count * 3)
        mesh.vertices.foreach_get("co", co)
        co = co.reshape(count, 3)
        world = placed(co, np.array(obj.matrix_world if matrix is None else matrix))
        edges = np.empty(len(mesh.edges) * 2, dtype=np.int64)
        mesh.edges.foreach_get("vertices", edges)
        loop_starts = np.empty(len(mesh.polygons), dtype=np.int64)
        loop_totals = np.empty(len(mesh.polygons), dtype=np.int64)
        mesh.polygons.foreach_get("loop_start", loop_starts)
        mesh.polygons.foreach_get("loop_total", loop_totals)
        loop_vertices = np.empty(len(mesh.loops), dtype=np.int64)
        mesh.loops.foreach_get("vertex_index", loop_vertices)
        polygons = [loop_vertices[s:s + t] for s, t in zip(loop_starts, loop_totals)]
    finally:
        evaluated.to_mesh_clear()
    return world, polygons, edges.reshape(-1, 2)


def is_instancer(obj) -> bool:
    """An Empty showing a collection (Add > Collection Instance)."""
    return obj.type == "EMPTY" and obj.instance_type == "COLLECTION" and obj.instance_collection is not None


def shown_instances(obj, depsgraph) -> list:
    """(original object, world matrix) of every object the collection instance ``obj`` shows, as
    the evaluated depsgraph has them (nested instances and the collection's offset included)."""
    shown = {}
    for instance in depsgraph.object_instances:
        if instance.is_instance and instance.parent is not None and instance.parent.original == obj:
            # a Text or curve is listed once per geometry component (curve and mesh): one key each
            matrix = np.array(instance.matrix_world)
            shown.setdefault((instance.object.original.name, matrix.round(9).tobytes()),
                             (instance.object.original, matrix))
    return list(shown.values())


def instanced_mesh_arrays(obj, depsgraph) -> tuple:
    """World vertices (Blender units) and polygons of the mesh objects the collection instance
    ``obj`` shows, joined as one mesh, where it shows them."""
    shown = [(o, m) for o, m in shown_instances(obj, depsgraph) if o.type == "MESH"]
    if not shown:
        raise SceneInputError(f"collection instance {obj.name!r} shows no mesh object")
    vertices, polygons, count = [], [], 0
    for shown_obj, matrix in shown:
        world, faces, _ = evaluated_mesh_arrays(shown_obj, depsgraph, matrix)
        vertices.append(world)
        polygons += [face + count for face in faces]
        count += len(world)
    return np.concatenate(vertices), polygons


def outlines_in_work(obj, depsgraph, frame: "WorkFrame") -> list:
    """Closed outlines (work mm, (k, 2) arrays) of a Text, curve or mesh object, seen from above;
    of a collection instance, those of the Text, curve and mesh objects it shows, where it shows them.

    Faces (a Text object, a filled curve, mesh faces) are merged into one region, so T-junctions
    and faces of either winding are fine; a wire must form closed loops.
    """
    if is_instancer(obj):
        check_level(obj, "collection instance")
        shown = [(o, m) for o, m in shown_instances(obj, depsgraph) if o.type in {"MESH", "CURVE", "FONT", "SURFACE"}]
        if not shown:
            raise SceneInputError(f"collection instance {obj.name!r} shows no Text, curve or mesh object")
        return [loop for shown_obj, matrix in shown for loop in object_outlines(shown_obj, depsgraph, frame, matrix)]
    return object_outlines(obj, depsgraph, frame)


def object_outlines(obj, depsgraph, frame: "WorkFrame", matrix=None) -> list:
    """:func:`outlines_in_work` of one Text, curve or mesh object (``matrix``: its world matrix
    when shown through an instance)."""
    if obj.type not in {"MESH", "CURVE", "FONT", "SURFACE"}:
        raise SceneInputError(f"object {obj.name!r} is a {obj.type.lower()}; use a Text, curve or mesh")
    check_level(obj, "object", matrix)
    vertices, polygons, edges = evaluated_mesh_arrays(obj, depsgraph, matrix)
    if not np.all(np.isfinite(vertices)):
        raise SceneInputError(f"object {obj.name!r} has a vertex with a non-finite coordinate")
    work = frame.to_work(vertices)
    if polygons:
        return region.loops(region.union_of_faces([work[p, :2] for p in polygons], f"object {obj.name!r}"))
    return [loop[:, :2] for loop in meshdata.edge_loops(work, edges, obj.name)]


@dataclass
class Plate:
    """A plate (stock) in work coordinates: top face outline (mm) and thickness."""

    outline: list      # [(k, 2) arrays] in work mm
    size: tuple        # (x, y, z) bounding-box size in mm
    frame: WorkFrame
    name: str = ""     # the plate object's name, for messages


# The largest travel (mm) of any machine the presets know, for a program written for a post with
# no machine of its own: a plate larger than this is no plate any machine here cuts.
def largest_travel() -> tuple:
    from ..toolpath.ir import machine as machines
    return tuple(max(p.travel[axis] for p in machines.PRESETS.values()) for axis in range(3))


def check_design_fits(name: str, size_mm, scene) -> None:
    """A design larger than any machine preset's travel (a unit-scale mistake), refused by name
    before any planning."""
    travel = largest_travel()
    size = f"{size_mm[0]:.6g} x {size_mm[1]:.6g} x {size_mm[2]:.6g}"
    for axis, letter in enumerate("XYZ"):
        if travel[axis] > 0 and size_mm[axis] > travel[axis] + 1e-6:
            raise SceneInputError(
                f"design {name!r} is {size} mm at the scene's unit "
                f"scale of {scene.unit_settings.scale_length:g} m per unit, larger than the {travel[axis]:g} mm "
                f"{letter} travel of any machine preset: check Scene > Units (Unit Scale) or the design's size")


def check_fits(plate: Plate, scene) -> None:
    """Plausibility before any planning: a plate larger than any machine preset's travel (X, Y; the
    thickness against Z) is a unit-scale mistake (200 units in a metre scene is 200 m), which would
    otherwise be planned for minutes.  A plate within that but larger than the job's own machine is
    not refused here: a small engraving on a big board fits the machine; the export gate measures
    what the program spans against the machine's travel."""
    travel = largest_travel()
    for axis, letter in enumerate("XYZ"):
        if not (travel[axis] > 0 and plate.size[axis] > travel[axis] + 1e-6):
            continue
        size = f"{plate.size[0]:.6g} x {plate.size[1]:.6g} x {plate.size[2]:.6g}"
        scale = f"{scene.unit_settings.scale_length:g}"
        raise SceneInputError(
            f"plate {plate.name!r} is {size} mm at the scene's unit scale of {scale} m per unit, larger than the "
            f"{travel[axis]:g} mm {letter} travel of any machine preset: check Scene > Units (Unit Scale) or the "
            f"plate's size")


def plate_from_object(obj, depsgraph, scene, origin: str = "CENTER") -> Plate:
    """The plate's top face, in a work frame with Z = 0 on the top.

    origin: "CENTER" (centre of the top face, as the paper programs its name plate) or
    "CORNER" (front-left corner of the top face, the usual router zero).
    """
    if obj is None:
        raise SceneInputError("no plate: pick the stock object (a mesh) in the CAM panel")
    if obj.type != "MESH":
        raise SceneInputError(f"plate {obj.name!r} must be a mesh object, not a {obj.type.lower()}")
    check_level(obj, "plate")
    vertices, polygons, edges = evaluated_mesh_arrays(obj, depsgraph)
    if len(vertices) < 3 or not polygons:
        raise SceneInputError(f"plate {obj.name!r} has no faces")
    if not np.all(np.isfinite(vertices)):
        raise SceneInputError(f"plate {obj.name!r} has a vertex with a non-finite coordinate")
    scale = mm_per_unit(scene)
    lo, hi = vertices.min(axis=0) * scale, vertices.max(axis=0) * scale
    reach = float(np.abs(np.concatenate([lo, hi])).max())
    if reach > MAX_REACH_MM:    # a unit scale of 1e9 m: Clipper's "Values exceed permitted range" traceback
        raise SceneInputError(f"plate {obj.name!r} reaches {reach:g} mm from the world origin (more than "
                              f"{MAX_REACH_MM:g} mm) at the scene's unit scale of {scene.unit_settings.scale_length:g} "
                              f"m per unit: is the unit scale right?")
    if origin == "CENTER":
        origin_mm = ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2])
    elif origin == "CORNER":
        origin_mm = (lo[0], lo[1], hi[2])
    else:
        raise SceneInputError(f"unknown work origin {origin!r}")
    frame = WorkFrame(scale, origin_mm)
    top_faces = meshdata.top_faces(vertices, polygons)
    if top_faces:
        work = frame.to_work(vertices)
        outline = region.loops(region.union_of_faces([work[p, :2] for p in top_faces], f"plate {obj.name!r}"))
    else:
        outline = [np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]]) - origin_mm[:2]]
    return Plate(outline, tuple(float(v) for v in hi - lo), frame, obj.name)


# ----------------------------------------------------------------------------------------
# Results -> scene
# ----------------------------------------------------------------------------------------

def result_collection(scene):
    collection = bpy.data.collections.get(COLLECTION)
    if collection is None:
        collection = bpy.data.collections.new(COLLECTION)
    if collection.name not in scene.collection.children:
        scene.collection.children.link(collection)
    return collection


def remove_objects(prefix: str):
    """Remove earlier results (objects and their data) whose names start with ``prefix``."""
    for obj in [o for o in bpy.data.objects if o.name.startswith(prefix)]:
        data = obj.data
        bpy.data.objects.remove(obj, do_unlink=True)
        if data is not None and data.users == 0:
            if isinstance(data, bpy.types.Mesh):
                bpy.data.meshes.remove(data)
            elif isinstance(data, bpy.types.Curve):
                bpy.data.curves.remove(data)


def polyline_object(scene, name: str, paths, frame: WorkFrame, color=(1, 1, 1, 1), tube_mm: float = 0.3):
    """A thin tube through each (k, 3) work-mm path: how toolpaths and contours are shown.

    A curve with a small bevel, not a wire mesh, so Solid mode draws it as a surface: in the
    object's colour with Color: Object, in its material's with the default Color: Material
    (toolpaths get their move kind's material: :mod:`.pathview`).
    """
    curve = bpy.data.curves.new(name, type="CURVE")
    curve.dimensions = "3D"
    curve.bevel_depth = tube_mm / frame.mm_per_unit
    curve.bevel_resolution = 0
    for path in paths:
        if len(path) < 2:
            continue
        points = frame.to_world(path)
        spline = curve.splines.new("POLY")
        spline.points.add(len(points) - 1)
        spline.points.foreach_set("co", np.hstack([points, np.ones((len(points), 1))]).ravel())
    obj = bpy.data.objects.new(name, curve)
    obj.color = color
    obj.show_in_front = True   # toolpaths run below the stock's top: draw them over it
    result_collection(scene).objects.link(obj)
    return obj


def curve_points(obj) -> np.ndarray:
    """World coordinates (Blender units) of every point of a polyline_object."""
    return np.array([p.co[:3] for spline in obj.data.splines for p in spline.points])


def fill_mesh(mesh, vertices, faces):
    """Fill an empty mesh with (k, 3) vertices and faces (an (f, n) array or a list of index
    sequences) with bulk array calls; faces drawn flat (the "sharp_face" attribute), as
    ``Mesh.from_pydata`` does, without its per-element Python loops."""
    vertices = np.ascontiguousarray(vertices, np.float32).reshape(-1, 3)
    if isinstance(faces, np.ndarray) and faces.ndim == 2:
        lengths = np.full(len(faces), faces.shape[1], np.int64)
        flat = faces.astype(np.int32).ravel()
    else:
        lengths = np.fromiter((len(face) for face in faces), np.int64, len(faces))
        flat = np.fromiter((int(i) for face in faces for i in face), np.int32, int(lengths.sum()))
    if len(flat) and not (0 <= flat.min() and flat.max() < len(vertices)):
        raise ValueError(f"mesh {mesh.name!r}: a face index is outside 0..{len(vertices) - 1}")
    mesh.vertices.add(len(vertices))
    mesh.vertices.foreach_set("co", vertices.ravel())
    mesh.loops.add(len(flat))
    mesh.polygons.add(len(lengths))
    if len(lengths):
        mesh.polygons.foreach_set("loop_start", (np.cumsum(lengths) - lengths).astype(np.int32))
        mesh.polygons.foreach_set("vertices", flat)
        sharp = mesh.attributes.new("sharp_face", "BOOLEAN", "FACE")
        sharp.data.foreach_set("value", np.ones(len(lengths), bool))
        mesh.update(calc_edges=True)
    return mesh


def mesh_object(scene, name: str, vertices_mm, faces, frame: WorkFrame, color=(0.8, 0.7, 0.5, 1)):
    """A mesh from work-mm vertices and triangle/polygon indices (simulated stock, flat patterns)."""
    mesh = bpy.data.meshes.new(name)
    fill_mesh(mesh, frame.to_world(np.asarray(vertices_mm, float)), faces)
    obj = bpy.data.objects.new(name, mesh)
    obj.color = color
    result_collection(scene).objects.link(obj)
    return obj
