"""Blender side of tests/blender_engine_ui.rs: rt in Blender as an artist meets it (run
with the bpy venv's python, RT_BINARY set and TMPDIR pointing into OUT, so that the
engine's cache folder is under OUT). Each mode writes OUT/MODE.json.

    engine_ui.py ui OUT             the Shader Editor flag, which of Blender's and Cycles'
                                    panels show under rt, and the options the render
                                    settings give rt
    engine_ui.py preview OUT        a material preview rendered through rt
    engine_ui.py levels BLEND OUT   F12 of BLEND (render and viewport differ): OUT/levels.exr,
                                    multilayer with the Noise pass, and what was exported
    engine_ui.py passes OUT         F12 of a plane facing the camera with every pass on:
                                    OUT/passes.exr (multilayer), and OUT/passes_scene/
    engine_ui.py size OUT           Blender's size rules: 103x79 at 50%, border with and
                                    without crop: OUT/size_*.exr
    engine_ui.py progressive OUT    a time-limited F12 that refines: how often the image
                                    was updated, the samples it reached
    engine_ui.py transparent OUT    F12 with Film › Transparent of a plane filling part of the
                                    view: OUT/transparent.exr (multilayer), the exported scene
    engine_ui.py holdout OUT        F12 of that plane in a held-out collection, the film
                                    opaque: OUT/holdout.exr (multilayer), the exported scene
    engine_ui.py motion OUT         F12 with Motion Blur of tests/cycles/make_motion_refs.py's
                                    moving objects: OUT/motion.exr, the exported scene and the
                                    frame after
"""

import json
import math
import os
import sys
import time

import bpy

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "blender"))
import rt_blender  # noqa: E402
from rt_blender import rt_engine, rt_panels, rt_run  # noqa: E402

# Panels an artist needs under rt (material, world, light, camera, output, geometry).
MUST_SHOW = (
    "CYCLES_PT_context_material", "CYCLES_MATERIAL_PT_surface", "CYCLES_MATERIAL_PT_volume",
    "CYCLES_MATERIAL_PT_preview", "CYCLES_WORLD_PT_surface", "CYCLES_LIGHT_PT_light", "CYCLES_LIGHT_PT_beam_shape",
    "DATA_PT_lens", "DATA_PT_camera", "CYCLES_CAMERA_PT_dof", "CYCLES_CAMERA_PT_dof_aperture",
    "RENDER_PT_format", "RENDER_PT_output", "RENDER_PT_frame_range", "RENDER_PT_color_management",
    "DATA_PT_vertex_groups", "DATA_PT_uv_texture", "DATA_PT_shape_keys", "OBJECT_PT_shadow_terminator",
    "PARTICLE_PT_emission", "PHYSICS_PT_cloth", "CYCLES_RENDER_PT_motion_blur", "CYCLES_OBJECT_PT_motion_blur",
)
# Panels of what rt does not render, or of Cycles' own settings that rt's panels replace.
MUST_HIDE = (
    "CYCLES_RENDER_PT_sampling", "CYCLES_RENDER_PT_light_paths", "CYCLES_RENDER_PT_bake",
    "CYCLES_RENDER_PT_motion_blur_curve", "CYCLES_RENDER_PT_passes", "DATA_PT_lightprobe", "RENDER_PT_stereoscopy",
    "CYCLES_LIGHT_PT_settings", "VIEWLAYER_PT_freestyle",
)


def setup():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    rt_blender.register()
    return bpy.context.scene


def save(out, mode, report):
    with open(os.path.join(out, f"{mode}.json"), "w") as f:
        json.dump(report, f, indent=1)


