"""Cycles references for tests/cycles_environment.rs: small scenes lit by a World with an
Environment Texture.

    /work/main/.venv-bpy/bin/python tests/cycles/make_environment_refs.py [--spp 2048] [NAME ...]

`courtyard`: Blender's own CC0 Poly Haven HDRI (datafiles/studiolights/world/courtyard.exr,
1024x512, DWAB) behind a Mapping node that rotates it about X and Z, at strength 1.5,
over a grey floor with a mirror ball, a diffuse ball and a box. `spot`: a synthetic
128x64 map, dim blue-grey except for a 2x2-texel spot 10^4 times brighter, over the same
objects. Each is rendered by Cycles at 64x64 into tests/cycles/NAME.exr (linear, 32-bit)
and exported with blender/rt_export.py into tests/cycles/scenes/NAME/ (NAME.toml and its
assets, the image among them). CI does not run Cycles: it compares rt against the
committed files.

Cycles counts bounces after the first hit, rt counts hits: Cycles' max_bounces = BOUNCES
is rt's max_bounces = BOUNCES + 1 (cycles_environment.rs).
"""

import argparse
import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "blender"))
sys.path.insert(0, HERE)
import rt_export  # noqa: E402
from make_refs import add, cycles, diffuse  # noqa: E402

SIZE = 64
COURTYARD = os.path.join(bpy.utils.system_resource("DATAFILES"), "studiolights", "world", "courtyard.exr")
# The synthetic map: its size, its dim level and its 2x2 spot (top-left texel, 10^4 times brighter).
SPOT_MAP = (128, 64)
SPOT_BASE = (0.05, 0.06, 0.08)
SPOT_TEXEL = (75, 20)


def objects():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
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


def world(image, strength, rotation=None):
    world = bpy.data.worlds.new("environment")
    tree = world.node_tree
    background = tree.nodes["Background"]
    background.inputs["Strength"].default_value = strength
    texture = tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image = image
    tree.links.new(texture.outputs["Color"], background.inputs["Color"])
    if rotation is not None:
        coords = tree.nodes.new("ShaderNodeTexCoord")
        mapping = tree.nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = [math.radians(a) for a in rotation]
        tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    bpy.context.scene.world = world


def courtyard():
    scene = objects()
    world(bpy.data.images.load(COURTYARD), 1.5, rotation=(20.0, 0.0, 110.0))
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
    world(bpy.data.images.load(path), 1.0)
    return scene


SCENES = {"courtyard": courtyard, "spot": spot}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--spp", type=int, default=2048)
    parser.add_argument("names", nargs="*", default=sorted(SCENES))
    args = parser.parse_args()
    for name in args.names:
        scene = SCENES[name]()
        cycles(scene, args.spp)
        folder = os.path.join(HERE, "scenes", f"environment_{name}")
        os.makedirs(folder, exist_ok=True)
        rt_export.export_scene(scene, os.path.join(folder, "assets"), os.path.join(folder, f"environment_{name}.toml"))
        scene.render.filepath = os.path.join(HERE, f"environment_{name}.exr")
        bpy.ops.render.render(write_still=True)
        print(f"make_environment_refs: {name}: {args.spp} spp written", flush=True)


if __name__ == "__main__":
    main()
