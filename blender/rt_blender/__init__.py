"""rt for Blender, as an extension (Blender 4.2+): the exporter (File > Export > rt, the
"rt" sidebar tab, live export on save or on every edit) and the "rt" render engine (F12,
material previews, the viewport's Rendered mode through a streaming rt), with render
settings and panels laid out as Cycles' are. Its preferences are the path to the rt
binary and the cache folder of F12 renders.

This folder is the whole package, built with Blender's own extension builder
(`blender --command extension build`, or scripts/package_blender); blender/rt_export.py,
the exporter's command line, imports it from here.
"""

from . import rt_engine, rt_export, rt_panels, rt_settings

# For Blender before 4.2, which installs this folder as a legacy add-on (Blender 4.2+ reads
# blender_manifest.toml instead). rt supports 4.2+. The add-on's only bl_info: Blender
# reads it from this file's text without running it, so it must stay a literal here.
bl_info = {
    "name": "rt",
    "author": "rt maintainers",
    "version": (0, 1, 0),
    "blender": (4, 2, 0),
    "location": "Render Properties > Render Engine > rt; File > Export > rt; 3D View > Sidebar > rt",
    "description": "Render and export with the rt GPU path tracer",
    "category": "Render",
}

MODULES = (rt_settings, rt_export, rt_engine, rt_panels)


def register():
    for module in MODULES:
        module.register()


def unregister():
    for module in reversed(MODULES):
        module.unregister()
