"""Cycles references for rt's camera (tests/cycles_camera.rs compares rt against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_camera_refs.py [--spp 8192] [NAME...]

Builds one small scene in bpy, views it through each camera below, renders it with
Cycles into tests/cycles/camera_NAME.exr, and exports it with blender/rt_export.py into
tests/cycles/scenes/camera_NAME/ (scene.toml and its assets). CI does not run Cycles:
commit both.

The scene is nine emissive cubes of different colours at three depths and five small
bright ones far behind them before an emissive wall, under a dim uniform world. The
panoramic cameras (names starting `pano_`) stand instead among boxes all around them: one
of its own colour in each of the six axis directions, a smaller one towards each of the
eight corners, and a floor. Every surface only emits (black base colour, no specular
layer), so a pixel's value is the emission its camera rays meet: the comparison tests where
the rays go (roll, projection, panorama mapping, shift, sensor fit, aperture, clip planes)
and nothing else.

Cycles settings: box filter of width 1, no clamping, denoising or adaptive sampling,
blur_glossy 0, linear 32-bit EXR.
"""

import math

import bpy
from mathutils import Matrix, Vector

import cycles_reference as cycles
from cycles_reference import emissive

# Multiples of 1/8, so that Cycles' f32 sum of a pixel's equal samples is exact and the
# faces' inner pixels match rt's to rounding.
COLOURS = [
    (0.875, 0.125, 0.125),
    (0.125, 0.75, 0.25),
    (0.125, 0.25, 1.0),
    (1.0, 0.875, 0.125),
    (0.125, 0.875, 0.875),
    (0.875, 0.125, 0.75),
    (1.0, 1.0, 1.0),
    (1.0, 0.5, 0.0),
    (0.5, 0.25, 0.75),
]
# Depth (Blender Y) of the cube in grid cell (i, j).
DEPTHS = (-3.0, 0.0, 3.0)

# Where the panoramic cameras stand and look (build_surroundings' boxes are about it).
PANO_VIEW = {"location": (0.2, -0.3, 0.1), "target": (1.2, 0.9, 0.5), "roll_deg": 15.0}

