"""Cycles references for the film's alpha: holdouts and Film › Transparent Glass
(tests/cycles_film.rs compares rt against them, colour and alpha).

    /work/main/.venv-bpy/bin/python tests/cycles/make_film_refs.py [--spp 1024] [NAME...]

Every scene is exported with blender/rt_export.py into tests/cycles/scenes/NAME/ and
rendered into tests/cycles/NAME.exr (RGBA). CI does not run Cycles: commit both.
"""

import math

import bpy

import cycles_reference as cycles
from make_node_graph_refs import mix_material, new, noise


def holdout_scene():
    """Holdouts in front of a mirror, under a uniform sky, with an opaque film: a sphere of the
    Holdout shader, one that mixes a red diffuse with a Holdout by a constant 0.4, one that
    picks between a Holdout and a blue diffuse by noise, a green sphere whose object is held
    out, and a cube in a held-out collection. Cycles makes each pixel's alpha the share the
    camera saw unheld, whatever the film; the mirror shows the objects' own materials (the
    Holdout shader's as black)."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 96, 64, bounces=8)
    cycles.uniform_world(scene, (0.6, 0.7, 0.9))
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    bpy.context.active_object.data.materials.append(cycles.diffuse("floor", (0.7, 0.7, 0.65)))
    bpy.ops.mesh.primitive_plane_add(size=7.0, location=(0.0, 3.0, 2.0), rotation=(math.radians(90.0), 0.0, 0.0))
    mirror = bpy.data.materials.new("mirror")
    principled = mirror.node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (0.9, 0.9, 0.9, 1.0)
    principled.inputs["Metallic"].default_value = 1.0
    principled.inputs["Roughness"].default_value = 0.0
    bpy.context.active_object.data.materials.append(mirror)

    def holdout(tree):
        return tree.nodes.new("ShaderNodeHoldout")

    bare = bpy.data.materials.new("holdout shader")
    bare.node_tree.nodes.clear()
    bare.node_tree.links.new(holdout(bare.node_tree).outputs[0],
                             bare.node_tree.nodes.new("ShaderNodeOutputMaterial").inputs["Surface"])
    part = mix_material("part held out", lambda t: new(t, "ShaderNodeValue").outputs[0], holdout,
                        lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.8, 0.1, 0.1, 1.0)}))
    # A constant factor, unlinked: 0.4 of the first shader (the Holdout).
    mix = next(n for n in part.node_tree.nodes if n.type == "MIX_SHADER")
    part.node_tree.links.remove(mix.inputs["Fac"].links[0])
    mix.inputs["Fac"].default_value = 0.6
    spheres = {
        "holdout shader": bare,
        "part held out": part,
        "holes by noise": mix_material(
            "holes by noise", lambda t: noise(t, Scale=4.0, Detail=1.0).outputs["Fac"], holdout,
            lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.1, 0.2, 0.8, 1.0)})),
        "held-out object": cycles.diffuse("green", (0.1, 0.7, 0.1)),
    }
    for i, (name, material) in enumerate(spheres.items()):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, segments=32, ring_count=16, location=(-2.7 + 1.8 * i, 0.0, 0.7))
        bpy.ops.object.shade_smooth()
        sphere = bpy.context.active_object
        sphere.name = name
        sphere.data.materials.append(material)
        sphere.is_holdout = name == "held-out object"
    held = bpy.data.collections.new("held out")
    scene.collection.children.link(held)
    bpy.ops.mesh.primitive_cube_add(size=0.9, location=(0.0, -1.6, 0.45))
    cube = bpy.context.active_object
    cube.data.materials.append(cycles.diffuse("orange", (0.9, 0.5, 0.1)))
    for collection in cube.users_collection:
        collection.objects.unlink(cube)
    held.objects.link(cube)
    bpy.context.view_layer.layer_collection.children["held out"].holdout = True
    cycles.camera(scene, (0.0, -9.0, 2.4), 82.0)
    return scene


def glass(name, roughness):
    return cycles.principled(name, (1.0, 1.0, 1.0), Roughness=roughness, IOR=1.45, **{"Transmission Weight": 1.0})


def transparent_glass_scene():
    """Film › Transparent with Transparent Glass (Roughness Threshold 0.1): a clear glass
    sphere half over the sky and half over a small floor, a frosted one (roughness 0.08,
    under the threshold: clear too), a rough one (0.2, over it: opaque; Cycles compares the
    roughness, not GGX's α = roughness², with the threshold), and a held-out cube seen
    through the clear sphere. The sky seen
    through clear glass is left out (alpha: what the glass reflects), as is the hole behind
    it; the rough sphere covers its pixels."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 96, 64, bounces=8)
    cycles.uniform_world(scene, (0.6, 0.7, 0.9))
    scene.render.film_transparent = True
    scene.cycles.film_transparent_glass = True
    scene.cycles.film_transparent_roughness = 0.1
    bpy.ops.mesh.primitive_plane_add(size=3.0, location=(-1.0, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(cycles.diffuse("floor", (0.7, 0.7, 0.65)))
    # Cycles compares the roughness with the threshold: 0.08 lets the background through, 0.2 does not.
    for name, roughness, x, radius in (("clear", 0.0, -1.2, 0.8), ("frosted", 0.08, 1.1, 0.6), ("rough", 0.2, 2.6, 0.35)):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, segments=48, ring_count=24, location=(x, 0.0, radius))
        bpy.ops.object.shade_smooth()
        bpy.context.active_object.data.materials.append(glass(name, roughness))
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(-1.2, 1.6, 0.9))
    cube = bpy.context.active_object
    cube.data.materials.append(cycles.diffuse("orange", (0.9, 0.5, 0.1)))
    cube.is_holdout = True
    cycles.camera(scene, (0.0, -7.0, 1.6), 84.0)
    return scene


SCENES = {
    "holdouts": holdout_scene,
    "transparent_glass": transparent_glass_scene,
}


if __name__ == "__main__":
    cycles.make(__doc__, 1024, SCENES)
