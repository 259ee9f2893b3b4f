"""Cycles references for the shader node graphs rt evaluates (tests/cycles_node_graphs.rs
compares rt against them).

    /work/main/.venv-bpy/bin/python tests/cycles/make_node_graph_refs.py [--spp 1024] [NAME...]

The per-node scenes (`graph_noise`, `graph_math`, `graph_color`, `graph_vector`,
`graph_convert`, `graph_map_range`, `graph_brick`, `graph_white_noise`, `graph_noise_dimensions`, `graph_spectrum`, `graph_object_info`, `graph_camera`, `graph_shading` and the other textures) are a 4 x 4 grid of tiles seen from above by an orthographic camera, under
a black world; each tile only emits, its Emission colour the output of a small node graph
(its own material), so a pixel is the graph's mean value over the pixel: the comparison
tests the nodes and nothing else. `graph_shading`'s tiles are smooth spheres, for the nodes
that read the normal and the view. `graph_material` is a whole procedural material, a
sphere and a floor whose Principled inputs come from noise, ramps, checkers and maths, lit
by a uniform world. `graph_bump` is a grid of tiles and spheres whose Normal is a Bump
node of many heights, lit by a low sun and seen in perspective. Every scene is exported with blender/rt_export.py into
tests/cycles/scenes/NAME/ and rendered into tests/cycles/NAME.exr. CI does not run Cycles:
commit both.
"""

import math

import bpy

import cycles_reference as cycles

SIZE = 128
GRID = 4
PITCH = 2.2


def new(tree, kind, inputs=None, **props):
    node = tree.nodes.new(kind)
    for key, value in props.items():
        setattr(node, key, value)
    for key, value in (inputs or {}).items():
        socket = input_socket(node, key)
        if isinstance(value, bpy.types.NodeSocket):
            tree.links.new(value, socket)
        else:
            socket.default_value = value
    return node


def input_socket(node, key):
    """An enabled input by name, or any input by identifier."""
    found = [s for s in node.inputs if s.enabled and s.name == key]
    return found[0] if found else next(s for s in node.inputs if s.identifier == key)


def output(node, key):
    found = [s for s in node.outputs if s.enabled and s.name == key]
    return found[0] if found else next(s for s in node.outputs if s.identifier == key)


def coords(tree, which="Object"):
    return new(tree, "ShaderNodeTexCoord").outputs[which]


def math_node(tree, operation, a, b=0.5, c=0.5, clamp=False):
    node = new(tree, "ShaderNodeMath", operation=operation, use_clamp=clamp)
    for socket, value in zip(node.inputs, (a, b, c)):
        if isinstance(value, bpy.types.NodeSocket):
            tree.links.new(value, socket)
        else:
            socket.default_value = value
    return node.outputs[0]


def shown(tree, value, scale=0.1, offset=0.2):
    """|scale × value + offset|: a value of any sign made a visible emission."""
    return math_node(tree, "ABSOLUTE", math_node(tree, "MULTIPLY_ADD", value, scale, offset))


def rgb(tree, r, g, b):
    return new(tree, "ShaderNodeCombineXYZ", {"X": r, "Y": g, "Z": b}).outputs[0]


def xyz(tree, source, scale=3.0):
    separate = new(tree, "ShaderNodeSeparateXYZ", {"Vector": source})
    return [math_node(tree, "MULTIPLY", separate.outputs[i], scale) for i in range(3)]


def emission_material(name, build):
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    emission = new(tree, "ShaderNodeEmission", {"Strength": 1.0})
    tree.links.new(build(tree), emission.inputs["Color"])
    tree.links.new(emission.outputs[0], out.inputs["Surface"])
    return material


def add_tile(i, shape, segments=32):
    """Tile `i` of the grid (row by row from the top left): a 2 × 2 plane, or a smooth
    sphere of radius 1 and `segments` around; returns the object."""
    x = (i % GRID - (GRID - 1) / 2) * PITCH
    y = ((GRID - 1) / 2 - i // GRID) * PITCH
    if shape == "plane":
        bpy.ops.mesh.primitive_plane_add(size=2.0, location=(x, y, 0.0))
    else:
        bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=segments, ring_count=segments // 2,
                                             location=(x, y, 0.0))
        bpy.ops.object.shade_smooth()
    return bpy.context.active_object


def shader_material(name, build):
    """A material whose Surface is the shader output `build(tree)` gives."""
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(build(tree), out.inputs["Surface"])
    return material


def grid_scene(name, builders, shape="plane", make=emission_material):
    scene = dark_grid()
    for i, build in enumerate(builders):
        obj = add_tile(i, shape)
        obj.name = f"tile_{i}"
        obj.data.materials.append(make(f"{name}_{i}", build))
    return scene


def dark_grid():
    """An empty scene under a black world, seen from above by an orthographic camera that
    frames the grid of tiles (`add_tile`)."""
    scene = cycles.new_scene()
    cycles.set_up(scene, SIZE, bounces=1)
    cycles.uniform_world(scene, (0.0, 0.0, 0.0))
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = GRID * PITCH
    camera.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene


def noise(tree, vector=None, noise_type="FBM", normalize=True, dimensions="3D", **inputs):
    node = new(tree, "ShaderNodeTexNoise", inputs, noise_dimensions=dimensions, noise_type=noise_type,
               normalize=normalize)
    if vector is not None and dimensions != "1D":
        tree.links.new(vector, node.inputs["Vector"])
    return node


def ramp(tree, fac, interpolation, stops):
    node = new(tree, "ShaderNodeValToRGB")
    tree.links.new(fac, node.inputs["Fac"])
    elements = node.color_ramp.elements
    elements[0].position, elements[0].color = stops[0]
    elements[1].position, elements[1].color = stops[-1]
    for position, colour in stops[1:-1]:
        elements.new(position).color = colour
    node.color_ramp.interpolation = interpolation
    return node.outputs["Color"]


STOPS = [(0.2, (0.9, 0.1, 0.1, 1.0)), (0.45, (0.1, 0.8, 0.2, 1.0)), (0.7, (0.1, 0.2, 0.9, 1.0))]


def fractal(noise_type, **inputs):
    return lambda t: shown(t, noise(t, coords(t), noise_type, Scale=2.0, Detail=3.5, **inputs).outputs["Fac"], 0.3, 0.0)


NOISE = [
    lambda t: noise(t, Scale=5.0, Detail=2.0).outputs["Fac"],
    lambda t: noise(t, coords(t), Scale=3.0, Detail=4.5, Roughness=0.6).outputs["Color"],
    lambda t: shown(t, noise(t, coords(t), normalize=False, Scale=2.5, Detail=3.0).outputs["Fac"], 0.5, 0.5),
    lambda t: noise(t, coords(t), Scale=2.0, Detail=1.0, Distortion=2.0).outputs["Color"],
    fractal("MULTIFRACTAL"),
    fractal("RIDGED_MULTIFRACTAL", Offset=1.0, Gain=2.0),
    fractal("HYBRID_MULTIFRACTAL", Offset=0.5, Gain=1.5),
    fractal("HETERO_TERRAIN", Offset=0.8),
    lambda t: noise(t, coords(t), Scale=1.5, Detail=6.0, Roughness=0.35, Lacunarity=3.1).outputs["Color"],
    lambda t: noise(t, new(t, "ShaderNodeMapping", {"Vector": coords(t, "Generated"), "Location": (0.3, -0.2, 0.1),
                                                    "Rotation": (0.4, -0.7, 1.1), "Scale": (1.5, 0.5, 2.0)},
                           vector_type="TEXTURE").outputs[0], Scale=4.0).outputs["Color"],
    lambda t: noise(t, new(t, "ShaderNodeNewGeometry").outputs["Position"], Scale=1.2, Detail=2.0).outputs["Fac"],
    lambda t: ramp(t, noise(t, coords(t), Scale=3.0).outputs["Fac"], "LINEAR", STOPS),
    lambda t: ramp(t, noise(t, coords(t), Scale=3.0).outputs["Fac"], "CONSTANT", STOPS),
    lambda t: ramp(t, noise(t, coords(t), Scale=3.0).outputs["Fac"], "B_SPLINE", STOPS),
    lambda t: new(t, "ShaderNodeTexChecker", {"Vector": coords(t, "UV"), "Color1": (0.9, 0.6, 0.1, 1.0),
                                               "Color2": (0.1, 0.3, 0.8, 1.0), "Scale": 4.0}).outputs["Color"],
    lambda t: new(t, "ShaderNodeTexChecker", {"Scale": 3.5}).outputs["Fac"],
]

MATH_OPERATIONS = [
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "LOGARITHM", "SQRT", "INVERSE_SQRT",
    "ABSOLUTE", "EXPONENT", "MINIMUM", "MAXIMUM", "LESS_THAN", "GREATER_THAN", "SIGN", "COMPARE", "SMOOTH_MIN",
    "SMOOTH_MAX", "ROUND", "FLOOR", "CEIL", "TRUNC", "FRACT", "MODULO", "FLOORED_MODULO", "WRAP", "SNAP",
    "PINGPONG", "SINE", "COSINE", "ARCSINE", "ARCCOSINE", "ARCTANGENT", "ARCTAN2", "SINH", "COSH", "TANH",
    "RADIANS", "DEGREES",
]
# The cases Cycles defines for itself, as (operation, b, c) on a = x × 3 (−3…3): division and
# modulo by zero, a log to base −1, ping-pong to 0, a power of a negative base to a
# fractional exponent.
EDGES = [
    [("DIVIDE", 0.0, 0.0), ("MODULO", 0.0, 0.0), ("FLOORED_MODULO", 0.0, 0.0)],
    [("LOGARITHM", -1.0, 0.0), ("POWER", 0.5, 0.0), ("PINGPONG", 0.0, 0.0)],
]


def math_tile(operations, clamp):
    """Three operations, on a = x × 3 (−3…3) and b = y × 0.8 + 2 (1.2…2.8, clear of the
    poles of division, logarithms and powers, whose pixel means are not defined), c = 0.7."""
    def build(t):
        a, b, _ = xyz(t, coords(t))
        b = math_node(t, "MULTIPLY_ADD", b, 0.8 / 3.0, 2.0)
        channels = [shown(t, math_node(t, op, a, b, 0.7, clamp)) for op in operations]
        return rgb(t, *channels)
    return build


def edge_tile(cases):
    def build(t):
        a, _, _ = xyz(t, coords(t))
        return rgb(t, *[shown(t, math_node(t, op, a, b, c)) for op, b, c in cases])
    return build


# Three operations per tile, 40 in 14 tiles (the last with Clamp on), then the edge cases.
MATH = ([math_tile(MATH_OPERATIONS[3 * i:3 * i + 3], False) for i in range(13)]
        + [math_tile(["DEGREES", "COMPARE", "SINH"], True)] + [edge_tile(e) for e in EDGES])

