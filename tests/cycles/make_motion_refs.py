"""Cycles references for motion blur (tests/cycles_motion.rs compares rt against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_motion_refs.py [--spp 1024] [NAME...]

Every scene is keyframed in bpy, exported with blender/rt_export.py (which evaluates the
moving objects and the camera over the shutter, as Cycles does) into
tests/cycles/scenes/NAME/, and rendered with Cycles into tests/cycles/NAME.exr. CI does not
run Cycles: commit both.
"""

import math

import bpy

import cycles_reference as cycles


def keyframe(obj, path, frames_and_values):
    """Keys `obj.path` at each (frame, value), interpolated linearly between them."""
    for frame, value in frames_and_values:
        setattr(obj, path, value)
        obj.keyframe_insert(path, frame=frame)
    for curve in curves_of(obj):
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"


def curves_of(obj):
    """The F-curves of `obj`'s action (Blender 5's layered actions keep them in channelbags)."""
    action = obj.animation_data.action
    if hasattr(action, "fcurves"):
        return list(action.fcurves)
    return [c for layer in action.layers for strip in layer.strips for bag in strip.channelbags for c in bag.fcurves]


def stage(scene):
    """A floor under a uniform sky, blurred over one frame centred on frame 2 by default."""
    cycles.set_up(scene, 96, 64, bounces=8)
    cycles.uniform_world(scene, (0.6, 0.7, 0.9))
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 1.0
    scene.frame_set(2)
    bpy.ops.mesh.primitive_plane_add(size=20.0)
    bpy.context.active_object.data.materials.append(cycles.diffuse("floor", (0.7, 0.7, 0.65)))


def objects_scene():
    """Object motion: a red sphere sliding 2 m along X, a blue cube turning 150° about Z (3
    Motion Steps: 9 keys, so the rotation's arc is followed), a green cube growing to twice its
    size, a yellow cube that moves but has its Motion Blur off (sharp where the frame has it),
    and a white one standing still; the shutter starts on the frame (Position Start)."""
    scene = cycles.new_scene()
    stage(scene)
    scene.render.motion_blur_position = "START"
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, segments=32, ring_count=16)
    sphere = bpy.context.active_object
    sphere.data.materials.append(cycles.diffuse("red", (0.8, 0.1, 0.1)))
    keyframe(sphere, "location", [(2, (-2.5, 0.0, 0.5)), (3, (-0.5, 0.0, 0.5))])
    cubes = {
        "turning": ((0.2, 0.3, 0.9), (1.0, 1.5, 0.5)),
        "growing": ((0.1, 0.7, 0.2), (2.2, -0.5, 0.4)),
        "unblurred": ((0.9, 0.8, 0.1), (-1.5, 2.5, 0.4)),
        "still": ((0.9, 0.9, 0.9), (2.5, 2.0, 0.4)),
    }
    for name, (colour, location) in cubes.items():
        bpy.ops.mesh.primitive_cube_add(size=0.8, location=location)
        cube = bpy.context.active_object
        cube.name = name
        cube.data.materials.append(cycles.diffuse(name, colour))
    turning = bpy.data.objects["turning"]
    turning.cycles.motion_steps = 3
    keyframe(turning, "rotation_euler", [(2, (0.0, 0.0, 0.0)), (3, (0.0, 0.0, math.radians(150.0)))])
    keyframe(bpy.data.objects["growing"], "scale", [(2, (1.0, 1.0, 1.0)), (3, (2.0, 2.0, 2.0))])
    unblurred = bpy.data.objects["unblurred"]
    unblurred.cycles.use_motion_blur = False
    keyframe(unblurred, "location", [(2, (-1.5, 2.5, 0.4)), (3, (0.5, 2.5, 0.4))])
    cycles.camera(scene, (0.0, -8.0, 4.0), 62.0)
    scene.frame_set(2)
    return scene


def camera_scene():
    """Camera motion: the camera pans 12° and slides 0.6 m while the shutter is open (half a
    frame, ending on the frame: Position End), over a row of still cubes and a sphere."""
    scene = cycles.new_scene()
    stage(scene)
    scene.render.motion_blur_shutter = 0.5
    scene.render.motion_blur_position = "END"
    for i, colour in enumerate([(0.8, 0.1, 0.1), (0.1, 0.7, 0.2), (0.2, 0.3, 0.9), (0.9, 0.8, 0.1)]):
        bpy.ops.mesh.primitive_cube_add(size=0.7, location=(-2.4 + 1.6 * i, 1.0, 0.35))
        bpy.context.active_object.data.materials.append(cycles.diffuse(f"cube {i}", colour))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, segments=32, ring_count=16, location=(0.0, -0.8, 0.5))
    bpy.context.active_object.data.materials.append(cycles.diffuse("white", (0.9, 0.9, 0.9)))
    camera = cycles.camera(scene, (0.0, -7.0, 3.0), 70.0)
    keyframe(camera, "location", [(1, (-0.6, -7.0, 3.0)), (2, (0.0, -7.0, 3.0))])
    keyframe(camera, "rotation_euler", [(1, (math.radians(70.0), 0.0, math.radians(12.0))),
                                        (2, (math.radians(70.0), 0.0, 0.0))])
    scene.frame_set(2)
    return scene


SCENES = {
    "motion_objects": objects_scene,
    "motion_camera": camera_scene,
}


if __name__ == "__main__":
    cycles.make(__doc__, 1024, SCENES)
