"""Cycles references for the Attribute and Color Attribute nodes (tests/cycles_node_graphs.rs
compares rt against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_attribute_refs.py [--spp 1024] [NAME...]

`graph_attributes` is make_node_graph_refs.py's grid of emitting tiles, each tile a plane of
8 × 8 quads carrying attributes of every kind Cycles reads: a byte colour and a float colour
on points and on corners (which differ across a face's edges), a value, a vector, an
integer on faces, a boolean, the uv map, and names the mesh lacks; each tile's emission is
one output of one node. `graph_attributes_bump` is a row of spheres lit by a low sun, whose
Normal is a Bump of an attribute (alone and plus a noise). `graph_random_per_island` is
Geometry's Random Per Island of two meshes of eight islands each, `graph_parametric` its
Parametric on tiles of quads, `graph_pointiness` its Pointiness of solids seen from above
(one a cube of unconnected faces, whose duplicate vertices Cycles welds). Each scene is exported with
blender/rt_export.py into tests/cycles/scenes/NAME/ and rendered into
tests/cycles/NAME.exr. CI does not run Cycles: commit both.
"""


import bpy
import numpy as np

import cycles_reference as cycles
from make_node_graph_refs import GRID, PITCH, STOPS, dark_grid, emission_material, math_node, new, noise, output, ramp, \
    vector_shown


def attribute(t, name, which="Color"):
    return output(new(t, "ShaderNodeAttribute", attribute_type="GEOMETRY", attribute_name=name), which)


def color_attribute(t, name, which="Color"):
    return output(new(t, "ShaderNodeVertexColor", layer_name=name), which)


def set_attribute(mesh, name, kind, domain, key, values):
    layer = mesh.attributes.new(name, kind, domain)
    layer.data.foreach_set(key, np.ascontiguousarray(values).ravel())


def paint(mesh):
    """The attributes every tile's mesh carries, functions of where each point is."""
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    x, y = co[:, 0], co[:, 1]
    corner_vertex = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", corner_vertex)
    corner_face = np.repeat(np.arange(len(mesh.polygons)), [len(p.vertices) for p in mesh.polygons])
    ones = np.ones_like(x)
    byte = np.stack([0.5 + 0.5 * np.sin(3.0 * x), 0.5 + 0.5 * np.cos(2.0 * y), 0.5 + 0.4 * x * y, 0.3 + 0.3 * (x + 1)], 1)
    set_attribute(mesh, "Col", "BYTE_COLOR", "POINT", "color", np.clip(byte, 0.0, 1.0))
    # Per corner: each face's corners differ from its neighbours' at the same point.
    cx, cy, cf = x[corner_vertex], y[corner_vertex], corner_face.astype(np.float32)
    corner = np.stack([0.2 + 0.1 * (cf % 7), 0.5 + 0.4 * cx, 0.5 - 0.4 * cy, 0.2 + 0.1 * (cf % 5)], 1)
    set_attribute(mesh, "Paint", "FLOAT_COLOR", "CORNER", "color", corner)
    set_attribute(mesh, "height", "FLOAT", "POINT", "value", 0.5 + 0.45 * np.sin(2.5 * x + 1.0) * np.cos(1.7 * y))
    set_attribute(mesh, "offset", "FLOAT_VECTOR", "POINT", "vector", np.stack([x, y * 0.5, x * y + 1.0], 1))
    set_attribute(mesh, "face_id", "INT", "FACE", "value", np.arange(len(mesh.polygons), dtype=np.int32) % 9)
    set_attribute(mesh, "flag", "BOOLEAN", "POINT", "value", (x + y > 0.3) & (ones > 0))
    mesh.attributes.default_color_name = "Paint"


def add_painted_tile(i):
    x = (i % GRID - (GRID - 1) / 2) * PITCH
    y = ((GRID - 1) / 2 - i // GRID) * PITCH
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=8, y_subdivisions=8, size=2.0, location=(x, y, 0.0))
    obj = bpy.context.active_object
    paint(obj.data)
    return obj


