"""Makes assets/environment/courtyard_256.exr: Blender's own CC0 Poly Haven HDRI
"courtyard" (shipped with Blender in datafiles/studiolights/world/, 1024x512 DWAB)
box-filtered down to 256x128 and written as a half-float ZIP EXR.

    /work/main/.venv-bpy/bin/python blender/make_environment.py
"""

import os

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(os.path.dirname(HERE), "assets", "environment", "courtyard_256.exr")
SOURCE = os.path.join(bpy.utils.system_resource("DATAFILES"), "studiolights", "world", "courtyard.exr")
FACTOR = 4


def main():
    image = bpy.data.images.load(SOURCE)
    w, h = image.size
    pixels = np.empty(w * h * image.channels, np.float32)
    image.pixels.foreach_get(pixels)
    rgba = pixels.reshape(h, w, image.channels)
    small = rgba.reshape(h // FACTOR, FACTOR, w // FACTOR, FACTOR, image.channels).mean(axis=(1, 3))
    small[:, :, 3] = 1.0
    out = bpy.data.images.new("courtyard_256", w // FACTOR, h // FACTOR, alpha=True, float_buffer=True)
    out.colorspace_settings.name = "Linear Rec.709"
    out.pixels.foreach_set(small.astype(np.float32).ravel())
    scene = bpy.context.scene
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGB"
    settings.color_depth = "16"
    settings.exr_codec = "ZIP"
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    out.save_render(OUT, scene=scene)
    print(f"make_environment: {OUT}: {w // FACTOR}x{h // FACTOR}")


if __name__ == "__main__":
    main()
