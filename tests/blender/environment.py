"""Exports Worlds with an Environment Texture for tests/blender_environment.rs.

    python tests/blender/environment.py OUT

Two exports of a world with Blender's courtyard HDRI behind a Mapping node (Texture
Coordinate → Mapping → Environment Texture → Background, strength 2.5), then one of a
world whose Environment Texture shows an 8-bit sRGB image. Writes OUT/report.json with
what each export wrote and the values the Rust side checks against, and the courtyard
as Blender writes it with ZIP, PIZ, DWAB and no compression.
"""

import json
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cycles"))
from cycles_reference import environment_world, rt_export  # noqa: E402

COURTYARD = os.path.join(bpy.utils.system_resource("DATAFILES"), "studiolights", "world", "courtyard.exr")


def main():
    out = sys.argv[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.object.camera_add(location=(0.0, -4.0, 1.0))
    bpy.context.scene.camera = bpy.context.object
    environment_world(bpy.context.scene, bpy.data.images.load(COURTYARD), 2.5, rotation_deg=(10.0, 0.0, 45.0))
    scene = bpy.context.scene
    toml = os.path.join(out, "hdri.toml")
    first = rt_export.export_scene(scene, os.path.join(out, "assets"), toml).written
    second = rt_export.export_scene(scene, os.path.join(out, "assets"), toml).written

    # An 8-bit sRGB image: the exporter writes the linear values Cycles reads.
    codes = np.zeros((4, 8, 4), np.float32)
    codes[:, :, :3] = np.linspace(0.0, 1.0, 8)[None, :, None]
    codes[:, :, 3] = 1.0
    image = bpy.data.images.new("ramp", 8, 4, alpha=True)
    image.pixels.foreach_set(codes.ravel())
    image.filepath_raw = os.path.join(out, "ramp.png")
    image.file_format = "PNG"
    image.save()
    environment_world(scene, bpy.data.images.load(image.filepath_raw), 1.0)
    ramp = rt_export.export_scene(scene, os.path.join(out, "assets"), os.path.join(out, "ramp.toml")).written
    report = {
        "first": first,
        "second": second,
        "ramp": ramp,
        "courtyard": COURTYARD,
        "ramp_linear": [float(rt_export.srgb_to_linear(np.array([c]))[0]) for c in np.linspace(0.0, 1.0, 8)],
    }
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f)
    codecs(out)


def codecs(out):
    """The courtyard written by Blender with each EXR compression: 32-bit floats, but DWAB
    in half floats (DWA compresses only half channels lossily)."""
    scene = bpy.context.scene
    image = bpy.data.images.load(COURTYARD)
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGB"
    for codec in ("ZIP", "PIZ", "DWAB", "NONE"):
        settings.color_depth = "16" if codec == "DWAB" else "32"
        settings.exr_codec = codec
        image.save_render(os.path.join(out, f"courtyard_{codec.lower()}.exr"), scene=scene)


if __name__ == "__main__":
    main()