BLENDS = ["MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE", "ADD", "OVERLAY", "SOFT_LIGHT",
          "LINEAR_LIGHT", "DIFFERENCE", "EXCLUSION", "SUBTRACT", "DIVIDE"]


def gradient(t, kind, vector=None):
    node = new(t, "ShaderNodeTexGradient", gradient_type=kind)
    if vector is not None:
        t.links.new(vector, node.inputs["Vector"])
    return node


def blend_tile(blend):
    def build(t):
        a = noise(t, coords(t), Scale=2.0).outputs["Color"]
        # Clear of 0, where Divide's pixel means are not defined.
        b = ramp(t, gradient(t, "LINEAR", coords(t, "Generated")).outputs["Fac"], "LINEAR",
                 [(0.0, (0.3, 0.35, 0.4, 1.0)), (1.0, (0.95, 0.9, 0.8, 1.0))])
        factor = math_node(t, "MULTIPLY_ADD", output(new(t, "ShaderNodeSeparateXYZ", {"Vector": coords(t)}), "Y"), 0.6, 0.5)
        mix = new(t, "ShaderNodeMix", {"Factor_Float": factor, "A_Color": a, "B_Color": b}, data_type="RGBA",
                  blend_type=blend, clamp_factor=True, clamp_result=blend in {"ADD", "DODGE"})
        return output(mix, "Result_Color")
    return build


def float_mix(t):
    a, b, _ = xyz(t, coords(t), 1.0)
    mix = new(t, "ShaderNodeMix", {"Factor_Float": 1.3, "A_Float": a, "B_Float": b}, data_type="FLOAT",
              clamp_factor=False)
    return shown(t, output(mix, "Result_Float"), 0.5, 0.5)


COLOR = [blend_tile(b) for b in BLENDS] + [float_mix]

GRADIENTS = ["LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE", "RADIAL"]
VECTOR_OPERATIONS = ["ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT", "REFLECT",
                     "REFRACT", "FACEFORWARD", "SCALE", "NORMALIZE", "ABSOLUTE", "MINIMUM", "MAXIMUM", "FLOOR", "CEIL",
                     "FRACTION", "MODULO", "WRAP", "SNAP", "SINE", "COSINE", "DOT_PRODUCT", "DISTANCE", "LENGTH"]


def vector_tile(operations):
    """Up to three operations, each on (object coordinates × 2, a constant, generated), shown."""
    def build(t):
        channels = []
        for op in operations:
            node = new(t, "ShaderNodeVectorMath", operation=op)
            scaled = new(t, "ShaderNodeVectorMath", {"Vector": coords(t), "Scale": 2.0}, operation="SCALE")
            t.links.new(scaled.outputs["Vector"], node.inputs[0])
            node.inputs[1].default_value = (0.3, -0.5, 0.8)
            t.links.new(coords(t, "Generated"), node.inputs[2])
            input_socket(node, "Scale").default_value = 0.7
            value = node.outputs["Value"] if op in {"DOT_PRODUCT", "DISTANCE", "LENGTH"} else node.outputs["Vector"]
            channels.append(shown(t, value, 0.2, 0.3))
        return rgb(t, *(channels + channels)[:3])
    return build


def map_range(t, interpolation, clamp, reverse=False):
    value = output(new(t, "ShaderNodeSeparateXYZ", {"Vector": coords(t)}), "X")
    lo, hi = (0.6, -0.4) if reverse else (-0.4, 0.6)
    node = new(t, "ShaderNodeMapRange", {"Value": value, "From Min": lo, "From Max": hi, "To Min": 0.1,
                                          "To Max": 0.9, "Steps": 4.0},
               data_type="FLOAT", interpolation_type=interpolation, clamp=clamp)
    return output(node, "Result")


def vector_map_range(t, interpolation, clamp=True, lo=(-1.0, -1.0, -1.0), hi=(1.0, 1.0, 1.0),
                     to=((0.1, 0.2, 0.3), (0.9, 0.8, 0.7)), steps=(2.0, 4.0, 6.0)):
    """A Map Range of vectors of the Object coordinates × 1.3."""
    node = new(t, "ShaderNodeMapRange", data_type="FLOAT_VECTOR", interpolation_type=interpolation, clamp=clamp)
    for key, value in (("From_Min_FLOAT3", lo), ("From_Max_FLOAT3", hi), ("To_Min_FLOAT3", to[0]),
                       ("To_Max_FLOAT3", to[1]), ("Steps_FLOAT3", steps)):
        input_socket(node, key).default_value = value
    t.links.new(texture_coordinate(t, "Object", 1.3), input_socket(node, "Vector"))
    return output(node, "Vector")


MAP_RANGE = [
    lambda t: vector_map_range(t, "LINEAR"),
    lambda t: vector_map_range(t, "LINEAR", clamp=False, to=((0.3, 0.2, 0.1), (0.6, 0.7, 0.8))),
    lambda t: vector_map_range(t, "LINEAR", lo=(0.8, -1.0, 0.5), hi=(-0.6, 1.0, -0.5)),
    lambda t: vector_map_range(t, "LINEAR", to=((0.9, 0.1, 0.6), (0.1, 0.9, 0.2))),
    lambda t: vector_map_range(t, "STEPPED"),
    lambda t: vector_map_range(t, "STEPPED", clamp=False, steps=(1.0, 0.0, 3.0)),
    lambda t: vector_map_range(t, "SMOOTHSTEP"),
    lambda t: vector_map_range(t, "SMOOTHERSTEP", lo=(0.7, 0.7, -0.7), hi=(-0.7, -0.2, 0.7)),
    # Components whose range is empty.
    lambda t: vector_map_range(t, "LINEAR", lo=(0.0, -1.0, 0.5), hi=(0.0, 1.0, 0.5)),
    lambda t: vector_map_range(t, "SMOOTHSTEP", clamp=False, lo=(0.3, 0.3, -1.0), hi=(0.3, 1.0, 1.0)),
    # Read as a value: the mean of its components.
    lambda t: math_node(t, "ADD", vector_map_range(t, "LINEAR"), 0.0),
]


def converters(t):
    c = noise(t, coords(t), Scale=2.5).outputs["Color"]
    inverted = new(t, "ShaderNodeInvert", {"Fac": 0.7, "Color": c}).outputs[0]
    separate = new(t, "ShaderNodeSeparateColor", {"Color": inverted}, mode="RGB")
    bw = new(t, "ShaderNodeRGBToBW", {"Color": c}).outputs[0]
    clamp = new(t, "ShaderNodeClamp", {"Value": separate.outputs["Red"], "Min": 0.6, "Max": 0.3},
                clamp_type="RANGE").outputs[0]
    return new(t, "ShaderNodeCombineColor", {"Red": clamp, "Green": bw, "Blue": separate.outputs["Blue"]},
               mode="RGB").outputs[0]


def vector_mix(t):
    mix = new(t, "ShaderNodeMix", {"Factor_Vector": (0.2, 0.9, 1.4), "A_Vector": coords(t, "Generated"),
                                    "B_Vector": (0.9, 0.1, 0.5)}, data_type="VECTOR", factor_mode="NON_UNIFORM")
    return output(mix, "Result_Vector")


def clamp_minmax(t):
    x, y, z = xyz(t, coords(t), 1.0)
    return rgb(t, *[new(t, "ShaderNodeClamp", {"Value": v, "Min": 0.1, "Max": 0.7}).outputs[0] for v in (x, y, z)])


VECTOR = ([lambda t, k=k: gradient(t, k).outputs["Color"] for k in GRADIENTS]
          + [vector_tile(VECTOR_OPERATIONS[i:i + 3]) for i in range(0, len(VECTOR_OPERATIONS), 3)])
def hsv_blend_tile(blend):
    def build(t):
        a = noise(t, coords(t), Scale=2.0).outputs["Color"]
        b = new(t, "ShaderNodeCombineColor", {"Red": output(new(t, "ShaderNodeSeparateXYZ", {"Vector": coords(t, "Generated")}), "X"),
                                               "Green": 0.8, "Blue": 0.7}, mode="HSV").outputs[0]
        mix = new(t, "ShaderNodeMix", {"Factor_Float": 0.7, "A_Color": a, "B_Color": b}, data_type="RGBA", blend_type=blend)
        return output(mix, "Result_Color")
    return build


def cells(t, scale=4.0):
    """The object coordinates floored to cells of 1/scale: white noise is then constant per cell."""
    scaled = new(t, "ShaderNodeVectorMath", {"Vector": coords(t), "Scale": scale}, operation="SCALE")
    return new(t, "ShaderNodeVectorMath", {"Vector": scaled.outputs["Vector"]}, operation="FLOOR").outputs["Vector"]


def colour_nodes(t):
    c = noise(t, coords(t), Scale=2.5).outputs["Color"]
    hue = new(t, "ShaderNodeHueSaturation", {"Hue": 0.3, "Saturation": 1.6, "Value": 0.9, "Fac": 0.8, "Color": c})
    bright = new(t, "ShaderNodeBrightContrast", {"Color": hue.outputs[0], "Bright": 0.1, "Contrast": 0.4})
    return new(t, "ShaderNodeGamma", {"Color": bright.outputs[0], "Gamma": 1.8}).outputs[0]


def hsv_round_trip(t):
    separate = new(t, "ShaderNodeSeparateColor", {"Color": noise(t, coords(t), Scale=3.0).outputs["Color"]}, mode="HSV")
    return rgb(t, separate.outputs[0], separate.outputs[1], separate.outputs[2])


def bend(curve, points):
    """Moves a curve's two points and adds more, (x, y) each."""
    curve.points[0].location, curve.points[1].location = points[0], points[-1]
    for x, y in points[1:-1]:
        curve.points.new(x, y)


def curves(t):
    """R: a Float Curve of the noise; G and B: RGB Curves (through the combined curve) and
    Vector Curves, extrapolated past their points, over the object coordinates."""
    fac = noise(t, coords(t), Scale=2.5).outputs["Fac"]
    float_curve = new(t, "ShaderNodeFloatCurve", {"Value": fac, "Factor": 0.9})
    bend(float_curve.mapping.curves[0], [(0.2, 0.1), (0.5, 0.8), (0.8, 0.3)])
    rgb_curves = new(t, "ShaderNodeRGBCurve", {"Color": coords(t, "Generated")})
    bend(rgb_curves.mapping.curves[3], [(0.0, 0.1), (0.6, 0.7), (1.0, 0.9)])
    bend(rgb_curves.mapping.curves[1], [(0.0, 0.0), (0.3, 0.6), (1.0, 1.0)])
    vector_curves = new(t, "ShaderNodeVectorCurve", {"Vector": coords(t)})
    bend(vector_curves.mapping.curves[2], [(-1.0, 0.5), (0.2, -0.3), (1.0, 1.0)])
    for node in (float_curve, rgb_curves, vector_curves):
        node.mapping.update()
    green = output(new(t, "ShaderNodeSeparateXYZ", {"Vector": rgb_curves.outputs[0]}), "Y")
    blue = shown(t, output(new(t, "ShaderNodeSeparateXYZ", {"Vector": vector_curves.outputs[0]}), "Z"), 0.5, 0.2)
    return rgb(t, float_curve.outputs[0], green, blue)


