"""Objects whose Shadow Terminator settings (Object > Shading) differ from Blender's defaults,
exported with rt_export.py, for `tests/cycles_terminator.rs`: each object's settings land in its
[[mesh]] entry, and instances of a collection holding two objects of the same mesh with other
settings go into two instance files, each entry with its object's settings.

    python tests/blender/shadow_terminator_export.py OUT_DIR
"""

import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender"))
import rt_export  # noqa: E402


def sphere(name, location, geometry, shading, collection=None):
    bpy.ops.mesh.primitive_uv_sphere_add(location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.shadow_terminator_geometry_offset = geometry
    obj.shadow_terminator_shading_offset = shading
    if collection is not None:
        for owner in obj.users_collection:
            owner.objects.unlink(obj)
        collection.objects.link(obj)
    return obj


def main():
    out = sys.argv[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    # name: (Geometry Offset, Shading Offset)
    settings = {"plain": (0.1, 0.0), "lifted": (0.3, 0.0), "shifted": (0.1, 0.5)}
    for i, (name, (geometry, shading)) in enumerate(settings.items()):
        sphere(name, (3.0 * i, 0.0, 0.0), geometry, shading)
    # A hidden collection of two objects sharing a mesh, one of them with offsets of its own,
    # instanced twice.
    kit = bpy.data.collections.new("kit")
    scene.collection.children.link(kit)
    own = sphere("kit_own", (0.0, 3.0, 0.0), 0.0, 0.6, kit)
    shared = sphere("kit_default", (0.0, 6.0, 0.0), 0.1, 0.0, kit)
    shared.data = own.data
    bpy.context.view_layer.layer_collection.children["kit"].exclude = True
    for x in (-6.0, -12.0):
        inst = bpy.data.objects.new(f"kit_at_{x:g}", None)
        inst.instance_type = "COLLECTION"
        inst.instance_collection = kit
        inst.location = (x, 0.0, 0.0)
        scene.collection.objects.link(inst)
    rt_export.export_scene(scene, os.path.join(out, "assets"), os.path.join(out, "scene.toml"))


if __name__ == "__main__":
    main()
