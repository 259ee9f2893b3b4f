#!/usr/bin/env python3
"""Builds small textured scenes in bpy, renders them with Cycles and exports them with
blender/rt_export.py, for `tests/cycles_textures.rs`:

    /work/main/.venv-bpy/bin/python tests/cycles/make_texture_refs.py [--spp N] [NAME...]

References are rendered at 4096 samples per pixel (`--spp` overrides it), the figure
`tests/cycles_textures.rs` assumes.

For each NAME it writes `tests/cycles/texture_NAME.exr` (Cycles, linear, 32-bit) and
`tests/cycles/scenes/texture_NAME/` (the exported assets, their images and
`scene.toml`). Images are generated in bpy and packed into the (unsaved) .blend.

Cycles is set up as a reference: box pixel filter of width 1, no clamping, no
denoising, no adaptive sampling, blur_glossy 0, bounce limits raised, Multiscatter GGX
(rt's default model), Specular IOR Level 0 on non-metals (plain Lambert diffuse).
"""

import math
import os

import bpy
import numpy as np

import cycles_reference as cycles
from cycles_reference import uniform_world

SIZE = 64


def reset():
    """A new scene with Cycles set up as the reference, transparent bounces raised for
    alpha-blended layers."""
    scene = cycles.new_scene()
    cycles.set_up(scene, SIZE, bounces=12, transparent_max_bounces=64)
    return scene


def camera(scene, location, look_at, fov_deg=40.0):
    from mathutils import Vector

    data = bpy.data.cameras.new("camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fov_deg)
    obj = bpy.data.objects.new("camera", data)
    scene.collection.objects.link(obj)
    obj.location = location
    direction = Vector(look_at) - Vector(location)
    obj.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    data.dof.focus_distance = direction.length
    scene.camera = obj


def image(name, pixels, srgb=True):
    """A packed image from an (h, w, 4) array of values in [0, 1], rows from the top."""
    h, w, _ = pixels.shape
    img = bpy.data.images.new(name, w, h, alpha=True)
    img.colorspace_settings.name = "sRGB" if srgb else "Non-Color"
    img.pixels.foreach_set(np.ascontiguousarray(pixels[::-1], dtype=np.float32).ravel())
    img.update()
    img.pack()
    return img


def principled(name):
    m = bpy.data.materials.new(name)
    tree = m.node_tree
    bsdf = tree.nodes["Principled BSDF"]
    bsdf.inputs["Specular IOR Level"].default_value = 0.0
    bsdf.distribution = "MULTI_GGX"
    return m, tree, bsdf


def image_node(tree, img, extension="REPEAT"):
    node = tree.nodes.new("ShaderNodeTexImage")
    node.image = img
    node.extension = extension
    node.interpolation = "Linear"
    return node


def add_object(scene, name, mesh_op, material, **kwargs):
    mesh_op(**kwargs)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material)
    return obj


def floor(scene, colour, size, z=0.0, roughness=1.0):
    """A square floor of side `size` at height `z`, diffuse (no specular layer)."""
    m, _, bsdf = principled("floor")
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    add_object(scene, "floor", bpy.ops.mesh.primitive_plane_add, m, size=size, location=(0, 0, z))


def checker(n, a, b):
    y, x = np.mgrid[0:n, 0:n]
    on = ((x + y) % 2 == 0)[:, :, None]
    return np.where(on, np.array([*a, 1.0]), np.array([*b, 1.0]))


def mapped_checker(tree):
    """In `tree`: the checker image through a Mapping node (rotation, offset; its Scale left
    to the caller) of the UV coordinates; (the image node, the Mapping node)."""
    tex = image_node(tree, image("checker", checker(8, (0.9, 0.1, 0.05), (0.95, 0.95, 0.9))))
    mapping = tree.nodes.new("ShaderNodeMapping")
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(20.0))
    mapping.inputs["Location"].default_value = (0.1, 0.25, 0.0)
    coords = tree.nodes.new("ShaderNodeTexCoord")
    tree.links.new(coords.outputs["UV"], mapping.inputs["Vector"])
    tree.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    return tex, mapping


def checker_plane(scene, m, bsdf):
    """The checker scenes' rough tilted plane of material `m` under a white world, and their camera."""
    uniform_world(scene, (1.0, 1.0, 1.0))
    bsdf.inputs["Roughness"].default_value = 1.0
    add_object(scene, "plane", bpy.ops.mesh.primitive_plane_add, m, size=2.0, rotation=(math.radians(60), 0, 0))
    camera(scene, (0.0, -3.0, 1.2), (0.0, 0.0, 0.0), 40.0)


def scene_checker(scene):
    """A checker base colour through a Mapping node (scale, rotation, offset) on a tilted plane."""
    m, tree, bsdf = principled("checker")
    tex, mapping = mapped_checker(tree)
    mapping.inputs["Scale"].default_value = (2.0, 1.5, 1.0)
    tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    checker_plane(scene, m, bsdf)


