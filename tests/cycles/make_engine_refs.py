"""Cycles references for rt as Blender's render engine (tests/blender_engine_ui.rs renders
the same .blend with F12 through rt and compares).

    /work/main/.venv-bpy/bin/python tests/cycles/make_engine_refs.py [--spp 2048] [levels]

`levels`: a .blend whose render and viewport differ. A cube whose Subdivision Surface
modifier has 0 levels in the viewport and 3 in renders (a rounded blob in F12, a cube in
the viewport), a red sphere hidden in renders (in the viewport only) in front of it, and a
blue sphere disabled in viewports (in renders only), on a grey floor under a sun and a
dim world. It is saved as tests/cycles/scenes/engine_levels/scene.blend and rendered with
Cycles into tests/cycles/engine_levels.exr, 64x48. CI does not run Cycles: commit both.
"""

import math
import os

import bpy

import cycles_reference as cycles
from cycles_reference import diffuse

NAMES = ("levels",)


def levels(args):
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, 48, bounces=2)
    cycles.uniform_world(scene, (0.1, 0.1, 0.1))
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    bpy.context.object.data.materials.append(diffuse("floor", (0.5, 0.5, 0.5)))
    bpy.ops.mesh.primitive_cube_add(size=1.6, location=(0.0, 0.0, 0.8))
    rounded = bpy.context.object
    rounded.name = "Rounded"
    rounded.data.materials.append(diffuse("orange", (0.8, 0.4, 0.1)))
    subdivision = rounded.modifiers.new("Subdivision", "SUBSURF")
    subdivision.levels, subdivision.render_levels = 0, 3
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(-0.6, -1.5, 0.5))
    viewport_only = bpy.context.object
    viewport_only.name = "ViewportOnly"
    viewport_only.data.materials.append(diffuse("red", (0.8, 0.05, 0.05)))
    viewport_only.hide_render = True
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(1.4, -0.8, 0.5))
    render_only = bpy.context.object
    render_only.name = "RenderOnly"
    render_only.data.materials.append(diffuse("blue", (0.05, 0.1, 0.8)))
    render_only.hide_viewport = True
    bpy.ops.object.light_add(type="SUN", rotation=(math.radians(40.0), 0.0, math.radians(30.0)))
    bpy.context.object.data.energy = 3.0
    bpy.context.object.data.angle = math.radians(5.0)
    bpy.ops.object.camera_add(location=(0.0, -6.0, 2.5), rotation=(math.radians(72.0), 0.0, 0.0))
    scene.camera = bpy.context.object
    folder = os.path.join(cycles.HERE, "scenes", "engine_levels")
    os.makedirs(folder, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(folder, "scene.blend"), compress=True)
    cycles.render(scene, "engine_levels", args)


if __name__ == "__main__":
    arguments = cycles.arguments(__doc__, 2048, NAMES)
    for name in arguments.names:
        {"levels": levels}[name](arguments)
