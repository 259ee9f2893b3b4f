"""Blender side of tests/blender_engine.rs (run with the bpy venv's python, RT_BINARY set
and TMPDIR pointing into OUT, so that the engine's cache folder is OUT/rt-engine).

    engine.py f12 OUT        builds OUT/engine.blend, renders it with F12 through the RT
                             engine into OUT/f12.exr; writes OUT/f12.json (cache folder,
                             settings, timings)
    engine.py frames OUT     Ctrl+F12 over frames 1-2 of OUT/engine.blend with the cube
                             keyframed; OUT/anim_0001.exr, OUT/anim_0002.exr, OUT/frames.json
    engine.py cancel OUT     the stop path: render_frame with a should_stop that fires
                             mid-render; OUT/cancel.json
    engine.py error OUT      a lamp of negative power (rt refuses it) through F12, and a
                             broken scene file through run_rt; OUT/error.json
    engine.py package ZIP OUT  installs the extension zip, sets its preferences, F12
    engine.py legacy ZIP OUT   the zip's files as a legacy add-on folder (as Blender before
                             4.2 installs the package): listed by its bl_info, enabled
"""

import json
import os
import sys
import time
import zipfile

import bpy

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def engine_module():
    sys.path.insert(0, os.path.join(REPO, "blender"))
    import rt_blender
    from rt_blender import rt_engine

    rt_blender.register()
    return rt_engine


def build(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 64, 48
    bpy.ops.mesh.primitive_cube_add(location=(0.0, 0.0, 1.0))
    bpy.ops.mesh.primitive_plane_add(size=8)
    bpy.ops.object.light_add(type="POINT", location=(2.0, -2.0, 4.0))
    bpy.context.object.data.energy = 500.0
    bpy.ops.object.camera_add(location=(6.0, -6.0, 4.0), rotation=(1.1, 0.0, 0.785))
    scene.camera = bpy.context.object
    scene.render.engine = "RT"
    scene.rt_render.spp = 16
    scene.rt_render.max_bounces = 4
    scene.rt_render.seed = 3
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "engine.blend"))
    return scene


def f12(out):
    rt_engine = engine_module()
    assert "RT" in {e.bl_idname for e in bpy.types.RenderEngine.__subclasses__() if hasattr(e, "bl_idname")}, "the engine registers"
    scene = build(out)
    assert scene.rt_render.spp == 16, "the settings live in the scene"
    scene.render.filepath = os.path.join(out, "f12.exr")
    start = time.perf_counter()
    result = bpy.ops.render.render(write_still=True)
    total = time.perf_counter() - start
    settings = scene.rt_render
    report = {
        "result": sorted(result),
        "cache": rt_engine.cache_dir(),
        "spp": settings.spp,
        "max_bounces": settings.max_bounces + 1,  # rt counts the surfaces a path shades: one more
        "sampling": settings.sampling,
        "seed": settings.seed,
        "f12_s": total,
    }
    # The same frame again through the engine's own steps, timed one by one.
    _, _, report["timings"] = rt_engine.render_frame(scene, settings, rt_engine.cache_dir(), rt_engine.rt_binary())
    with open(os.path.join(out, "f12.json"), "w") as f:
        json.dump(report, f)


def frames(out):
    rt_engine = engine_module()
    bpy.ops.wm.open_mainfile(filepath=os.path.join(out, "engine.blend"))
    scene = bpy.context.scene
    cube = scene.objects["Cube"]
    for frame, z in ((1, 1.0), (2, 3.0)):
        cube.location = (0.0, 0.0, z)
        cube.keyframe_insert("location", frame=frame)
    scene.frame_start, scene.frame_end = 1, 2
    scene.frame_set(1)
    scene.rt_render.spp = 4
    scene.render.filepath = os.path.join(out, "anim_")
    exported = {}

    def after_frame(scene, _depsgraph=None):
        with open(os.path.join(rt_engine.cache_dir(), "scene.toml")) as f:
            cube_entry = f.read().split("# Cube\n", 1)[1]
        matrix = json.loads(cube_entry.split("matrix = ", 1)[1].split("\n", 1)[0])
        exported[scene.frame_current] = matrix

    bpy.app.handlers.render_post.append(after_frame)
    bpy.ops.render.render(animation=True)
    with open(os.path.join(out, "frames.json"), "w") as f:
        json.dump({"cube_matrix": exported}, f)


