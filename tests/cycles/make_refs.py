"""Cycles references for tests/cycles_lamps.rs: small scenes lit by Blender's lamps.

    /work/main/.venv-bpy/bin/python tests/cycles/make_refs.py [--spp 4096] [NAME ...]

Each scene is built here in bpy (a diffuse floor and wall, a box and a ball; one kind
of lamp per scene, one with several coloured lamps under a grey sky, one of lamps with a
blackbody Temperature), rendered by
Cycles at 64x64 into tests/cycles/NAME.exr (linear, 32-bit), and exported with
blender/rt_export.py into tests/cycles/scenes/NAME/ (NAME.toml and its assets). CI
does not run Cycles: it compares rt against the committed files.

Cycles counts bounces after the first hit (0 = direct light only), rt counts hits:
Cycles' max_bounces = BOUNCES is rt's max_bounces = BOUNCES + 1 (cycles_lamps.rs).
"""

import math

import bpy
from mathutils import Vector

import cycles_reference as cycles
from cycles_reference import diffuse

SIZE = 64
BOUNCES = 4


def add(obj, name, material):
    obj.name = obj.data.name = name
    obj.data.materials.append(material)
    return obj


def room(background):
    scene = cycles.new_scene()
    bpy.ops.mesh.primitive_plane_add(size=8)
    add(bpy.context.object, "floor", diffuse("floor", (0.5, 0.5, 0.5)))
    bpy.ops.mesh.primitive_plane_add(size=8, location=(0.0, 2.0, 4.0), rotation=(math.pi / 2, 0.0, 0.0))
    add(bpy.context.object, "wall", diffuse("wall", (0.7, 0.7, 0.6)))
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(-0.7, 0.3, 0.4), rotation=(0.0, 0.0, 0.5))
    add(bpy.context.object, "box", diffuse("box", (0.8, 0.3, 0.2)))
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3, radius=0.45, location=(0.7, -0.3, 0.45))
    add(bpy.context.object, "ball", diffuse("ball", (0.2, 0.4, 0.8)))
    bpy.ops.object.camera_add(location=(0.0, -4.5, 2.0))
    camera = bpy.context.object
    camera.rotation_euler = (Vector((0.0, 0.0, 0.5)) - camera.location).to_track_quat("-Z", "Y").to_euler()
    camera.data.lens = 30
    scene.camera = camera
    cycles.uniform_world(scene, background, "sky")
    return scene


def lamp(kind, name, location, target=None, **settings):
    bpy.ops.object.light_add(type=kind, location=location)
    obj = bpy.context.object
    obj.name = obj.data.name = name
    if target is not None:
        obj.rotation_euler = (Vector(target) - Vector(location)).to_track_quat("-Z", "Y").to_euler()
    for key, value in settings.items():
        if key == "visible_camera":
            obj.visible_camera = value
        else:
            setattr(obj.data, key, value)
    return obj


def point():
    room((0.0, 0.0, 0.0))
    lamp("POINT", "bulb", (0.4, -0.9, 1.8), energy=150.0, shadow_soft_size=0.1, color=(1.0, 0.9, 0.8),
         visible_camera=True)


def spot():
    room((0.0, 0.0, 0.0))
    lamp("SPOT", "spot", (-1.6, -1.8, 2.6), (0.2, 0.0, 0.3), energy=600.0, shadow_soft_size=0.15,
         use_soft_falloff=False, spot_size=math.radians(50.0), spot_blend=0.3)


def area():
    room((0.0, 0.0, 0.0))
    light = lamp("AREA", "panel", (0.3, -0.6, 2.3), (0.0, 0.2, 0.0), energy=250.0, shape="RECTANGLE",
                 size=1.2, size_y=0.5)
    light.rotation_euler.rotate_axis("Z", 0.4)


def sun():
    room((0.0, 0.0, 0.0))
    lamp("SUN", "sun", (0.0, 0.0, 5.0), (1.2, 1.5, 0.0), energy=3.0, angle=math.radians(10.0))


