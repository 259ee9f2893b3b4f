"""Materials whose shader nodes rt cannot render exactly, exported with rt_export.py, for
`tests/blender_shader_nodes.rs`: every approximation is a warning naming the material and
the node (and a rough Diffuse BSDF, which rt renders as Cycles does, is not warned about).

    python tests/blender/shader_node_warnings.py OUT_DIR
"""

import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender"))
import rt_export  # noqa: E402


def material(name, build):
    m = bpy.data.materials.new(name)
    tree = m.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    surface = build(tree)
    tree.links.new(surface.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    return m


def node(tree, kind, name, **inputs):
    n = tree.nodes.new(kind)
    n.name = name
    for key, value in inputs.items():
        n.inputs[key].default_value = value
    return n


def mix(tree, name, a, b, fac=0.5):
    n = node(tree, "ShaderNodeMixShader", name, Fac=fac)
    tree.links.new(a.outputs[0], n.inputs[1])
    tree.links.new(b.outputs[0], n.inputs[2])
    return n


def hair(tree):
    return node(tree, "ShaderNodeBsdfHair", "Strands")


def toon(tree):
    return node(tree, "ShaderNodeBsdfToon", "Cartoon", Size=0.3)


def linked_fac(tree):
    m = mix(tree, "Blend", node(tree, "ShaderNodeBsdfDiffuse", "Matte"), node(tree, "ShaderNodeBsdfTransparent", "Clear"))
    noise = node(tree, "ShaderNodeTexNoise", "Clouds")
    tree.links.new(noise.outputs["Fac"], m.inputs["Fac"])
    return m


def glossy_glass(tree):
    """A Glossy and a Refraction BSDF (a pair rt does not mix per shading point, as it does a
    Glossy and a Glass): the heavier one, warned."""
    return mix(tree, "Both", node(tree, "ShaderNodeBsdfGlossy", "Shine"), node(tree, "ShaderNodeBsdfRefraction", "Pane"),
               0.7)


def subsurface(tree):
    p = node(tree, "ShaderNodeBsdfPrincipled", "Skin")
    p.inputs["Subsurface Weight"].default_value = 0.5
    return p


def rough_diffuse(tree):
    return node(tree, "ShaderNodeBsdfDiffuse", "Felt", Roughness=0.5)


def translucent(tree):
    return node(tree, "ShaderNodeBsdfTranslucent", "Leaf")


def half_empty(tree):
    """A Mix Shader with one input left empty: Cycles takes it as black."""
    n = node(tree, "ShaderNodeMixShader", "Half", Fac=0.5)
    tree.links.new(node(tree, "ShaderNodeBsdfDiffuse", "Paint", Color=(0.8, 0.6, 0.4, 1.0)).outputs[0], n.inputs[1])
    return n


def image_ior(tree):
    """An image straight into the IOR, whose values (0-1) need a Map Range node to be an index."""
    p = node(tree, "ShaderNodeBsdfPrincipled", "Lens")
    img = tree.nodes.new("ShaderNodeTexImage")
    img.image = bpy.data.images.new("ior_map", 4, 4)
    tree.links.new(img.outputs["Color"], p.inputs["IOR"])
    # And into the Subsurface Weight, which rt reads no texture of (its subsurface is the diffuse base).
    tree.links.new(img.outputs["Alpha"], p.inputs["Subsurface Weight"])
    return p


def main():
    out = sys.argv[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    builds = {"hair_mat": hair, "noisy_mix": linked_fac, "glossy_glass": glossy_glass,
              "skin_mat": subsurface, "felt_mat": rough_diffuse, "leaf_mat": translucent,
              "half_empty": half_empty, "lens_mat": image_ior, "toon_mat": toon}
    for i, (name, build) in enumerate(builds.items()):
        bpy.ops.mesh.primitive_cube_add(location=(3.0 * i, 0.0, 0.0))
        obj = bpy.context.active_object
        obj.name = f"cube_{name}"
        obj.data.materials.append(material(name, build))
    rt_export.export_scene(scene, os.path.join(out, "assets"), os.path.join(out, "scene.toml"))


if __name__ == "__main__":
    main()
