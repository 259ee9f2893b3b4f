"""Cycles references for the render passes rt writes beside the image (tests/cycles_passes.rs
compares rt's AOVs against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_pass_refs.py [--spp 1024] [NAME...]

`pass_diffuse_color`: Principled spheres of every layer that takes from the diffuse
(the default dielectric specular, a half metal, a coat, a sheen, some transmission, a
Diffuse BSDF) on a floor, under a uniform world; Cycles' Diffuse Color pass is the weight
of the first surface's diffuse closures. Exported with blender/rt_export.py into
tests/cycles/scenes/NAME/ and rendered into tests/cycles/NAME.exr, a multilayer EXR whose
view layer holds Combined and Diffuse Color. CI does not run Cycles: commit both.
"""

import bpy

import cycles_reference as cycles


def diffuse_bsdf(name, colour):
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    node = tree.nodes.new("ShaderNodeBsdfDiffuse")
    node.inputs["Color"].default_value = (*colour, 1.0)
    tree.links.new(node.outputs[0], tree.nodes.new("ShaderNodeOutputMaterial").inputs["Surface"])
    return material


def diffuse_color_scene():
    scene = cycles.new_scene()
    cycles.set_up(scene, 96, 64, bounces=4)
    cycles.uniform_world(scene, (0.6, 0.7, 0.9))
    scene.view_layers[0].use_pass_diffuse_color = True
    scene.render.image_settings.media_type = "MULTI_LAYER_IMAGE"
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = "32"
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    bpy.context.active_object.data.materials.append(cycles.principled("floor", (0.5, 0.45, 0.4)))
    spheres = [
        cycles.principled("default", (0.8, 0.8, 0.8)),
        cycles.principled("half metal", (0.9, 0.3, 0.2), Metallic=0.5, Roughness=0.3),
        cycles.principled("coated", (0.2, 0.7, 0.3), **{"Coat Weight": 1.0, "Coat Tint": (0.8, 0.9, 1.0, 1.0)}),
        cycles.principled("sheen", (0.2, 0.3, 0.9), **{"Sheen Weight": 1.0}),
        cycles.principled("part glass", (0.9, 0.8, 0.3), **{"Transmission Weight": 0.3}),
        diffuse_bsdf("diffuse", (0.7, 0.6, 0.1)),
    ]
    for i, material in enumerate(spheres):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, segments=48, ring_count=24, location=(-3.5 + 1.4 * i, 0.0, 0.6))
        bpy.ops.object.shade_smooth()
        bpy.context.active_object.data.materials.append(material)
    cycles.camera(scene, (0.0, -9.0, 3.0), 78.0)
    return scene


SCENES = {"pass_diffuse_color": diffuse_color_scene}


if __name__ == "__main__":
    cycles.make(__doc__, 1024, SCENES)
