"""Cycles references for Worlds whose Background a node graph drives (tests/cycles_node_graphs.rs
compares rt against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_world_refs.py [--spp 1024] [NAME...]

`graph_world` lights a diffuse sphere, a rough metal sphere and a floor by a sky gradient (a
Color Ramp of the direction's height) with noise clouds, times a strength; the camera sees
another colour where the world is seen directly (Light Path's Is Camera Ray), as artists
light with one sky and show another. `graph_world_sun` is the same gradient beside a sun
lamp, so that light samples share between the two. `graph_world_camera` is a World of
Texture Coordinate's Window (a checker) and Camera (a ramp of its x), seen directly and in a
metal sphere, which Cycles places at the camera; `graph_world_ortho` the same through an
orthographic camera; `graph_world_equirect`, `graph_world_fisheye`,
`graph_world_fisheye_equidistant` and `graph_world_mirror_ball` through panoramic cameras,
a floor of Window beside them. Each scene is exported with
blender/rt_export.py into tests/cycles/scenes/NAME/ and rendered into tests/cycles/NAME.exr.
CI does not run Cycles: commit both.
"""


import math

import bpy

import cycles_reference as cycles
from make_node_graph_refs import math_node, new, noise, output, ramp

SKY_STOPS = [(0.0, (0.9, 0.55, 0.3, 1.0)), (0.35, (0.55, 0.7, 0.95, 1.0)), (1.0, (0.15, 0.3, 0.85, 1.0))]


def sky_graph(world, camera_colour=None, strength=1.5):
    """The world's Background: a ramp of the direction's height plus noise clouds; the camera
    sees `camera_colour` where it sees the world, if given."""
    tree = world.node_tree
    background = tree.nodes["Background"]
    direction = new(tree, "ShaderNodeTexCoord").outputs["Generated"]
    height = new(tree, "ShaderNodeSeparateXYZ", {"Vector": direction}).outputs["Z"]
    sky = ramp(tree, math_node(tree, "MULTIPLY_ADD", height, 0.8, 0.2), "LINEAR", SKY_STOPS)
    clouds = output(noise(tree, direction, Scale=3.0, Detail=2.0), "Fac")
    cloudy = new(tree, "ShaderNodeMix", {"Factor_Float": math_node(tree, "MULTIPLY", clouds, 0.6, clamp=True),
                                         "A_Color": sky, "B_Color": (1.0, 1.0, 1.0, 1.0)}, data_type="RGBA")
    colour = output(cloudy, "Result_Color")
    if camera_colour is not None:
        seen = new(tree, "ShaderNodeMix", {"Factor_Float": new(tree, "ShaderNodeLightPath").outputs["Is Camera Ray"],
                                           "A_Color": colour, "B_Color": camera_colour}, data_type="RGBA")
        colour = output(seen, "Result_Color")
    tree.links.new(colour, background.inputs["Color"])
    background.inputs["Strength"].default_value = strength


def camera_graph(world):
    """The world's Background: a checker of where a direction falls on the image (Window)
    over a ramp of its x in camera space (Camera)."""
    tree = world.node_tree
    coordinates = new(tree, "ShaderNodeTexCoord")
    checker = new(tree, "ShaderNodeTexChecker", {"Scale": 6.0, "Color1": (0.9, 0.85, 0.3, 1.0),
                                                  "Color2": (0.1, 0.1, 0.1, 1.0)})
    tree.links.new(coordinates.outputs["Window"], checker.inputs["Vector"])
    x = new(tree, "ShaderNodeSeparateXYZ", {"Vector": coordinates.outputs["Camera"]}).outputs["X"]
    across = ramp(tree, math_node(tree, "MULTIPLY_ADD", x, 0.5, 0.5), "LINEAR", SKY_STOPS)
    mixed = new(tree, "ShaderNodeMix", {"Factor_Float": output(checker, "Fac"), "A_Color": across,
                                        "B_Color": output(checker, "Color")}, data_type="RGBA")
    tree.links.new(output(mixed, "Result_Color"), tree.nodes["Background"].inputs["Color"])