def scene_grouped_checker(scene):
    """`scene_checker`'s plane, its checker, Mapping and coordinates inside a node group (as
    texture sets from asset libraries come), whose Color output feeds the Base Color and
    whose Scale input sets the Mapping's."""
    m, tree, bsdf = principled("grouped checker")
    group = bpy.data.node_groups.new("texture set", "ShaderNodeTree")
    group.interface.new_socket("Scale", in_out="INPUT", socket_type="NodeSocketVector")
    group.interface.new_socket("Color", in_out="OUTPUT", socket_type="NodeSocketColor")
    inner_in, inner_out = group.nodes.new("NodeGroupInput"), group.nodes.new("NodeGroupOutput")
    tex, mapping = mapped_checker(group)
    group.links.new(inner_in.outputs["Scale"], mapping.inputs["Scale"])
    group.links.new(tex.outputs["Color"], inner_out.inputs["Color"])
    node = tree.nodes.new("ShaderNodeGroup")
    node.node_tree = group
    node.inputs["Scale"].default_value = (2.0, 1.5, 1.0)
    tree.links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
    checker_plane(scene, m, bsdf)


def sun(scene, rotation):
    light = bpy.data.lights.new("sun", "SUN")
    # rt's default sun: irradiance pi at normal incidence.
    light.energy = math.pi
    light.angle = math.radians(0.53)
    obj = bpy.data.objects.new("sun", light)
    scene.collection.objects.link(obj)
    obj.rotation_euler = rotation


