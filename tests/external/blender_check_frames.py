"""Runs inside Blender (blender -b --python this -- FRAMES_DIR FRAME PNG REPORT_JSON).

Imports every OBJ and PLY file of one frame of a moreau output directory with Blender's own
importers (File > Import > Wavefront OBJ and Stanford PLY), checks each imported mesh against the
file (vertex and face counts, every coordinate), renders the frame with Cycles on the CPU (meshes
with an emission colour each, the PLY points through a "Mesh to Points" geometry node) and writes
a report: per object, its colour, its vertices' projected centre in the image and its count.
"""
import json
import math
import pathlib
import struct
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

frames, frame, png, report_path = sys.argv[sys.argv.index("--") + 1:]
frames = pathlib.Path(frames)
COLOURS = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1), (0, 1, 1)]


def to_blender(x, y, z):
    """OBJ import's default axes (forward -Z, up Y): moreau's y-up (x, y, z) is Blender's (x, -z, y)."""
    return (x, -z, y)


def read_obj(path):
    vertices, faces = [], 0
    for line in path.read_text().splitlines():
        if line.startswith("v "):
            vertices.append(tuple(float(v) for v in line.split()[1:4]))
        elif line.startswith("f "):
            faces += 1
    return vertices, faces


def read_ply(path):
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    count = int(next(line for line in header if line.startswith("element vertex")).split()[2])
    properties = [line.split()[2] for line in header if line.startswith("property double")]
    rows = struct.iter_unpack("<" + "d" * len(properties), data[end:])
    return [row[:3] for row in rows], count, properties


def emission(name, colour):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    light = nodes.new("ShaderNodeEmission")
    light.inputs["Color"].default_value = (*colour, 1)
    light.inputs["Strength"].default_value = 1
    out = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(light.outputs["Emission"], out.inputs["Surface"])
    return material


def as_points(obj, radius, material):
    """A geometry-nodes modifier that renders a vertex-only mesh as spheres of `radius`."""
    tree = bpy.data.node_groups.new("points_" + obj.name, "GeometryNodeTree")
    tree.inputs.new("NodeSocketGeometry", "Geometry")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    source, sink = tree.nodes.new("NodeGroupInput"), tree.nodes.new("NodeGroupOutput")
    points = tree.nodes.new("GeometryNodeMeshToPoints")
    points.inputs["Radius"].default_value = radius
    coloured = tree.nodes.new("GeometryNodeSetMaterial")
    coloured.inputs["Material"].default_value = material
    tree.links.new(source.outputs["Geometry"], points.inputs["Mesh"])
    tree.links.new(points.outputs["Points"], coloured.inputs["Geometry"])
    tree.links.new(coloured.outputs["Geometry"], sink.inputs["Geometry"])
    obj.modifiers.new("points", "NODES").node_group = tree


bpy.ops.wm.read_factory_settings(use_empty=True)
report = {"objects": {}, "problems": []}
colour_index = 0
for path in sorted(frames.glob(f"*_{int(frame):06d}.obj")) + sorted(frames.glob(f"*_{int(frame):06d}.ply")):
    before = set(bpy.data.objects)
    if path.suffix == ".obj":
        bpy.ops.wm.obj_import(filepath=str(path))
        expected, faces = read_obj(path)
        expected = [to_blender(*v) for v in expected]
    else:
        bpy.ops.import_mesh.ply(filepath=str(path))
        expected, count, properties = read_ply(path)
        expected = [to_blender(*v) for v in expected]
        faces = 0
        if count != len(expected):
            report["problems"].append(f"{path.name}: header says {count} vertices, the data holds {len(expected)}")
    (obj,) = set(bpy.data.objects) - before
    if path.suffix == ".ply":
        obj.rotation_euler = (math.pi / 2, 0, 0)  # the PLY importer has no axis option: the OBJ importer's turn
        bpy.context.view_layer.update()
    mesh = obj.data
    got = [tuple(obj.matrix_world @ v.co) for v in mesh.vertices]
    if len(got) != len(expected) or len(mesh.polygons) != faces:
        report["problems"].append(f"{path.name}: Blender imported {len(got)} vertices and {len(mesh.polygons)} faces; "
                                  f"the file has {len(expected)} and {faces}")
    else:
        worst = max((max(abs(a - b) for a, b in zip(g, e)) for g, e in zip(got, expected)), default=0)
        if worst > 1e-5:  # single precision in Blender of metre-scale coordinates
            report["problems"].append(f"{path.name}: a vertex moved by {worst} m on import")
    colour = COLOURS[colour_index % len(COLOURS)]
    colour_index += 1
    material = emission(path.stem, colour)
    if path.suffix == ".ply":
        as_points(obj, 0.02, material)
    else:
        mesh.materials.append(material)
    report["objects"][path.stem] = {"colour": colour, "vertices": len(got), "file": path.name,
                                    "centre": [sum(c) / len(got) for c in zip(*got)] if got else None}

# A camera looking at the centre of everything from the front (-y in Blender: moreau's +z side).
lo = [min(v[i] for o in bpy.data.objects for v in (o.matrix_world @ w.co for w in o.data.vertices)) for i in range(3)]
hi = [max(v[i] for o in bpy.data.objects for v in (o.matrix_world @ w.co for w in o.data.vertices)) for i in range(3)]
centre = Vector([(a + b) / 2 for a, b in zip(lo, hi)])
size = max(b - a for a, b in zip(lo, hi))
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
bpy.context.scene.collection.objects.link(camera)
camera.location = centre + Vector((0, -2.2 * size, 0.6 * size))
camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
scene = bpy.context.scene
scene.camera = camera
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 4
scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
scene.render.resolution_x, scene.render.resolution_y = 240, 180
scene.render.resolution_percentage = 100
scene.world = bpy.data.worlds.new("black")
scene.world.color = (0, 0, 0)
scene.view_settings.view_transform = "Standard"
scene.render.filepath = png
bpy.ops.render.render(write_still=True)
for name, entry in report["objects"].items():
    if entry["centre"]:
        x, y, _ = world_to_camera_view(scene, camera, Vector(entry["centre"]))
        entry["image_centre"] = [x, 1 - y]  # fractions of the width and height, from the top left
# Where each colour landed in the render: the share of the image it covers and its centroid.
image = bpy.data.images.load(png)
width, height = image.size
pixels = list(image.pixels)  # RGBA rows from the bottom
for name, entry in report["objects"].items():
    want = entry["colour"]
    xs, ys = [], []
    for k in range(width * height):
        r, g, b = pixels[4 * k:4 * k + 3]
        if all((c > 0.5) if w else (c < 0.2) for c, w in zip((r, g, b), want)):
            xs.append((k % width + 0.5) / width)
            ys.append(1 - (k // width + 0.5) / height)
    entry["rendered_share"] = len(xs) / (width * height)
    entry["rendered_centre"] = [sum(xs) / len(xs), sum(ys) / len(ys)] if xs else None
pathlib.Path(report_path).write_text(json.dumps(report, indent=1))