ATTRIBUTES = [
    lambda t: color_attribute(t, ""),
    lambda t: color_attribute(t, "Col"),
    lambda t: math_node(t, "MULTIPLY_ADD", color_attribute(t, "Col", "Alpha"), 0.8, 0.1),
    lambda t: ramp(t, attribute(t, "height", "Fac"), "LINEAR", STOPS),
    lambda t: attribute(t, "height"),
    lambda t: vector_shown(t, attribute(t, "offset", "Vector")),
    lambda t: math_node(t, "MULTIPLY_ADD", attribute(t, "offset", "Fac"), 0.3, 0.4),
    lambda t: attribute(t, "UVMap", "Vector"),
    lambda t: attribute(t, "UVMap", "Fac"),
    lambda t: math_node(t, "MULTIPLY", attribute(t, "face_id", "Fac"), 0.1),
    lambda t: math_node(t, "MULTIPLY_ADD", attribute(t, "flag", "Fac"), 0.6, 0.2),
    lambda t: attribute(t, "Paint", "Alpha"),
    lambda t: attribute(t, "Paint", "Fac"),
    lambda t: math_node(t, "ADD", attribute(t, "nope", "Alpha"), attribute(t, "nope", "Fac")),
    lambda t: math_node(t, "ADD", color_attribute(t, "nope", "Alpha"), 0.3),
    lambda t: output(noise(t, attribute(t, "offset", "Vector"), Scale=2.0, Detail=2.0), "Fac"),
]


def attribute_scene():
    scene = dark_grid()
    for i, build in enumerate(ATTRIBUTES):
        obj = add_painted_tile(i)
        obj.name = f"tile_{i}"
        obj.data.materials.append(emission_material(f"attributes_{i}", build))
    return scene


def bumped_by_attribute(name, height):
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    bsdf = tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.4
    bump = new(tree, "ShaderNodeBump", {"Height": height(tree), "Strength": 1.0, "Distance": 0.3})
    tree.links.new(bump.outputs["Normal"], bsdf.inputs["Normal"])
    return material


def bump_scene():
    """Spheres whose Normal is a Bump of a point attribute (ripples of the height), alone
    and plus a noise, lit by a low sun."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 128, 64, bounces=2)
    cycles.uniform_world(scene, (0.05, 0.05, 0.05))
    heights = [
        lambda t: attribute(t, "ripple", "Fac"),
        lambda t: math_node(t, "ADD", attribute(t, "ripple", "Fac"),
                            output(noise(t, None, Scale=3.0, Detail=1.0), "Fac")),
    ]
    for i, height in enumerate(heights):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=64, ring_count=32, location=(2.3 * i - 1.15, 0, 1))
        bpy.ops.object.shade_smooth()
        mesh = bpy.context.active_object.data
        co = np.empty(len(mesh.vertices) * 3, np.float32)
        mesh.vertices.foreach_get("co", co)
        co = co.reshape(-1, 3)
        set_attribute(mesh, "ripple", "FLOAT", "POINT", "value", 0.5 + 0.5 * np.sin(9.0 * co[:, 2] + 3.0 * co[:, 0]))
        mesh.materials.append(bumped_by_attribute(f"ripple_{i}", height))
    cycles.sun(scene, 3.0, (60.0, 0.0, 40.0))
    cycles.camera(scene, (0.0, -6.0, 1.0), 90.0)
    return scene


def island_scene():
    """Geometry's Random Per Island of one mesh of 16 islands (tiles of 2 × 2 quads, each
    turned, joined into one object in turn), and of the same through a ramp on a second."""
    scene = dark_grid()
    for half, show in enumerate((lambda t, r: r, lambda t, r: ramp(t, r, "LINEAR", STOPS))):
        tiles = []
        for i in range(8):
            i += 8 * half
            x = (i % GRID - (GRID - 1) / 2) * PITCH
            y = ((GRID - 1) / 2 - i // GRID) * PITCH
            bpy.ops.mesh.primitive_grid_add(x_subdivisions=2, y_subdivisions=2, size=1.4, location=(x, y, 0.0),
                                            rotation=(0.0, 0.0, 0.3 * i))
            tiles.append(bpy.context.active_object)
        bpy.ops.object.select_all(action="DESELECT")
        for tile in tiles:
            tile.select_set(True)
        bpy.context.view_layer.objects.active = tiles[0]
        bpy.ops.object.join()
        obj = bpy.context.active_object
        obj.name = f"islands_{half}"
        obj.data.materials.append(emission_material(
            f"islands_{half}", lambda t, show=show: show(t, new(t, "ShaderNodeNewGeometry").outputs["Random Per Island"])))
    return scene


def parametric(t):
    return new(t, "ShaderNodeNewGeometry").outputs["Parametric"]


def edges(t):
    """The smallest of a triangle's three parametric coordinates: 0 on its edges."""
    x, y, _ = [new(t, "ShaderNodeSeparateXYZ", {"Vector": parametric(t)}).outputs[i] for i in range(3)]
    third = math_node(t, "SUBTRACT", math_node(t, "SUBTRACT", 1.0, x), y)
    return math_node(t, "MINIMUM", math_node(t, "MINIMUM", x, y), third)


