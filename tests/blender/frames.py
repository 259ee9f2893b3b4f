"""Blender side of tests/blender_frames.rs (run with the bpy venv's python).

    frames.py build OUT   builds OUT/frames.blend: over frames 1 to 4 a cube slides (its mesh
                          does not change), a plane's shape key bends it on frames 2 and 3
                          and lets it go on 4 (two shapes), a floor stands still; a camera
                          looks on.
    frames.py addon OUT   the add-on's Export now with Frame range on, into OUT/addon/
    frames.py live OUT    Live export on every edit with the render's Motion Blur on: an
                          edit exports once, sharp, and the frame stays (a live export runs
                          from Blender's update handler, where moving the frame would start
                          another update); prints what happened
"""

import os
import sys

import bpy


def linear(obj):
    """Makes every key of `obj`'s animation linear."""
    action = obj.animation_data.action
    curves = list(action.fcurves) if hasattr(action, "fcurves") else [
        c for layer in action.layers for strip in layer.strips for bag in strip.channelbags for c in bag.fcurves]
    for curve in curves:
        for point in curve.keyframe_points:
            point.interpolation = "CONSTANT"


def build(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 48, 32
    scene.frame_start, scene.frame_end = 1, 4
    bpy.ops.mesh.primitive_plane_add(size=10.0)
    bpy.context.object.name = "floor"
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(-2.0, 0.0, 0.5))
    cube = bpy.context.object
    cube.name = "slider"
    for frame in range(1, 5):
        cube.location.x = -2.0 + frame
        cube.keyframe_insert("location", frame=frame)
    linear(cube)
    bpy.ops.mesh.primitive_plane_add(size=1.5, location=(0.0, 2.0, 1.0), rotation=(1.2, 0.0, 0.0))
    sheet = bpy.context.object
    sheet.name = "sheet"
    sheet.shape_key_add(name="basis")
    bent = sheet.shape_key_add(name="bent")
    bent.data[0].co.z += 0.5
    for frame, value in ((1, 0.0), (2, 1.0), (3, 1.0), (4, 0.0)):
        bent.value = value
        bent.keyframe_insert("value", frame=frame)
    linear(sheet.data.shape_keys)
    bpy.ops.object.camera_add(location=(0.0, -8.0, 3.0), rotation=(1.25, 0.0, 0.0))
    scene.camera = bpy.context.object
    world = bpy.data.worlds.new("sky")
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.7, 0.9, 1)
    scene.world = world
    scene.frame_set(1)
    os.makedirs(out, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "frames.blend"))




def addon(out):
    """The add-on's Export now with Frame range on: OUT/addon/shot_####.toml for frames 1 to 4."""
    bpy.ops.wm.open_mainfile(filepath=os.path.join(out, "frames.blend"))
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                    "blender"))
    import rt_blender

    rt_blender.register()
    settings = bpy.context.scene.rt_export
    settings.out_dir = os.path.join(out, "addon", "assets")
    settings.scene_file = os.path.join(out, "addon", "shot_####.toml")
    settings.frame_range = True
    assert bpy.ops.rt.export_now() == {"FINISHED"}
    settings.scene_file = os.path.join(out, "addon", "no_hashes.toml")
    try:
        bpy.ops.rt.export_now()
    except RuntimeError as e:
        print(f"refused: {e}", file=sys.stderr)


def live(out):
    bpy.ops.wm.open_mainfile(filepath=os.path.join(out, "frames.blend"))
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                    "blender"))
    import rt_blender
    from rt_blender import rt_export

    rt_blender.register()
    scene = bpy.context.scene
    scene.render.use_motion_blur = True
    scene.frame_set(2)
    settings = scene.rt_export
    settings.out_dir = os.path.join(out, "live", "assets")
    settings.scene_file = os.path.join(out, "live", "scene.toml")
    rt_export.live_export(scene)
    exports = []
    original = rt_export.live_export

    def counted(s):
        exports.append(s.frame_current)
        return original(s)

    rt_export.live_export = counted
    settings.live_edits = True
    bpy.data.objects["floor"].location.z += 0.01
    bpy.context.view_layer.update()
    text = open(settings.scene_file).read()
    print(f"live exports: {len(exports)}; frame {scene.frame_current}; motion keys: {text.count('motion =')}",
          file=sys.stderr)


if __name__ == "__main__":
    {"build": build, "addon": addon, "live": live}[sys.argv[-2]](sys.argv[-1])
