"""A Cornell box built in Blender for the screenshots of rt inside Blender
(docs/blender/screenshots.py): red and green side walls, a white floor, ceiling and back
wall, a tall box, a sphere, a square area lamp under the ceiling and a camera in front,
with depth of field focused on the sphere. Made from bmesh primitives, so that it needs
no operator context (it runs from a timer) and works in Blender 3.4 as in 5.0.
"""

import math

import bmesh
import bpy
from mathutils import Matrix

# Diffuse albedos of the classic box, roughly.
WHITE = (0.73, 0.73, 0.73)
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)


def material(name, color, roughness=1.0, metallic=0.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    mat.diffuse_color = (*color, 1.0)
    return mat


def mesh_object(name, build, mat, matrix=Matrix(), smooth=False):
    """An object of a mesh that `build(bm)` fills, with one material."""
    bm = bmesh.new()
    build(bm)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    for polygon in mesh.polygons:
        polygon.use_smooth = smooth
    mesh.materials.append(mat)
    obj = bpy.data.objects.new(name, mesh)
    obj.matrix_world = matrix
    bpy.context.scene.collection.objects.link(obj)
    return obj


def quad(corners):
    def build(bm):
        bm.faces.new([bm.verts.new(c) for c in corners])

    return build


def build(width=256, height=256):
    """Replaces the scene's contents with the box; returns (scene, camera, sphere)."""
    scene = bpy.context.scene
    for obj in list(scene.objects):
        bpy.data.objects.remove(obj)
    white, red, green = material("white", WHITE), material("red", RED), material("green", GREEN)
    # The box spans x, y in [-1, 1] and z in [0, 2], open towards -y; faces point inwards.
    walls = {
        "floor": ([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], white),
        "ceiling": ([(-1, -1, 2), (-1, 1, 2), (1, 1, 2), (1, -1, 2)], white),
        "back": ([(-1, 1, 0), (1, 1, 0), (1, 1, 2), (-1, 1, 2)], white),
        "left": ([(-1, -1, 0), (-1, 1, 0), (-1, 1, 2), (-1, -1, 2)], red),
        "right": ([(1, -1, 0), (1, -1, 2), (1, 1, 2), (1, 1, 0)], green),
    }
    for name, (corners, mat) in walls.items():
        mesh_object(name, quad(corners), mat)
    tall = Matrix.Translation((-0.35, 0.35, 0.6)) @ Matrix.Rotation(math.radians(20), 4, "Z")
    mesh_object(
        "tall_box",
        lambda bm: bmesh.ops.create_cube(bm, size=1.0),
        white,
        tall @ Matrix.Diagonal((0.55, 0.55, 1.2, 1.0)),
    )
    sphere = mesh_object(
        "sphere",
        lambda bm: bmesh.ops.create_uvsphere(bm, u_segments=48, v_segments=24, radius=0.35),
        material("plastic", (0.15, 0.3, 0.8), roughness=0.2),
        Matrix.Translation((0.4, -0.25, 0.35)),
        smooth=True,
    )

    lamp = bpy.data.lights.new("lamp", "AREA")
    lamp.shape = "SQUARE"
    lamp.size = 0.5
    lamp.energy = 60.0
    lamp_object = bpy.data.objects.new("lamp", lamp)
    lamp_object.location = (0.0, 0.0, 1.98)  # an area lamp shines down its -Z
    scene.collection.objects.link(lamp_object)

    cam = bpy.data.cameras.new("Camera")
    cam.lens = 42.0
    cam.dof.use_dof = True
    cam.dof.focus_object = sphere
    cam.dof.aperture_fstop = 1.0
    camera = bpy.data.objects.new("Camera", cam)
    camera.location = (0.0, -3.9, 1.0)
    camera.rotation_euler = (math.radians(90), 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera

    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    world.color = (0.0, 0.0, 0.0)
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    return scene, camera, sphere
