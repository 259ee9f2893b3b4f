"""Blender side of tests/blender_live_watch.rs (run with the bpy venv's python):
an artist's session with the add-on's live export on, one edit per step.

    live_watch.py OUT

Builds a small scene, turns on live export and saves (which exports everything), then
writes OUT/done-0. For each step i = 1, 2, 3 it waits for OUT/go-i, makes the step's
edit, saves (a live export of what changed) and writes OUT/done-i:
    1. the cube's material turns red     (its .gltf is rewritten)
    2. the camera moves                  (the scene file is rewritten)
    3. the cube grows taller             (its .rtmesh is rewritten)
"""

import os
import sys
import time

import bpy

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "blender"))
import rt_export  # noqa: E402


def wait_for(path):
    deadline = time.monotonic() + 300
    while not os.path.exists(path):
        if time.monotonic() > deadline:
            sys.exit(f"gave up waiting for {path}")
        time.sleep(0.02)


def build():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 48, 32
    bpy.ops.mesh.primitive_plane_add(size=8)
    floor = bpy.context.object
    floor.name = floor.data.name = "floor"
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 0.5))
    cube = bpy.context.object
    cube.name = cube.data.name = "cube"
    paint = bpy.data.materials.new("paint")
    paint.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1)
    cube.data.materials.append(paint)
    bpy.ops.object.camera_add(location=(0.0, -5.0, 2.0), rotation=(1.25, 0.0, 0.0))
    scene.camera = bpy.context.object
    bpy.ops.object.light_add(type="SUN", rotation=(0.6, 0.0, 0.8))
    world = bpy.data.worlds.new("sky")
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.4, 0.5, 0.6, 1)
    scene.world = world
    return scene, cube, paint


def edits(scene, cube, paint):
    """The live tests' edits of build()'s scene, by name: the cube moves, its material turns
    red, it grows taller (its mesh changes), the camera moves."""

    def move():
        cube.location.x += 0.5

    def material():
        paint.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.9, 0.1, 0.1, 1)

    def mesh():
        for vertex in cube.data.vertices:
            if vertex.co.z > 0:
                vertex.co.z += 0.5
        cube.data.update()

    def camera():
        scene.camera.location.x += 0.5

    return {"move": move, "material": material, "mesh": mesh, "camera": camera}


def exporter(scene, out):
    """The add-on registered, exporting `scene` into OUT/assets and OUT/scene.toml: its settings."""
    rt_export.register()
    settings = scene.rt_export
    settings.out_dir = os.path.join(out, "assets")
    settings.scene_file = os.path.join(out, "scene.toml")
    return settings


def main(out):
    scene, cube, paint = build()
    settings = exporter(scene, out)
    settings.live = True
    blend = os.path.join(out, "scene.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    open(os.path.join(out, "done-0"), "w").close()

    edit = edits(scene, cube, paint)
    for step, name in enumerate(("material", "camera", "mesh"), start=1):
        wait_for(os.path.join(out, f"go-{step}"))
        edit[name]()
        bpy.context.view_layer.update()
        bpy.ops.wm.save_as_mainfile(filepath=blend)
        open(os.path.join(out, f"done-{step}"), "w").close()
    rt_export.unregister()


if __name__ == "__main__":
    main(sys.argv[1])