CONVERT = [
    lambda t: rgb(t, map_range(t, "LINEAR", True), map_range(t, "STEPPED", False), map_range(t, "SMOOTHSTEP", False)),
    lambda t: rgb(t, map_range(t, "SMOOTHERSTEP", False, True), map_range(t, "LINEAR", False, True),
                  map_range(t, "SMOOTHSTEP", False, True)),
    converters,
    vector_mix,
    clamp_minmax,
    colour_nodes,
    hsv_round_trip,
    lambda t: new(t, "ShaderNodeTexWhiteNoise", {"Vector": cells(t)}, noise_dimensions="3D").outputs["Color"],
    lambda t: new(t, "ShaderNodeTexWhiteNoise", {"Vector": cells(t, 7.0)}, noise_dimensions="3D").outputs["Value"],
    lambda t: new(t, "ShaderNodeTexWhiteNoise", noise_dimensions="3D").outputs["Color"],
    lambda t: new(t, "ShaderNodeHueSaturation", {"Hue": 0.8, "Saturation": 0.3, "Value": 1.4, "Fac": 1.0,
                                                  "Color": coords(t, "Generated")}).outputs[0],
] + [hsv_blend_tile(b) for b in ("HUE", "SATURATION", "VALUE", "COLOR")] + [curves]


def layer_weight(t, blend, which):
    return new(t, "ShaderNodeLayerWeight", {"Blend": blend}).outputs[which]


SHADING = [
    lambda t: layer_weight(t, 0.5, "Fresnel"),
    lambda t: layer_weight(t, 0.2, "Facing"),
    lambda t: layer_weight(t, 0.8, "Facing"),
    lambda t: layer_weight(t, 0.5, "Facing"),
    lambda t: new(t, "ShaderNodeFresnel", {"IOR": 1.45}).outputs[0],
    lambda t: new(t, "ShaderNodeFresnel", {"IOR": 3.0}).outputs[0],
    lambda t: shown(t, output(new(t, "ShaderNodeSeparateXYZ", {"Vector": new(t, "ShaderNodeNewGeometry").outputs["Normal"]}), "X"), 0.5, 0.5),
    lambda t: new(t, "ShaderNodeVectorMath", {"Vector": new(t, "ShaderNodeNewGeometry").outputs["Incoming"]}, operation="ABSOLUTE").outputs[0],
    lambda t: new(t, "ShaderNodeVectorMath", {"Vector": coords(t, "Normal")}, operation="ABSOLUTE").outputs[0],
    lambda t: coords(t, "Generated"),
    lambda t: new(t, "ShaderNodeVectorMath", {"Vector": new(t, "ShaderNodeNewGeometry").outputs["True Normal"]}, operation="ABSOLUTE").outputs[0],
    lambda t: noise(t, Scale=4.0, Detail=3.0).outputs["Color"],
    lambda t: new(t, "ShaderNodeTexChecker", {"Scale": 5.0}).outputs["Color"],
    lambda t: gradient(t, "SPHERICAL", coords(t)).outputs["Color"],
    lambda t: ramp(t, layer_weight(t, 0.3, "Facing"), "EASE", STOPS),
    lambda t: new(t, "ShaderNodeMix", {"Factor_Float": layer_weight(t, 0.4, "Fresnel"), "A_Color": (0.8, 0.2, 0.1, 1.0),
                                        "B_Color": (0.1, 0.4, 0.9, 1.0)}, data_type="RGBA").outputs[2],
]


def voronoi(t, which, vector=True, feature="F1", distance="EUCLIDEAN", normalize=False, dimensions="3D", w=None,
            **inputs):
    w_input = {"W": w(t)} if w is not None and dimensions in ("1D", "4D") else {}
    node = new(t, "ShaderNodeTexVoronoi", {"Scale": 4.0, **inputs, **w_input}, voronoi_dimensions=dimensions,
               feature=feature, distance=distance, normalize=normalize)
    if vector and dimensions != "1D":
        t.links.new(coords(t), node.inputs["Vector"])
    return output(node, which)


def x_times(factor):
    return lambda t: math_node(t, "MULTIPLY", new(t, "ShaderNodeSeparateXYZ", {"Vector": coords(t)}).outputs["X"], factor)


def voronoi_of(dimensions, which="Distance", show=None, w=x_times(1.5), **settings):
    """Voronoi of 1, 2 or 4 dimensions over the object coordinates (W from `w`); `show` =
    (scale, offset) for values outside 0…1."""
    def build(t):
        out = voronoi(t, which, dimensions=dimensions, w=w, **settings)
        return shown(t, out, *show) if show else out
    return build


VORONOI = [
    lambda t: voronoi(t, "Distance", vector=False),
    lambda t: voronoi(t, "Color"),
    lambda t: new(t, "ShaderNodeVectorMath", {"Vector": voronoi(t, "Position")}, operation="FRACTION").outputs[0],
    lambda t: shown(t, voronoi(t, "Distance", feature="F2"), 0.6, 0.0),
    lambda t: voronoi(t, "Distance", feature="SMOOTH_F1", Smoothness=1.0),
    lambda t: voronoi(t, "Color", feature="SMOOTH_F1", Smoothness=0.4),
    lambda t: shown(t, voronoi(t, "Distance", feature="DISTANCE_TO_EDGE"), 2.0, 0.0),
    lambda t: shown(t, voronoi(t, "Radius", feature="N_SPHERE_RADIUS"), 1.5, 0.0),
    lambda t: shown(t, voronoi(t, "Distance", distance="MANHATTAN"), 0.5, 0.0),
    lambda t: voronoi(t, "Distance", distance="CHEBYCHEV"),
    lambda t: shown(t, voronoi(t, "Distance", distance="MINKOWSKI", Exponent=0.7), 0.3, 0.0),
    lambda t: voronoi(t, "Color", Randomness=0.4),
    lambda t: voronoi(t, "Distance", normalize=True, Detail=2.5, Roughness=0.6),
    lambda t: voronoi(t, "Color", Detail=1.5, Roughness=0.5, Lacunarity=2.5),
    lambda t: shown(t, voronoi(t, "Distance", feature="DISTANCE_TO_EDGE", normalize=True, Detail=1.5), 1.0, 0.0),
    lambda t: voronoi(t, "Distance", feature="SMOOTH_F1", Smoothness=0.6, Detail=2.0, Roughness=0.5),
]


def texture(t, kind, which, vector, scale, props):
    """A texture node of type `kind` at Scale `scale`: capitalised `props` are its inputs,
    the rest its settings; `vector`: on Object coordinates, else its default ones."""
    inputs = {k: props.pop(k) for k in list(props) if k[0].isupper()}
    node = new(t, kind, {"Scale": scale, **inputs}, **props)
    if vector:
        t.links.new(coords(t), node.inputs["Vector"])
    return node.outputs[which]


def wave(t, which="Fac", vector=True, **props):
    return texture(t, "ShaderNodeTexWave", which, vector, 1.5, props)


WAVE = [
    lambda t: wave(t, vector=False),
    lambda t: wave(t, "Color", bands_direction="Y", wave_profile="SAW"),
    lambda t: wave(t, bands_direction="DIAGONAL", wave_profile="TRI", **{"Phase Offset": 1.3}),
    lambda t: wave(t, bands_direction="Z"),
    lambda t: wave(t, wave_type="RINGS", rings_direction="X"),
    lambda t: wave(t, wave_type="RINGS", rings_direction="Y", wave_profile="SAW"),
    lambda t: wave(t, wave_type="RINGS", rings_direction="Z", wave_profile="TRI"),
    lambda t: wave(t, wave_type="RINGS", rings_direction="SPHERICAL"),
    lambda t: wave(t, Distortion=4.0, Detail=2.5, **{"Detail Scale": 1.5, "Detail Roughness": 0.6}),
    lambda t: wave(t, wave_type="RINGS", Distortion=2.0, Detail=1.0),
    lambda t: ramp(t, wave(t, bands_direction="X", Distortion=6.0, Detail=3.0), "LINEAR", STOPS),
]


def magic(t, which="Color", vector=True, **props):
    return texture(t, "ShaderNodeTexMagic", which, vector, 0.8, props)


# Every depth Blender offers, the Fac output, the default coordinates and no distortion.
MAGIC = [lambda t, d=d: magic(t, turbulence_depth=d, Distortion=1.0 + 0.4 * d) for d in range(11)] + [
    lambda t: magic(t, "Fac", turbulence_depth=3, Distortion=2.5),
    lambda t: magic(t, vector=False, turbulence_depth=2),
    lambda t: magic(t, turbulence_depth=4, Distortion=0.0),
    lambda t: ramp(t, magic(t, "Fac", turbulence_depth=5, Distortion=3.0), "LINEAR", STOPS),
]


def brick(t, which="Color", vector=True, **props):
    colours = {"Color1": (0.8, 0.25, 0.1, 1.0), "Color2": (0.1, 0.3, 0.9, 1.0), "Mortar": (0.2, 0.7, 0.3, 1.0)}
    return texture(t, "ShaderNodeTexBrick", which, vector, 2.5, {**colours, **props})


# Offsets and squashes of other frequencies, hard and no mortar, biased tints, other
# brick sizes, the Fac output and the default coordinates; Object coordinates reach
# negative rows and bricks.
BRICK = [
    lambda t: brick(t),
    lambda t: brick(t, "Fac"),
    lambda t: brick(t, offset=0.25, offset_frequency=3),
    lambda t: brick(t, squash=0.5, squash_frequency=3),
    lambda t: brick(t, squash=1.7, squash_frequency=2, offset=0.8, offset_frequency=1),
    lambda t: brick(t, **{"Mortar Smooth": 0.0, "Mortar Size": 0.05}),
    lambda t: brick(t, **{"Mortar Smooth": 0.8, "Mortar Size": 0.08}),
    lambda t: brick(t, **{"Mortar Size": 0.0}),
    lambda t: brick(t, Bias=0.5),
    lambda t: brick(t, Bias=-0.7),
    lambda t: brick(t, **{"Brick Width": 0.3, "Row Height": 0.4}),
    lambda t: brick(t, vector=False, Scale=6.0),
    lambda t: ramp(t, brick(t, "Fac", **{"Mortar Smooth": 1.0, "Mortar Size": 0.1}), "LINEAR", STOPS),
    lambda t: brick(t, Scale=7.0, offset=0.0),
]


