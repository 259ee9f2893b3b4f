"""Blender side of tests/blender_roundtrip.rs (run with the bpy venv's python).

    roundtrip.py build OUT     builds OUT/roundtrip.blend (and OUT/ortho.blend and OUT/pano.blend,
                               the same through its orthographic and its panoramic camera)
                               and writes OUT/expected.json
                               with what rt must find (raw Blender values; the Rust test
                               converts them itself), plus Blender's own glTF, GLB and OBJ
                               exports of the `probe` object into OUT/formats/
    roundtrip.py live OUT      the add-on: registers it, turns on live export, saves, edits
                               one material, saves again; writes OUT/live.json
"""

import json
import math
import os
import sys

import bpy

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "blender"))
import rt_export  # noqa: E402


def principled(name, **inputs):
    material = bpy.data.materials.new(name)
    node = material.node_tree.nodes["Principled BSDF"]
    for key, value in inputs.items():
        node.inputs[key.replace("_", " ")].default_value = value
    return material


def select_only(obj):
    for o in bpy.context.scene.objects:
        o.select_set(o == obj)
    bpy.context.view_layer.objects.active = obj


def build(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 160, 90

    bpy.ops.mesh.primitive_monkey_add(location=(0.5, 1.0, 1.2), rotation=(0.3, 0.0, 0.6))
    suzanne = bpy.context.object
    suzanne.name = suzanne.data.name = "suzanne"
    suzanne.scale = (1.2, 1.2, 1.2)
    suzanne.modifiers.new("subdivision", "SUBSURF").levels = 1
    glass = principled("glass", Transmission_Weight=1.0, IOR=1.45, Roughness=0.05)
    # Off here (Blender's default is on): the exporter must say so.
    glass.cycles.use_bump_map_correction = False
    suzanne.data.materials.append(glass)

    bpy.ops.mesh.primitive_plane_add(size=8)
    plane = bpy.context.object
    plane.name = plane.data.name = "plane"
    plane.data.materials.append(principled("floor", Base_Color=(0.5, 0.5, 0.5, 1)))
    # A linked duplicate shares the mesh data: one asset folder, two [[mesh]] entries.
    twin = plane.copy()
    twin.name = "plane_twin"
    twin.location = (0.0, 8.0, 0.0)
    scene.collection.objects.link(twin)

    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=0.5, location=(-1.5, 0.5, 1.0))
    lamp = bpy.context.object
    lamp.name = lamp.data.name = "lamp"
    lamp.data.materials.append(principled("lamp", Emission_Color=(1.0, 0.5, 0.25, 1), Emission_Strength=5.0))

    # Two materials on one mesh with a non-uniform transform, for the format comparison.
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, location=(2.0, -1.0, 0.8), rotation=(0.3, 0.2, 0.1))
    probe = bpy.context.object
    probe.name = probe.data.name = "probe"
    probe.scale = (1.0, 1.5, 0.8)
    probe.data.materials.append(principled("red", Base_Color=(0.8, 0.1, 0.1, 1)))
    probe.data.materials.append(principled("blue", Base_Color=(0.1, 0.1, 0.8, 1)))
    for polygon in probe.data.polygons:
        polygon.material_index = int(polygon.center.z > 0)

    # Rolled (the Y rotation turns it about its view), shifted, focused on the lamp.
    bpy.ops.object.camera_add(location=(0.0, -7.0, 2.5), rotation=(1.35, 0.3, 0.1))
    camera = bpy.context.object
    camera.data.lens = 35
    camera.data.shift_x, camera.data.shift_y = 0.1, -0.05
    dof = camera.data.dof
    dof.use_dof, dof.focus_object, dof.aperture_fstop = True, lamp, 2.8
    dof.aperture_blades, dof.aperture_rotation, dof.aperture_ratio = 6, 0.3, 1.2
    scene.camera = camera
    # Exported from ortho.blend, where it is the scene's camera.
    bpy.ops.object.camera_add(location=(4.0, -4.0, 3.0), rotation=(1.1, 0.0, 0.8))
    ortho = bpy.context.object
    ortho.name = "ortho"
    ortho.data.type, ortho.data.ortho_scale, ortho.data.sensor_fit = "ORTHO", 5.0, "VERTICAL"
    ortho.data.shift_y = 0.2
    # Exported from pano.blend: a window of an equirectangular panorama, with depth of field.
    bpy.ops.object.camera_add(location=(-1.0, 0.5, 1.5), rotation=(1.2, 0.1, -0.6))
    pano = bpy.context.object
    pano.name = "pano"
    pano.data.type, pano.data.panorama_type, pano.data.lens = "PANO", "EQUIRECTANGULAR", 24.0
    pano.data.latitude_min, pano.data.latitude_max = math.radians(-30.0), math.radians(60.0)
    pano.data.longitude_min, pano.data.longitude_max = math.radians(-120.0), math.radians(75.0)
    pano.data.dof.use_dof, pano.data.dof.aperture_fstop, pano.data.dof.focus_distance = True, 1.4, 2.0
    bpy.ops.object.light_add(type="SUN", rotation=(0.6, 0.0, 0.8))
    lamps = {"sun": bpy.context.object}
    lamps["sun"].data.energy = 2.5
    lamps["sun"].data.angle = 0.05
    bpy.ops.object.light_add(type="POINT", location=(1.0, -2.0, 3.0))
    lamps["point"] = bpy.context.object
    lamps["point"].data.energy, lamps["point"].data.shadow_soft_size = 150.0, 0.2
    lamps["point"].data.color = (1.0, 0.8, 0.6)
    lamps["point"].data.exposure = 1.0
    bpy.ops.object.light_add(type="SPOT", location=(-2.0, 1.0, 4.0), rotation=(0.2, -0.4, 0.0))
    lamps["spot"] = bpy.context.object
    lamps["spot"].data.spot_size, lamps["spot"].data.spot_blend = 1.0, 0.3
    lamps["spot"].data.use_soft_falloff = False
    bpy.ops.object.light_add(type="AREA", location=(0.0, 2.0, 3.5), rotation=(0.0, 0.3, 1.0))
    lamps["area"] = bpy.context.object
    lamps["area"].data.shape, lamps["area"].data.size, lamps["area"].data.size_y = "RECTANGLE", 1.0, 0.5
    lamps["area"].scale = (2.0, 1.0, 1.0)
    lamps["area"].data.normalize = False
    lamps["area"].visible_camera = True
    for name, obj in lamps.items():
        obj.name = name

    world = bpy.data.worlds.new("sky")
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.4, 0.5, 0.6, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.5
    scene.world = world
    os.makedirs(out, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "roundtrip.blend"))
    scene.camera = ortho
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "ortho.blend"), copy=True)
    scene.camera = pano
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "pano.blend"), copy=True)
    scene.camera = camera

    # What renders: the subdivision's render levels (2), not the viewport's 1 saved above.
    suzanne.modifiers["subdivision"].levels = suzanne.modifiers["subdivision"].render_levels
    depsgraph = bpy.context.evaluated_depsgraph_get()
    expected = {"objects": {}}
    for obj in (suzanne, plane, lamp, probe):
        evaluated = obj.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        mesh.calc_loop_triangles()
        world_positions = [list(obj.matrix_world @ v.co) for v in mesh.vertices]
        expected["objects"][obj.name] = {
            "triangles": len(mesh.loop_triangles),
            "world_positions": world_positions,
        }
        evaluated.to_mesh_clear()
    expected["camera"] = {
        "matrix_world": [list(row) for row in camera.matrix_world],
        "lens": camera.data.lens,
        "sensor_width": camera.data.sensor_width,
        "resolution": [scene.render.resolution_x, scene.render.resolution_y],
        "focus_object_location": list(lamp.matrix_world.translation),
    }
    expected["ortho"] = {"matrix_world": [list(row) for row in ortho.matrix_world]}
    expected["pano"] = {"matrix_world": [list(row) for row in pano.matrix_world]}
    expected["lights"] = {
        name: {
            "type": obj.data.type,
            "energy": obj.data.energy,
            "exposure": obj.data.exposure,
            "normalize": obj.data.normalize,
            "color": list(obj.data.color),
            "matrix_world": [list(row) for row in obj.matrix_world],
            "radius": obj.data.shadow_soft_size,
            "soft_falloff": getattr(obj.data, "use_soft_falloff", True),
            "spot_size": getattr(obj.data, "spot_size", 0.0),
            "spot_blend": getattr(obj.data, "spot_blend", 0.0),
            "size": getattr(obj.data, "size", 0.0),
            "size_y": getattr(obj.data, "size_y", 0.0),
            "angle": getattr(obj.data, "angle", 0.0),
            "visible_camera": obj.visible_camera,
        }
        for name, obj in lamps.items()
    }
    with open(os.path.join(out, "expected.json"), "w") as f:
        json.dump(expected, f)

    formats = os.path.join(out, "formats")
    os.makedirs(formats, exist_ok=True)
    select_only(probe)
    for fmt, name in (("GLTF_SEPARATE", "probe.gltf"), ("GLB", "probe.glb")):
        bpy.ops.export_scene.gltf(
            filepath=os.path.join(formats, name), export_format=fmt, use_selection=True, export_apply=True
        )
    bpy.ops.wm.obj_export(
        filepath=os.path.join(formats, "probe.obj"), export_selected_objects=True, apply_modifiers=True
    )


def live(out):
    """Live export: the first save exports everything, the next only what changed."""
    bpy.ops.wm.open_mainfile(filepath=os.path.join(out, "roundtrip.blend"))
    rt_export.register()
    settings = bpy.context.scene.rt_export
    settings.out_dir = os.path.join(out, "live", "assets")
    settings.scene_file = os.path.join(out, "live", "scene.toml")
    settings.live = True
    first = os.path.join(out, "live", "first.blend")
    os.makedirs(os.path.dirname(first), exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=first)
    written_first = list(rt_export._last_export[bpy.context.scene.name].written)

    floor = bpy.data.materials["floor"]
    floor.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.9, 0.2, 0.2, 1)
    bpy.context.view_layer.update()
    evaluated = sorted(rt_export.changed_objects(bpy.context.scene))
    bpy.ops.wm.save_as_mainfile(filepath=first)
    written_second = list(rt_export._last_export[bpy.context.scene.name].written)
    rt_export.unregister()
    with open(os.path.join(out, "live.json"), "w") as f:
        json.dump({"first": written_first, "changed": evaluated, "second": written_second}, f)


if __name__ == "__main__":
    {"build": build, "live": live}[sys.argv[1]](sys.argv[2])