def cancel(out):
    rt_engine = engine_module()
    bpy.ops.wm.open_mainfile(filepath=os.path.join(out, "engine.blend"))
    scene = bpy.context.scene
    folder, binary = rt_engine.cache_dir(), rt_engine.rt_binary()
    # A first, short render leaves the exported files and the BVH caches in place.
    scene.rt_render.spp = 1
    output, _, _ = rt_engine.render_frame(scene, scene.rt_render, folder, binary)
    os.remove(output)

    def listing():
        return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, fs in os.walk(folder) for f in fs)

    before = listing()
    scene.rt_render.spp = 1_000_000
    progress = []
    stop_at = []

    def should_stop():
        if progress and not stop_at:
            stop_at.append(time.perf_counter())
        return bool(stop_at)

    cancelled = False
    try:
        rt_engine.render_frame(scene, scene.rt_render, folder, binary, progress.append, should_stop)
    except rt_engine.RtCancelled as e:
        cancelled = True
        status = e.args[0] if e.args else None
    stopped_s = time.perf_counter() - stop_at[0] if stop_at else None
    with open(os.path.join(out, "cancel.json"), "w") as f:
        json.dump(
            {
                "cancelled": cancelled,
                "status": status if cancelled else None,
                "progress_events": len(progress),
                "stopped_s": stopped_s,
                "before": before,
                "after": listing(),
            },
            f,
        )


def error(out):
    rt_engine = engine_module()
    bpy.ops.wm.open_mainfile(filepath=os.path.join(out, "engine.blend"))
    scene = bpy.context.scene
    scene.objects["Point"].data.energy = -100.0
    # Blender prints an engine's reports in background mode: the Rust side reads them.
    reported = []
    scene.render.filepath = os.path.join(out, "error.exr")
    try:
        bpy.ops.render.render(write_still=True)
    except RuntimeError as e:
        reported.append([["RuntimeError"], str(e)])
    broken = os.path.join(out, "broken.toml")
    with open(broken, "w") as f:
        f.write("[camera]\nfov_y_dge = 40.0\n")
    try:
        rt_engine.run_rt([rt_engine.rt_binary(), "render", broken, "-o", os.path.join(out, "b.exr"), "--progress", "json"])
        direct = None
    except rt_engine.RtError as e:
        direct = str(e)
    with open(os.path.join(out, "error.json"), "w") as f:
        json.dump({"reported": reported, "run_rt": direct}, f)


def package(zip_path, out):
    """Installs the zip as Blender does on drag and drop (into BLENDER_USER_RESOURCES,
    which the test points into OUT), sets its preferences and renders with F12."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.extensions.package_install_files(
        filepath=zip_path, repo="user_default", enable_on_install=True
    )
    assert result == {"FINISHED"}, result
    prefs = bpy.context.preferences.addons["bl_ext.user_default.rt_blender"].preferences
    prefs.rt_binary = os.environ["RT_BINARY"]
    prefs.cache_dir = os.path.join(out, "package_cache")
    bpy.ops.wm.open_mainfile(filepath=os.path.join(out, "engine.blend"))
    scene = bpy.context.scene
    scene.render.engine = "RT"  # a TypeError unless the extension registered the engine
    assert hasattr(bpy.ops.export_scene, "rt"), "the exporter's operator registers too"
    scene.render.filepath = os.path.join(out, "package.exr")
    bpy.ops.render.render(write_still=True)
    frame = os.path.join(prefs.cache_dir, "rt-engine", "frame_0001.exr")
    assert os.path.isfile(frame), f"no {frame}: the cache preference was not used"
    print("package: installed, rendered through its preferences")


def legacy(zip_path, out):
    """The package's files in a folder rt_blender among the user's legacy add-ons: Blender
    lists it by the bl_info it reads from __init__.py's text, and enabling it registers the
    exporter and the engine."""
    import addon_utils  # importable once bpy is

    bpy.ops.wm.read_factory_settings(use_empty=True)
    addons = bpy.utils.user_resource("SCRIPTS", path="addons", create=True)
    with zipfile.ZipFile(zip_path) as z:
        z.extractall(os.path.join(addons, "rt_blender"))
    bpy.utils.refresh_script_paths()  # the new add-ons folder onto sys.path
    listed = {m.__name__: m.bl_info for m in addon_utils.modules(refresh=True)}
    info = listed.get("rt_blender")
    assert info is not None and info["name"] == "rt", f"rt_blender listed as {info}"
    errors = []
    assert addon_utils.enable("rt_blender", default_set=True, handle_error=errors.append) is not None, errors
    bpy.context.scene.render.engine = "RT"  # a TypeError unless the engine registered
    assert hasattr(bpy.types.Scene, "rt_export"), "the exporter's settings register too"
    print(f"legacy: listed as {info['name']!r} {info['version']}, enabled with the exporter and the engine")


if __name__ == "__main__":
    mode = sys.argv[1]
    if mode in ("package", "legacy"):
        {"package": package, "legacy": legacy}[mode](sys.argv[2], sys.argv[3])
    else:
        {"f12": f12, "frames": frames, "cancel": cancel, "error": error}[mode](sys.argv[2])
