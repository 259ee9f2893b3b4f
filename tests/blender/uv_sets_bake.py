"""Exports two scenes of tests/cycles/make_texture_refs.py with blender/rt_export.py into
the folder given as the first argument, for tests/blender_uv_sets.rs: `uv_sets` (a
texture on the second uv map, one on the first) and `baked_noise` with --bake (32 texels)
and without. Writes report.json with what the node trees looked like around the bake."""

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
with open(os.path.join(out, "report.json"), "w") as f:
    json.dump(report, f)
