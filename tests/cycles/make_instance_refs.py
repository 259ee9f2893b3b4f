"""Cycles references for instances exported from Blender (tests/cycles_instances.rs
compares rt against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_instance_refs.py [--spp 8192] [NAME...]

Builds each scene below in bpy, renders it with Cycles into
tests/cycles/instances_NAME.exr, and exports it with blender/rt_export.py into
tests/cycles/scenes/instances_NAME/ (scene.toml, its instance files and assets). CI does
not run Cycles: commit both.

- collections: a collection of two cubes sharing one mesh, one of them with an
  object-linked material (a material override), instanced three times, rotated and
  scaled, by a second collection, itself instanced twice (nested), rotated and scaled.
- scatter: a geometry-nodes scatter (Distribute Points on Faces, then Instance on Points
  with the points' rotations) of an icosphere over one plane, whose faces stay as
  realized geometry; a hair particle system rendering a cone as its object over another;
  and a small plane whose nodes output only instances of the cone (its faces are gone).
- object_info: a geometry-nodes scatter of a pebble whose colour is Object Info's Random
  through a ramp (each instance its own), two cubes coloured by their Object Color,
  instanced twice, and a plain object coloured by its Random.
- overrides: one two-slot slab mesh (a grey body, a blue top) shown by three objects of a
  collection, one with its own materials, one with an object-linked red top, one with an
  object-linked emissive body, the collection instanced three times, rotated: one asset
  folder whose instance file picks a material set per instance.

Every surface is diffuse (no specular layer) under a uniform world, so the comparison
tests where the instances are and which material they show.

Cycles settings: box filter of width 1, no clamping, denoising or adaptive sampling,
blur_glossy 0, bounces raised, linear 32-bit EXR.
"""

import math

import bpy
from mathutils import Vector

import cycles_reference as cycles
from cycles_reference import diffuse, emissive

SIZE = 64


def hidden_collection(scene, name):
    """A collection that renders only through its instances."""
    collection = bpy.data.collections.new(name)
    scene.collection.children.link(collection)
    bpy.context.view_layer.layer_collection.children[name].exclude = True
    return collection


def move_to(obj, collection):
    for c in obj.users_collection:
        c.objects.unlink(obj)
    collection.objects.link(obj)


def ground(name, size, location, colour):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location)
    plane = bpy.context.object
    plane.name = plane.data.name = name
    plane.data.materials.append(diffuse(name, colour))
    return plane


def collection_instance(name, collection, location, rotation, scale, parent):
    empty = bpy.data.objects.new(name, None)
    empty.instance_type = "COLLECTION"
    empty.instance_collection = collection
    empty.location, empty.rotation_euler, empty.scale = location, rotation, scale
    parent.objects.link(empty)
    return empty


def build_collections(scene):
    ground("floor", 12.0, (0.0, 0.0, 0.0), (0.6, 0.6, 0.6))
    leaf = hidden_collection(scene, "leaf")
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(0.0, 0.0, 0.3))
    cube = bpy.context.object
    cube.name, cube.data.name = "cube", "box"
    cube.data.materials.append(diffuse("blue", (0.1, 0.2, 0.8)))
    move_to(cube, leaf)
    # The same mesh data with an object-linked material: a material override.
    twin = bpy.data.objects.new("twin", cube.data)
    twin.location, twin.rotation_euler = (0.8, 0.1, 0.45), (0.0, 0.0, 0.6)
    twin.scale = (0.7, 0.7, 1.5)
    leaf.objects.link(twin)
    twin.material_slots[0].link = "OBJECT"
    twin.material_slots[0].material = diffuse("red", (0.8, 0.15, 0.1))

    cluster = hidden_collection(scene, "cluster")
    for k in range(3):
        angle = 2.0 * math.pi * k / 3.0
        collection_instance(
            f"leaf_{k}",
            leaf,
            (1.4 * math.cos(angle), 1.4 * math.sin(angle), 0.0),
            (0.0, 0.0, angle + 0.3),
            (1.0 + 0.2 * k,) * 3,
            cluster,
        )
    collection_instance("cluster_a", cluster, (-1.6, 0.5, 0.0), (0.0, 0.0, 0.4), (0.8, 0.8, 0.8), scene.collection)
    collection_instance("cluster_b", cluster, (1.9, -0.8, 0.0), (0.0, 0.0, -0.9), (1.0, 1.3, 0.7), scene.collection)
    return Vector((0.0, -8.5, 6.5)), Vector((0.0, 0.0, 0.4)), 35.0