def white_noise(t, dimensions, which, scale=4.0):
    """White Noise of `dimensions` over cells (constant per cell), W the cell's column."""
    vector = cells(t, scale)
    w = math_node(t, "MULTIPLY_ADD", new(t, "ShaderNodeSeparateXYZ", {"Vector": vector}).outputs["X"], 0.5, 0.25)
    node = new(t, "ShaderNodeTexWhiteNoise", {"Vector": vector, "W": w}, noise_dimensions=dimensions)
    return node.outputs[which]


WHITE_NOISE = [lambda t, d=d, o=o, s=s: white_noise(t, d, o, s) for d in ("1D", "2D", "3D", "4D")
               for o, s in (("Color", 4.0), ("Value", 6.0))]


def noise_of(dimensions, which="Fac", noise_type="FBM", w=None, show=None, **inputs):
    """Noise of 1, 2 or 4 dimensions over the object coordinates; W from `w` (a function of
    the tree) or the x coordinate × 3; `show` = (scale, offset) for values of any sign."""
    def build(t):
        w_socket = w(t) if w else x_times(3.0)(t)
        node = noise(t, coords(t), noise_type, dimensions=dimensions, W=w_socket, **inputs)
        out = node.outputs[which]
        return shown(t, out, *show) if show else out
    return build


def y_plus(offset):
    return lambda t: math_node(t, "ADD", new(t, "ShaderNodeSeparateXYZ", {"Vector": coords(t)}).outputs["Y"], offset)


NOISE_DIMENSIONS = [
    noise_of("1D", Scale=2.0, Detail=3.0),
    noise_of("1D", "Color", Scale=1.5, Detail=2.0, Distortion=1.5),
    noise_of("1D", noise_type="RIDGED_MULTIFRACTAL", show=(0.3, 0.0), Scale=2.0, Detail=3.5, Offset=1.0, Gain=2.0),
    noise_of("1D", normalize=False, show=(0.5, 0.5), Scale=2.5, Detail=4.5, Roughness=0.6),
    noise_of("2D", Scale=3.0, Detail=2.0),
    noise_of("2D", "Color", Scale=2.0, Detail=1.0, Distortion=2.0),
    noise_of("2D", noise_type="MULTIFRACTAL", show=(0.3, 0.0), Scale=2.0, Detail=3.5),
    noise_of("2D", noise_type="HETERO_TERRAIN", show=(0.3, 0.0), Scale=2.0, Detail=3.5, Offset=0.8),
    noise_of("4D", w=lambda t: 0.7, Scale=3.0, Detail=2.0),
    noise_of("4D", "Color", w=y_plus(0.3), Scale=2.0, Detail=1.5, Distortion=1.2),
    noise_of("4D", noise_type="HYBRID_MULTIFRACTAL", show=(0.3, 0.0), Scale=2.0, Detail=3.5, Offset=0.5, Gain=1.5),
    noise_of("4D", noise_type="RIDGED_MULTIFRACTAL", w=y_plus(-1.1), show=(0.3, 0.0), Scale=1.5, Detail=2.5,
             Offset=1.0, Gain=2.0),
    noise_of("1D", "Color", w=y_plus(0.0), Scale=4.0, Detail=6.0, Roughness=0.35, Lacunarity=3.1),
    noise_of("2D", normalize=False, show=(0.5, 0.5), Scale=1.5, Detail=6.0, Roughness=0.35, Lacunarity=3.1),
    noise_of("4D", "Color", normalize=False, w=lambda t: -2.4, Scale=2.5, Detail=0.0),
    noise_of("2D", "Color", noise_type="HETERO_TERRAIN", show=(0.2, 0.1), Scale=1.0, Detail=2.0, Distortion=0.7),
]


VORONOI_DIMENSIONS = [
    voronoi_of("1D"),
    voronoi_of("1D", "Color", feature="F2", Scale=3.0),
    voronoi_of("1D", "W", show=(0.3, 0.5)),
    voronoi_of("1D", feature="SMOOTH_F1", Smoothness=0.8, Detail=1.5, Roughness=0.6),
    voronoi_of("1D", feature="DISTANCE_TO_EDGE", show=(2.0, 0.0)),
    voronoi_of("1D", "Radius", feature="N_SPHERE_RADIUS", show=(1.5, 0.0), Randomness=0.7),
    voronoi_of("2D", normalize=True, Detail=2.0, Roughness=0.5),
    voronoi_of("2D", "Color", feature="F2", distance="MANHATTAN"),
    lambda t: vector_op(t, "FRACTION", voronoi(t, "Position", dimensions="2D")),
    voronoi_of("2D", "Color", feature="SMOOTH_F1", distance="CHEBYCHEV", Smoothness=0.5),
    voronoi_of("2D", feature="DISTANCE_TO_EDGE", show=(2.0, 0.0)),
    voronoi_of("2D", "Distance", distance="MINKOWSKI", show=(0.4, 0.0), Exponent=1.5),
    voronoi_of("4D", w=lambda t: 0.7, Scale=3.0),
    voronoi_of("4D", "Color", feature="F2", w=y_plus(0.3), Scale=2.5),
    voronoi_of("4D", "W", show=(0.5, 0.5), w=y_plus(-0.4), Scale=2.0),
    voronoi_of("4D", "Radius", feature="N_SPHERE_RADIUS", show=(1.5, 0.0), Scale=2.0),
]


def glow(color=(1.0, 0.5, 0.2, 1.0), strength=None, principled=False):
    """An Emission shader (or a black Principled's emission) of `color` (a value or a
    function of the tree) and `strength` (a function of the tree)."""
    def build(t):
        c = color(t) if callable(color) else color
        if principled:
            node = new(t, "ShaderNodeBsdfPrincipled", {"Base Color": (0.0, 0.0, 0.0, 1.0), "Emission Color": c,
                                                        "Emission Strength": strength(t), "Specular IOR Level": 0.0})
        else:
            node = new(t, "ShaderNodeEmission", {"Color": c, "Strength": strength(t)})
        return node.outputs[0]
    return build


def value_of(t, value):
    node = new(t, "ShaderNodeValue")
    node.outputs[0].default_value = value
    return node.outputs[0]


EMISSION_STRENGTH = [
    glow(strength=lambda t: math_node(t, "MULTIPLY", noise(t, coords(t), Scale=3.0, Detail=2.0).outputs["Fac"], 3.0)),
    glow(strength=lambda t: gradient(t, "LINEAR", coords(t)).outputs["Fac"]),
    glow(color=lambda t: new(t, "ShaderNodeTexChecker", {"Scale": 4.0}).outputs["Color"],
         strength=lambda t: math_node(t, "ADD", voronoi(t, "Distance"), 0.2)),
    glow(color=(0.2, 0.6, 1.0, 1.0), strength=lambda t: value_of(t, 1.7)),
    glow(strength=lambda t: math_node(t, "MULTIPLY", noise(t, coords(t), Scale=2.0).outputs["Fac"], 2.5),
         principled=True),
    glow(color=(0.3, 1.0, 0.4, 1.0), strength=lambda t: gradient(t, "SPHERICAL", coords(t)).outputs["Fac"],
         principled=True),
    glow(color=lambda t: gradient_colour(t), strength=lambda t: math_node(t, "ADD", noise(t, coords(t), Scale=5.0).outputs["Fac"], 0.5),
         principled=True),
    glow(color=lambda t: noise(t, coords(t), Scale=3.0).outputs["Color"],
         strength=lambda t: math_node(t, "MULTIPLY_ADD", new(t, "ShaderNodeTexChecker", {"Scale": 3.0}).outputs["Fac"],
                                      1.5, 0.5)),
]


def along_x(t, middle, half_width):
    """middle + half_width × the object's x (−1…1 on a tile)."""
    x = new(t, "ShaderNodeSeparateXYZ", {"Vector": coords(t)}).outputs["X"]
    return math_node(t, "MULTIPLY_ADD", x, half_width, middle)


def blackbody(t, middle, half_width):
    return new(t, "ShaderNodeBlackbody", {"Temperature": along_x(t, middle, half_width)}).outputs["Color"]


def wavelength(t, middle, half_width):
    return new(t, "ShaderNodeWavelength", {"Wavelength": along_x(t, middle, half_width)}).outputs["Color"]


def vector_op(t, operation, a, b=(0.0, 0.0, 0.0), c=(0.0, 0.0, 0.0)):
    return new(t, "ShaderNodeVectorMath", {"Vector": a, "Vector_001": b, "Vector_002": c},
               operation=operation).outputs["Vector"]


def vector_shown(t, v):
    """|0.3 v + 0.5| per component: a vector of any sign made a visible colour."""
    return vector_op(t, "ABSOLUTE", vector_op(t, "MULTIPLY_ADD", v, (0.3, 0.3, 0.3), (0.5, 0.5, 0.5)))


def spread(t):
    """(2x, 2y, 1.5 (x + y)) of the object's coordinates."""
    x, y, _ = xyz(t, coords(t), 1.0)
    return rgb(t, math_node(t, "MULTIPLY", x, 2.0), math_node(t, "MULTIPLY", y, 2.0),
               math_node(t, "MULTIPLY", math_node(t, "ADD", x, y), 1.5))


def hsl_combined(t):
    x, y, _ = xyz(t, coords(t), 1.0)
    hue = math_node(t, "MULTIPLY_ADD", x, 0.5, 0.5)
    lightness = math_node(t, "MULTIPLY_ADD", y, 0.6, 0.5)
    node = new(t, "ShaderNodeCombineColor", {"Red": hue, "Green": 0.8, "Blue": lightness}, mode="HSL")
    return node.outputs["Color"]


def hsl_separated(t, colour):
    parts = new(t, "ShaderNodeSeparateColor", {"Color": colour}, mode="HSL").outputs
    return rgb(t, parts[0], parts[1], parts[2])


def gradient_colour(t):
    """A colour that changes hue and brightness over the tile, above 1 at a corner."""
    x, y, _ = xyz(t, coords(t), 1.0)
    return rgb(t, math_node(t, "MULTIPLY_ADD", x, 0.7, 0.6), math_node(t, "MULTIPLY_ADD", y, 0.5, 0.4),
               math_node(t, "MULTIPLY_ADD", math_node(t, "MULTIPLY", x, y), 0.4, 0.3))


