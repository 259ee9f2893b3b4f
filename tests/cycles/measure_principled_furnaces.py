#!/usr/bin/env python3
"""What Cycles keeps of white light: white Principled spheres at roughness 1 (metal, glass,
a coated white diffuse, a rough Oren-Nayar diffuse) filling the view under a white world, the
scenes of `tests/furnace.rs` (`kept`). Prints each image's mean luminance:

    /work/main/.venv-bpy/bin/python tests/cycles/measure_principled_furnaces.py [CASE...]

Measured (Blender 5.0.1, 512 spp): metal 0.99975, glass 0.98540, coated 0.99988, rough_diffuse 0.99987.
"""

import os
import sys
import tempfile

import bpy
import numpy as np

import cycles_reference as cycles
import make_texture_refs as refs
from make_principled_refs import principled

CASES = {
    "metal": {"Base Color": (1, 1, 1), "Metallic": 1.0, "Roughness": 1.0},
    "glass": {"Base Color": (1, 1, 1), "Transmission Weight": 1.0, "Roughness": 1.0, "IOR": 1.5},
    "coated": {"Base Color": (1, 1, 1), "Roughness": 1.0, "Specular IOR Level": 0.5},
    "coat": {"Base Color": (1, 1, 1), "Specular IOR Level": 0.0, "Coat Weight": 1.0, "Coat Roughness": 1.0},
    "rough_diffuse": {"Base Color": (1, 1, 1), "Specular IOR Level": 0.0, "Diffuse Roughness": 1.0},
}
OUT = tempfile.mkdtemp()
for name, inputs in CASES.items():
    if sys.argv[1:] and name not in sys.argv[1:]:
        continue
    scene = refs.reset()
    scene.render.resolution_x = scene.render.resolution_y = 32
    c = scene.cycles
    c.max_bounces = c.glossy_bounces = c.transmission_bounces = 64
    cycles.uniform_world(scene, (1.0, 1.0, 1.0))
    m = principled(name, inputs)
    refs.add_object(scene, "s", bpy.ops.mesh.primitive_uv_sphere_add, m, radius=1.0, segments=96, ring_count=48)
    bpy.ops.object.shade_smooth()
    refs.camera(scene, (0.0, -3.0, 0.0), (0.0, 0.0, 0.0), 20.0)
    scene.cycles.samples = 512
    path = os.path.join(OUT, f"{name}.exr")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(path)
    px = np.array(img.pixels[:]).reshape(-1, 4)[:, :3]
    lum = px @ np.array([0.2126, 0.7152, 0.0722])
    print(f"Cycles {name}: mean {lum.mean():.5f} (pixel sd {lum.std():.4f}, n {lum.size})")
