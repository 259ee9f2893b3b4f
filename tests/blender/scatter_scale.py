"""A geometry-nodes scatter of COUNT instances of a 10,000-triangle sphere on a grid,
exported with blender/rt_export.py; prints the export's wall time as JSON.

    python tests/blender/scatter_scale.py COUNT OUT_DIR

OUT_DIR receives assets/ and scene.toml (with scene_instances/); the JSON line has the
instance counts per asset, the seconds of depsgraph evaluation and of export, and the
peak resident memory of this process in MiB. The grid has
side × side points, side = ceil(sqrt(COUNT)), trimmed to COUNT by deleting the last
points; each instance is turned and scaled by a random amount.
"""

import json
import math
import os
import resource
import sys
import time

import bpy

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "blender"))
import rt_export  # noqa: E402


def build(count):
    scene = bpy.context.scene
    # 100 segments × 51 rings: 100 × 49 × 2 quads' triangles + 2 × 100 fan triangles = 10,000.
    bpy.ops.mesh.primitive_uv_sphere_add(segments=100, ring_count=51, radius=0.4)
    sphere = bpy.context.object
    sphere.name = sphere.data.name = "sphere"
    sphere.hide_render = True
    material = bpy.data.materials.new("sphere")
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.7, 0.3, 0.1, 1.0)
    bsdf.inputs["Specular IOR Level"].default_value = 0.0
    bsdf.inputs["Roughness"].default_value = 1.0
    sphere.data.materials.append(material)

    side = math.ceil(math.sqrt(count))
    field = bpy.data.objects.new("field", bpy.data.meshes.new("field"))
    scene.collection.objects.link(field)
    tree = bpy.data.node_groups.new("scatter", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = tree.nodes, tree.links
    group_out = nodes.new("NodeGroupOutput")
    grid = nodes.new("GeometryNodeMeshGrid")
    grid.inputs["Size X"].default_value = grid.inputs["Size Y"].default_value = float(side)
    grid.inputs["Vertices X"].default_value = grid.inputs["Vertices Y"].default_value = side
    # Points past COUNT go: index >= count.
    index = nodes.new("GeometryNodeInputIndex")
    beyond = nodes.new("FunctionNodeCompare")
    beyond.data_type, beyond.operation = "INT", "GREATER_EQUAL"
    beyond.inputs[3].default_value = count
    links.new(index.outputs[0], beyond.inputs[2])
    trim = nodes.new("GeometryNodeDeleteGeometry")
    trim.domain = "POINT"
    links.new(grid.outputs["Mesh"], trim.inputs["Geometry"])
    links.new(beyond.outputs[0], trim.inputs["Selection"])
    on_points = nodes.new("GeometryNodeInstanceOnPoints")
    info = nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = sphere
    turn = nodes.new("FunctionNodeRandomValue")
    turn.data_type = "FLOAT_VECTOR"
    turn.inputs["Max"].default_value = (0.0, 0.0, 2.0 * math.pi)
    size = nodes.new("FunctionNodeRandomValue")
    size.data_type = "FLOAT"
    size.inputs[2].default_value, size.inputs[3].default_value = 0.6, 1.1
    links.new(trim.outputs[0], on_points.inputs["Points"])
    links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
    links.new(turn.outputs[0], on_points.inputs["Rotation"])
    links.new(size.outputs[1], on_points.inputs["Scale"])
    links.new(on_points.outputs["Instances"], group_out.inputs[0])
    field.modifiers.new("scatter", "NODES").node_group = tree

    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    cam.location = (0.0, -0.75 * side - 2.0, 0.5 * side + 2.0)
    cam.rotation_euler = (math.radians(55.0), 0.0, 0.0)
    scene.camera = cam
    scene.render.resolution_x = scene.render.resolution_y = 64
    world = bpy.data.worlds.new("world")
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.5, 0.6, 0.8, 1.0)
    scene.world = world
    return scene


def main():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
    count, out = int(argv[0]), os.path.abspath(argv[1])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = build(count)
    start = time.perf_counter()
    bpy.context.view_layer.update()
    evaluated = time.perf_counter()
    export = rt_export.export_scene(scene, os.path.join(out, "assets"), os.path.join(out, "scene.toml"))
    done = time.perf_counter()
    counts = export.instance_counts()
    peak_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    report = {"instances": counts, "evaluate_s": evaluated - start, "export_s": done - evaluated, "peak_mib": peak_mib}
    print(json.dumps(report), flush=True)


if __name__ == "__main__":
    main()