SPECTRUM = [
    lambda t: blackbody(t, 1000.0, 500.0),
    lambda t: blackbody(t, 2500.0, 1000.0),
    lambda t: blackbody(t, 5000.0, 2000.0),
    lambda t: blackbody(t, 10000.0, 3000.0),
    lambda t: wavelength(t, 400.0, 30.0),
    lambda t: wavelength(t, 480.0, 40.0),
    lambda t: wavelength(t, 580.0, 50.0),
    lambda t: wavelength(t, 720.0, 70.0),
    lambda t: vector_shown(t, vector_op(t, "POWER", spread(t), (0.5, 2.0, 3.0))),
    lambda t: vector_shown(t, vector_op(t, "POWER", (1.5, 0.7, 2.0), spread(t))),
    lambda t: vector_shown(t, vector_op(t, "SIGN", spread(t))),
    lambda t: hsl_combined(t),
    lambda t: hsl_separated(t, gradient_colour(t)),
    lambda t: new(t, "ShaderNodeCombineColor", {c: s for c, s in zip(("Red", "Green", "Blue"),
              new(t, "ShaderNodeSeparateColor", {"Color": gradient_colour(t)}, mode="HSL").outputs)},
                  mode="HSL").outputs["Color"],
    lambda t: blackbody(t, 790.0, 20.0),
    lambda t: new(t, "ShaderNodeBlackbody", {"Temperature": math_node(
        t, "MULTIPLY_ADD", noise(t, coords(t), Scale=3.0).outputs["Fac"], 9000.0, 1000.0)}).outputs["Color"],
]


def texture_coordinate(t, which, scale=1.0, offset=(0.0, 0.0, 0.0)):
    """Texture Coordinate's `which` × `scale` + `offset`."""
    return vector_op(t, "MULTIPLY_ADD", coords(t, which), (scale,) * 3, offset)


CAMERA_COORDINATES = (
    [lambda t: vector_shown(t, texture_coordinate(t, "Camera", 0.25))] * 4
    + [lambda t: coords(t, "Window")] * 4
    + [lambda t: vector_op(t, "FRACTION", texture_coordinate(t, "Window", 6.0))] * 4
    + [lambda t: vector_shown(t, coords(t, "Reflection"))] * 4
)


def camera_scene():
    """Texture Coordinate's Camera, Window and Reflection on spheres seen in perspective
    through a shifted lens."""
    return camera_scene_of("camera", CAMERA_COORDINATES)


def camera_data(t, which):
    return new(t, "ShaderNodeCameraData").outputs[which]


CAMERA_DATA = (
    [lambda t: vector_shown(t, camera_data(t, "View Vector"))] * 4
    + [lambda t: math_node(t, "FRACT", math_node(t, "MULTIPLY", camera_data(t, "View Z Depth"), 0.8))] * 4
    + [lambda t: math_node(t, "FRACT", math_node(t, "MULTIPLY", camera_data(t, "View Distance"), 1.3))] * 4
    + [lambda t: ramp(t, math_node(t, "SUBTRACT", camera_data(t, "View Distance"), camera_data(t, "View Z Depth")),
                      "LINEAR", STOPS)] * 4
)


def camera_scene_of(name, builders):
    """Spheres of `builders` seen in perspective through a shifted lens."""
    scene = grid_scene(name, builders, shape="sphere")
    camera = cycles.camera(scene, (0.5, -9.0, 7.0), 52.0)
    camera.data.lens, camera.data.shift_x, camera.data.shift_y = 30.0, 0.06, -0.04
    return scene


def camera_data_scene():
    """The Camera Data node on spheres seen in perspective through a shifted lens."""
    return camera_scene_of("camera_data", CAMERA_DATA)


def transformed(t, v, kind, source, target, scale=1.0):
    """A Vector Transform of `v` (a socket, or a function of the tree) × `scale`, shown."""
    node = new(t, "ShaderNodeVectorTransform", {"Vector": v(t) if callable(v) else v}, vector_type=kind,
               convert_from=source, convert_to=target)
    return vector_shown(t, vector_op(t, "MULTIPLY", node.outputs[0], (scale,) * 3) if scale != 1.0 else node.outputs[0])


def geometry(t, which):
    return new(t, "ShaderNodeNewGeometry").outputs[which]


VECTOR_TRANSFORM = [
    lambda t: transformed(t, geometry(t, "Position"), "POINT", "WORLD", "OBJECT"),
    lambda t: transformed(t, coords(t, "Object"), "POINT", "OBJECT", "WORLD", 0.3),
    lambda t: transformed(t, geometry(t, "Position"), "POINT", "WORLD", "CAMERA", 0.1),
    lambda t: transformed(t, coords(t, "Camera"), "POINT", "CAMERA", "WORLD", 0.3),
    lambda t: transformed(t, coords(t, "Object"), "POINT", "OBJECT", "CAMERA", 0.1),
    lambda t: transformed(t, coords(t, "Camera"), "POINT", "CAMERA", "OBJECT"),
    lambda t: transformed(t, (0.3, 0.5, 0.8), "VECTOR", "WORLD", "OBJECT"),
    lambda t: transformed(t, (0.3, 0.5, 0.8), "VECTOR", "OBJECT", "WORLD"),
    lambda t: transformed(t, geometry(t, "Incoming"), "VECTOR", "WORLD", "CAMERA"),
    lambda t: transformed(t, (0.2, -0.4, 0.9), "VECTOR", "CAMERA", "WORLD"),
    lambda t: transformed(t, (0.2, -0.4, 0.9), "VECTOR", "CAMERA", "OBJECT"),
    lambda t: transformed(t, geometry(t, "Normal"), "NORMAL", "WORLD", "OBJECT"),
    lambda t: transformed(t, coords(t, "Normal"), "NORMAL", "OBJECT", "WORLD"),
    lambda t: transformed(t, geometry(t, "Normal"), "NORMAL", "WORLD", "CAMERA"),
    lambda t: transformed(t, (0.0, 0.6, 0.8), "NORMAL", "CAMERA", "WORLD"),
    lambda t: transformed(t, coords(t, "Normal"), "NORMAL", "OBJECT", "CAMERA"),
]


def vector_transform_scene():
    """Vector Transform of points, vectors and normals between world, object and camera
    space, on spheres turned and stretched, in perspective through a shifted lens."""
    scene = camera_scene_of("vector_transform", VECTOR_TRANSFORM)
    for i, obj in enumerate(o for o in scene.objects if o.name.startswith("tile_")):
        obj.rotation_euler = (0.4 * (i % 3), 0.3 + 0.2 * (i % 4), 0.5 * (i % 5))
        obj.scale = (0.9, 0.75, 1.1) if i % 2 else (0.8, 0.8, 0.8)
    return scene


def normal_node(t, direction, which="Dot", normal=None):
    node = new(t, "ShaderNodeNormal", {} if normal is None else {"Normal": normal})
    node.outputs["Normal"].default_value = direction
    return node.outputs[which]


NORMAL_NODE = [
    lambda t: normal_node(t, (0.0, -0.6, 0.8), normal=geometry(t, "Normal")),
    lambda t: normal_node(t, (0.5, 0.5, 0.2), normal=geometry(t, "Normal")),
    lambda t: shown(t, normal_node(t, (-0.3, 0.2, 0.9), normal=coords(t, "Object")), 0.5, 0.5),
    lambda t: vector_shown(t, normal_node(t, (1.0, 2.0, -2.0), "Normal")),
    lambda t: ramp(t, normal_node(t, (0.2, -0.9, 0.4), normal=geometry(t, "Incoming")), "LINEAR", STOPS),
    lambda t: math_node(t, "ABSOLUTE", normal_node(t, (0.0, 0.0, 1.0))),
]


TANGENT = [
    lambda t: vector_shown(t, geometry(t, "Tangent")),
    lambda t: vector_shown(t, geometry(t, "Tangent")),
    lambda t: vector_shown(t, geometry(t, "Tangent")),
    lambda t: vector_shown(t, vector_op(t, "CROSS_PRODUCT", geometry(t, "Tangent"), geometry(t, "Normal"))),
    lambda t: ramp(t, new(t, "ShaderNodeVectorMath", {"Vector": geometry(t, "Tangent"),
                                                       "Vector_001": geometry(t, "Incoming")},
                          operation="DOT_PRODUCT").outputs["Value"], "LINEAR", STOPS),
    lambda t: vector_shown(t, geometry(t, "Tangent")),
]
# Each tile's rotation (radians about X, Y, Z) and scale: the tangent turns with the object's Z axis.
TANGENT_PLACES = [((0.0, 0.0, 0.0), (1.0, 1.0, 1.0)), ((0.9, 0.0, 0.3), (1.0, 1.0, 1.0)),
                  ((0.0, -1.2, 0.0), (1.0, 0.6, 1.0)), ((0.5, 0.4, 0.0), (1.0, 1.0, 1.0)),
                  ((-0.7, 0.0, 1.1), (1.0, 1.0, 1.0)), ((1.57, 0.0, 0.0), (1.3, 1.0, 0.7))]


def tangent_scene():
    """Geometry's Tangent on spheres turned and stretched (the radial tangent about each
    object's Z axis), crossed with the normal, against the view, seen in perspective."""
    scene = camera_scene_of("tangent", TANGENT)
    for i, (rotation, scale) in enumerate(TANGENT_PLACES):
        tile = bpy.data.objects[f"tile_{i}"]
        tile.rotation_euler, tile.scale = rotation, scale
    return scene


def object_info(t, which):
    return new(t, "ShaderNodeObjectInfo").outputs[which]


OBJECT_INFO = (
    [lambda t: object_info(t, "Random")] * 6
    + [lambda t: ramp(t, object_info(t, "Random"), "LINEAR", STOPS)] * 2
    + [lambda t: object_info(t, "Color")] * 3
    + [lambda t: math_node(t, "MULTIPLY_ADD", object_info(t, "Alpha"), 0.8, 0.1)]
    + [lambda t: vector_shown(t, object_info(t, "Location"))] * 4
)


def material_index_scene():
    """Object Info's Material Index: tiles of materials of Pass Index 0 to 7, through a ramp
    and as a value, two tiles sharing one material."""
    scene = dark_grid()
    for i in range(9):
        obj = add_tile(i, "plane")
        obj.name = f"tile_{i}"
        index = min(i, 7)
        name = f"material_index_{index}"
        material = bpy.data.materials.get(name)
        if material is None:
            show = (lambda t: ramp(t, math_node(t, "MULTIPLY", object_info(t, "Material Index"), 0.125), "LINEAR",
                                   STOPS)) if index % 2 else (lambda t: math_node(t, "MULTIPLY",
                                                                                  object_info(t, "Material Index"), 0.1))
            material = emission_material(name, show)
            material.pass_index = index
        obj.data.materials.append(material)
    return scene


def view_layer_attribute(t, name, which="Color"):
    node = new(t, "ShaderNodeAttribute", attribute_type="VIEW_LAYER", attribute_name=name)
    return node.outputs[which]