def ui(out):
    scene = setup()
    scene.render.engine = "RT"
    panels = {name: "RT" in getattr(bpy.types, name).COMPAT_ENGINES for name in MUST_SHOW + MUST_HIDE}
    s = scene.rt_render
    plain = rt_run.render_options(s, frame=7)
    s.use_adaptive_sampling, s.adaptive_threshold, s.time_limit = True, 0.02, 30.0
    s.use_denoising, s.denoising_device, s.clamp, s.max_bounces = True, "cpu", 10.0, 4
    s.seed, s.use_animated_seed, s.adapter = 5, True, "H200"
    every = rt_run.render_options(s, frame=7)
    report = {
        "shading_nodes_custom": rt_engine.RtRenderEngine.bl_use_shading_nodes_custom,
        "use_preview": rt_engine.RtRenderEngine.bl_use_preview,
        "panels": panels,
        "shown_under_rt": len(rt_panels.compatible_panels()),
        "options_plain": plain,
        "options_every": every,
        "preview_options": rt_run.render_options(s, frame=7, preview=True),
    }
    save(out, "ui", report)


def preview(out):
    scene = setup()
    scene.render.engine = "RT"
    material = bpy.data.materials.new("Red")
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.05, 0.05, 1.0)
    bpy.ops.mesh.primitive_cube_add()
    bpy.context.object.data.materials.append(material)
    icon = material.preview_ensure()
    start = time.perf_counter()
    assert bpy.ops.wm.previews_ensure() == {"FINISHED"}
    took = time.perf_counter() - start
    pixels = list(icon.image_pixels_float)
    rgb = [pixels[i : i + 3] for i in range(0, len(pixels), 4)]
    lit = [p for p in rgb if max(p) > 0.02]
    reds = sum(1 for r, g, b in lit if r > 2.0 * g and r > 2.0 * b)
    folder = os.path.join(rt_run.cache_dir(), "preview")
    report = {
        "size": list(icon.image_size),
        "lit": len(lit),
        "reddish": reds,
        "pixels": len(rgb),
        "seconds": took,
        "scene": open(os.path.join(folder, "scene.toml")).read() if os.path.isfile(os.path.join(folder, "scene.toml")) else "",
    }
    save(out, "preview", report)


def f12_multilayer(scene, path):
    scene.render.image_settings.media_type = "MULTI_LAYER_IMAGE"
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    start = time.perf_counter()
    result = bpy.ops.render.render(write_still=True)
    assert result == {"FINISHED"}, result
    return time.perf_counter() - start


def levels(blend, out):
    setup()
    bpy.ops.wm.open_mainfile(filepath=blend)
    scene = bpy.context.scene
    scene.render.engine = "RT"
    scene.rt_render.spp = int(os.environ.get("RT_TEST_SPP", "256"))
    scene.rt_render.max_bounces = scene.cycles.max_bounces
    layer = bpy.context.view_layer
    layer.rt.noise = layer.rt.sample_count = True
    took = f12_multilayer(scene, os.path.join(out, "levels.exr"))
    text = open(os.path.join(rt_run.cache_dir(), "scene.toml")).read()
    report = {"seconds": took, "scene": text, "spp": scene.rt_render.spp}
    save(out, "levels", report)


def facing_plane_scene():
    """A 20 m plane 5 m in front of a perspective camera, facing it, under a uniform sky."""
    scene = setup()
    scene.render.resolution_x, scene.render.resolution_y = 48, 32
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 0.0, 0.0), rotation=(math.pi / 2, 0.0, 0.0))
    bpy.ops.object.camera_add(location=(0.0, -5.0, 0.0), rotation=(math.pi / 2, 0.0, 0.0))
    scene.camera = bpy.context.object
    scene.camera.data.lens = 20.0
    world = bpy.data.worlds.new("sky")
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
    scene.world = world
    scene.render.engine = "RT"
    scene.rt_render.spp = 8
    return scene


def passes(out):
    scene = facing_plane_scene()
    layer = bpy.context.view_layer
    layer.use_pass_z = layer.use_pass_normal = True
    layer.use_pass_position = layer.use_pass_emit = layer.use_pass_diffuse_color = True
    layer.rt.denoising_data = layer.rt.sample_count = layer.rt.noise = True
    f12_multilayer(scene, os.path.join(out, "passes.exr"))
    report = {"cache": rt_run.cache_dir(), "spp": scene.rt_render.spp, "max_bounces": scene.rt_render.max_bounces + 1}
    save(out, "passes", report)


