#!/usr/bin/env python3
"""Normal-mapped and alpha-blended scenes built in bpy, rendered by Cycles and exported
with blender/rt_export.py, for `tests/cycles_normal_maps.rs`:

    /work/main/.venv-bpy/bin/python tests/cycles/make_normal_map_refs.py [--spp 4096] [NAME...]

For each NAME it writes `tests/cycles/texture_NAME.exr` and
`tests/cycles/scenes/texture_NAME/`, with the Cycles settings and helpers of
`make_texture_refs.py`. The normal maps are baked here from a height field with numpy:
for h(u, v), the tangent-space normal is (−∂h/∂u, −∂h/∂v, 1) normalised, stored as
RGB = (n + 1) / 2 in a Non-Color image, and read by a Normal Map node (tangent space,
the mesh's uv map, strength 1) linked into the Principled BSDF's Normal.
"""

import math

import bpy
import numpy as np

import cycles_reference as cycles
import make_texture_refs as refs


def bump_normals(n, bumps_u, bumps_v, amplitude):
    """An (n, n, 4) normal map of h = a·sin(2π bu u)·sin(2π bv v): rows from the top, v up."""
    y, x = np.mgrid[0:n, 0:n]
    u = (x + 0.5) / n
    v = 1.0 - (y + 0.5) / n
    ku, kv = 2.0 * math.pi * bumps_u, 2.0 * math.pi * bumps_v
    dh_du = amplitude * ku * np.cos(ku * u) * np.sin(kv * v)
    dh_dv = amplitude * kv * np.sin(ku * u) * np.cos(kv * v)
    normal = np.stack([-dh_du, -dh_dv, np.ones_like(u)], axis=2)
    normal /= np.linalg.norm(normal, axis=2, keepdims=True)
    pixels = np.ones((n, n, 4))
    pixels[:, :, :3] = 0.5 * (normal + 1.0)
    return pixels