# name: (width, height, camera settings). Positions and targets are in Blender's Z-up
# coordinates; `roll_deg` turns the camera about its view axis.
CAMERAS = {
    "rolled": (64, 64, {"location": (0.8, -6.0, 0.6), "target": (0.0, 0.0, 0.0), "roll_deg": 25.0, "lens": 40.0}),
    "ortho": (
        64,
        64,
        {"location": (4.0, -7.0, 2.5), "target": (0.0, 0.0, 0.0), "roll_deg": -10.0, "type": "ORTHO", "ortho_scale": 6.5},
    ),
    "ortho_dof": (
        64,
        64,
        {
            "location": (4.0, -7.0, 2.5),
            "target": (0.0, 0.0, 0.0),
            "type": "ORTHO",
            "ortho_scale": 6.5,
            "fstop": 0.5,
            "focus_object": "cube_1_1",
        },
    ),
    "shift": (
        64,
        48,
        {
            "location": (0.0, -6.0, 0.0),
            "target": (0.0, 0.0, 0.0),
            "lens": 35.0,
            "sensor_fit": "VERTICAL",
            "shift_x": 0.2,
            "shift_y": -0.15,
        },
    ),
    # clip_start removes the nearest row of cubes, clip_end cuts through the middle row
    # (showing the inside of its cubes) and hides the far row, the points and the wall; a
    # wide lens makes clipping at planes differ from clipping at spheres towards the corners.
    "clipped": (
        64,
        64,
        {"location": (0.8, -6.0, 0.6), "target": (0.0, 0.0, 0.0), "lens": 22.0, "clip_start": 4.5, "clip_end": 6.2},
    ),
    "ortho_clipped": (
        64,
        64,
        {
            "location": (4.0, -7.0, 2.5),
            "target": (0.0, 0.0, 0.0),
            "type": "ORTHO",
            "ortho_scale": 6.5,
            "clip_start": 6.0,
            "clip_end": 9.5,
        },
    ),
    "dof_round": (
        64,
        64,
        {"location": (0.0, -6.0, 0.3), "target": (0.0, 0.0, 0.0), "lens": 50.0, "fstop": 0.3, "focus_distance": 6.0},
    ),
    "dof_blades": (
        64,
        64,
        {
            "location": (0.0, -6.0, 0.3),
            "target": (0.0, 0.0, 0.0),
            "lens": 50.0,
            "fstop": 0.12,
            "focus_object": "cube_0_0",
            "blades": 6,
            "blade_rotation_deg": 20.0,
            "aperture_ratio": 1.6,
        },
    ),
    # Panoramas, from a point among boxes all around (build_surroundings), looking
    # off-axis and rolled so that a wrong axis or sign shows.
    "pano_equirect": (128, 64, {**PANO_VIEW, "panorama": "EQUIRECTANGULAR"}),
    # A window of the sphere, moved by a lens shift.
    "pano_equirect_window": (
        128,
        64,
        {
            **PANO_VIEW,
            "panorama": "EQUIRECTANGULAR",
            "latitude_deg": (-30.0, 60.0),
            "longitude_deg": (-120.0, 75.0),
            "shift_x": 0.05,
            "shift_y": -0.1,
        },
    ),
    # A wide fisheye on a landscape image: a circle stretched to an ellipse.
    "pano_fisheye_equidistant": (96, 64, {**PANO_VIEW, "panorama": "FISHEYE_EQUIDISTANT", "fisheye_fov_deg": 220.0}),
    # Its circle cut by the sensor's height; the vertical fit spans the height by the sensor's.
    "pano_fisheye_equisolid": (
        96,
        64,
        {**PANO_VIEW, "panorama": "FISHEYE_EQUISOLID", "fisheye_fov_deg": 190.0, "fisheye_lens": 7.0},
    ),
    "pano_fisheye_equisolid_vertical": (
        64,
        96,
        {
            **PANO_VIEW,
            "panorama": "FISHEYE_EQUISOLID",
            "fisheye_fov_deg": 160.0,
            "fisheye_lens": 5.0,
            "sensor_fit": "VERTICAL",
        },
    ),
    "pano_mirror_ball": (64, 64, {**PANO_VIEW, "panorama": "MIRRORBALL"}),
    # Depth of field on a sphere in focus (Cycles focuses panoramas at a distance along
    # each ray, with the aperture across it), through a six-bladed aperture.
    "pano_equirect_dof": (
        128,
        64,
        {**PANO_VIEW, "panorama": "EQUIRECTANGULAR", "fstop": 0.04, "focus_distance": 1.2, "blades": 6},
    ),
    # Pixels twice as wide as high make a portrait image a landscape picture: the automatic
    # fit turns to the width, and the shift follows it.
    "pixel_aspect": (
        40,
        64,
        {"location": (0.8, -6.0, 0.6), "target": (0.0, 0.0, 0.0), "lens": 35.0, "shift_x": 0.1, "pixel_aspect": (2.0, 1.0)},
    ),
    # Tall pixels on the equisolid fisheye, whose sensor follows the picture's aspect.
    "pano_fisheye_equisolid_pixel_aspect": (
        96,
        48,
        {**PANO_VIEW, "panorama": "FISHEYE_EQUISOLID", "fisheye_fov_deg": 190.0, "fisheye_lens": 7.0,
         "pixel_aspect": (1.0, 1.5)},
    ),
    # Clipped at spheres about the camera: clip_start cuts into the corner boxes, clip_end
    # into the axis boxes and hides the floor's far parts.
    "pano_equirect_clipped": (
        128,
        64,
        {**PANO_VIEW, "panorama": "EQUIRECTANGULAR", "clip_start": 2.5, "clip_end": 3.3},
    ),
}


def build_objects(scene):
    for i in range(3):
        for j in range(3):
            location = ((i - 1) * 1.6, DEPTHS[(i + 2 * j) % 3], (j - 1) * 1.3)
            bpy.ops.mesh.primitive_cube_add(size=0.9, location=location, rotation=(0.0, 0.0, 0.3 * (i - j)))
            cube = bpy.context.object
            cube.name = cube.data.name = f"cube_{i}_{j}"
            cube.data.materials.append(emissive(cube.name, COLOURS[3 * j + i]))
    # Small bright points far behind: out of focus they show the aperture's shape.
    for k, (x, z) in enumerate([(-2.2, 1.6), (0.7, 2.0), (2.4, -0.4), (-0.9, -1.9), (1.5, 0.9)]):
        bpy.ops.mesh.primitive_cube_add(size=0.12, location=(x, 5.0, z))
        point = bpy.context.object
        point.name = point.data.name = f"point_{k}"
        point.data.materials.append(emissive(point.name, (4.0, 4.0, 4.0)))
    bpy.ops.mesh.primitive_plane_add(size=40.0, location=(0.0, 7.0, 0.0), rotation=(math.pi / 2, 0.0, 0.0))
    wall = bpy.context.object
    wall.name = wall.data.name = "wall"
    wall.data.materials.append(emissive("wall", (0.125, 0.125, 0.25)))
    cycles.uniform_world(scene, (0.0625, 0.0625, 0.0625))