def size(out):
    scene = facing_plane_scene()
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 103, 79, 50
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    sizes = {}
    for name, border, crop in (("full", False, False), ("border", True, False), ("crop", True, True)):
        r = scene.render
        r.use_border, r.use_crop_to_border = border, crop
        r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = 0.25, 0.75, 0.5, 1.0
        r.filepath = os.path.join(out, f"size_{name}.exr")
        assert bpy.ops.render.render(write_still=True) == {"FINISHED"}
        image = bpy.data.images.load(r.filepath)
        sizes[name] = list(image.size)
    save(out, "size", {"sizes": sizes})


def transparent(out):
    scene = facing_plane_scene()
    bpy.data.objects["Plane"].scale = (0.2, 0.2, 0.2)
    scene.render.film_transparent = True
    f12_multilayer(scene, os.path.join(out, "transparent.exr"))
    text = open(os.path.join(rt_run.cache_dir(), "scene.toml")).read()
    save(out, "transparent", {"scene": text})


def holdout(out):
    """A small plane in a held-out collection, the film opaque."""
    scene = facing_plane_scene()
    plane = bpy.data.objects["Plane"]
    plane.scale = (0.2, 0.2, 0.2)
    held = bpy.data.collections.new("held out")
    scene.collection.children.link(held)
    for collection in plane.users_collection:
        collection.objects.unlink(plane)
    held.objects.link(plane)
    bpy.context.view_layer.layer_collection.children["held out"].holdout = True
    f12_multilayer(scene, os.path.join(out, "holdout.exr"))
    text = open(os.path.join(rt_run.cache_dir(), "scene.toml")).read()
    save(out, "holdout", {"scene": text})


def motion(out):
    """F12 of the moving objects that tests/cycles/motion_objects.exr shows as Cycles renders
    them (the engine evaluates the render's depsgraph over the shutter)."""
    setup()
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "cycles"))
    import make_motion_refs

    scene = make_motion_refs.objects_scene()
    scene.render.engine = "RT"
    scene.rt_render.spp = int(os.environ.get("RT_TEST_SPP", "256"))
    scene.rt_render.max_bounces = scene.cycles.max_bounces
    bpy.context.view_layer.rt.noise = True
    took = f12_multilayer(scene, os.path.join(out, "motion.exr"))
    text = open(os.path.join(rt_run.cache_dir(), "scene.toml")).read()
    save(out, "motion", {"seconds": took, "scene": text, "frame": [scene.frame_current, scene.frame_subframe]})


def progressive(out):
    scene = facing_plane_scene()
    scene.rt_render.spp = 1_000_000
    scene.rt_render.time_limit = 4.0
    scene.rt_render.progressive_every = 0.5
    snapshots = []
    original = rt_run.run_rt

    def counting(command, on_progress=None, should_stop=lambda: False, poll_s=0.05, on_snapshot=None):
        def seen(event):
            snapshots.append(event.get("spp"))
            on_snapshot(event)

        return original(command, on_progress, should_stop, poll_s, seen if on_snapshot else None)

    rt_run.run_rt = counting
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.filepath = os.path.join(out, "progressive.exr")
    start = time.perf_counter()
    assert bpy.ops.render.render(write_still=True) == {"FINISHED"}
    save(out, "progressive", {"snapshots": snapshots, "seconds": time.perf_counter() - start})


if __name__ == "__main__":
    mode, args = sys.argv[1], sys.argv[2:]
    modes = {"ui": ui, "preview": preview, "levels": levels, "passes": passes, "size": size, "progressive": progressive}
    modes["transparent"], modes["holdout"], modes["motion"] = transparent, holdout, motion
    modes[mode](*args)