def camera_scene():
    scene = cycles.new_scene()
    cycles.set_up(scene, 96, bounces=4)
    world = bpy.data.worlds.new("window")
    scene.world = world
    camera_graph(world)
    objects()
    # Turned and rolled, so that camera space is not the world's.
    cycles.camera(scene, (0.3, -5.0, 1.2), 80.0).rotation_euler[1:] = (0.12, 0.15)
    return scene


def ortho_camera_scene():
    """`camera_scene` through an orthographic camera: Cycles reads Window at a camera ray's
    origin there, and at the direction itself for other rays."""
    scene = camera_scene()
    camera = scene.camera.data
    camera.type, camera.ortho_scale, camera.shift_x = "ORTHO", 5.0, 0.05
    return scene


def panorama_scene(kind, **settings):
    """`camera_scene` through a panoramic camera of type `kind` (its settings by name), the
    floor's colour a checker of Window too: Cycles maps a direction through the panorama's
    inverse (`direction_to_panorama`), and reads Camera in the panoramic camera's space."""
    scene = camera_scene()
    camera = scene.camera.data
    camera.type, camera.panorama_type = "PANO", kind
    for key, value in settings.items():
        setattr(camera, key, value)
    tree = bpy.data.materials["floor"].node_tree
    checker = new(tree, "ShaderNodeTexChecker", {"Vector": new(tree, "ShaderNodeTexCoord").outputs["Window"],
                                                  "Scale": 10.0, "Color1": (0.8, 0.3, 0.2, 1.0),
                                                  "Color2": (0.3, 0.6, 0.8, 1.0)})
    tree.links.new(output(checker, "Color"), tree.nodes["Principled BSDF"].inputs["Base Color"])
    return scene


def objects():
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, segments=48, ring_count=24, location=(-0.9, 0.0, 0.8))
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(cycles.principled("matte", (0.8, 0.8, 0.8), Roughness=1.0))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, segments=48, ring_count=24, location=(0.9, 0.0, 0.8))
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(
        cycles.principled("metal", (0.9, 0.8, 0.6), Metallic=1.0, Roughness=0.3))
    bpy.ops.mesh.primitive_plane_add(size=10.0)
    bpy.context.active_object.data.materials.append(cycles.principled("floor", (0.5, 0.5, 0.5), Roughness=1.0))


def world_scene(sun=False):
    scene = cycles.new_scene()
    cycles.set_up(scene, 96, bounces=4)
    world = bpy.data.worlds.new("sky")
    scene.world = world
    sky_graph(world, camera_colour=None if sun else (0.2, 0.2, 0.25, 1.0), strength=0.8 if sun else 1.5)
    objects()
    if sun:
        cycles.sun(scene, 2.0, (50.0, 0.0, 30.0))
    cycles.camera(scene, (0.0, -5.0, 1.6), 80.0)
    return scene


SCENES = {
    "graph_world": world_scene,
    "graph_world_sun": lambda: world_scene(sun=True),
    "graph_world_camera": camera_scene,
    "graph_world_ortho": ortho_camera_scene,
    "graph_world_equirect": lambda: panorama_scene(
        "EQUIRECTANGULAR", latitude_min=math.radians(-60.0), latitude_max=math.radians(80.0),
        longitude_min=math.radians(-150.0), longitude_max=math.radians(120.0), shift_x=0.05),
    "graph_world_fisheye": lambda: panorama_scene(
        "FISHEYE_EQUISOLID", fisheye_fov=math.radians(190.0), fisheye_lens=7.0, shift_y=0.03),
    "graph_world_fisheye_equidistant": lambda: panorama_scene(
        "FISHEYE_EQUIDISTANT", fisheye_fov=math.radians(200.0)),
    "graph_world_mirror_ball": lambda: panorama_scene("MIRRORBALL"),
}


if __name__ == "__main__":
    cycles.make(__doc__, 1024, SCENES)