VIEW_LAYER_ATTRIBUTES = [
    lambda t: view_layer_attribute(t, "tint"),
    lambda t: view_layer_attribute(t, "tint", "Fac"),
    lambda t: vector_shown(t, view_layer_attribute(t, "tint", "Vector")),
    lambda t: view_layer_attribute(t, "gain"),
    lambda t: view_layer_attribute(t, "haze"),
    lambda t: view_layer_attribute(t, "haze", "Alpha"),
    lambda t: view_layer_attribute(t, "shadowed"),
    lambda t: math_node(t, "MULTIPLY", view_layer_attribute(t, "render.resolution_x", "Fac"), 0.004),
    lambda t: view_layer_attribute(t, "missing"),
    lambda t: math_node(t, "ADD", view_layer_attribute(t, "missing", "Alpha"), 0.3),
    lambda t: view_layer_attribute(t, "flag", "Fac"),
    lambda t: math_node(t, "MULTIPLY", view_layer_attribute(t, "counts", "Fac"), 0.3),
    lambda t: view_layer_attribute(t, "counts"),
    lambda t: view_layer_attribute(t, "gain", "Alpha"),
    lambda t: view_layer_attribute(t, "name"),
    lambda t: ramp(t, view_layer_attribute(t, "gain", "Fac"), "LINEAR", STOPS),
]


def view_layer_attributes_scene():
    """Attribute nodes of the View Layer type: custom properties of the view layer (a colour,
    one that shadows the scene's), of the scene (a value, an integer array, a string, which
    is no attribute), of the World (four values: Alpha the fourth), a boolean, an RNA path
    (the scene's render.resolution_x), a name none has (zero, Alpha too); each output."""
    scene = grid_scene("view_layer_attributes", VIEW_LAYER_ATTRIBUTES)
    layer = scene.view_layers[0]
    layer["tint"] = (0.8, 0.3, 0.1)
    layer["shadowed"] = 0.9
    layer["flag"] = True
    scene["shadowed"] = 0.1
    scene["gain"] = 0.7
    scene["counts"] = [1, 0, 2]
    scene["name"] = "not a number"
    scene.world["haze"] = (0.2, 0.4, 0.6, 0.5)
    return scene


def object_index_material():
    """One material for every tile: its Object Index × 0.03, through a ramp on the odd ones
    (by the index's parity, read in the graph)."""
    def show(t):
        scaled = math_node(t, "MULTIPLY", object_info(t, "Object Index"), 0.03)
        odd = math_node(t, "FLOORED_MODULO", object_info(t, "Object Index"), 2.0)
        mix = new(t, "ShaderNodeMix", data_type="RGBA")
        t.links.new(odd, mix.inputs["Factor"])
        t.links.new(scaled, mix.inputs[6])
        t.links.new(ramp(t, scaled, "LINEAR", STOPS), mix.inputs[7])
        return mix.outputs[2]
    return emission_material("object_index", show)


def object_index_scene():
    """Object Info's Object Index (Pass Index): twelve tiles of indices 0 to 33 sharing one
    material, and four instances of a collection whose tile has index 20 (Cycles reads the
    instanced object's)."""
    scene = dark_grid()
    material = object_index_material()
    for i in range(12):
        obj = add_tile(i, "plane")
        obj.name = f"tile_{i}"
        obj.pass_index = 3 * i
        obj.data.materials.append(material)
    stamp = bpy.data.collections.new("stamp")
    scene.collection.children.link(stamp)
    bpy.ops.mesh.primitive_plane_add(size=2.0, location=(0.0, 0.0, 0.0))
    tile = bpy.context.active_object
    for collection in tile.users_collection:
        collection.objects.unlink(tile)
    stamp.objects.link(tile)
    tile.pass_index = 20
    tile.data.materials.append(material)
    bpy.context.view_layer.layer_collection.children["stamp"].exclude = True
    for i in range(12, 16):
        x = (i % GRID - (GRID - 1) / 2) * PITCH
        y = ((GRID - 1) / 2 - i // GRID) * PITCH
        empty = bpy.data.objects.new(f"stamp_{i}", None)
        empty.instance_type = "COLLECTION"
        empty.instance_collection = stamp
        empty.location = (x, y, 0.0)
        scene.collection.objects.link(empty)
    return scene


def object_info_scene():
    """Object Info: Random of differently named tiles (plain and through a ramp), their
    Object Colors and Alpha, and their Locations."""
    scene = grid_scene("object_info", OBJECT_INFO)
    colours = {8: (0.9, 0.3, 0.1, 1.0), 9: (0.2, 0.7, 0.4, 0.5), 10: (0.1, 0.2, 0.95, 0.25), 11: (0.5, 0.5, 0.5, 0.3)}
    for i, colour in colours.items():
        bpy.data.objects[f"tile_{i}"].color = colour
    names = {0: "Rock.001", 1: "Rock.002", 2: "crate", 3: "Ünïcode tile", 4: "a", 5: "tile with a long name 12345"}
    for i, name in names.items():
        bpy.data.objects[f"tile_{i}"].name = name
    return scene


def procedural_material(name, build):
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    bsdf = tree.nodes["Principled BSDF"]
    bsdf.distribution = "MULTI_GGX"
    build(tree, bsdf)
    return material


def sphere_inputs(t, bsdf):
    fac = noise(t, coords(t), Scale=3.0, Detail=4.0).outputs["Fac"]
    t.links.new(ramp(t, fac, "LINEAR", STOPS), bsdf.inputs["Base Color"])
    rough = new(t, "ShaderNodeMapRange", {"Value": fac, "From Min": 0.3, "From Max": 0.7, "To Min": 0.15, "To Max": 0.6},
                data_type="FLOAT", clamp=True)
    t.links.new(output(rough, "Result"), bsdf.inputs["Roughness"])
    metal = new(t, "ShaderNodeTexChecker", {"Scale": 3.0})
    t.links.new(metal.outputs["Fac"], bsdf.inputs["Metallic"])


def floor_inputs(t, bsdf):
    bsdf.inputs["Specular IOR Level"].default_value = 0.0
    bsdf.inputs["Roughness"].default_value = 1.0
    mix = new(t, "ShaderNodeMix", {"Factor_Float": gradient(t, "LINEAR", coords(t, "Generated")).outputs["Fac"],
                                    "A_Color": (0.7, 0.65, 0.5, 1.0), "B_Color": (0.2, 0.3, 0.5, 1.0)},
              data_type="RGBA", blend_type="MULTIPLY")
    t.links.new(output(mix, "Result_Color"), bsdf.inputs["Base Color"])


def bump(t, height, normal=None, **inputs):
    """A Bump node of `height` (a socket) with `inputs` (Distance 0.1 unless given)."""
    props = {k: inputs.pop(k) for k in list(inputs) if k[0].islower()}
    node = new(t, "ShaderNodeBump", {"Height": height, "Distance": 0.1, **inputs}, **props)
    if normal is not None:
        t.links.new(normal, node.inputs["Normal"])
    return node.outputs["Normal"]


def bumped(height, **inputs):
    """A Principled material's builder: its Normal a Bump of the socket `height(t)` gives."""
    return lambda t, b: t.links.new(bump(t, height(t), **inputs), b.inputs["Normal"])


def bumped_noise(which="Object", scale=4.0, detail=2.0, **inputs):
    return bumped(lambda t: noise(t, coords(t, which), Scale=scale, Detail=detail).outputs["Fac"], **inputs)


def metal(t, b):
    b.inputs["Metallic"].default_value, b.inputs["Roughness"].default_value = 1.0, 0.25
    bumped_noise(scale=3.0, Distance=0.15)(t, b)


def chained(t, b):
    first = bump(t, noise(t, coords(t), Scale=6.0, Detail=1.0).outputs["Fac"], Distance=0.05)
    second = bump(t, wave(t, Scale=2.0), normal=first, Distance=0.04)
    t.links.new(second, b.inputs["Normal"])


def facing_of_bump(t, b):
    normal = bump(t, noise(t, coords(t), Scale=3.0, Detail=1.0).outputs["Fac"], Distance=0.2)
    t.links.new(normal, b.inputs["Normal"])
    facing = new(t, "ShaderNodeLayerWeight", {"Blend": 0.3, "Normal": normal}).outputs["Facing"]
    t.links.new(ramp(t, facing, "LINEAR", STOPS), b.inputs["Base Color"])


def diffuse_bumped(name):
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    diffuse = new(tree, "ShaderNodeBsdfDiffuse", {"Color": (0.7, 0.6, 0.4, 1.0)})
    tree.links.new(bump(tree, voronoi(tree, "Distance", Scale=3.0), Distance=0.15), diffuse.inputs["Normal"])
    tree.links.new(diffuse.outputs[0], out.inputs["Surface"])
    return material


def uv_wave(t):
    node = new(t, "ShaderNodeTexWave", {"Scale": 3.0, "Phase Offset": 0.5})
    t.links.new(coords(t, "UV"), node.inputs["Vector"])
    return node.outputs["Fac"]


def sine_of_position(t):
    x = output(new(t, "ShaderNodeSeparateXYZ", {"Vector": new(t, "ShaderNodeNewGeometry").outputs["Position"]}), "X")
    return math_node(t, "SINE", math_node(t, "MULTIPLY", x, 6.0))


# Each tile's material (a function of its name) and shape; tile 10 is turned and stretched.
BUMP = [
    (bumped_noise(), "plane"),
    (bumped_noise(invert=True), "plane"),
    (bumped_noise(Strength=0.4, Distance=0.3), "plane"),
    (bumped_noise("Generated", scale=3.0, detail=0.0, Distance=0.3), "plane"),
    (bumped(uv_wave, Distance=0.05), "plane"),
    (bumped(sine_of_position, Distance=0.04), "plane"),
    (bumped(lambda t: texture(t, "ShaderNodeTexMagic", "Fac", True, 2.0, {"turbulence_depth": 2}), Distance=0.05),
     "plane"),
    (chained, "plane"),
    (None, "plane"),
    (metal, "plane"),
    (bumped_noise(scale=2.0, Distance=0.2), "plane"),
    (bumped_noise("Camera", scale=1.5, Distance=0.2), "plane"),
    (facing_of_bump, "plane"),
    (bumped_noise(scale=3.0, Distance=0.1), "sphere"),
    (bumped_noise(scale=4.0, detail=1.0, Distance=-0.15), "sphere"),
    (bumped(lambda t: texture(t, "ShaderNodeTexVoronoi", "Distance", True, 2.5, {"feature": "F1"}), Distance=0.2),
     "sphere"),
]


def bump_scene():
    """Bump nodes lit by a low sun: heights of noise on every coordinate, waves on UVs, the
    Position's sine, Magic, Voronoi; inverted, half strength, chained into another Bump,
    into a Diffuse BSDF, under a metal, read by Layer Weight, on a turned and stretched
    tile and on smooth spheres; seen in perspective, so the steps follow the footprint."""
    scene = cycles.new_scene()
    cycles.set_up(scene, SIZE, bounces=1)
    cycles.uniform_world(scene, (0.04, 0.04, 0.05))
    for i, (build, shape) in enumerate(BUMP):
        obj = add_tile(i, shape, segments=48)
        if i == 10:
            obj.rotation_euler, obj.scale = (0.0, 0.0, math.radians(30.0)), (0.9, 0.45, 1.0)
        name = f"bump_{i}"
        obj.data.materials.append(diffuse_bumped(name) if build is None else procedural_material(name, build))
    cycles.sun(scene, 3.0, (55.0, 0.0, 35.0), angle=math.radians(1.0))
    camera = cycles.camera(scene, (0.0, 0.0, 10.0), 0.0)
    camera.data.lens = 40.0
    return scene


def mix_material(name, fac, first, second):
    """A Mix Shader of `first` and `second` (functions of the tree giving a shader node), its
    factor from `fac` (a function of the tree giving a socket, or a number)."""
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    mix = tree.nodes.new("ShaderNodeMixShader")
    if isinstance(fac, float):
        mix.inputs["Fac"].default_value = fac
    else:
        tree.links.new(fac(tree), mix.inputs["Fac"])
    tree.links.new(first(tree).outputs[0], mix.inputs[1])
    tree.links.new(second(tree).outputs[0], mix.inputs[2])
    tree.links.new(mix.outputs[0], out.inputs["Surface"])
    return material


def mix_scene():
    """The classic: a Mix Shader of a diffuse and a glossy by Layer Weight's Facing on a
    sphere, and a floor of two diffuse colours mixed by noise."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=8)
    cycles.uniform_world(scene, (0.8, 0.85, 1.0))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=64, ring_count=32, location=(0.0, 0.0, 1.0))
    bpy.ops.object.shade_smooth()
    sphere = mix_material(
        "layered", lambda t: layer_weight(t, 0.35, "Facing"),
        lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.7, 0.15, 0.1, 1.0)}),
        lambda t: new(t, "ShaderNodeBsdfGlossy", {"Color": (0.9, 0.9, 0.9, 1.0), "Roughness": 0.2},
                      distribution="MULTI_GGX"))
    bpy.context.active_object.data.materials.append(sphere)
    bpy.ops.mesh.primitive_plane_add(size=8.0)
    floor = mix_material(
        "patchy", lambda t: noise(t, Scale=3.0, Detail=2.0).outputs["Fac"],
        lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.8, 0.8, 0.75, 1.0)}),
        lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.1, 0.2, 0.5, 1.0)}))
    bpy.context.active_object.data.materials.append(floor)
    cycles.camera(scene, (0.0, -5.5, 2.6), 72.0)
    return scene


def constant_mix_scene():
    """Mix Shaders of a constant factor of shaders no one parameter set holds: a diffuse and
    a glossy, a gold metal and a blue plastic, a glass and a diffuse; and a floor of a
    diffuse and a rough glossy. Cycles weighs both closures by the factor."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=8)
    cycles.uniform_world(scene, (0.8, 0.85, 1.0))
    spheres = [
        ("diffuse and glossy", 0.3, lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.7, 0.15, 0.1, 1.0)}),
         lambda t: new(t, "ShaderNodeBsdfGlossy", {"Color": (0.9, 0.9, 0.9, 1.0), "Roughness": 0.15},
                       distribution="MULTI_GGX")),
        ("metal and plastic", 0.5,
         lambda t: new(t, "ShaderNodeBsdfPrincipled", {"Base Color": (1.0, 0.7, 0.3, 1.0), "Metallic": 1.0,
                                                        "Roughness": 0.3}),
         lambda t: new(t, "ShaderNodeBsdfPrincipled", {"Base Color": (0.1, 0.2, 0.8, 1.0), "Roughness": 0.4})),
        ("glass and diffuse", 0.4, lambda t: new(t, "ShaderNodeBsdfGlass", {"Roughness": 0.0, "IOR": 1.45}),
         lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.2, 0.7, 0.3, 1.0)})),
    ]
    for i, (name, fac, first, second) in enumerate(spheres):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, segments=48, ring_count=24,
                                             location=(1.6 * (i - 1), 0.0, 0.7))
        bpy.ops.object.shade_smooth()
        bpy.context.active_object.data.materials.append(mix_material(name, fac, first, second))
    bpy.ops.mesh.primitive_plane_add(size=8.0)
    floor = mix_material(
        "satin floor", 0.25, lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.8, 0.8, 0.75, 1.0)}),
        lambda t: new(t, "ShaderNodeBsdfGlossy", {"Color": (0.8, 0.8, 0.8, 1.0), "Roughness": 0.35},
                      distribution="MULTI_GGX"))
    bpy.context.active_object.data.materials.append(floor)
    cycles.camera(scene, (0.0, -5.5, 2.6), 72.0)
    return scene


