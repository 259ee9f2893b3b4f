"""Cycles as a reference renderer, for the `make_*_refs.py` scripts beside this file.

Each script builds its scenes in bpy and, per scene NAME, exports it with
blender/rt_export.py into tests/cycles/scenes/NAME/ and renders it with Cycles into
tests/cycles/NAME.exr. What they share is here: the command line (`--spp`, `--export-only`,
the names), the Cycles settings that make Cycles a reference for rt (`set_up`), the export
and the render, and the scene pieces more than one script builds (worlds, diffuse
materials).
"""

import argparse
import math
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "blender"))
import rt_export  # noqa: E402


def arguments(description, default_spp, names):
    """The command line: `--spp`, `--export-only` and the names to make (default: all of
    `names`, in their order); arguments after `--` when run as `blender -b -P`."""
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else sys.argv[1:]
    parser = argparse.ArgumentParser(description=description.split("\n\n")[0])
    parser.add_argument("--spp", type=int, default=default_spp, help="Cycles samples per pixel")
    parser.add_argument("--export-only", action="store_true", help="export the scenes, keep the committed references")
    parser.add_argument("names", nargs="*", help=f"references to make (default: all of {', '.join(names)})")
    args = parser.parse_args(argv)
    unknown = [n for n in args.names if n not in names]
    if unknown:
        parser.error(f"unknown reference {', '.join(unknown)}; the references are {', '.join(names)}")
    args.names = args.names or list(names)
    return args


def new_scene():
    """An empty scene: Blender's factory settings, no objects."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return bpy.context.scene


def set_up(scene, width, height=None, bounces=16, seed=0, **cycles_settings):
    """Cycles as a reference on the CPU: a box filter of one pixel (as rt samples pixels), no
    clamping, denoising, adaptive sampling or glossy blur, every bounce limit at `bounces`,
    `width` x `height` (square by default), linear 32-bit EXR with the Standard view.
    `cycles_settings` are further `scene.cycles` properties of one script's own."""
    render = scene.render
    render.engine = "CYCLES"
    render.resolution_x, render.resolution_y = width, height or width
    render.resolution_percentage = 100
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    render.image_settings.exr_codec = "ZIP"
    scene.view_settings.view_transform = "Standard"
    c = scene.cycles
    c.device = "CPU"
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
    c.volume_bounces = 0
    c.caustics_reflective = c.caustics_refractive = True
    c.seed = seed
    for key, value in cycles_settings.items():
        setattr(c, key, value)


def export(scene, name, toml="scene.toml", **options):
    """Exports `scene` with rt_export into tests/cycles/scenes/NAME/ (`toml` and its assets
    folder); `options` go to `rt_export.export_scene`. Returns its result."""
    bpy.context.view_layer.update()
    folder = os.path.join(HERE, "scenes", name)
    os.makedirs(folder, exist_ok=True)
    return rt_export.export_scene(scene, os.path.join(folder, "assets"), os.path.join(folder, toml), **options)


def render(scene, name, args):
    """Renders `scene` with Cycles at `args.spp` into tests/cycles/NAME.exr, unless
    `args.export_only`."""
    if args.export_only:
        print(f"{name}: exported", flush=True)
        return
    scene.cycles.samples = args.spp
    scene.render.filepath = os.path.join(HERE, f"{name}.exr")
    bpy.ops.render.render(write_still=True)
    size = f"{scene.render.resolution_x}x{scene.render.resolution_y}"
    print(f"{name}: {size} at {args.spp} spp -> {scene.render.filepath}", flush=True)


def make(description, default_spp, scenes):
    """The main of a script whose `scenes` (name: function building the scene) are each
    exported and rendered under their own name."""
    args = arguments(description, default_spp, scenes)
    for name in args.names:
        scene = scenes[name]()
        export(scene, name)
        render(scene, name, args)


def camera(scene, location, tilt_deg):
    """The scene's camera at `location`, turned `tilt_deg` about X (90: level, looking along +Y)."""
    obj = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    obj.location = location
    obj.rotation_euler = (math.radians(tilt_deg), 0.0, 0.0)
    scene.collection.objects.link(obj)
    scene.camera = obj
    return obj


def sun(scene, energy, rotation_deg, **settings):
    """A Sun lamp of `energy` (W/m²) turned by the XYZ Euler angles `rotation_deg`, its other
    settings by name."""
    obj = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    obj.data.energy = energy
    for key, value in settings.items():
        setattr(obj.data, key, value)
    obj.rotation_euler = [math.radians(a) for a in rotation_deg]
    scene.collection.objects.link(obj)
    return obj


def principled(name, colour, **inputs):
    """A Principled BSDF of Base Color `colour`, its other inputs by name."""
    material = bpy.data.materials.new(name)
    node = material.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    return material


def uniform_world(scene, colour, name="world"):
    """A World of one colour at strength 1."""
    world = bpy.data.worlds.new(name)
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*colour, 1.0)
    background.inputs["Strength"].default_value = 1.0
    scene.world = world
    return world


def environment_world(scene, image, strength, rotation_deg=None):
    """A World showing `image` through an Environment Texture at `strength`; with
    `rotation_deg`, behind a Mapping node that rotates the generated coordinates (XYZ Euler)."""
    world = bpy.data.worlds.new("environment")
    tree = world.node_tree
    background = tree.nodes["Background"]
    background.inputs["Strength"].default_value = strength
    texture = tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image = image
    tree.links.new(texture.outputs["Color"], background.inputs["Color"])
    if rotation_deg is not None:
        coords = tree.nodes.new("ShaderNodeTexCoord")
        mapping = tree.nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = [math.radians(a) for a in rotation_deg]
        tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    scene.world = world
    return world


def diffuse(name, colour):
    """A Principled BSDF with no specular layer: Lambertian in Cycles and in rt."""
    material = bpy.data.materials.new(name)
    node = material.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    node.inputs["Specular IOR Level"].default_value = 0.0
    node.inputs["Roughness"].default_value = 1.0
    return material


def emissive(name, colour, strength=1.0):
    """`diffuse` with a black base that only emits `colour` at `strength`."""
    material = diffuse(name, (0.0, 0.0, 0.0))
    node = material.node_tree.nodes["Principled BSDF"]
    node.inputs["Emission Color"].default_value = (*colour, 1.0)
    node.inputs["Emission Strength"].default_value = strength
    return material
