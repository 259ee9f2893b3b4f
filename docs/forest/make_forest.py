"""The README's geometry-nodes forest: built in bpy, rendered by Cycles, exported for rt.

    .venv-bpy/bin/python docs/forest/make_forest.py [--trees-per-m2 1.5] [--spp 128]

A 40 m hill of ground scattered with trees by geometry nodes (Distribute Points on
Faces, then Instance on Points of one tree: a trunk and a crown, two materials, with
random scale and rotation), under a sun and a sky colour. Writes
docs/images/forest_cycles.png (Cycles, Standard view transform) and exports the scene
into /tmp/rt-forest/ (scene.toml, one asset and an instance file); then
`rt render /tmp/rt-forest/scene.toml -o docs/images/forest_rt.png` renders rt's twin.
"""

import argparse
import math
import os
import sys

import bpy
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "blender"))
sys.path.insert(0, os.path.join(REPO, "tests", "cycles"))
import rt_export  # noqa: E402
from make_instance_refs import add_camera, diffuse, hidden_collection, move_to  # noqa: E402

WIDTH, HEIGHT = 480, 270


def tree(sources):
    """One tree: a trunk and a crown (two cones), one mesh with two materials."""
    bpy.ops.mesh.primitive_cylinder_add(vertices=8, radius=0.12, depth=1.2, location=(0, 0, 0.6))
    trunk = bpy.context.object
    bpy.ops.mesh.primitive_cone_add(vertices=12, radius1=0.9, depth=2.2, location=(0, 0, 2.0))
    crown = bpy.context.object
    bpy.ops.mesh.primitive_cone_add(vertices=12, radius1=0.65, depth=1.6, location=(0, 0, 2.9))
    top = bpy.context.object
    trunk.data.materials.append(diffuse("bark", (0.25, 0.15, 0.08)))
    for c in (crown, top):
        c.data.materials.append(diffuse("needles", (0.05, 0.25, 0.08)))
    bpy.ops.object.select_all(action="DESELECT")
    for o in (trunk, crown, top):
        o.select_set(True)
    bpy.context.view_layer.objects.active = trunk
    bpy.ops.object.join()
    trunk.name = trunk.data.name = "tree"
    move_to(trunk, sources)
    return trunk


def forest_modifier(ground, instance, density):
    nodes_tree = bpy.data.node_groups.new("forest", "GeometryNodeTree")
    nodes_tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    nodes_tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = nodes_tree.nodes, nodes_tree.links
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    distribute = nodes.new("GeometryNodeDistributePointsOnFaces")
    distribute.distribute_method = "POISSON"
    distribute.inputs["Distance Min"].default_value = 0.9
    distribute.inputs["Density Max"].default_value = density
    distribute.inputs["Seed"].default_value = 11
    on_points = nodes.new("GeometryNodeInstanceOnPoints")
    info = nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = instance
    scale = nodes.new("FunctionNodeRandomValue")
    scale.data_type = "FLOAT"
    scale.inputs["Min"].default_value = 0.6
    scale.inputs["Max"].default_value = 1.4
    spin = nodes.new("FunctionNodeRandomValue")
    spin.data_type = "FLOAT_VECTOR"
    spin.inputs["Min"].default_value = (0.0, 0.0, 0.0)
    spin.inputs["Max"].default_value = (0.0, 0.0, 2.0 * math.pi)
    join = nodes.new("GeometryNodeJoinGeometry")
    links.new(group_in.outputs[0], distribute.inputs["Mesh"])
    links.new(distribute.outputs["Points"], on_points.inputs["Points"])
    links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
    links.new(scale.outputs["Value"], on_points.inputs["Scale"])
    links.new(spin.outputs["Value"], on_points.inputs["Rotation"])
    links.new(on_points.outputs["Instances"], join.inputs[0])
    links.new(group_in.outputs[0], join.inputs[0])
    links.new(join.outputs[0], group_out.inputs[0])
    ground.modifiers.new("forest", "NODES").node_group = nodes_tree


def build(scene, density):
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=40, y_subdivisions=40, size=40.0)
    ground = bpy.context.object
    ground.name = ground.data.name = "hill"
    for v in ground.data.vertices:
        v.co.z = 1.5 * math.sin(0.15 * v.co.x) * math.cos(0.11 * v.co.y) + 0.04 * v.co.y
    ground.data.materials.append(diffuse("grass", (0.18, 0.3, 0.1)))
    sources = hidden_collection(scene, "sources")
    forest_modifier(ground, tree(sources), density)
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 3.0
    sun.data.angle = math.radians(2.0)
    sun.rotation_euler = (math.radians(50), 0.0, math.radians(-35))
    scene.collection.objects.link(sun)
    return Vector((0.0, -24.0, 7.0)), Vector((0.0, 2.0, 0.5)), 30.0


def main():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trees-per-m2", type=float, default=1.5)
    parser.add_argument("--spp", type=int, default=128)
    parser.add_argument("--out", default="/tmp/rt-forest")
    args = parser.parse_args(argv)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    add_camera(scene, *build(scene, args.trees_per_m2))
    world = bpy.data.worlds.new("world")
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.55, 0.7, 1.0, 1.0)
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"
    c = scene.cycles
    c.device, c.samples, c.use_denoising, c.use_adaptive_sampling = "CPU", args.spp, False, False
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    c.max_bounces = c.diffuse_bounces = 8
    bpy.context.view_layer.update()
    export = rt_export.export_scene(scene, os.path.join(args.out, "assets"), os.path.join(args.out, "scene.toml"))
    print("instances:", export.instance_counts(), flush=True)
    scene.render.filepath = os.path.join(REPO, "docs", "images", "forest_cycles.png")
    bpy.ops.render.render(write_still=True)
    print("wrote", scene.render.filepath, flush=True)


if __name__ == "__main__":
    main()