def scatter_modifier(obj, instance, density, scale, keep_surface=True):
    tree = bpy.data.node_groups.new("scatter", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = tree.nodes, tree.links
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    distribute = nodes.new("GeometryNodeDistributePointsOnFaces")
    distribute.inputs["Density"].default_value = density
    distribute.inputs["Seed"].default_value = 3
    on_points = nodes.new("GeometryNodeInstanceOnPoints")
    on_points.inputs["Scale"].default_value = (scale, scale, scale)
    info = nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = instance
    join = nodes.new("GeometryNodeJoinGeometry")
    links.new(group_in.outputs[0], distribute.inputs["Mesh"])
    links.new(distribute.outputs["Points"], on_points.inputs["Points"])
    links.new(distribute.outputs["Rotation"], on_points.inputs["Rotation"])
    links.new(info.outputs["Geometry"], on_points.inputs["Instance"])
    # The instances, and (with `keep_surface`) the surface they stand on as realized geometry.
    links.new(on_points.outputs["Instances"], join.inputs[0])
    if keep_surface:
        links.new(group_in.outputs[0], join.inputs[0])
    links.new(join.outputs[0], group_out.inputs[0])
    obj.modifiers.new("scatter", "NODES").node_group = tree


def build_scatter(scene):
    ground("floor", 12.0, (0.0, 0.0, -0.01), (0.5, 0.5, 0.5))
    sources = hidden_collection(scene, "sources")
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1, radius=0.5)
    pebble = bpy.context.object
    pebble.name = pebble.data.name = "pebble"
    pebble.data.materials.append(diffuse("pebble", (0.8, 0.5, 0.1)))
    move_to(pebble, sources)
    bpy.ops.mesh.primitive_cone_add(radius1=0.12, depth=0.5)
    cone = bpy.context.object
    cone.name = cone.data.name = "cone"
    cone.data.materials.append(diffuse("cone", (0.1, 0.6, 0.2)))
    move_to(cone, sources)

    bed = ground("bed", 2.6, (-1.3, 0.2, 0.0), (0.7, 0.7, 0.7))
    bed.rotation_euler = (0.0, 0.0, 0.3)
    scatter_modifier(bed, pebble, 6.0, 0.4)

    # Nodes that output only instances: the object itself must not become an empty mesh.
    pile = ground("pile", 0.8, (0.2, 1.8, 0.3), (1.0, 0.0, 1.0))
    scatter_modifier(pile, cone, 30.0, 1.0, keep_surface=False)

    lawn = ground("lawn", 2.4, (1.5, -0.3, 0.0), (0.3, 0.25, 0.2))
    lawn.modifiers.new("hair", "PARTICLE_SYSTEM")
    settings = lawn.particle_systems[0].settings
    settings.type = "HAIR"
    settings.count = 40
    settings.hair_length = 0.5
    settings.render_type = "OBJECT"
    settings.instance_object = cone
    settings.particle_size = 1.0
    lawn.particle_systems[0].seed = 7
    return Vector((0.0, -6.5, 5.5)), Vector((0.0, 0.0, 0.2)), 35.0


def build_overrides(scene):
    ground("floor", 12.0, (0.0, 0.0, 0.0), (0.6, 0.6, 0.6))
    trio = hidden_collection(scene, "trio")
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.0, 0.0, 0.25))
    slab = bpy.context.object
    slab.name, slab.data.name = "slab", "slab"
    slab.scale = (1.6, 0.8, 1.0)
    slab.data.materials.append(diffuse("grey", (0.5, 0.5, 0.5)))
    slab.data.materials.append(diffuse("blue", (0.1, 0.2, 0.8)))
    for face in slab.data.polygons:
        face.material_index = 1 if face.normal.z > 0.5 else 0
    move_to(slab, trio)
    red_top = bpy.data.objects.new("red_top", slab.data)
    red_top.location, red_top.rotation_euler, red_top.scale = (0.0, 0.9, 0.0), (0.0, 0.0, 0.4), (1.2, 0.8, 1.4)
    trio.objects.link(red_top)
    red_top.material_slots[1].link = "OBJECT"
    red_top.material_slots[1].material = diffuse("red", (0.8, 0.15, 0.1))
    glowing = bpy.data.objects.new("glowing", slab.data)
    glowing.location, glowing.rotation_euler = (0.9, -0.5, 0.0), (0.0, 0.0, -0.7)
    trio.objects.link(glowing)
    glowing.material_slots[0].link = "OBJECT"
    glowing.material_slots[0].material = emissive("glow", (1.0, 0.5, 0.25), 2.0)
    for k in range(3):
        angle = 2.0 * math.pi * k / 3.0
        collection_instance(
            f"trio_{k}",
            trio,
            (1.8 * math.cos(angle), 1.8 * math.sin(angle), 0.0),
            (0.0, 0.0, angle + 0.5),
            (1.0 - 0.15 * k,) * 3,
            scene.collection,
        )
    return Vector((0.0, -8.0, 6.0)), Vector((0.0, 0.0, 0.3)), 35.0