def normal_mapped(name, pixels, base_color, roughness):
    m, tree, bsdf = refs.principled(name)
    bsdf.inputs["Base Color"].default_value = (*base_color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    tex = refs.image_node(tree, refs.image(f"{name}_normal", pixels, srgb=False))
    node = tree.nodes.new("ShaderNodeNormalMap")
    node.space = "TANGENT"
    node.inputs["Strength"].default_value = 1.0
    tree.links.new(tex.outputs["Color"], node.inputs["Color"])
    tree.links.new(node.outputs["Normal"], bsdf.inputs["Normal"])
    return m


def bumpy_sphere(scene, segments, rings):
    """A smooth diffuse sphere of `segments` × `rings` faces with a normal map of 8 × 4
    bumps, lit by a low sun, over a floor."""
    cycles.uniform_world(scene, (0.2, 0.2, 0.2))
    refs.sun(scene, (math.radians(55), 0.0, math.radians(-40)))
    m = normal_mapped("bumpy", bump_normals(128, 8, 4, 0.01), (0.8, 0.8, 0.8), 1.0)
    refs.add_object(scene, "sphere", bpy.ops.mesh.primitive_uv_sphere_add, m, radius=1.0, segments=segments,
                    ring_count=rings)
    bpy.ops.object.shade_smooth()
    refs.floor(scene, (0.5, 0.5, 0.5), 8.0, -1.0)
    refs.camera(scene, (0.0, -3.6, 0.8), (0.0, 0.0, -0.1), 45.0)


def scene_normal_sphere(scene):
    """`bumpy_sphere` of 48 × 24 faces."""
    bumpy_sphere(scene, 48, 24)


def scene_normal_cube(scene):
    """A diffuse cube (each face its own uv island and orientation) with a normal map of
    3 × 3 bumps, under a sun and a grey sky: every face's tangent frame shows."""
    cycles.uniform_world(scene, (0.25, 0.25, 0.25))
    refs.sun(scene, (math.radians(50), 0.0, math.radians(-25)))
    m = normal_mapped("bumpy", bump_normals(128, 3, 3, 0.025), (0.7, 0.55, 0.4), 0.4)
    cube = refs.add_object(scene, "cube", bpy.ops.mesh.primitive_cube_add, m, size=1.4, location=(0, 0, -0.3))
    cube.rotation_euler = (0.0, 0.0, math.radians(35.0))
    refs.floor(scene, (0.5, 0.5, 0.5), 8.0, -1.0)
    refs.camera(scene, (0.0, -3.4, 1.6), (0.0, 0.0, -0.3), 45.0)


def scene_normal_second_uv(scene):
    """The cube of `scene_normal_cube` with a normal map of 3 × 2 bumps on a second uv map,
    laid out unlike the first (each face's island turned a quarter and scaled): the
    Normal Map node and the image (through a UV Map node) name it, so the tangent frame
    is that map's, and the first map's frame would show other bumps."""
    cycles.uniform_world(scene, (0.25, 0.25, 0.25))
    refs.sun(scene, (math.radians(50), 0.0, math.radians(-25)))
    m = normal_mapped("bumpy", bump_normals(128, 3, 2, 0.025), (0.7, 0.55, 0.4), 0.4)
    tree = m.node_tree
    node = next(n for n in tree.nodes if n.type == "NORMAL_MAP")
    node.uv_map = "second"
    uv_node = tree.nodes.new("ShaderNodeUVMap")
    uv_node.uv_map = "second"
    tex = next(n for n in tree.nodes if n.type == "TEX_IMAGE")
    tree.links.new(uv_node.outputs["UV"], tex.inputs["Vector"])
    cube = refs.add_object(scene, "cube", bpy.ops.mesh.primitive_cube_add, m, size=1.4, location=(0, 0, -0.3))
    cube.rotation_euler = (0.0, 0.0, math.radians(35.0))
    mesh = cube.data
    first = mesh.uv_layers[0]
    second = mesh.uv_layers.new(name="second")
    uvs = np.empty(len(mesh.loops) * 2, np.float32)
    first.uv.foreach_get("vector", uvs)
    u, v = uvs[0::2].copy(), uvs[1::2].copy()
    uvs[0::2], uvs[1::2] = 2.0 * (1.0 - v), 2.0 * u
    second.uv.foreach_set("vector", uvs)
    first.active_render = True
    mesh.uv_layers.active = first
    refs.floor(scene, (0.5, 0.5, 0.5), 8.0, -1.0)
    refs.camera(scene, (0.0, -3.4, 1.6), (0.0, 0.0, -0.3), 45.0)


def scene_normal_mapping(scene):
    """The cube of `scene_normal_cube` with a normal map of 3 × 2 bumps behind a Mapping
    node (scaled 1.5, turned a quarter, moved) and a checker base colour read as it is, on
    the one uv map: the map tiles and turns on its own, in the tangent frame of the uv map
    (Cycles' Normal Map node takes its tangents from the map, not from the Mapping node)."""
    cycles.uniform_world(scene, (0.25, 0.25, 0.25))
    refs.sun(scene, (math.radians(50), 0.0, math.radians(-25)))
    m = normal_mapped("bumpy", bump_normals(128, 3, 2, 0.025), (0.7, 0.55, 0.4), 0.4)
    tree = m.node_tree
    tex = next(n for n in tree.nodes if n.type == "TEX_IMAGE")
    coords = tree.nodes.new("ShaderNodeTexCoord")
    mapping = refs.mapping(tree, (1.5, 1.5), 90.0, (0.1, 0.05), coords.outputs["UV"])
    tree.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    bsdf = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
    colour = refs.image_node(tree, refs.image("checker", refs.checker(4, (0.7, 0.55, 0.4), (0.3, 0.45, 0.6))))
    tree.links.new(colour.outputs["Color"], bsdf.inputs["Base Color"])
    cube = refs.add_object(scene, "cube", bpy.ops.mesh.primitive_cube_add, m, size=1.4, location=(0, 0, -0.3))
    cube.rotation_euler = (0.0, 0.0, math.radians(35.0))
    refs.floor(scene, (0.5, 0.5, 0.5), 8.0, -1.0)
    refs.camera(scene, (0.0, -3.4, 1.6), (0.0, 0.0, -0.3), 45.0)


def scene_alpha_blend(scene):
    """A quad whose base colour texture has alpha 0.25 and 0.75 in stripes, over a floor
    under a sun: Cycles mixes by alpha, for the camera and for the shadow alike."""
    cycles.uniform_world(scene, (0.1, 0.1, 0.1))
    m, tree, bsdf = refs.principled("veil")
    n = 32
    y, x = np.mgrid[0:n, 0:n]
    pixels = np.zeros((n, n, 4))
    pixels[:, :, 0] = np.where(x < n // 2, 0.9, 0.1)
    pixels[:, :, 1] = 0.3
    pixels[:, :, 2] = np.where(x < n // 2, 0.1, 0.9)
    pixels[:, :, 3] = np.where((y // 8) % 2 == 0, 0.25, 0.75)
    tex = refs.image_node(tree, refs.image("veil", pixels), "EXTEND")
    tex.interpolation = "Closest"
    tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    tree.links.new(tex.outputs["Alpha"], bsdf.inputs["Alpha"])
    bsdf.inputs["Roughness"].default_value = 1.0
    refs.add_object(scene, "veil", bpy.ops.mesh.primitive_plane_add, m, size=1.6, location=(0, 0, 0.7),
                    rotation=(math.radians(10), 0, 0))
    refs.floor(scene, (0.5, 0.5, 0.5), 6.0)
    refs.sun(scene, (math.radians(25), 0.0, math.radians(30)))
    refs.camera(scene, (0.0, -2.6, 3.2), (0.0, 0.0, 0.2), 45.0)


def scene_normal_coarse_sphere(scene):
    """`bumpy_sphere` of 12 × 6 faces: Cycles starts its shadow rays from the smooth surface
    that the interpolated normals describe, normal map or not, so faces turned from the sun
    whose normals still face it are lit."""
    bumpy_sphere(scene, 12, 6)


SCENES = {
    "normal_sphere": scene_normal_sphere,
    "normal_cube": scene_normal_cube,
    "normal_second_uv": scene_normal_second_uv,
    "normal_mapping": scene_normal_mapping,
    "alpha_blend": scene_alpha_blend,
    "normal_coarse_sphere": scene_normal_coarse_sphere,
}


def main():
    args = cycles.arguments(__doc__, 4096, list(SCENES))
    for name in args.names:
        scene = refs.reset()
        SCENES[name](scene)
        cycles.export(scene, f"texture_{name}")
        cycles.render(scene, f"texture_{name}", args)


if __name__ == "__main__":
    main()