def several():
    """Coloured lamps of every kind at once, under a grey sky."""
    room((0.05, 0.05, 0.05))
    lamp("POINT", "red", (-1.4, -1.0, 1.4), energy=60.0, shadow_soft_size=0.0, color=(1.0, 0.2, 0.1))
    lamp("SPOT", "green", (1.8, -1.2, 2.4), (0.7, -0.3, 0.45), energy=300.0, shadow_soft_size=0.0,
         spot_size=math.radians(35.0), spot_blend=0.0, color=(0.2, 1.0, 0.3))
    lamp("AREA", "blue", (0.0, 0.6, 2.4), (0.0, 0.6, 0.0), energy=120.0, shape="DISK", size=0.8,
         color=(0.3, 0.4, 1.0))
    lamp("SUN", "sun", (0.0, 0.0, 5.0), (-1.0, 2.0, 0.0), energy=0.6, angle=0.0, color=(1.0, 0.95, 0.8))


def temperature():
    """Lamps coloured by Blender's blackbody Temperature (a warm bulb, a tinted daylight panel)."""
    room((0.0, 0.0, 0.0))
    lamp("POINT", "warm", (-0.6, -0.9, 1.8), energy=120.0, shadow_soft_size=0.1, use_temperature=True,
         temperature=2700.0)
    lamp("AREA", "daylight", (0.8, -0.4, 2.3), (0.5, 0.2, 0.0), energy=150.0, shape="SQUARE", size=0.7,
         use_temperature=True, temperature=6500.0, color=(1.0, 0.85, 0.85))


def emission_of(light, colour_node, strength_node=None):
    """The lamp's node tree: its Emission's Color from `colour_node` ((type, settings, inputs)),
    its Strength from a Value node of `strength_node` when given."""
    light.data.use_nodes = True
    tree = light.data.node_tree
    emission = tree.nodes["Emission"]
    kind, settings, inputs = colour_node
    node = tree.nodes.new(kind)
    for key, value in settings.items():
        setattr(node, key, value)
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    tree.links.new(node.outputs[0], emission.inputs["Color"])
    if strength_node is not None:
        value = tree.nodes.new("ShaderNodeValue")
        value.outputs[0].default_value = strength_node
        tree.links.new(value.outputs[0], emission.inputs["Strength"])
    return node


def lamp_nodes():
    """Lamps of constant node trees, which Cycles folds: a bulb's Emission coloured by a
    Blackbody node (3200 K) at Strength 1.5, a panel's by an RGB node at a Value node's 2."""
    room((0.0, 0.0, 0.0))
    bulb = lamp("POINT", "bulb", (-0.6, -0.9, 1.8), energy=80.0, shadow_soft_size=0.1)
    emission_of(bulb, ("ShaderNodeBlackbody", {}, {"Temperature": 3200.0}))
    bulb.data.node_tree.nodes["Emission"].inputs["Strength"].default_value = 1.5
    panel = lamp("AREA", "panel", (0.8, -0.4, 2.3), (0.5, 0.2, 0.0), energy=60.0, shape="SQUARE", size=0.7)
    rgb = emission_of(panel, ("ShaderNodeRGB", {}, {}), 2.0)
    rgb.outputs[0].default_value = (0.3, 0.6, 1.0, 1.0)


SCENES = {"point": point, "spot": spot, "area": area, "sun": sun, "several": several, "temperature": temperature,
          "lamp_nodes": lamp_nodes}


def set_up(scene):
    """The reference's Cycles settings, with light threshold off (every lamp sampled)."""
    cycles.set_up(scene, SIZE, bounces=BOUNCES, seed=1, light_sampling_threshold=0.0)


def main():
    args = cycles.arguments(__doc__, 4096, sorted(SCENES))
    for name in args.names:
        SCENES[name]()
        scene = bpy.context.scene
        set_up(scene)
        cycles.export(scene, name, f"{name}.toml")
        cycles.render(scene, name, args)


if __name__ == "__main__":
    main()
