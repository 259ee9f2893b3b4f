#!/usr/bin/env python3
"""Rows of five spheres under a uniform world, each sphere's material built from Blender's
shader nodes other than the Principled BSDF, rendered with Cycles and exported with
blender/rt_export.py, for `tests/cycles_shader_nodes.rs`:

    /work/main/.venv-bpy/bin/python tests/cycles/make_shader_node_refs.py [--spp 2048] [NAME...]

For each NAME it writes `tests/cycles/nodes_NAME.exr` (Cycles, linear, 32-bit) and
`tests/cycles/scenes/nodes_NAME/` (the exported assets and `scene.toml`). Cycles is set up
as a reference as in make_texture_refs.py; the nodes use Multiscatter GGX, rt's default.
Every node set-up here is one that the exporter maps exactly (README: "Other shader nodes").
"""

import bpy

import cycles_reference as cycles
import make_principled_refs as principled_refs
import make_texture_refs as refs


def node(tree, kind, **inputs):
    n = tree.nodes.new(kind)
    for key, value in inputs.items():
        if key == "distribution":
            n.distribution = value
        else:
            principled_refs.set_input(n, key, value)
    return n


def diffuse(tree, color, roughness=0.0):
    return node(tree, "ShaderNodeBsdfDiffuse", Color=color, Roughness=roughness)


def glossy(tree, color, roughness):
    return node(tree, "ShaderNodeBsdfGlossy", Color=color, Roughness=roughness, distribution="MULTI_GGX")


def glass(tree, roughness, ior=1.45):
    return node(tree, "ShaderNodeBsdfGlass", Color=(1.0, 1.0, 1.0), Roughness=roughness, IOR=ior,
                distribution="MULTI_GGX")


def emission(tree, color, strength):
    return node(tree, "ShaderNodeEmission", Color=color, Strength=strength)


def transparent(tree):
    return node(tree, "ShaderNodeBsdfTransparent", Color=(1.0, 1.0, 1.0))


def mix(tree, fac, a, b):
    n = tree.nodes.new("ShaderNodeMixShader")
    n.inputs["Fac"].default_value = fac
    tree.links.new(a.outputs[0], n.inputs[1])
    tree.links.new(b.outputs[0], n.inputs[2])
    return n


def add(tree, a, b):
    n = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(a.outputs[0], n.inputs[0])
    tree.links.new(b.outputs[0], n.inputs[1])
    return n


# Per row, per sphere: a function of the node tree that returns the surface shader node.
ROWS = {
    "single": [
        lambda t: diffuse(t, (0.8, 0.3, 0.2)),
        lambda t: glossy(t, (0.9, 0.6, 0.3), 0.3),
        lambda t: glossy(t, (0.3, 0.6, 0.9), 0.0),
        lambda t: glass(t, 0.1),
        lambda t: emission(t, (1.0, 0.5, 0.2), 2.0),
    ],
    "mixed": [
        lambda t: mix(t, 0.4, diffuse(t, (0.2, 0.4, 0.8)), transparent(t)),
        lambda t: mix(t, 0.3, diffuse(t, (0.3, 0.8, 0.3)), emission(t, (1.0, 0.8, 0.2), 3.0)),
        lambda t: add(t, emission(t, (0.2, 0.3, 1.0), 0.5), glossy(t, (0.8, 0.8, 0.8), 0.5)),
        lambda t: mix(t, 0.25, diffuse(t, (0.9, 0.1, 0.1)), diffuse(t, (0.1, 0.1, 0.9))),
        lambda t: mix(t, 0.7, transparent(t), glossy(t, (0.9, 0.9, 0.2), 0.2)),
    ],
    # The Diffuse BSDF's Roughness: Cycles' Oren-Nayar closure, the Principled's Diffuse Roughness.
    "rough_diffuse_sun": [lambda t, r=r: diffuse(t, (0.3, 0.5, 0.9), r) for r in principled_refs.STEPS],
}
# Rows lit by a sun (from the front, in a dim world) rather than a white world.
SUNLIT = {"rough_diffuse_sun": principled_refs.FRONT_SUN}


def build(scene, name):
    if name in SUNLIT:
        rotation, sky = SUNLIT[name]
        cycles.uniform_world(scene, sky)
        refs.sun(scene, rotation)
    else:
        cycles.uniform_world(scene, (1.0, 1.0, 1.0))
    principled_refs.sphere_row(scene, (material(f"{name}_{i}", make) for i, make in enumerate(ROWS[name])))


def material(name, make):
    """A material whose surface is the node `make` builds in its tree."""
    m = bpy.data.materials.new(name)
    tree = m.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    tree.links.new(make(tree).outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    return m


def main():
    args = cycles.arguments(__doc__, 2048, list(ROWS))
    for name in args.names:
        scene = principled_refs.row_scene()
        build(scene, name)
        cycles.export(scene, f"nodes_{name}")
        cycles.render(scene, f"nodes_{name}", args)


if __name__ == "__main__":
    main()
