"""rt for Blender, as an extension (Blender 4.2+): the exporter (File > Export > rt, the
"rt" sidebar tab, live export on save or on every edit) and the "rt" render engine (F12,
and the viewport's Rendered mode through a streaming rt). Its preferences
are the path to the rt binary and the cache folder of F12 renders.

In the repository, the modules live beside this folder (blender/rt_export.py,
blender/rt_shader_nodes.py, blender/rt_engine.py, blender/rt_viewport.py) so that they also run as scripts; scripts/package_blender copies
them next to this file into rt_blender.zip.
"""

from . import rt_engine, rt_export

# For Blender before 4.2, which installs this folder as a legacy add-on (Blender 4.2+ reads
# blender_manifest.toml instead). rt supports 4.2+; the screenshots in docs/images were
# taken on 3.4 this way. The add-on's only bl_info: Blender reads it from this file's
# text without running it, so it must stay a literal here; rt_export.py installed on its
# own would lack rt_shader_nodes.py, so the exporter comes only as part of this package.
bl_info = {
    "name": "rt",
    "author": "rt",
    "version": (0, 1, 0),
    "blender": (4, 2, 0),
    "location": "Render Properties > Render Engine > rt; File > Export > rt; 3D View > Sidebar > rt",
    "description": "Render and export with the rt GPU path tracer",
    "category": "Render",
}


def register():
    rt_export.register()
    rt_engine.register()


def unregister():
    rt_engine.unregister()
    rt_export.unregister()