def spheres_on_a_floor(spheres, floor):
    """Three smooth spheres of `spheres`' materials side by side on a floor of `floor`'s."""
    for i, material in enumerate(spheres):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, segments=48, ring_count=24,
                                             location=(1.6 * (i - 1), 0.0, 0.7))
        bpy.ops.object.shade_smooth()
        bpy.context.active_object.data.materials.append(material)
    bpy.ops.mesh.primitive_plane_add(size=8.0)
    bpy.context.active_object.data.materials.append(floor)


def toon(t, colour, size, smooth, component="DIFFUSE"):
    return new(t, "ShaderNodeBsdfToon", {"Color": colour, "Size": size, "Smooth": smooth}, component=component)


def noisy_toon(t, size, smooth):
    """A Toon Diffuse whose Color is a noise texture's."""
    shader = toon(t, (1.0, 1.0, 1.0, 1.0), size, smooth)
    t.links.new(noise(t, Scale=3.0, Detail=2.0).outputs["Color"], shader.inputs["Color"])
    return shader


def toon_scene():
    """Cel shading with the Toon BSDF (an rt lobe module) under a low sun: a Toon Diffuse of
    noise colours under a Toon Glossy rim by Layer Weight's Fresnel (a mix per shading point
    by a graph), a Toon Diffuse and a Diffuse BSDF mixed by a constant, and a Toon Diffuse of
    a soft edge whose colour is noise, on a diffuse floor."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=6)
    cycles.uniform_world(scene, (0.1, 0.1, 0.12))
    spheres = [
        mix_material("cel", lambda t: layer_weight(t, 0.3, "Fresnel"), lambda t: noisy_toon(t, 0.45, 0.05),
                     lambda t: toon(t, (1.0, 1.0, 1.0, 1.0), 0.15, 0.05, "GLOSSY")),
        mix_material("half toon", 0.5, lambda t: toon(t, (1.0, 0.5, 0.1, 1.0), 0.5, 0.1),
                     lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.1, 0.3, 0.8, 1.0)})),
        shader_material("soft toon", lambda t: noisy_toon(t, 0.7, 0.3).outputs[0]),
    ]
    spheres_on_a_floor(spheres, cycles.diffuse("floor", (0.6, 0.6, 0.6)))
    cycles.sun(scene, 3.0, (50.0, 0.0, 40.0), angle=math.radians(1.0))
    cycles.camera(scene, (0.0, -5.5, 2.6), 72.0)
    return scene


def node_group(name, inputs, build):
    """A shader node group of inputs `inputs` ((name, socket type, default)) and one Shader
    output, which `build(tree, group_input)` gives."""
    group = bpy.data.node_groups.new(name, "ShaderNodeTree")
    for key, kind, default in inputs:
        socket = group.interface.new_socket(key, in_out="INPUT", socket_type=kind)
        socket.default_value = default
    group.interface.new_socket("Shader", in_out="OUTPUT", socket_type="NodeSocketShader")
    group_input = group.nodes.new("NodeGroupInput")
    group_output = group.nodes.new("NodeGroupOutput")
    group.links.new(build(group, group_input), group_output.inputs["Shader"])
    return group


def grouped(t, group, **values):
    """A Group node of `group` in tree `t`, its inputs' values set."""
    node = t.nodes.new("ShaderNodeGroup")
    node.node_tree = group
    for key, value in values.items():
        node.inputs[key.replace("_", " ")].default_value = value
    return node


def painted_metal(t, gi):
    bsdf = new(t, "ShaderNodeBsdfPrincipled", {"Metallic": 1.0}, distribution="MULTI_GGX")
    t.links.new(gi.outputs["Base Color"], bsdf.inputs["Base Color"])
    t.links.new(gi.outputs["Roughness"], bsdf.inputs["Roughness"])
    return bsdf.outputs[0]


def cel_mix(t, gi):
    diffuse = new(t, "ShaderNodeBsdfDiffuse")
    t.links.new(gi.outputs["Color"], diffuse.inputs["Color"])
    glossy = new(t, "ShaderNodeBsdfGlossy", {"Color": (0.9, 0.9, 0.9, 1.0), "Roughness": 0.15},
                 distribution="MULTI_GGX")
    mix = t.nodes.new("ShaderNodeMixShader")
    t.links.new(layer_weight(t, 0.35, "Facing"), mix.inputs["Fac"])
    t.links.new(diffuse.outputs[0], mix.inputs[1])
    t.links.new(glossy.outputs[0], mix.inputs[2])
    return mix.outputs[0]


def checkered(t, gi):
    """A Principled BSDF of checker colours made inside the group, its Roughness the group's input."""
    bsdf = new(t, "ShaderNodeBsdfPrincipled", distribution="MULTI_GGX")
    checker = new(t, "ShaderNodeTexChecker", {"Scale": 4.0, "Color1": (0.8, 0.7, 0.2, 1.0),
                                              "Color2": (0.1, 0.3, 0.6, 1.0)})
    t.links.new(checker.outputs["Color"], bsdf.inputs["Base Color"])
    t.links.new(gi.outputs["Roughness"], bsdf.inputs["Roughness"])
    return bsdf.outputs[0]


