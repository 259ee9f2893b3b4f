#!/usr/bin/env python3
"""Textured glTF files as Blender's own importer reads them, rendered with Cycles, for
`tests/cycles_textures.rs`: rt reads the same files directly, and must render them as
Cycles renders Blender's import.

    /work/main/.venv-bpy/bin/python tests/cycles/make_gltf_import_refs.py [--spp N] [NAME...]

For each NAME it writes `tests/cycles/scenes/texture_NAME/` (the glTF file, its image and
a `scene.toml` naming it as the one asset) and `tests/cycles/texture_NAME.exr` (Cycles,
4096 samples per pixel unless `--spp`, set up as `make_texture_refs.py` sets it up).

The glTF geometry is a sphere that Blender's exporter writes (its uvs and normals as
Blender has them); the material is then written by hand, with the extension and texture
under test.
"""

import json
import math
import os
import shutil

import bpy
import numpy as np

import cycles_reference as cycles
import make_texture_refs as refs
from cycles_reference import uniform_world


def png(path, pixels):
    """Writes an (h, w, 4) array of values in [0, 1] (rows from the top) as an 8-bit PNG of
    non-colour data."""
    img = refs.image(os.path.basename(path), pixels, srgb=False)
    img.filepath_raw = path
    img.file_format = "PNG"
    img.save()


def sphere_gltf(folder, material):
    """A smooth sphere turned 30° about Blender's Z, written by Blender's glTF exporter into
    `folder`/sphere.gltf with `material` (glTF JSON) as its one material."""
    scene = refs.reset()
    m, _, _ = refs.principled("plain")
    refs.add_object(scene, "sphere", bpy.ops.mesh.primitive_uv_sphere_add, m, radius=1.0, segments=96,
                    ring_count=48)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.rotation_euler = (0.0, 0.0, math.radians(30.0))
    path = os.path.join(folder, "sphere.gltf")
    bpy.ops.export_scene.gltf(filepath=path, export_format="GLTF_SEPARATE", export_cameras=False,
                              export_lights=False, export_materials="PLACEHOLDER")
    with open(path) as f:
        document = json.load(f)
    document["materials"] = [material]
    for mesh in document["meshes"]:
        for primitive in mesh["primitives"]:
            primitive["material"] = 0
    return path, document


def anisotropy_direction(folder):
    """`KHR_materials_anisotropy` with a texture on a rough gold sphere in sunlight: stripes
    across u of directions along the tangent and along the bitangent (RG), bands along v of
    strength 1 and 0.4 (B), the extension's rotation a sixth of a turn on top."""
    pixels = np.zeros((32, 32, 4))
    i, j = np.mgrid[0:32, 0:32]
    along = (j // 8) % 2 == 0
    pixels[:, :, 0] = np.where(along, 1.0, 0.5)
    pixels[:, :, 1] = np.where(along, 0.5, 1.0)
    pixels[:, :, 2] = np.where((i // 8) % 2 == 0, 1.0, 0.4)
    pixels[:, :, 3] = 1.0
    png(os.path.join(folder, "anisotropy.png"), pixels)
    material = {
        "name": "brushed_gold",
        "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.75, 0.5, 1.0], "metallicFactor": 1.0,
                                 "roughnessFactor": 0.4},
        "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1.0,
                                                    "anisotropyRotation": math.pi / 3.0,
                                                    "anisotropyTexture": {"index": 0}}},
    }
    path, document = sphere_gltf(folder, material)
    document["images"] = [{"uri": "anisotropy.png"}]
    document["textures"] = [{"source": 0}]
    document.setdefault("extensionsUsed", []).append("KHR_materials_anisotropy")
    return path, document


def lit(scene):
    uniform_world(scene, (0.1, 0.1, 0.1))
    refs.sun(scene, (math.radians(35), 0.0, math.radians(25)))
    refs.camera(scene, (0.0, -3.6, 0.4), (0.0, 0.0, 0.0), 40.0)


SCENES = {"gltf_anisotropy": anisotropy_direction}


def main():
    args = cycles.arguments(__doc__, 4096, list(SCENES))
    for name in args.names:
        folder = os.path.join(cycles.HERE, "scenes", f"texture_{name}")
        os.makedirs(folder, exist_ok=True)
        path, document = SCENES[name](folder)
        with open(path, "w") as f:
            json.dump(document, f, indent=1)
        scene = refs.reset()
        lit(scene)
        bpy.ops.import_scene.gltf(filepath=path)
        # The scene file of an export, its one mesh the glTF file as it is.
        cycles.export(scene, f"texture_{name}", toml="scene_lights.toml")
        with open(os.path.join(folder, "scene_lights.toml")) as f:
            header = f.read().split("\n[[mesh]]", 1)[0].rstrip("\n").split("\n")
        os.remove(os.path.join(folder, "scene_lights.toml"))
        shutil.rmtree(os.path.join(folder, "assets"))
        header = "\n".join(header[:-1] if header[-1].startswith("# ") else header)
        with open(os.path.join(folder, "scene.toml"), "w") as f:
            f.write(header.rstrip("\n") + '\n\n[[mesh]]\nasset = "sphere.gltf"\n')
        cycles.render(scene, f"texture_{name}", args)


if __name__ == "__main__":
    main()