def build_surroundings(scene):
    """Boxes all around PANO_VIEW's location: one in each axis direction, smaller ones
    towards the corners, a floor below; a dim world."""
    centre = Vector(PANO_VIEW["location"])
    axes = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    for k, axis in enumerate(axes):
        location = centre + 3.0 * Vector(axis)
        bpy.ops.mesh.primitive_cube_add(size=1.1, location=location, rotation=(0.2 * k, 0.0, 0.35 * k))
        box = bpy.context.object
        box.name = box.data.name = f"axis_{k}"
        box.data.materials.append(emissive(box.name, COLOURS[k]))
    k = 0
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                location = centre + 1.5 * Vector((sx, sy, sz))
                bpy.ops.mesh.primitive_cube_add(size=0.5, location=location, rotation=(0.0, 0.4, 0.2 * k))
                box = bpy.context.object
                box.name = box.data.name = f"corner_{k}"
                box.data.materials.append(emissive(box.name, COLOURS[(k + 6) % len(COLOURS)]))
                k += 1
    bpy.ops.mesh.primitive_plane_add(size=12.0, location=centre + Vector((0.0, 0.0, -3.6)))
    floor = bpy.context.object
    floor.name = floor.data.name = "floor"
    floor.data.materials.append(emissive("floor", (0.25, 0.125, 0.0625)))
    cycles.uniform_world(scene, (0.0625, 0.125, 0.1875))


def add_camera(scene, settings):
    bpy.ops.object.camera_add(location=settings["location"])
    cam = bpy.context.object
    view = Vector(settings["target"]) - Vector(settings["location"])
    # Looking at the target with +Y up, then turned about the view axis (its local Z).
    roll = Matrix.Rotation(math.radians(settings.get("roll_deg", 0.0)), 3, "Z")
    cam.rotation_euler = (view.to_track_quat("-Z", "Y").to_matrix() @ roll).to_euler()
    data = cam.data
    data.type = settings.get("type", "PERSP")
    data.lens = settings.get("lens", 50.0)
    data.ortho_scale = settings.get("ortho_scale", 6.0)
    data.sensor_fit = settings.get("sensor_fit", "AUTO")
    data.shift_x = settings.get("shift_x", 0.0)
    data.shift_y = settings.get("shift_y", 0.0)
    if "panorama" in settings:
        data.type = "PANO"
        data.panorama_type = settings["panorama"]
        data.latitude_min, data.latitude_max = (math.radians(a) for a in settings.get("latitude_deg", (-90.0, 90.0)))
        data.longitude_min, data.longitude_max = (
            math.radians(a) for a in settings.get("longitude_deg", (-180.0, 180.0))
        )
        data.fisheye_fov = math.radians(settings.get("fisheye_fov_deg", 180.0))
        data.fisheye_lens = settings.get("fisheye_lens", 10.5)
    if "clip_start" in settings:
        data.clip_start, data.clip_end = settings["clip_start"], settings["clip_end"]
    if "fstop" in settings:
        dof = data.dof
        dof.use_dof = True
        dof.aperture_fstop = settings["fstop"]
        dof.focus_distance = settings.get("focus_distance", 10.0)
        if "focus_object" in settings:
            dof.focus_object = bpy.data.objects[settings["focus_object"]]
        dof.aperture_blades = settings.get("blades", 0)
        dof.aperture_rotation = math.radians(settings.get("blade_rotation_deg", 0.0))
        dof.aperture_ratio = settings.get("aperture_ratio", 1.0)
    scene.camera = cam
    return cam


def main():
    args = cycles.arguments(__doc__, 8192, list(CAMERAS))
    for name in args.names:
        width, height, settings = CAMERAS[name]
        scene = cycles.new_scene()
        (build_surroundings if name.startswith("pano_") else build_objects)(scene)
        add_camera(scene, settings)
        cycles.set_up(scene, width, height)
        scene.render.pixel_aspect_x, scene.render.pixel_aspect_y = settings.get("pixel_aspect", (1.0, 1.0))
        cycles.export(scene, f"camera_{name}")
        cycles.render(scene, f"camera_{name}", args)


if __name__ == "__main__":
    main()
