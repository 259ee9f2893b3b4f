"""Cycles references for tests/cycles_environment.rs: small scenes lit by a World with an
Environment Texture.

    /work/main/.venv-bpy/bin/python tests/cycles/make_environment_refs.py [--spp 2048] [NAME ...]

`courtyard`: Blender's own CC0 Poly Haven HDRI (datafiles/studiolights/world/courtyard.exr,
1024x512, DWAB) behind a Mapping node that rotates it about X and Z, at strength 1.5,
over a grey floor with a mirror ball, a diffuse ball and a box. `spot`: a synthetic
128x64 map, dim blue-grey except for a 2x2-texel spot 10^4 times brighter, over the same
objects. `srgb_spot` and `srgb_stripes`: maps whose Color Space is sRGB, a float EXR and
an 8-bit PNG, which Cycles interpolates as codes and decodes after. Each is rendered by Cycles at 64x64 into tests/cycles/NAME.exr (linear, 32-bit)
and exported with blender/rt_export.py into tests/cycles/scenes/NAME/ (NAME.toml and its
assets, the image among them). CI does not run Cycles: it compares rt against the
committed files.

Cycles counts bounces after the first hit, rt counts hits: Cycles' max_bounces = BOUNCES
is rt's max_bounces = BOUNCES + 1 (cycles_environment.rs).
"""

import os

import bpy
import numpy as np
from mathutils import Vector

import cycles_reference as cycles
from cycles_reference import diffuse, environment_world, rt_export
from make_refs import add, set_up

COURTYARD = os.path.join(bpy.utils.system_resource("DATAFILES"), "studiolights", "world", "courtyard.exr")
# The synthetic map: its size, its dim level and its 2x2 spot (top-left texel, 10^4 times brighter).
SPOT_MAP = (128, 64)
SPOT_BASE = (0.05, 0.06, 0.08)
SPOT_TEXEL = (75, 20)


def objects():
    scene = cycles.new_scene()
    bpy.ops.mesh.primitive_plane_add(size=6)
    add(bpy.context.object, "floor", diffuse("floor", (0.5, 0.5, 0.5)))
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(-0.9, 0.5, 0.4), rotation=(0.0, 0.0, 0.5))
    add(bpy.context.object, "box", diffuse("box", (0.8, 0.3, 0.2)))
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=0.45, location=(0.8, 0.2, 0.45))
    add(bpy.context.object, "ball", diffuse("ball", (0.2, 0.4, 0.8)))
    mirror = bpy.data.materials.new("mirror")
    node = mirror.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (0.9, 0.9, 0.9, 1.0)
    node.inputs["Metallic"].default_value = 1.0
    node.inputs["Roughness"].default_value = 0.0
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.4, location=(0.0, -0.6, 0.4))
    add(bpy.context.object, "mirror", mirror)
    bpy.ops.object.shade_smooth()
    bpy.ops.object.camera_add(location=(0.0, -4.5, 1.6))
    camera = bpy.context.object
    camera.rotation_euler = (Vector((0.0, 0.0, 0.6)) - camera.location).to_track_quat("-Z", "Y").to_euler()
    camera.data.lens = 28
    scene.camera = camera
    return scene


def courtyard():
    scene = objects()
    environment_world(scene, bpy.data.images.load(COURTYARD), 1.5, rotation_deg=(20.0, 0.0, 110.0))
    return scene


def spot():
    scene = objects()
    w, h = SPOT_MAP
    pixels = np.empty((h, w, 3), np.float32)
    pixels[:, :] = SPOT_BASE
    x, y = SPOT_TEXEL
    # Rows from the top.
    pixels[y : y + 2, x : x + 2] = [1e4 * c for c in SPOT_BASE]
    # Written as rt's exporter writes images, and loaded: Cycles and rt read the same file.
    path = os.path.join(bpy.app.tempdir, "spot.exr")
    with open(path, "wb") as f:
        f.write(rt_export.exr_bytes(pixels[:, :, :3]))
    environment_world(scene, bpy.data.images.load(path), 1.0)
    return scene


def srgb_world(scene, name, data):
    """A World of the image file `data` (written as `name`), its Color Space sRGB."""
    path = os.path.join(bpy.app.tempdir, name)
    with open(path, "wb") as f:
        f.write(data)
    image = bpy.data.images.load(path)
    image.colorspace_settings.name = "sRGB"
    environment_world(scene, image, 1.0)


def srgb_spot():
    """A float EXR whose Color Space is sRGB: Cycles interpolates its codes and decodes
    after (a dim map with a 2x2 spot of code 8, ~130 decoded)."""
    scene = objects()
    w, h = SPOT_MAP
    pixels = np.full((h, w, 3), 0.25, np.float32)
    x, y = SPOT_TEXEL
    pixels[y : y + 2, x : x + 2] = [8.0, 6.0, 4.0]
    srgb_world(scene, "srgb_spot.exr", rt_export.exr_bytes(pixels))
    return scene


def srgb_stripes():
    """An 8-bit PNG of black and white columns (and an orange patch), sRGB: interpolated
    as codes, a stripe's edge is darker than the linear mean."""
    scene = objects()
    w, h = SPOT_MAP
    pixels = np.zeros((h, w, 4), np.uint8)
    pixels[:, :, 3] = 255
    pixels[:, ::2, :3] = 255
    x, y = SPOT_TEXEL
    pixels[y : y + 4, x : x + 8, :3] = [255, 90, 0]
    srgb_world(scene, "srgb_stripes.png", rt_export.png_bytes(pixels))
    return scene


SCENES = {"courtyard": courtyard, "spot": spot, "srgb_spot": srgb_spot, "srgb_stripes": srgb_stripes}


def main():
    args = cycles.arguments(__doc__, 2048, sorted(SCENES))
    for name in args.names:
        scene = SCENES[name]()
        set_up(scene)
        cycles.export(scene, f"environment_{name}", f"environment_{name}.toml")
        cycles.render(scene, f"environment_{name}", args)


if __name__ == "__main__":
    main()
