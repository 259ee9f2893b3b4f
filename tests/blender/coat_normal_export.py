"""Coated materials whose Coat Normal is fed three ways, exported with rt_export.py, for
`tests/blender_coat_normal.rs`: one Normal Map node into both Normal and Coat Normal
(`shared`), a Normal Map node into Coat Normal only (`own`), a Bump node into Coat Normal
(`bumped`, which rt cannot follow and warns about), a Normal Map node into Normal on the
default uv map and another into Coat Normal on the plane's second map (`two_sets`), and a
coat weight texture on the second map under a base normal map on the default one
(`weight_on_second`).

    python tests/blender/coat_normal_export.py OUT_DIR
"""

import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender"))
import rt_export  # noqa: E402


def normal_map(tree, strength, uv_map=""):
    """A Normal Map node of `strength` reading a small tilted-normal image, both on uv map
    `uv_map` (the default one where empty)."""
    image = bpy.data.images.new("tilted", 4, 4, alpha=True)
    image.colorspace_settings.name = "Non-Color"
    pixels = np.tile(np.array([0.6, 0.5, 0.95, 1.0], np.float32), 16)
    image.pixels.foreach_set(pixels)
    image.update()
    image.pack()
    tex = tree.nodes.new("ShaderNodeTexImage")
    tex.image = image
    node = tree.nodes.new("ShaderNodeNormalMap")
    node.inputs["Strength"].default_value = strength
    tree.links.new(tex.outputs["Color"], node.inputs["Color"])
    if uv_map:
        node.uv_map = uv_map
        tree.links.new(uv_map_node(tree, uv_map).outputs["UV"], tex.inputs["Vector"])
    return node


def uv_map_node(tree, name):
    node = tree.nodes.new("ShaderNodeUVMap")
    node.uv_map = name
    return node


def coated(name, build):
    m = bpy.data.materials.new(name)
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Coat Weight"].default_value = 1.0
    build(m.node_tree, bsdf)
    return m


def shared(tree, bsdf):
    node = normal_map(tree, 0.8)
    tree.links.new(node.outputs["Normal"], bsdf.inputs["Normal"])
    tree.links.new(node.outputs["Normal"], bsdf.inputs["Coat Normal"])


def own(tree, bsdf):
    tree.links.new(normal_map(tree, 0.6).outputs["Normal"], bsdf.inputs["Coat Normal"])


def bumped(tree, bsdf):
    bump = tree.nodes.new("ShaderNodeBump")
    bump.name = "Flakes"
    noise = tree.nodes.new("ShaderNodeTexNoise")
    tree.links.new(noise.outputs["Fac"], bump.inputs["Height"])
    tree.links.new(bump.outputs["Normal"], bsdf.inputs["Coat Normal"])


def two_sets(tree, bsdf):
    tree.links.new(normal_map(tree, 0.8).outputs["Normal"], bsdf.inputs["Normal"])
    tree.links.new(normal_map(tree, 0.6, "second").outputs["Normal"], bsdf.inputs["Coat Normal"])


def weight_on_second(tree, bsdf):
    tree.links.new(normal_map(tree, 0.8).outputs["Normal"], bsdf.inputs["Normal"])
    image = bpy.data.images.new("weight", 4, 4, alpha=True)
    image.colorspace_settings.name = "Non-Color"
    image.pixels.foreach_set(np.tile(np.array([0.5, 0.5, 0.5, 1.0], np.float32), 16))
    image.update()
    image.pack()
    tex = tree.nodes.new("ShaderNodeTexImage")
    tex.image = image
    tree.links.new(uv_map_node(tree, "second").outputs["UV"], tex.inputs["Vector"])
    tree.links.new(tex.outputs["Color"], bsdf.inputs["Coat Weight"])


CASES = {"shared": shared, "own": own, "bumped": bumped, "two_sets": two_sets, "weight_on_second": weight_on_second}


def main():
    out = sys.argv[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    for i, (name, build) in enumerate(CASES.items()):
        bpy.ops.mesh.primitive_plane_add(location=(3.0 * i, 0.0, 0.0))
        obj = bpy.context.active_object
        obj.name = obj.data.name = name
        # A second uv map, the first turned a quarter.
        second = obj.data.uv_layers.new(name="second")
        uvs = np.empty(len(obj.data.loops) * 2, np.float32)
        obj.data.uv_layers[0].uv.foreach_get("vector", uvs)
        uvs[0::2], uvs[1::2] = 1.0 - uvs[1::2], uvs[0::2].copy()
        second.uv.foreach_set("vector", uvs)
        obj.data.uv_layers.active = obj.data.uv_layers[0]
        obj.data.uv_layers[0].active_render = True
        obj.data.materials.append(coated(name, build))
    rt_export.export_scene(scene, os.path.join(out, "assets"), os.path.join(out, "scene.toml"))


if __name__ == "__main__":
    main()