def scene_rough_metal(scene):
    """Roughness and metallic maps (separate images, combined by the exporter) on a sunlit
    sphere: highlights of rough and sharp metal against diffuse stripes. No floor: the sun
    reflected by the sharp metal would light it by rare bright paths, whose noise a pixel's
    own standard error misses (a block of floor seemed 8.6 σ off at 256 spp and agreed at
    2048), so the test would check the noise estimate rather than the maps."""
    uniform_world(scene, (0.3, 0.3, 0.3))
    sun(scene, (math.radians(40), 0.0, math.radians(-35)))
    m, tree, bsdf = principled("rough_metal")
    bsdf.inputs["Base Color"].default_value = (0.95, 0.95, 0.95, 1.0)
    y, x = np.mgrid[0:32, 0:32]
    rough = np.where((x // 8) % 2 == 0, 0.25, 0.7)[:, :, None].repeat(3, 2)
    metal = np.where((y // 8) % 2 == 0, 1.0, 0.0)[:, :, None].repeat(3, 2)
    ones = np.ones((32, 32, 1))
    rough_tex = image_node(tree, image("roughness", np.concatenate([rough, ones], 2), srgb=False))
    metal_tex = image_node(tree, image("metallic", np.concatenate([metal, ones], 2), srgb=False))
    tree.links.new(rough_tex.outputs["Color"], bsdf.inputs["Roughness"])
    tree.links.new(metal_tex.outputs["Color"], bsdf.inputs["Metallic"])
    sphere = add_object(scene, "sphere", bpy.ops.mesh.primitive_uv_sphere_add, m, radius=1.0, segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    sphere.rotation_euler = (0.0, 0.0, math.radians(30.0))
    camera(scene, (0.0, -3.6, 0.8), (0.0, 0.0, -0.1), 45.0)


def scene_leaves(scene):
    """An alpha-masked leaf (a disc with a notch) over a floor, casting its shape's shadow."""
    uniform_world(scene, (0.05, 0.05, 0.05))
    m, tree, bsdf = principled("leaf")
    n = 64
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n - 0.5
    inside = (x * x + y * y < 0.2) & ~((np.abs(x) < 0.08) & (y > 0.0))
    pixels = np.zeros((n, n, 4))
    pixels[:, :, 0], pixels[:, :, 1], pixels[:, :, 2] = 0.15, 0.55, 0.1
    pixels[:, :, 3] = inside
    tex = image_node(tree, image("leaf", pixels), "EXTEND")
    tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    tree.links.new(tex.outputs["Alpha"], bsdf.inputs["Alpha"])
    bsdf.inputs["Roughness"].default_value = 1.0
    add_object(scene, "leaf", bpy.ops.mesh.primitive_plane_add, m, size=1.6, location=(0, 0, 0.8),
               rotation=(math.radians(10), 0, 0))
    floor(scene, (0.8, 0.8, 0.8), 6.0)
    sun(scene, (math.radians(25), 0.0, math.radians(30)))
    camera(scene, (0.0, -2.6, 3.2), (0.0, 0.0, 0.2), 45.0)


def scene_emissive(scene):
    """An emission texture (strength 3) on a panel that lights a floor."""
    uniform_world(scene, (0.0, 0.0, 0.0))
    m, tree, bsdf = principled("screen")
    bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    y, x = np.mgrid[0:16, 0:16]
    pixels = np.zeros((16, 16, 4))
    pixels[:, :, 0] = np.where(x < 8, 1.0, 0.1)
    pixels[:, :, 1] = np.where(y < 8, 0.8, 0.2)
    pixels[:, :, 2] = 0.3
    pixels[:, :, 3] = 1.0
    tex = image_node(tree, image("screen", pixels), "EXTEND")
    tree.links.new(tex.outputs["Color"], bsdf.inputs["Emission Color"])
    bsdf.inputs["Emission Strength"].default_value = 3.0
    add_object(scene, "screen", bpy.ops.mesh.primitive_plane_add, m, size=1.2, location=(0, 0.6, 0.7),
               rotation=(math.radians(80), 0, 0))
    floor(scene, (0.8, 0.8, 0.8), 6.0)
    camera(scene, (0.0, -2.8, 1.6), (0.0, 0.2, 0.4), 45.0)


def scene_emission_strength_map(scene):
    """A grey image (a ramp across u from 0.2 to 1, its colour read as a number) into the
    Emission Strength of a panel of one warm colour that lights a floor. A ramp, not sharp
    stripes: glTF's emission texture is sRGB, which rt filters before decoding as Cycles
    filters sRGB images, while Cycles filters this Non-Color image's linear values (between
    texels of 1 and 0.25 the two differ by up to 12%)."""
    uniform_world(scene, (0.0, 0.0, 0.0))
    m, tree, bsdf = principled("strip_light")
    bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bsdf.inputs["Emission Color"].default_value = (1.0, 0.7, 0.4, 1.0)
    pixels = np.ones((16, 16, 4))
    pixels[:, :, :3] = np.linspace(0.2, 1.0, 16)[None, :, None]
    tex = image_node(tree, image("strip_light", pixels, srgb=False), "EXTEND")
    tree.links.new(tex.outputs["Color"], bsdf.inputs["Emission Strength"])
    add_object(scene, "screen", bpy.ops.mesh.primitive_plane_add, m, size=1.2, location=(0, 0.6, 0.7),
               rotation=(math.radians(80), 0, 0))
    floor(scene, (0.8, 0.8, 0.8), 6.0)
    camera(scene, (0.0, -2.8, 1.6), (0.0, 0.2, 0.4), 45.0)


def add_second_uv_map(mesh):
    """A second uv map "second" of `mesh`, its first one turned a quarter, scaled 1.5 and
    moved; the first stays the one Cycles reads by default."""
    second = mesh.uv_layers.new(name="second")
    first = mesh.uv_layers[0]
    uvs = np.empty(len(mesh.loops) * 2, np.float32)
    first.uv.foreach_get("vector", uvs)
    u, v = uvs[0::2].copy(), uvs[1::2].copy()
    uvs[0::2], uvs[1::2] = 1.5 * (1.0 - v) + 0.1, 1.5 * u + 0.2
    second.uv.foreach_set("vector", uvs)
    first.active_render = True
    mesh.uv_layers.active = first


def scene_uv_sets(scene):
    """A sunlit plane with two uv maps: its base colour (a checker) reads the second map
    through a UV Map node, laid out unlike the first (turned a quarter, scaled, moved),
    and its roughness (stripes) reads the default map, so the sun's glint shows them."""
    uniform_world(scene, (0.2, 0.2, 0.2))
    m, tree, bsdf = principled("two_maps")
    bsdf.inputs["Specular IOR Level"].default_value = 0.5
    colour = image_node(tree, image("checker", checker(4, (0.8, 0.15, 0.1), (0.9, 0.9, 0.85))))
    uv_node = tree.nodes.new("ShaderNodeUVMap")
    uv_node.uv_map = "second"
    tree.links.new(uv_node.outputs["UV"], colour.inputs["Vector"])
    tree.links.new(colour.outputs["Color"], bsdf.inputs["Base Color"])
    y, x = np.mgrid[0:32, 0:32]
    stripes = np.where((x // 8) % 2 == 0, 0.15, 0.6)[:, :, None].repeat(3, 2)
    rough = image_node(tree, image("stripes", np.concatenate([stripes, np.ones((32, 32, 1))], 2), srgb=False))
    tree.links.new(rough.outputs["Color"], bsdf.inputs["Roughness"])
    plane = add_object(scene, "plane", bpy.ops.mesh.primitive_plane_add, m, size=2.0,
                       rotation=(math.radians(60), 0, 0))
    add_second_uv_map(plane.data)
    # The sun near the mirror direction of the view at the plane's centre.
    sun(scene, (math.radians(48.0), 0.0, math.radians(8.0)))
    camera(scene, (0.0, -3.0, 1.2), (0.0, 0.0, 0.0), 40.0)


def mapping(tree, scale, rotation_deg, location, source):
    """A Mapping node (Point) fed by `source`'s output."""
    node = tree.nodes.new("ShaderNodeMapping")
    node.inputs["Scale"].default_value = (*scale, 1.0)
    node.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(rotation_deg))
    node.inputs["Location"].default_value = (*location, 0.0)
    tree.links.new(source, node.inputs["Vector"])
    return node


def scene_uv_mappings(scene):
    """The plane of `scene_uv_sets`, each texture behind its own Mapping node: the checker
    on the second map scaled, turned and moved one way, the roughness stripes on the
    default map another, so that each uv set carries its own transform."""
    scene_uv_sets(scene)
    tree = bpy.data.materials["two_maps"].node_tree
    colour = next(n for n in tree.nodes if n.type == "TEX_IMAGE" and n.image.name == "checker")
    rough = next(n for n in tree.nodes if n.type == "TEX_IMAGE" and n.image.name == "stripes")
    uv_node = next(n for n in tree.nodes if n.type == "UVMAP")
    a = mapping(tree, (1.5, 0.75), 30.0, (0.2, -0.1), uv_node.outputs["UV"])
    tree.links.new(a.outputs["Vector"], colour.inputs["Vector"])
    coords = tree.nodes.new("ShaderNodeTexCoord")
    b = mapping(tree, (0.5, 2.0), -15.0, (0.1, 0.3), coords.outputs["UV"])
    tree.links.new(b.outputs["Vector"], rough.inputs["Vector"])


def scene_mappings(scene):
    """A sunlit glossy plane whose base colour (a checker, scaled 1.5 and turned 20°) and
    roughness (stripes, tiled 4 times) read the one default uv map through Mapping nodes of
    their own, as a detail map tiled beside a base colour is: each texture its own
    transform on one uv set."""
    uniform_world(scene, (0.2, 0.2, 0.2))
    m, tree, bsdf = principled("mappings")
    bsdf.inputs["Specular IOR Level"].default_value = 0.5
    colour = image_node(tree, image("checker", checker(4, (0.8, 0.15, 0.1), (0.9, 0.9, 0.85))))
    tree.links.new(colour.outputs["Color"], bsdf.inputs["Base Color"])
    y, x = np.mgrid[0:32, 0:32]
    stripes = np.where((x // 8) % 2 == 0, 0.15, 0.6)[:, :, None].repeat(3, 2)
    rough = image_node(tree, image("stripes", np.concatenate([stripes, np.ones((32, 32, 1))], 2), srgb=False))
    tree.links.new(rough.outputs["Color"], bsdf.inputs["Roughness"])
    coords = tree.nodes.new("ShaderNodeTexCoord")
    a = mapping(tree, (1.5, 1.5), 20.0, (0.1, 0.2), coords.outputs["UV"])
    tree.links.new(a.outputs["Vector"], colour.inputs["Vector"])
    b = mapping(tree, (4.0, 4.0), 0.0, (0.0, 0.0), coords.outputs["UV"])
    tree.links.new(b.outputs["Vector"], rough.inputs["Vector"])
    add_object(scene, "plane", bpy.ops.mesh.primitive_plane_add, m, size=2.0, rotation=(math.radians(60), 0, 0))
    # The sun near the mirror direction of the view at the plane's centre, as in `scene_uv_sets`.
    sun(scene, (math.radians(48.0), 0.0, math.radians(8.0)))
    camera(scene, (0.0, -3.0, 1.2), (0.0, 0.0, 0.0), 40.0)


def procedural(tree, texture):
    """A Noise Texture's Color on coordinates turned by a Vector Rotate node (a node rt does
    not evaluate, so the exporter bakes it with `--bake`) or, with `texture` "noise", on its
    own coordinates (which rt evaluates as a node graph)."""
    noise = tree.nodes.new("ShaderNodeTexNoise")
    noise.inputs["Scale"].default_value = 4.0
    noise.inputs["Detail"].default_value = 2.0
    if texture == "rotated":
        rotate = tree.nodes.new("ShaderNodeVectorRotate")
        rotate.rotation_type = "Z_AXIS"
        rotate.inputs["Angle"].default_value = 0.3
        tree.links.new(tree.nodes.new("ShaderNodeTexCoord").outputs["Generated"], rotate.inputs["Vector"])
        tree.links.new(rotate.outputs["Vector"], noise.inputs["Vector"])
    return noise.outputs["Color"]


def scene_baked_noise(scene, texture="rotated"):
    """A procedural texture (`procedural`, in the plane's generated coordinates) into Base
    Color of a sunlit plane: Cycles renders the procedural material, rt the exporter's bake
    of it (`--bake`, BAKE_SIZES texels a side)."""
    uniform_world(scene, (0.3, 0.3, 0.3))
    m, tree, bsdf = principled("noise")
    bsdf.inputs["Roughness"].default_value = 1.0
    tree.links.new(procedural(tree, texture), bsdf.inputs["Base Color"])
    add_object(scene, "plane", bpy.ops.mesh.primitive_plane_add, m, size=2.0, rotation=(math.radians(60), 0, 0))
    sun(scene, (math.radians(30.0), 0.0, math.radians(20.0)))
    camera(scene, (0.0, -3.0, 1.2), (0.0, 0.0, 0.0), 40.0)


def scene_baked_bump(scene):
    """A Bump node fed by a Gabor Texture (which rt does not evaluate) into the Normal of a
    sunlit glossy plane: Cycles renders the procedural bump, rt the exporter's bake of
    Cycles' NORMAL pass in tangent space (`--bake`, BAKE_SIZES texels a side) read as a
    normal map. (A Bump of a Noise Texture is a node graph rt evaluates: graph_bump.)"""
    uniform_world(scene, (0.3, 0.3, 0.3))
    m, tree, bsdf = principled("bumpy")
    bsdf.inputs["Base Color"].default_value = (0.6, 0.6, 0.6, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.5
    bsdf.inputs["Specular IOR Level"].default_value = 0.5
    gabor = tree.nodes.new("ShaderNodeTexGabor")
    gabor.inputs["Scale"].default_value = 2.0
    bump = tree.nodes.new("ShaderNodeBump")
    bump.inputs["Strength"].default_value = 1.0
    bump.inputs["Distance"].default_value = 0.05
    tree.links.new(gabor.outputs["Value"], bump.inputs["Height"])
    tree.links.new(bump.outputs["Normal"], bsdf.inputs["Normal"])
    add_object(scene, "plane", bpy.ops.mesh.primitive_plane_add, m, size=2.0, rotation=(math.radians(60), 0, 0))
    sun(scene, (math.radians(40.0), 0.0, math.radians(20.0)))
    camera(scene, (0.0, -3.0, 1.2), (0.0, 0.0, 0.0), 40.0)


def stripes(n, period, a, b, axis=1):
    """(n, n, 4) opaque stripes of values a and b, `period` texels wide, across x (axis 1) or y (0)."""
    i = np.mgrid[0:n, 0:n][axis]
    return np.where(((i // period) % 2 == 0)[:, :, None], np.array([*a, 1.0]), np.array([*b, 1.0]))


def layered_sphere(scene, name, inputs, segments=48):
    """A smooth UV sphere of a Principled material with `inputs`, turned so that its
    texture's stripes run obliquely; returns the material's node tree and BSDF."""
    m, tree, bsdf = principled(name)
    for key, value in inputs.items():
        bsdf.inputs[key].default_value = (*value, 1.0) if isinstance(value, tuple) else value
    sphere = add_object(scene, "sphere", bpy.ops.mesh.primitive_uv_sphere_add, m, radius=1.0, segments=segments,
                        ring_count=segments // 2)
    bpy.ops.object.shade_smooth()
    sphere.rotation_euler = (0.0, 0.0, math.radians(30.0))
    camera(scene, (0.0, -3.6, 0.4), (0.0, 0.0, 0.0), 40.0)
    return tree, bsdf


def separated(tree, img_node):
    """A Separate Color (RGB) node reading an Image Texture's colour."""
    sep = tree.nodes.new("ShaderNodeSeparateColor")
    sep.mode = "RGB"
    tree.links.new(img_node.outputs["Color"], sep.inputs["Color"])
    return sep


def scene_coat_map(scene):
    """One image drives the coat (through Separate Color): R its weight (stripes of 1 and 0
    across u), G its roughness (a ramp from 0.05 at the bottom to 0.5 at the top: a sharp
    edge between a near-mirror coat and a rough one lines the edge with sun glints that
    move with where exactly the two renderers place it), on a red rough sphere in sunlight.
    The sphere is finely divided (192 segments): at 48, before rt started shadow rays near
    the terminator from the smooth surface as Cycles does (tests/cycles_terminator.rs), the
    sun's terminator showed the facets (one block 0.4% off)."""
    uniform_world(scene, (0.3, 0.3, 0.3))
    sun(scene, (math.radians(35), 0.0, math.radians(25)))
    tree, bsdf = layered_sphere(scene, "coat_map", {"Base Color": (0.8, 0.2, 0.1), "Roughness": 0.6,
                                                    "Coat Tint": (0.9, 0.8, 0.6)}, segments=192)
    pixels = stripes(32, 8, (1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    pixels[:, :, 1] = np.linspace(0.5, 0.05, 32)[:, None]
    sep = separated(tree, image_node(tree, image("coat", pixels, srgb=False)))
    tree.links.new(sep.outputs["Red"], bsdf.inputs["Coat Weight"])
    tree.links.new(sep.outputs["Green"], bsdf.inputs["Coat Roughness"])


def scene_sheen_map(scene):
    """A checker of sheen weight (1 and 0.2, grey) and stripes of sheen tint (warm and cool,
    sRGB) on a dark sphere in a white world, where the sheen glows along the rim."""
    uniform_world(scene, (1.0, 1.0, 1.0))
    tree, bsdf = layered_sphere(scene, "sheen_map", {"Base Color": (0.05, 0.05, 0.08), "Roughness": 0.5,
                                                     "Sheen Roughness": 0.4})
    weight = checker(4, (1.0, 1.0, 1.0), (0.2, 0.2, 0.2))
    tree.links.new(image_node(tree, image("sheen_weight", weight, srgb=False)).outputs["Color"],
                   bsdf.inputs["Sheen Weight"])
    tint = stripes(16, 4, (1.0, 0.6, 0.3), (0.4, 0.7, 1.0))
    tree.links.new(image_node(tree, image("sheen_tint", tint)).outputs["Color"], bsdf.inputs["Sheen Tint"])


def scene_anisotropy_map(scene):
    """One image drives the anisotropy (through Separate Color): R its amount (bands of 1
    and 0.3 along v), G its rotation (stripes of 0 and a quarter turn across u), on a rough
    gold sphere in sunlight."""
    uniform_world(scene, (0.1, 0.1, 0.1))
    sun(scene, (math.radians(35), 0.0, math.radians(25)))
    tree, bsdf = layered_sphere(scene, "anisotropy_map", {"Base Color": (0.95, 0.75, 0.5), "Metallic": 1.0,
                                                          "Roughness": 0.4})
    pixels = stripes(32, 8, (0.0, 0.0, 0.0), (0.0, 0.25, 0.0))
    pixels[:, :, 0] = stripes(32, 8, (1.0, 0.0, 0.0), (0.3, 0.0, 0.0), axis=0)[:, :, 0]
    sep = separated(tree, image_node(tree, image("anisotropy", pixels, srgb=False)))
    tree.links.new(sep.outputs["Red"], bsdf.inputs["Anisotropic"])
    tree.links.new(sep.outputs["Green"], bsdf.inputs["Anisotropic Rotation"])


def scene_film_roughness_map(scene):
    """One image drives the diffuse roughness and the thin film (through Separate Color): R
    the Diffuse Roughness (stripes of 1 and 0 across u), G through a Map Range node (0-1 to
    150-900 nm) the Thin Film Thickness (a ramp along v), on a sunlit sphere with the default
    specular layer."""
    uniform_world(scene, (0.3, 0.3, 0.3))
    sun(scene, (math.radians(35), 0.0, math.radians(25)))
    tree, bsdf = layered_sphere(scene, "film_roughness_map", {"Base Color": (0.6, 0.35, 0.2), "Roughness": 0.3,
                                                              "Specular IOR Level": 0.5, "Thin Film IOR": 1.33})
    pixels = stripes(32, 8, (1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    pixels[:, :, 1] = np.linspace(1.0, 0.0, 32)[:, None]
    sep = separated(tree, image_node(tree, image("film_roughness", pixels, srgb=False)))
    tree.links.new(sep.outputs["Red"], bsdf.inputs["Diffuse Roughness"])
    thickness = tree.nodes.new("ShaderNodeMapRange")
    thickness.inputs["To Min"].default_value = 150.0
    thickness.inputs["To Max"].default_value = 900.0
    tree.links.new(sep.outputs["Green"], thickness.inputs["Value"])
    tree.links.new(thickness.outputs["Result"], bsdf.inputs["Thin Film Thickness"])


def scene_transmission_level_map(scene):
    """One image drives the Transmission Weight and the Specular IOR Level (through Separate
    Color): R stripes of 1 and 0 across u (rough glass and a coated diffuse), G a ramp of the
    level along v from 0 at the bottom to 1 at the top, on a dark sphere (so that the level
    shows) over a dark floor in a white world (no sun: light seen through rough glass would
    come by rare bright paths)."""
    uniform_world(scene, (1.0, 1.0, 1.0))
    floor(scene, (0.1, 0.1, 0.1), 40.0, z=-1.0)
    tree, bsdf = layered_sphere(scene, "transmission_level_map", {"Base Color": (0.25, 0.06, 0.02), "Roughness": 0.2,
                                                                  "IOR": 1.5})
    pixels = stripes(32, 8, (1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    pixels[:, :, 1] = np.linspace(1.0, 0.0, 32)[:, None]
    sep = separated(tree, image_node(tree, image("transmission_level", pixels, srgb=False)))
    tree.links.new(sep.outputs["Red"], bsdf.inputs["Transmission Weight"])
    tree.links.new(sep.outputs["Green"], bsdf.inputs["Specular IOR Level"])


def coated_plane(scene, name):
    """A sunlit plane (the sun near the view's mirror direction, as in `scene_uv_sets`) of a
    red rough diffuse under a tinted glossy coat: the coat's highlight shows which normal it
    takes. Returns the material's node tree and BSDF."""
    uniform_world(scene, (0.2, 0.2, 0.2))
    m, tree, bsdf = principled(name)
    bsdf.inputs["Base Color"].default_value = (0.7, 0.15, 0.1, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.8
    bsdf.inputs["Coat Weight"].default_value = 1.0
    bsdf.inputs["Coat Roughness"].default_value = 0.3
    bsdf.inputs["Coat Tint"].default_value = (0.9, 0.8, 0.6, 1.0)
    add_object(scene, "plane", bpy.ops.mesh.primitive_plane_add, m, size=2.0, rotation=(math.radians(60), 0, 0))
    sun(scene, (math.radians(48.0), 0.0, math.radians(8.0)))
    camera(scene, (0.0, -3.0, 1.2), (0.0, 0.0, 0.0), 40.0)
    return tree, bsdf


def normal_map_node(tree, name, bumps):
    """A Normal Map node (tangent space, strength 1) reading a map of `bumps` × `bumps` bumps."""
    from make_normal_map_refs import bump_normals

    tex = image_node(tree, image(name, bump_normals(128, bumps, bumps, 0.06), srgb=False))
    node = tree.nodes.new("ShaderNodeNormalMap")
    node.space = "TANGENT"
    node.inputs["Strength"].default_value = 1.0
    tree.links.new(tex.outputs["Color"], node.inputs["Color"])
    return node


def scene_coat_over_normal_map(scene):
    """`coated_plane` with a strong normal map (4 × 4 bumps) on Normal and Coat Normal
    unlinked: the bumps shade the diffuse, the coat keeps the flat plane's normal (Cycles
    gives it `sd->N`, glTF no normal map without `clearcoatNormalTexture`), so its highlight
    is one smooth spot."""
    tree, bsdf = coated_plane(scene, "coat_over_normal_map")
    tree.links.new(normal_map_node(tree, "base_bumps", 4).outputs["Normal"], bsdf.inputs["Normal"])


def scene_coat_normal_map(scene):
    """`coated_plane` with a normal map (3 × 3 bumps) on Coat Normal only: the coat's highlight
    breaks up over the bumps, the diffuse under it stays flat."""
    tree, bsdf = coated_plane(scene, "coat_normal_map")
    tree.links.new(normal_map_node(tree, "coat_bumps", 3).outputs["Normal"], bsdf.inputs["Coat Normal"])


def scene_coat_over_normal_map_sphere(scene):
    """A smooth sphere (96 segments) of `coated_plane`'s material with a normal map of 8 × 4
    bumps on Normal, Coat Normal unlinked, in sunlight: the coat takes the sphere's
    interpolated normal, bent by Bump Map Correction where the view grazes it."""
    uniform_world(scene, (0.2, 0.2, 0.2))
    sun(scene, (math.radians(35), 0.0, math.radians(25)))
    tree, bsdf = layered_sphere(scene, "coat_over_normal_map_sphere",
                                {"Base Color": (0.7, 0.15, 0.1), "Roughness": 0.8, "Coat Weight": 1.0,
                                 "Coat Roughness": 0.3, "Coat Tint": (0.9, 0.8, 0.6)}, segments=96)
    from make_normal_map_refs import bump_normals

    tex = image_node(tree, image("sphere_bumps", bump_normals(128, 8, 4, 0.02), srgb=False))
    node = tree.nodes.new("ShaderNodeNormalMap")
    node.space = "TANGENT"
    tree.links.new(tex.outputs["Color"], node.inputs["Color"])
    tree.links.new(node.outputs["Normal"], bsdf.inputs["Normal"])


def scene_sheen_over_coat_normal(scene):
    """A sheen over a coat of weight 0.6 on a smooth sphere with a normal map of 8 × 4 bumps
    on Normal, Coat Normal unlinked, in sunlight: Cycles leans the sheen's normal from the
    bumps towards the coat's (the interpolated one) by the coat's weight, and shadows the
    sheen as a diffuse closure where its normal is not the interpolated one."""
    uniform_world(scene, (0.2, 0.2, 0.2))
    sun(scene, (math.radians(35), 0.0, math.radians(25)))
    tree, bsdf = layered_sphere(scene, "sheen_over_coat_normal",
                                {"Base Color": (0.06, 0.05, 0.1), "Roughness": 0.6, "Coat Weight": 0.6,
                                 "Coat Roughness": 0.3, "Sheen Weight": 1.0, "Sheen Roughness": 0.4,
                                 "Sheen Tint": (0.9, 0.75, 0.5)}, segments=96)
    from make_normal_map_refs import bump_normals

    tex = image_node(tree, image("sheen_bumps", bump_normals(128, 8, 4, 0.06), srgb=False))
    node = tree.nodes.new("ShaderNodeNormalMap")
    node.space = "TANGENT"
    tree.links.new(tex.outputs["Color"], node.inputs["Color"])
    tree.links.new(node.outputs["Normal"], bsdf.inputs["Normal"])


def layered_light(scene, name):
    """`scene_emissive`'s panel lighting a floor, of one warm emission under a sheen and a
    blue-tinted coat. Cycles dims the emission by both layers where a ray finds the panel, but
    not the light that its next-event estimation samples on it (only the coat's tint dims
    that), which carries most of the light on the floor. Returns the material's node tree and BSDF."""
    uniform_world(scene, (0.0, 0.0, 0.0))
    m, tree, bsdf = principled(name)
    for key, value in {"Base Color": (0.0, 0.0, 0.0, 1.0), "Emission Color": (1.0, 0.8, 0.6, 1.0),
                       "Emission Strength": 4.0, "Coat Weight": 1.0, "Coat Roughness": 0.2,
                       "Coat Tint": (0.35, 0.6, 1.0, 1.0), "Sheen Weight": 0.8, "Sheen Roughness": 0.3}.items():
        bsdf.inputs[key].default_value = value
    add_object(scene, "screen", bpy.ops.mesh.primitive_plane_add, m, size=1.2, location=(0, 0.6, 0.7),
               rotation=(math.radians(80), 0, 0))
    floor(scene, (0.8, 0.8, 0.8), 6.0)
    camera(scene, (0.0, -2.8, 1.6), (0.0, 0.2, 0.4), 45.0)
    return tree, bsdf


def scene_emission_under_layers(scene):
    layered_light(scene, "layered_light")


def scene_emission_under_coat_normal(scene):
    """`layered_light` with a normal map of 3 × 3 bumps on Coat Normal: the layers are seen
    along the bumps' normals (the sheen's leaned towards them)."""
    tree, bsdf = layered_light(scene, "coated_light")
    tree.links.new(normal_map_node(tree, "light_bumps", 3).outputs["Normal"], bsdf.inputs["Coat Normal"])


def mapped_range(tree, source, low, high):
    """A Map Range node taking `source` (0-1) to `low`-`high`."""
    node = tree.nodes.new("ShaderNodeMapRange")
    node.inputs["To Min"].default_value = low
    node.inputs["To Max"].default_value = high
    tree.links.new(source, node.inputs["Value"])
    return node.outputs["Result"]


def scene_ior_map(scene):
    """One image drives the IOR and the Coat IOR (through Separate Color and Map Range
    nodes): R stripes across u of IOR 1.1 and 2.5 under the default IOR Level, G a ramp
    along v of the coat's index from 1.2 at the bottom to 2.2 at the top, on a sunlit dark
    red sphere with a rough coat."""
    uniform_world(scene, (0.3, 0.3, 0.3))
    sun(scene, (math.radians(35), 0.0, math.radians(25)))
    tree, bsdf = layered_sphere(scene, "ior_map", {"Base Color": (0.3, 0.08, 0.05), "Roughness": 0.25,
                                                   "Specular IOR Level": 0.5, "Coat Weight": 1.0,
                                                   "Coat Roughness": 0.3}, segments=192)
    pixels = stripes(32, 8, (1.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    pixels[:, :, 1] = np.linspace(1.0, 0.0, 32)[:, None]
    sep = separated(tree, image_node(tree, image("indices", pixels, srgb=False)))
    tree.links.new(mapped_range(tree, sep.outputs["Red"], 1.1, 2.5), bsdf.inputs["IOR"])
    tree.links.new(mapped_range(tree, sep.outputs["Green"], 1.2, 2.2), bsdf.inputs["Coat IOR"])


def scene_film_ior_map(scene):
    """An image drives the Thin Film IOR (through Separate Color and a Map Range node): R
    stripes across u of film index 1.2 and 2.0 (eight around the sphere), on a film of 350
    nm over a sunlit near-black sphere with the default specular layer. At that thickness the
    film's optical path (and so its colour) and its reflectance both move with its index:
    the stripes show in the highlight and in the world's reflection alike."""
    uniform_world(scene, (0.3, 0.3, 0.3))
    sun(scene, (math.radians(35), 0.0, math.radians(25)))
    tree, bsdf = layered_sphere(scene, "film_ior_map", {"Base Color": (0.03, 0.03, 0.035), "Roughness": 0.2,
                                                        "Specular IOR Level": 0.5, "Thin Film Thickness": 350.0})
    sep = separated(tree, image_node(tree, image("film_index", stripes(32, 4, (1.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
                                                 srgb=False)))
    tree.links.new(mapped_range(tree, sep.outputs["Red"], 1.2, 2.0), bsdf.inputs["Thin Film IOR"])


def scene_coat_map_second_uv(scene):
    """`coated_plane` with a checker of base colour on the default uv map and the coat's
    weight (R, stripes of 1 and 0.2 across u) and roughness (G, a ramp from 0.1 to 0.5 along
    v) read through a UV Map node naming the plane's second map (the first turned a quarter,
    scaled and moved): the coat's stripes run across the checker's rows, not along them."""
    tree, bsdf = coated_plane(scene, "coat_map_second_uv")
    add_second_uv_map(bpy.data.objects["plane"].data)
    colour = image_node(tree, image("checker", checker(4, (0.7, 0.15, 0.1), (0.2, 0.45, 0.6))))
    tree.links.new(colour.outputs["Color"], bsdf.inputs["Base Color"])
    pixels = stripes(32, 8, (1.0, 0.0, 0.0), (0.2, 0.0, 0.0))
    pixels[:, :, 1] = np.linspace(0.5, 0.1, 32)[:, None]
    coat = image_node(tree, image("coat", pixels, srgb=False))
    uv_node = tree.nodes.new("ShaderNodeUVMap")
    uv_node.uv_map = "second"
    tree.links.new(uv_node.outputs["UV"], coat.inputs["Vector"])
    sep = separated(tree, coat)
    tree.links.new(sep.outputs["Red"], bsdf.inputs["Coat Weight"])
    tree.links.new(sep.outputs["Green"], bsdf.inputs["Coat Roughness"])


def blender_gltf(scene, out):
    """The same scene through Blender's own glTF exporter (a .glb with its textures
    embedded), placed by a copy of the exported scene file: for the tests that rt reads
    textured glTF files as Blender writes them (its KHR_texture_transform included)."""
    path = os.path.join(out, "blender.glb")
    bpy.ops.export_scene.gltf(filepath=path, export_format="GLB", export_cameras=False, export_lights=False)
    with open(os.path.join(out, "scene.toml")) as f:
        # Everything before the first mesh (its "# name" line too): render, camera, sky, lamps.
        lines = f.read().split("\n[[mesh]]", 1)[0].rstrip("\n").split("\n")
    header = "\n".join(lines[:-1] if lines[-1].startswith("# ") else lines)
    with open(os.path.join(out, "scene_blender_gltf.toml"), "w") as f:
        f.write(header.rstrip("\n") + '\n\n[[mesh]]\nasset = "blender.glb"\n')


SCENES = {
    "checker": scene_checker,
    "grouped_checker": scene_grouped_checker,
    "rough_metal": scene_rough_metal,
    "leaves": scene_leaves,
    "emissive": scene_emissive,
    "uv_sets": scene_uv_sets,
    "uv_mappings": scene_uv_mappings,
    "mappings": scene_mappings,
    "baked_noise": scene_baked_noise,
    "baked_bump": scene_baked_bump,
    "coat_map": scene_coat_map,
    "sheen_map": scene_sheen_map,
    "anisotropy_map": scene_anisotropy_map,
    "film_roughness_map": scene_film_roughness_map,
    "transmission_level_map": scene_transmission_level_map,
    "emission_strength_map": scene_emission_strength_map,
    "ior_map": scene_ior_map,
    "film_ior_map": scene_film_ior_map,
    "coat_over_normal_map": scene_coat_over_normal_map,
    "coat_normal_map": scene_coat_normal_map,
    "coat_map_second_uv": scene_coat_map_second_uv,
    "coat_over_normal_map_sphere": scene_coat_over_normal_map_sphere,
    "sheen_over_coat_normal": scene_sheen_over_coat_normal,
    "emission_under_layers": scene_emission_under_layers,
    "emission_under_coat_normal": scene_emission_under_coat_normal,
}
# Scenes exported with --bake, and the size of their baked images.
BAKE_SIZES = {"baked_noise": 512, "baked_bump": 512}


def main():
    args = cycles.arguments(__doc__, 4096, list(SCENES))
    for name in args.names:
        scene = reset()
        SCENES[name](scene)
        cycles.export(scene, f"texture_{name}", bake_size=BAKE_SIZES.get(name, 0))
        if name in ("leaves", "mappings"):
            blender_gltf(scene, os.path.join(cycles.HERE, "scenes", f"texture_{name}"))
        cycles.render(scene, f"texture_{name}", args)


if __name__ == "__main__":
    main()
