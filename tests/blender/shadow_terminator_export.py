"""Objects whose Shadow Terminator settings (Object > Shading) differ from Blender's defaults,
exported with rt_export.py, for `tests/cycles_terminator.rs`: rt renders every object with the
defaults, so each other setting is a warning naming the object (and the defaults are not).

    python tests/blender/shadow_terminator_warnings.py OUT_DIR
"""

import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender"))
import rt_export  # noqa: E402


def main():
    out = sys.argv[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    # name: (Geometry Offset, Shading Offset)
    settings = {"plain": (0.1, 0.0), "lifted": (0.3, 0.0), "shifted": (0.1, 0.5)}
    for i, (name, (geometry, shading)) in enumerate(settings.items()):
        bpy.ops.mesh.primitive_uv_sphere_add(location=(3.0 * i, 0.0, 0.0))
        obj = bpy.context.active_object
        obj.name = name
        obj.cycles.shadow_terminator_geometry_offset = geometry
        obj.cycles.shadow_terminator_offset = shading
    rt_export.export_scene(scene, os.path.join(out, "assets"), os.path.join(out, "scene.toml"))


if __name__ == "__main__":
    main()