def by_object_info(name, output):
    """`diffuse` whose base colour is Object Info's `output`: Random through a ramp of three
    colours, or the object's Color."""
    material = diffuse(name, (0.5, 0.5, 0.5))
    tree = material.node_tree
    info = tree.nodes.new("ShaderNodeObjectInfo")
    colour = info.outputs["Color"]
    if output == "Random":
        ramp = tree.nodes.new("ShaderNodeValToRGB")
        elements = ramp.color_ramp.elements
        elements[0].color, elements[1].color = (0.9, 0.1, 0.1, 1.0), (0.1, 0.2, 0.9, 1.0)
        elements.new(0.5).color = (0.1, 0.8, 0.2, 1.0)
        tree.links.new(info.outputs["Random"], ramp.inputs["Fac"])
        colour = ramp.outputs["Color"]
    tree.links.new(colour, tree.nodes["Principled BSDF"].inputs["Base Color"])
    return material


def build_object_info(scene):
    ground("floor", 12.0, (0.0, 0.0, -0.01), (0.6, 0.6, 0.6))
    sources = hidden_collection(scene, "sources")
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1, radius=0.5)
    pebble = bpy.context.object
    pebble.name = pebble.data.name = "pebble"
    pebble.data.materials.append(by_object_info("by_random", "Random"))
    move_to(pebble, sources)
    bed = ground("bed", 2.6, (-1.2, 0.3, 0.0), (0.7, 0.7, 0.7))
    scatter_modifier(bed, pebble, 5.0, 0.45)
    # Objects with their own Object Color, instanced twice; one plain object by its name.
    coloured = hidden_collection(scene, "coloured")
    for k, colour in enumerate([(0.9, 0.6, 0.1, 1.0), (0.2, 0.7, 0.9, 1.0)]):
        bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0.7 * k, 0.0, 0.25))
        cube = bpy.context.object
        cube.name = f"tinted_{k}"
        cube.color = colour
        cube.data.materials.append(by_object_info(f"by_colour_{k}", "Color"))
        move_to(cube, coloured)
    collection_instance("tinted_a", coloured, (1.0, -0.8, 0.0), (0.0, 0.0, 0.3), (1.0,) * 3, scene.collection)
    collection_instance("tinted_b", coloured, (1.3, 0.9, 0.0), (0.0, 0.0, -0.5), (0.8,) * 3, scene.collection)
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(-0.2, -1.6, 0.3))
    plain = bpy.context.object
    plain.name = "Plain object"
    plain.data.materials.append(by_object_info("plain_by_random", "Random"))
    return Vector((0.0, -6.5, 5.5)), Vector((0.0, 0.0, 0.2)), 35.0


SCENES = {"collections": build_collections, "scatter": build_scatter, "overrides": build_overrides,
          "object_info": build_object_info}


def add_camera(scene, location, target, lens):
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    cam.location = location
    cam.rotation_euler = (target - location).to_track_quat("-Z", "Y").to_euler()
    cam.data.lens = lens
    scene.camera = cam


def main():
    args = cycles.arguments(__doc__, 8192, list(SCENES))
    for name in args.names:
        scene = cycles.new_scene()
        add_camera(scene, *SCENES[name](scene))
        # Multiples of 1/16, so that Cycles' f32 sum of a sky pixel's equal samples is exact and
        # the sky matches rt's to rounding.
        cycles.uniform_world(scene, (0.875, 0.9375, 1.0))
        cycles.set_up(scene, SIZE)
        export = cycles.export(scene, f"instances_{name}")
        print(f"instances_{name}: instances {export.instance_counts()}", flush=True)
        cycles.render(scene, f"instances_{name}", args)


if __name__ == "__main__":
    main()