PARAMETRIC = [
    parametric,
    lambda t: ramp(t, new(t, "ShaderNodeSeparateXYZ", {"Vector": parametric(t)}).outputs["Y"], "LINEAR", STOPS),
    lambda t: ramp(t, math_node(t, "MULTIPLY", edges(t), 3.0), "LINEAR", STOPS),
    lambda t: math_node(t, "MULTIPLY", edges(t), 4.0),
]


def parametric_scene():
    """Geometry's Parametric on tiles of 3 × 3 quads: itself, its Y through a ramp, and the
    distance to a triangle's edges (the smallest of the three coordinates)."""
    scene = dark_grid()
    for i, build in enumerate(PARAMETRIC):
        x = (i % GRID - (GRID - 1) / 2) * PITCH
        y = ((GRID - 1) / 2 - i // GRID) * PITCH
        bpy.ops.mesh.primitive_grid_add(x_subdivisions=3, y_subdivisions=3, size=2.0, location=(x, y, 0.0))
        bpy.context.active_object.data.materials.append(emission_material(f"parametric_{i}", build))
    return scene


def pointiness(t):
    return new(t, "ShaderNodeNewGeometry").outputs["Pointiness"]


def stretched_pointiness(t):
    """Pointiness (0.5 on flat ground) stretched fourfold, through a ramp: red where concave,
    green where flat, blue where convex."""
    return ramp(t, math_node(t, "MULTIPLY_ADD", pointiness(t), 4.0, -1.6), "LINEAR", STOPS)


def subdivided(add, levels):
    """The solid `add` makes, smoothed by a Subdivision Surface modifier of `levels`."""
    def made():
        add()
        modifier = bpy.context.active_object.modifiers.new("subdivision", "SUBSURF")
        # Cycles renders the render levels; the exporter evaluates the viewport's.
        modifier.levels = modifier.render_levels = levels
    return made


def unconnected_cube(size):
    """A cube whose six faces have four vertices each of their own."""
    h = size / 2
    corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    verts = [corners[i] for face in faces for i in face]
    mesh = bpy.data.meshes.new("unconnected_cube")
    mesh.from_pydata(verts, [], [tuple(range(4 * f, 4 * f + 4)) for f in range(6)])
    obj = bpy.data.objects.new("unconnected_cube", mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


SOLIDS = [
    lambda: bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=0.9),
    subdivided(lambda: bpy.ops.mesh.primitive_cube_add(size=1.3), 2),
    lambda: bpy.ops.mesh.primitive_torus_add(major_radius=0.65, minor_radius=0.3, major_segments=24,
                                             minor_segments=12),
    lambda: bpy.ops.mesh.primitive_monkey_add(size=1.6),
    subdivided(lambda: bpy.ops.mesh.primitive_cone_add(vertices=12, radius1=0.9, depth=1.2), 1),
    subdivided(lambda: bpy.ops.mesh.primitive_cylinder_add(vertices=10, radius=0.8, depth=0.8), 2),
]


def pointiness_scene():
    """Geometry's Pointiness of six solids through a ramp, of the first three as it is, and of
    a cube of unconnected faces through the ramp, seen from above."""
    scene = dark_grid()
    shown = [(add, stretched_pointiness) for add in SOLIDS] + [(add, pointiness) for add in SOLIDS[:3]]
    shown.append((lambda: unconnected_cube(1.2), stretched_pointiness))
    for i, (add, show) in enumerate(shown):
        x = (i % GRID - (GRID - 1) / 2) * PITCH
        y = ((GRID - 1) / 2 - i // GRID) * PITCH
        made = add()
        obj = made if isinstance(made, bpy.types.Object) else bpy.context.active_object
        obj.location = (x, y, 0.0)
        obj.rotation_euler = (0.4, 0.3, 0.2 * i)
        obj.data.materials.append(emission_material(f"pointiness_{i}", show))
    return scene


SCENES = {
    "graph_attributes": attribute_scene,
    "graph_attributes_bump": bump_scene,
    "graph_random_per_island": island_scene,
    "graph_parametric": parametric_scene,
    "graph_pointiness": pointiness_scene,
}


if __name__ == "__main__":
    cycles.make(__doc__, 1024, SCENES)