def node_groups_scene():
    """Shaders inside node groups, as asset libraries ship them: a metal group whose colour a
    noise outside drives through its input, a group of a Diffuse and a Glossy mixed by Layer
    Weight inside it, a group holding another (checker colours made inside, the roughness
    passed through both), and a floor of a Diffuse BSDF group left at its input's default."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=6)
    cycles.uniform_world(scene, (0.8, 0.85, 1.0))
    metal = node_group("painted metal", [("Base Color", "NodeSocketColor", (0.5, 0.5, 0.5, 1.0)),
                                         ("Roughness", "NodeSocketFloat", 0.5)], painted_metal)
    cel = node_group("cel", [("Color", "NodeSocketColor", (0.8, 0.8, 0.8, 1.0))], cel_mix)
    checker = node_group("checkered", [("Roughness", "NodeSocketFloat", 0.5)], checkered)
    wrapper = node_group("wrapper", [("Roughness", "NodeSocketFloat", 0.5)],
                         lambda t, gi: t.links.new(gi.outputs["Roughness"], grouped(t, checker).inputs["Roughness"])
                         .to_node.outputs[0])
    matte = node_group("matte", [("Color", "NodeSocketColor", (0.2, 0.6, 0.3, 1.0))],
                       lambda t, gi: t.links.new(gi.outputs["Color"], new(t, "ShaderNodeBsdfDiffuse").inputs["Color"])
                       .to_node.outputs[0])

    def metal_of_noise(t):
        node = grouped(t, metal, Roughness=0.3)
        t.links.new(noise(t, Scale=3.0, Detail=2.0).outputs["Color"], node.inputs["Base Color"])
        return node.outputs[0]

    spheres = [
        shader_material("grouped metal", metal_of_noise),
        shader_material("grouped mix", lambda t: grouped(t, cel, Color=(0.7, 0.15, 0.1, 1.0)).outputs[0]),
        shader_material("nested groups", lambda t: grouped(t, wrapper, Roughness=0.2).outputs[0]),
    ]
    spheres_on_a_floor(spheres, shader_material("grouped floor", lambda t: grouped(t, matte).outputs[0]))
    cycles.camera(scene, (0.0, -5.5, 2.6), 72.0)
    return scene


def add_material(name, first, second):
    """An Add Shader of `first` and `second` (functions of the tree giving a shader node)."""
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    add = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(first(tree).outputs[0], add.inputs[0])
    tree.links.new(second(tree).outputs[0], add.inputs[1])
    tree.links.new(add.outputs[0], out.inputs["Surface"])
    return material


def add_shader_scene():
    """Add Shaders of two BSDFs, as older tutorials build materials: a Diffuse and a Glossy, a
    Toon Diffuse and a Toon Glossy (cel shading's classic), a Principled plastic and a Sheen,
    and a floor of a dim Diffuse and a dim rough Glossy, under a sun and a dim sky. Cycles adds
    the closures (past 1 where they sum so)."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=6)
    cycles.uniform_world(scene, (0.25, 0.27, 0.3))
    spheres = [
        add_material("diffuse plus glossy", lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.6, 0.1, 0.05, 1.0)}),
                     lambda t: new(t, "ShaderNodeBsdfGlossy", {"Color": (0.5, 0.5, 0.5, 1.0), "Roughness": 0.2},
                                   distribution="MULTI_GGX")),
        add_material("toon plus toon", lambda t: toon(t, (0.2, 0.4, 0.9, 1.0), 0.5, 0.05),
                     lambda t: toon(t, (0.8, 0.8, 0.8, 1.0), 0.1, 0.02, "GLOSSY")),
        add_material("plastic plus sheen",
                     lambda t: new(t, "ShaderNodeBsdfPrincipled", {"Base Color": (0.1, 0.5, 0.2, 1.0), "Roughness": 0.4},
                                   distribution="MULTI_GGX"),
                     lambda t: new(t, "ShaderNodeBsdfSheen", {"Color": (0.9, 0.8, 0.6, 1.0), "Roughness": 0.3})),
    ]
    floor = add_material("satin floor", lambda t: new(t, "ShaderNodeBsdfDiffuse", {"Color": (0.4, 0.4, 0.38, 1.0)}),
                         lambda t: new(t, "ShaderNodeBsdfGlossy", {"Color": (0.3, 0.3, 0.3, 1.0), "Roughness": 0.35},
                                       distribution="MULTI_GGX"))
    spheres_on_a_floor(spheres, floor)
    cycles.sun(scene, 2.0, (50.0, 0.0, 40.0), angle=math.radians(1.0))
    cycles.camera(scene, (0.0, -5.5, 2.6), 72.0)
    return scene


def light_path_scene():
    """Light Path tricks: a lamp sphere that shows red to the camera but lights the world
    green (Is Camera Ray into a Mix), above a floor whose colour is bright only where a
    diffuse bounce sees it (Is Diffuse Ray) and a glossy ball that darkens with Ray Length."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=6)
    cycles.uniform_world(scene, (0.05, 0.05, 0.05))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, segments=48, ring_count=24, location=(-0.8, 0.3, 1.6))
    bpy.ops.object.shade_smooth()
    lamp = bpy.data.materials.new("trick lamp")
    tree = lamp.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    camera_ray = new(tree, "ShaderNodeLightPath").outputs["Is Camera Ray"]
    colour = new(tree, "ShaderNodeMix", {"Factor_Float": camera_ray, "A_Color": (0.2, 1.0, 0.3, 1.0),
                                         "B_Color": (1.0, 0.1, 0.1, 1.0)}, data_type="RGBA")
    emission = new(tree, "ShaderNodeEmission", {"Color": output(colour, "Result_Color"), "Strength": 6.0})
    tree.links.new(emission.outputs[0], out.inputs["Surface"])
    bpy.context.active_object.data.materials.append(lamp)
    bpy.ops.mesh.primitive_plane_add(size=8.0)
    floor = procedural_material("diffuse seen", lambda t, b: t.links.new(
        output(new(t, "ShaderNodeMix", {"Factor_Float": new(t, "ShaderNodeLightPath").outputs["Is Diffuse Ray"],
                                        "A_Color": (0.3, 0.3, 0.3, 1.0), "B_Color": (0.9, 0.8, 0.2, 1.0)},
                   data_type="RGBA"), "Result_Color"), b.inputs["Base Color"]))
    bpy.context.active_object.data.materials.append(floor)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, segments=48, ring_count=24, location=(0.9, -0.2, 0.7))
    bpy.ops.object.shade_smooth()
    ball = procedural_material("far is dark", lambda t, b: t.links.new(
        math_node(t, "DIVIDE", 1.5, new(t, "ShaderNodeLightPath").outputs["Ray Length"]), b.inputs["Metallic"]))
    bpy.context.active_object.data.materials.append(ball)
    cycles.camera(scene, (0.0, -5.5, 2.6), 72.0)
    return scene


def depth_colour(tree, depth):
    """A colour of Light Path's depth output `depth`: 0 light grey, 1 pink, 2 and more red
    (a Map Range of the depth into each channel)."""
    count = new(tree, "ShaderNodeLightPath").outputs[depth]
    channel = [new(tree, "ShaderNodeMapRange", {"Value": count, "From Min": 0.0, "From Max": 2.0,
                                                "To Min": low, "To Max": high}).outputs["Result"]
               for low, high in ((0.8, 0.9), (0.8, 0.2), (0.8, 0.05))]
    return rgb(tree, *channel)


def light_path_depths_scene():
    """Light Path's per-kind depths (Diffuse, Glossy, Transmission Depth), each a colour: a
    diffuse floor coloured by its Diffuse Depth, two mirror balls facing each other coloured
    by their Glossy Depth (their reflections in each other count up), and a glass ball in
    front whose colour and the floor's seen through it follow Transmission Depth."""
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=6)
    cycles.uniform_world(scene, (1.0, 1.0, 1.0))
    bpy.ops.mesh.primitive_plane_add(size=10.0)
    floor = procedural_material("by diffuse depth", lambda t, b: t.links.new(
        depth_colour(t, "Diffuse Depth"), b.inputs["Base Color"]))
    bpy.context.active_object.data.materials.append(floor)
    for x in (-1.1, 1.1):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, segments=48, ring_count=24, location=(x, 0.6, 0.8))
        bpy.ops.object.shade_smooth()
        mirror = procedural_material(f"by glossy depth {x}", lambda t, b: (
            t.links.new(depth_colour(t, "Glossy Depth"), b.inputs["Base Color"]),
            setattr(b.inputs["Metallic"], "default_value", 1.0),
            setattr(b.inputs["Roughness"], "default_value", 0.05)))
        bpy.context.active_object.data.materials.append(mirror)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.55, segments=48, ring_count=24, location=(0.0, -1.0, 0.55))
    bpy.ops.object.shade_smooth()
    glass = procedural_material("by transmission depth", lambda t, b: (
        t.links.new(depth_colour(t, "Transmission Depth"), b.inputs["Base Color"]),
        setattr(b.inputs["Transmission Weight"], "default_value", 1.0),
        setattr(b.inputs["Roughness"], "default_value", 0.15)))
    bpy.context.active_object.data.materials.append(glass)
    cycles.camera(scene, (0.0, -5.5, 2.2), 74.0)
    return scene


def material_scene():
    scene = cycles.new_scene()
    cycles.set_up(scene, 64, bounces=8)
    cycles.uniform_world(scene, (0.8, 0.85, 1.0))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=64, ring_count=32, location=(0.0, 0.0, 1.0))
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(procedural_material("speckled", sphere_inputs))
    bpy.ops.mesh.primitive_plane_add(size=8.0)
    bpy.context.active_object.data.materials.append(procedural_material("graded floor", floor_inputs))
    cycles.camera(scene, (0.0, -5.5, 2.6), 72.0)
    return scene


SCENES = {
    "graph_noise": lambda: grid_scene("noise", NOISE),
    "graph_math": lambda: grid_scene("math", MATH),
    "graph_color": lambda: grid_scene("color", COLOR),
    "graph_vector": lambda: grid_scene("vector", VECTOR),
    "graph_convert": lambda: grid_scene("convert", CONVERT),
    "graph_voronoi": lambda: grid_scene("voronoi", VORONOI),
    "graph_wave": lambda: grid_scene("wave", WAVE),
    "graph_magic": lambda: grid_scene("magic", MAGIC),
    "graph_brick": lambda: grid_scene("brick", BRICK),
    "graph_white_noise": lambda: grid_scene("white_noise", WHITE_NOISE),
    "graph_noise_dimensions": lambda: grid_scene("noise_dimensions", NOISE_DIMENSIONS),
    "graph_spectrum": lambda: grid_scene("spectrum", SPECTRUM),
    "graph_object_info": object_info_scene,
    "graph_camera": camera_scene,
    "graph_shading": lambda: grid_scene("shading", SHADING, shape="sphere"),
    "graph_material": material_scene,
    "graph_mix": mix_scene,
    "graph_mix_constant": constant_mix_scene,
    "graph_light_path": light_path_scene,
    "graph_light_path_depths": light_path_depths_scene,
    "graph_bump": bump_scene,
    "graph_map_range": lambda: grid_scene("map_range", MAP_RANGE),
    "graph_voronoi_dimensions": lambda: grid_scene("voronoi_dimensions", VORONOI_DIMENSIONS),
    "graph_emission_strength": lambda: grid_scene("emission_strength", EMISSION_STRENGTH, make=shader_material),
    "graph_camera_data": camera_data_scene,
    "graph_vector_transform": vector_transform_scene,
    "graph_normal_node": lambda: camera_scene_of("normal_node", NORMAL_NODE),
    "graph_tangent": tangent_scene,
    "graph_material_index": material_index_scene,
    "graph_toon": toon_scene,
    "graph_node_groups": node_groups_scene,
    "graph_object_index": object_index_scene,
    "graph_add_shader": add_shader_scene,
    "graph_view_layer_attributes": view_layer_attributes_scene,
}


if __name__ == "__main__":
    cycles.make(__doc__, 1024, SCENES)
