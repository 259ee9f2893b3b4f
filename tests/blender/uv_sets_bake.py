"""Exports two scenes of tests/cycles/make_texture_refs.py with blender/rt_export.py into
the folder given as the first argument, for tests/blender_uv_sets.rs: `uv_sets` (a
texture on the second uv map, one on the first), `mappings` (two Mapping nodes on one uv
map) and `baked_noise` (a noise on coordinates turned by Vector Rotate, which rt does not
evaluate) with --bake (32 texels) and without; `baked_noise` of a Noise Texture, which rt evaluates as a node graph
(nothing baked, even with --bake); then, with --bake, the turned noise's
plane seen only through two collection instances (its collection excluded from the view
layer), and a plane whose Normal is a Bump node fed by a Gabor Texture; a Bump fed by the
noise, which rt evaluates as a node graph (nothing baked). Writes report.json with what
the node trees looked like around the bake."""

import json
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cycles"))
import make_texture_refs as refs  # noqa: E402
from cycles_reference import rt_export  # noqa: E402

out = sys.argv[1]

report = {}
scene = refs.reset()
refs.scene_uv_sets(scene)
rt_export.export_scene(scene, os.path.join(out, "uv_sets", "assets"), os.path.join(out, "uv_sets", "scene.toml"))

scene = refs.reset()
refs.scene_mappings(scene)
rt_export.export_scene(scene, os.path.join(out, "mappings", "assets"), os.path.join(out, "mappings", "scene.toml"))


scene = refs.reset()
refs.scene_baked_noise(scene, texture="noise")
rt_export.export_scene(scene, os.path.join(out, "graph", "assets"), os.path.join(out, "graph", "scene.toml"),
                       bake_size=32)

scene = refs.reset()
refs.scene_baked_noise(scene)
material = bpy.data.materials["noise"]


def tree_shape(m):
    return sorted(n.bl_idname for n in m.node_tree.nodes), sorted(
        f"{link.from_node.name}.{link.from_socket.name}->{link.to_node.name}.{link.to_socket.name}"
        for link in m.node_tree.links)


report["before"] = tree_shape(material)
rt_export.export_scene(scene, os.path.join(out, "baked", "assets"), os.path.join(out, "baked", "scene.toml"),
                            bake_size=32)
report["after"] = tree_shape(material)
report["images"] = len(bpy.data.images)
rt_export.export_scene(scene, os.path.join(out, "unbaked", "assets"), os.path.join(out, "unbaked", "scene.toml"))
scene = refs.reset()
refs.scene_baked_noise(scene)
plane = bpy.data.objects["plane"]
hidden = bpy.data.collections.new("hidden")
scene.collection.children.link(hidden)
scene.collection.objects.unlink(plane)
hidden.objects.link(plane)
bpy.context.view_layer.layer_collection.children["hidden"].exclude = True
for x in (-1.5, 1.5):
    inst = bpy.data.objects.new(f"instance_{x}", None)
    inst.instance_type = "COLLECTION"
    inst.instance_collection = hidden
    inst.location = (x, 0.0, 0.0)
    scene.collection.objects.link(inst)
rt_export.export_scene(scene, os.path.join(out, "instanced", "assets"),
                            os.path.join(out, "instanced", "scene.toml"), bake_size=32)
report["objects_after_instanced_bake"] = sorted(o.name for o in bpy.data.objects)

scene = refs.reset()
refs.scene_baked_noise(scene, texture="noise")
material = bpy.data.materials["noise"]
tree = material.node_tree
bsdf = tree.nodes["Principled BSDF"]
noise = next(n for n in tree.nodes if n.type == "TEX_NOISE")
bump = tree.nodes.new("ShaderNodeBump")
bump.inputs["Strength"].default_value = 0.5
bump.inputs["Distance"].default_value = 0.2  # Blender 5.0 defaults to 0.001: no visible tilt
tree.links.new(noise.outputs["Fac"], bump.inputs["Height"])
tree.links.new(bump.outputs["Normal"], bsdf.inputs["Normal"])
rt_export.export_scene(scene, os.path.join(out, "bump_graph", "assets"),
                       os.path.join(out, "bump_graph", "scene.toml"), bake_size=32)
gabor = tree.nodes.new("ShaderNodeTexGabor")
gabor.inputs["Scale"].default_value = 4.0
tree.links.new(gabor.outputs["Value"], bump.inputs["Height"])
report["bump_before"] = tree_shape(material)
rt_export.export_scene(scene, os.path.join(out, "bump", "assets"), os.path.join(out, "bump", "scene.toml"),
                            bake_size=32)
report["bump_after"] = tree_shape(material)
with open(os.path.join(out, "report.json"), "w") as f:
    json.dump(report, f)
