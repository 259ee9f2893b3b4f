"""Cycles references for Mix Shaders of an emitting shader and a BSDF by a node graph's factor
(tests/cycles_node_graphs.rs compares rt against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_emitting_mix_refs.py [--spp 1024] [NAME...]

`graph_mix_emission`: three spheres over a floor in a dim world, each a Mix Shader whose
factor a noise or a gradient drives: glowing cracks (an Emission first, a Principled
second), an emission second (the exporter puts the emitting shader first and turns the
factor over), and a Principled with its own emission mixed with a Diffuse BSDF. They light
the floor and each other, so light sampling of the mixed emitters is tested beside what
the camera sees. The scene is exported with blender/rt_export.py into
tests/cycles/scenes/NAME/ and rendered into tests/cycles/NAME.exr. CI does not run Cycles:
commit both.
"""

import bpy

import cycles_reference as cycles
from make_node_graph_refs import coords, math_node, mix_material, new, noise, output, ramp

CRACKS = [(0.45, (0.0, 0.0, 0.0, 1.0)), (0.55, (1.0, 1.0, 1.0, 1.0))]


def emission(colour, strength):
    return lambda t: new(t, "ShaderNodeEmission", {"Color": colour, "Strength": strength})


def principled(colour, **inputs):
    return lambda t: new(t, "ShaderNodeBsdfPrincipled", {"Base Color": colour, **inputs})


def cracks(t):
    return ramp(t, output(noise(t, coords(t), Scale=4.0, Detail=2.0), "Fac"), "LINEAR", CRACKS)


def bands(t):
    z = new(t, "ShaderNodeSeparateXYZ", {"Vector": coords(t)}).outputs["Z"]
    return math_node(t, "MULTIPLY_ADD", math_node(t, "SINE", math_node(t, "MULTIPLY", z, 9.0)), 0.5, 0.5)


def sphere(location, material):
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, segments=48, ring_count=24, location=location)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(material)


def scene():
    scene = cycles.new_scene()
    cycles.set_up(scene, 96, bounces=4)
    cycles.uniform_world(scene, (0.02, 0.02, 0.025))
    sphere((-1.4, 0.0, 0.6), mix_material("lava", cracks, emission((1.0, 0.45, 0.1, 1.0), 6.0),
                                          principled((0.1, 0.1, 0.1, 1.0), Roughness=0.6)))
    sphere((0.0, 0.3, 0.6), mix_material("banded", bands, principled((0.2, 0.4, 0.8, 1.0), Roughness=0.4),
                                         emission((1.0, 1.0, 0.9, 1.0), 3.0)))
    sphere((1.4, 0.0, 0.6), mix_material(
        "glowing paint", cracks,
        principled((0.8, 0.2, 0.2, 1.0), **{"Emission Color": (0.2, 1.0, 0.3, 1.0), "Emission Strength": 4.0}),
        lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.7, 0.7, 0.7, 1.0)})))
    bpy.ops.mesh.primitive_plane_add(size=8.0)
    bpy.context.active_object.data.materials.append(cycles.principled("floor", (0.6, 0.6, 0.6), Roughness=1.0))
    cycles.camera(scene, (0.0, -4.5, 1.8), 72.0)
    return scene


SCENES = {"graph_mix_emission": scene}


if __name__ == "__main__":
    cycles.make(__doc__, 1024, SCENES)
