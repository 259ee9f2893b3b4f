"""rt for Blender, as an extension (Blender 4.2+): the exporter (File > Export > rt, the
"rt" sidebar tab, live export on save or on every edit) and the "rt" render engine (F12,
and the viewport's Rendered mode through a streaming rt). Its preferences
are the path to the rt binary and the cache folder of F12 renders.

In the repository, the modules live beside this folder (blender/rt_export.py,
blender/rt_shader_nodes.py, blender/rt_engine.py, blender/rt_viewport.py) so that they also run as scripts; scripts/package_blender copies
them next to this file into rt_blender.zip.
"""

from . import rt_engine, rt_export


def register():
    rt_export.register()
    rt_engine.register()


def unregister():
    rt_engine.unregister()
    rt_export.unregister()
