"""A material's shader node graph for rt, for rt_export.py: the nodes that drive a
shader's inputs (through node groups, reroutes and muted nodes, as Blender evaluates
them) written as `extras.rt_node_graph` of the glTF material, format version 1
(docs/shader-nodes.md). rt compiles it to a node program its GPU interpreter runs at
every shading point, as Cycles' SVM does.

A socket is driven by a graph when everything that feeds it is a node rt evaluates
(EVALUATED, with the settings of EVALUATED_SETTINGS) and no image: image textures keep
rt_export's own path (followed into texture slots, or baked). Anything else stays on
that path too, which warns and names the node.
"""

from .rt_node_groups import resolve, unwrap

FORMAT_VERSION = 1
# The attributes the exporter makes of Geometry's Random Per Island, Parametric and
# Pointiness (rt_attributes), and the output of the Attribute node each is read through.
ISLAND = ".rt.random_per_island"
PARAMETRIC = ".rt.parametric"
POINTINESS = ".rt.pointiness"
MADE_ATTRIBUTES = {
    "Random Per Island": (ISLAND, "Fac", "VALUE"),
    "Parametric": (PARAMETRIC, "Vector", "VECTOR"),
    "Pointiness": (POINTINESS, "Fac", "VALUE"),
}

# Node types rt evaluates, and their outputs in rt's register order (crates/rt/src/asset/node_kinds.rs
# declares the same; a test checks both).
EVALUATED = {
    "VALUE": ("Value",),
    "RGB": ("Color",),
    "TEX_COORD": ("Generated", "Normal", "UV", "Object", "Camera", "Window", "Reflection"),
    "NEW_GEOMETRY": ("Position", "Normal", "True Normal", "Incoming", "Backfacing"),
    "LIGHT_PATH": ("Is Camera Ray", "Is Shadow Ray", "Is Diffuse Ray", "Is Glossy Ray", "Is Singular Ray", "Is Reflection Ray", "Is Transmission Ray", "Is Volume Scatter Ray", "Ray Length", "Ray Depth", "Diffuse Depth", "Glossy Depth", "Transmission Depth"),  # noqa: E501
    "MATH": ("Value",),
    "VECT_MATH": ("Vector", "Value"),
    "MIX": ("Result",),
    "MIX_RGB": ("Color",),
    "MAP_RANGE": ("Result",),
    "CLAMP": ("Result",),
    "INVERT": ("Color",),
    "VALTORGB": ("Color", "Alpha"),
    "CURVE_RGB": ("Color",),
    "CURVE_VEC": ("Vector",),
    "CURVE_FLOAT": ("Value",),
    "RGBTOBW": ("Val",),
    "SEPXYZ": ("X", "Y", "Z"),
    "SEPARATE_COLOR": ("Red", "Green", "Blue"),
    "COMBXYZ": ("Vector",),
    "COMBINE_COLOR": ("Color",),
    "MAPPING": ("Vector",),
    "TEX_NOISE": ("Fac", "Color"),
    "TEX_CHECKER": ("Color", "Fac"),
    "TEX_GRADIENT": ("Color", "Fac"),
    "LAYER_WEIGHT": ("Fresnel", "Facing"),
    "FRESNEL": ("Fac",),
    "HUE_SAT": ("Color",),
    "BRIGHTCONTRAST": ("Color",),
    "GAMMA": ("Color",),
    "TEX_WHITE_NOISE": ("Value", "Color"),
    "TEX_VORONOI": ("Distance", "Color", "Position", "W", "Radius"),
    "TEX_WAVE": ("Color", "Fac"),
    "TEX_MAGIC": ("Color", "Fac"),
    "TEX_BRICK": ("Color", "Fac"),
    "OBJECT_INFO": ("Location", "Color", "Alpha", "Random", "Object Index"),
    "CAMERA": ("View Vector", "View Z Depth", "View Distance"),
    "VECT_TRANSFORM": ("Vector",),
    "BLACKBODY": ("Color",),
    "WAVELENGTH": ("Color",),
    "BUMP": ("Normal",),
    "ATTRIBUTE": ("Color", "Vector", "Fac", "Alpha"),
    "VERTEX_COLOR": ("Color", "Alpha"),
}

BLEND_TYPES = {"MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE", "ADD", "OVERLAY", "SOFT_LIGHT",
               "LINEAR_LIGHT", "DIFFERENCE", "EXCLUSION", "SUBTRACT", "DIVIDE", "HUE", "SATURATION", "VALUE", "COLOR"}
VECTOR_MATH_OPERATIONS = {"ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT",
                          "REFLECT", "REFRACT", "FACEFORWARD", "DOT_PRODUCT", "DISTANCE", "LENGTH", "SCALE",
                          "NORMALIZE", "ABSOLUTE", "MINIMUM", "MAXIMUM", "FLOOR", "CEIL", "FRACTION", "MODULO",
                          "WRAP", "SNAP", "SINE", "COSINE", "TANGENT", "POWER", "SIGN"}
# The settings each node type writes, and the values of them rt evaluates (None: any).
EVALUATED_SETTINGS = {
    "MATH": {"operation": None, "use_clamp": None},
    "VECT_MATH": {"operation": VECTOR_MATH_OPERATIONS},
    "MIX": {"data_type": {"FLOAT", "VECTOR", "RGBA"}, "blend_type": None, "clamp_factor": None,
            "clamp_result": None, "factor_mode": None},
    "MIX_RGB": {"blend_type": BLEND_TYPES, "use_clamp": None},
    "MAP_RANGE": {"data_type": {"FLOAT", "FLOAT_VECTOR"}, "interpolation_type": None, "clamp": None},
    "CLAMP": {"clamp_type": None},
    "VALTORGB": {},
    "CURVE_RGB": {},
    "CURVE_VEC": {},
    "CURVE_FLOAT": {},
    "SEPARATE_COLOR": {"mode": None},
    "COMBINE_COLOR": {"mode": None},
    "TEX_WHITE_NOISE": {"noise_dimensions": None},
    "TEX_VORONOI": {"voronoi_dimensions": None, "feature": None, "distance": None, "normalize": None},
    "TEX_WAVE": {"wave_type": None, "bands_direction": None, "rings_direction": None, "wave_profile": None},
    "TEX_MAGIC": {"turbulence_depth": None},
    "TEX_BRICK": {"offset": None, "offset_frequency": None, "squash": None, "squash_frequency": None},
    "MAPPING": {"vector_type": None},
    "VECT_TRANSFORM": {"vector_type": None, "convert_from": None, "convert_to": None},
    "TEX_NOISE": {"noise_dimensions": None, "noise_type": None, "normalize": None},
    "TEX_GRADIENT": {"gradient_type": None},
    "BUMP": {"invert": None},
    "ATTRIBUTE": {"attribute_type": {"GEOMETRY"}, "attribute_name": None},
    "VERTEX_COLOR": {"layer_name": None},
}
MAP_RANGE_VECTOR_SOCKETS = {(False, "Vector"): "Value", (False, "From_Min_FLOAT3"): "From Min",
                            (False, "From_Max_FLOAT3"): "From Max", (False, "To_Min_FLOAT3"): "To Min",
                            (False, "To_Max_FLOAT3"): "To Max", (False, "Steps_FLOAT3"): "Steps",
                            (True, "Vector"): "Result"}
# Texture nodes' unlinked Vector, as in Cycles: the Generated coordinates (White Noise's is 0).
DEFAULT_VECTOR = {"TEX_NOISE": ("TEX_COORD", "Generated"), "TEX_CHECKER": ("TEX_COORD", "Generated"),
                  "TEX_GRADIENT": ("TEX_COORD", "Generated"), "TEX_VORONOI": ("TEX_COORD", "Generated"),
                  "TEX_WAVE": ("TEX_COORD", "Generated"), "TEX_MAGIC": ("TEX_COORD", "Generated"),
                  "TEX_BRICK": ("TEX_COORD", "Generated")}
# Entries of a ramp's table, at 0, 1/256, ..., 1, as Cycles bakes it.
RAMP_TABLE_SIZE = 257


class Unevaluated(Exception):
    """A node, or a setting of one, that rt does not evaluate."""


# The scene and view layer whose View Layer attributes graphs read (rt_export sets them for
# each export): Cycles folds those attributes to constants when it syncs a shader.
VIEW_LAYER = {"scene": None, "layer": None}


def rgba_of(value):
    """A property's value as RGBA, as Blender's `find_property_rgba` converts it: a number or
    boolean v is (v, v, v, 1), an array of 1 to 4 numbers fills (0, 0, 0, 1); else None."""
    if isinstance(value, (bool, int, float)):
        v = float(value)
        return [v, v, v, 1.0]
    try:
        items = list(value)
    except TypeError:
        return None
    if not 1 <= len(items) <= 4 or not all(isinstance(i, (bool, int, float)) for i in items):
        return None
    return [float(i) for i in items] + [0.0, 0.0, 0.0, 1.0][len(items):]


def property_rgba(owner, name):
    """`owner`'s custom property `name`, else the property at RNA path `name`, as RGBA."""
    if owner is None:
        return None
    try:
        return rgba_of(owner[name])
    except (KeyError, TypeError):
        pass
    try:
        return rgba_of(owner.path_resolve(name))
    except (ValueError, TypeError):
        return None


def view_layer_attribute(name):
    """An Attribute node's View Layer attribute `name` as Blender looks it up: the view layer,
    then the scene, then its World; (0, 0, 0, 0) where none has it."""
    scene, layer = VIEW_LAYER["scene"], VIEW_LAYER["layer"]
    for owner in (layer, scene, scene.world if scene is not None else None):
        found = property_rgba(owner, name)
        if found is not None:
            return found
    return [0.0, 0.0, 0.0, 0.0]


def view_layer_constant(node, socket, to_type):
    """What an Attribute node of the View Layer type gives socket `to_type` through output
    `socket`, as Cycles' resolve_view_layer_attributes folds it: Fac the mean of R, G and B,
    Alpha the fourth value, Color and Vector the first three (their mean into a value)."""
    x, y, z, w = view_layer_attribute(node.attribute_name)
    scalar = w if socket.identifier == "Alpha" else (x + y + z) / 3.0
    triple = [x, y, z] if socket.identifier in {"Color", "Vector"} else [scalar] * 3
    if to_type == "VALUE":
        return {"value": scalar}
    return {"value": triple + [1.0] if to_type == "RGBA" else triple}


def socket_type(socket):
    return socket.type if socket.type in {"VECTOR", "RGBA"} else "VALUE"


def socket_key(socket):
    """The name rt knows a socket by: its identifier, stable across Blender's versions (whose
    names change: Fac became Factor), the Mix node's without the data type's suffix, a vector
    Map Range's as the float one's."""
    key = socket.identifier
    if socket.node.type == "MIX":
        for suffix in ("_Float", "_Vector", "_Color"):
            key = key.removesuffix(suffix)
    if socket.node.type == "MAP_RANGE":
        # A Map Range of vectors has the float one's sockets (From_Min_FLOAT3 is From Min).
        key = MAP_RANGE_VECTOR_SOCKETS.get((socket.is_output, key), key)
    return key


def numbers(value):
    try:
        return [float(v) for v in value]
    except TypeError:
        return float(value)


def settings_of(node):
    wanted = EVALUATED_SETTINGS.get(node.type, {})
    out = {}
    for key, allowed in wanted.items():
        if not hasattr(node, key):
            continue
        value = getattr(node, key)
        if allowed is not None and value not in allowed:
            raise Unevaluated(f"{node.name} ({node.type}) with {key} {value}")
        out[key] = value if isinstance(value, (bool, str)) else float(value)
    if node.type in {"VALUE", "RGB"}:
        out["value"] = numbers(node.outputs[0].default_value)
    if node.type in {"CURVE_RGB", "CURVE_VEC", "CURVE_FLOAT"}:
        out.update(curve_settings(node))
    if node.type == "VALTORGB":
        ramp = node.color_ramp
        out["interpolation"] = ramp.interpolation
        out["table"] = [list(ramp.evaluate(i / (RAMP_TABLE_SIZE - 1))) for i in range(RAMP_TABLE_SIZE)]
    return out


def curve_settings(node):
    """A curves node's range and table, as Cycles bakes them: RAMP_TABLE_SIZE entries across
    the lowest to the highest x of its curves' points, each channel through its curve (an RGB
    Curves' through the combined curve C first)."""
    mapping = node.mapping
    mapping.initialize()
    mapping.update()
    curves = list(mapping.curves)
    used = curves[:1] if node.type == "CURVE_FLOAT" else curves[:4 if node.type == "CURVE_RGB" else 3]
    lo = min(c.points[0].location[0] for c in used)
    hi = max(c.points[-1].location[0] for c in used)
    table = []
    for i in range(RAMP_TABLE_SIZE):
        t = lo + i / (RAMP_TABLE_SIZE - 1) * (hi - lo)
        if node.type == "CURVE_FLOAT":
            v = mapping.evaluate(curves[0], t)
            table.append([v, v, v, 1.0])
            continue
        x = mapping.evaluate(curves[3], t) if node.type == "CURVE_RGB" else t
        table.append([mapping.evaluate(curves[c], x if node.type == "CURVE_RGB" else t) for c in range(3)] + [1.0])
    return {"extend": mapping.extend, "range": [lo, hi], "table": table}


class GraphWriter:
    """The graph feeding some sockets, as rt reads it; raises Unevaluated."""

    def __init__(self, material=None):
        # Object Info's Material Index: the Pass Index of the material whose graph this is.
        self.material_index = float(material.pass_index) if material is not None else 0.0
        self.nodes = []
        self.index = {}
        self.heights = 0  # how many Bump nodes' Height the node being added feeds

    def add(self, node, groups):
        key = (tuple(g.name for g in groups), node.name)
        if key in self.index:
            return self.index[key]
        if node.type not in EVALUATED:
            raise Unevaluated(f"{node.name} ({node.type})")
        if node.type == "BUMP" and (self.heights or node.inputs["Filter Width"].is_linked):
            # rt reads a Bump's height a step away with a constant width, and not a Bump's in another's.
            raise Unevaluated(f"{node.name} (BUMP) in another Bump's Height, or its Filter Width linked")
        entry = {"name": node.name, "type": node.type, "settings": settings_of(node), "inputs": {}}
        self.index[key] = len(self.nodes)
        self.nodes.append(entry)
        for socket in node.inputs:
            if not socket.enabled:
                continue
            height = node.type == "BUMP" and socket.identifier == "Height"
            self.heights += height
            value = self.input(socket, groups)
            self.heights -= height
            if value is None and node.type in DEFAULT_VECTOR and socket.identifier == "Vector":
                kind, output = DEFAULT_VECTOR[node.type]
                value = {"link": [self.default_vector(kind), output], "from": "VECTOR", "to": "VECTOR"}
            if value is not None:
                entry["inputs"][socket_key(socket)] = value
        return self.index[key]

    def default_vector(self, kind):
        key = ((), f"rt: default {kind}")
        if key not in self.index:
            self.index[key] = len(self.nodes)
            self.nodes.append({"name": key[1], "type": kind, "settings": {}, "inputs": {}})
        return self.index[key]

    def input(self, socket, groups, to_type=None):
        """What feeds input `socket`: its value, a link, or None (an unlinked hidden vector).
        A socket of a node inside a group (rt_node_groups) carries the groups around it."""
        socket, groups = unwrap(socket, groups)
        to_type = to_type or socket_type(socket)
        kind, found = resolve(socket, groups)
        if kind == "link":
            return self.output(found.from_socket.socket, found.from_socket.groups, to_type)
        if found is None:
            # A group with no Group Output gives nothing.
            return {"value": 0.0}
        if found.hide_value or not hasattr(found, "default_value"):
            return None
        return {"value": numbers(found.default_value)}

    def vector_math(self, operation, a, b=None):
        """A Vector Math node of rt's own on what feeds `a` (and `b`); its index."""
        inputs = {"Vector": a} if b is None else {"Vector": a, "Vector_001": b}
        self.nodes.append({"name": f"rt {operation.lower()} {len(self.nodes)}", "type": "VECT_MATH",
                           "settings": {"operation": operation}, "inputs": inputs})
        return len(self.nodes) - 1

    def normal_node(self, node, socket, groups, to_type):
        """The Normal node as Cycles' svm_node_normal, in Vector Math nodes: its direction
        (its output's own value) normalised, and the dot product of that with its input
        normalised."""
        direction = self.vector_math("NORMALIZE", {"value": numbers(node.outputs["Normal"].default_value)})
        if socket.identifier == "Normal":
            return {"link": [direction, "Vector"], "from": "VECTOR", "to": to_type}
        normal = self.input(node.inputs["Normal"], groups, "VECTOR")
        normalised = self.vector_math("NORMALIZE", normal)
        dot = self.vector_math("DOT_PRODUCT", {"link": [normalised, "Vector"], "from": "VECTOR", "to": "VECTOR"},
                               {"link": [direction, "Vector"], "from": "VECTOR", "to": "VECTOR"})
        return {"link": [dot, "Value"], "from": "VALUE", "to": to_type}

    def own_node(self, kind, settings, inputs):
        """A node of rt's own (not in the Blender tree); its index."""
        self.nodes.append({"name": f"rt {kind.lower()} {len(self.nodes)}", "type": kind, "settings": settings,
                           "inputs": inputs})
        return len(self.nodes) - 1

    def tangent(self, to_type):
        """Geometry's Tangent as Cycles' `primitive_tangent` makes it on a mesh: the tangent of
        circles about the object's Z axis through the Generated coordinates, (−(y − ½), x − ½, 0),
        taken to the world as a normal is, then made perpendicular to the shading normal N as
        N × normalize(that × N)."""
        key = ((), "rt tangent")
        if key not in self.index:
            link = lambda index, output, kind: {"link": [index, output], "from": kind, "to": kind}  # noqa: E731
            coords = self.own_node("TEX_COORD", {}, {})
            xyz = self.own_node("SEPXYZ", {}, {"Vector": link(coords, "Generated", "VECTOR")})
            minus = {"operation": "SUBTRACT", "use_clamp": False}
            x = self.own_node("MATH", minus, {"Value": link(xyz, "X", "VALUE"), "Value_001": {"value": 0.5}})
            y = self.own_node("MATH", minus, {"Value": {"value": 0.5}, "Value_001": link(xyz, "Y", "VALUE")})
            about_z = self.own_node("COMBXYZ", {}, {"X": link(y, "Value", "VALUE"), "Y": link(x, "Value", "VALUE"),
                                                    "Z": {"value": 0.0}})
            world = self.own_node("VECT_TRANSFORM", {"vector_type": "NORMAL", "convert_from": "OBJECT",
                                                     "convert_to": "WORLD"}, {"Vector": link(about_z, "Vector", "VECTOR")})
            normal = link(self.own_node("NEW_GEOMETRY", {}, {}), "Normal", "VECTOR")
            across = self.vector_math("CROSS_PRODUCT", link(world, "Vector", "VECTOR"), normal)
            unit = self.vector_math("NORMALIZE", link(across, "Vector", "VECTOR"))
            self.index[key] = self.vector_math("CROSS_PRODUCT", normal, link(unit, "Vector", "VECTOR"))
        return {"link": [self.index[key], "Vector"], "from": "VECTOR", "to": to_type}

    def made_attribute(self, what, name, output, from_type, to_type):
        """Geometry's Random Per Island, Parametric or Pointiness (`what`): an Attribute node of
        rt's own reading attribute `name`, which the exporter computes per face, corner or
        point (rt_attributes)."""
        key = ((), f"rt {what.lower()}")
        if key not in self.index:
            self.index[key] = len(self.nodes)
            self.nodes.append({"name": key[1], "type": "ATTRIBUTE", "inputs": {},
                               "settings": {"attribute_type": "GEOMETRY", "attribute_name": name}})
        return {"link": [self.index[key], output], "from": from_type, "to": to_type}

    def product(self, a, b):
        """A node of rt's own multiplying what feeds `a` and `b` (as colours): an emission's
        colour and strength, both driven."""
        vector = [{**x, "to": "VECTOR"} if "link" in x else x for x in (a, b)]
        return {"link": [self.vector_math("MULTIPLY", *vector), "Vector"], "from": "VECTOR", "to": "RGBA"}

    def output(self, socket, groups, to_type):
        """What output `socket` (reached through `groups`, past reroutes and into and out of
        groups by rt_node_groups.resolve) gives."""
        node = socket.node
        if node.mute:
            for link in node.internal_links:
                if link.to_socket == socket:
                    return self.input(link.from_socket, groups, to_type)
            return {"value": 0.0}
        if node.type == "GROUP_INPUT":
            raise Unevaluated(f"{node.name} (GROUP_INPUT) outside a group")
        if node.type == "NORMAL":
            return self.normal_node(node, socket, groups, to_type)
        if node.type == "ATTRIBUTE" and node.attribute_type == "VIEW_LAYER":
            return view_layer_constant(node, socket, to_type)
        if node.type == "OBJECT_INFO" and socket.identifier == "Material Index":
            return {"value": self.material_index}
        if node.type == "NEW_GEOMETRY" and socket.identifier == "Tangent":
            return self.tangent(to_type)
        if node.type == "NEW_GEOMETRY" and socket.identifier in MADE_ATTRIBUTES:
            return self.made_attribute(socket.identifier, *MADE_ATTRIBUTES[socket.identifier], to_type)
        if node.type in EVALUATED and socket_key(socket) not in EVALUATED[node.type]:
            raise Unevaluated(f"{node.name} ({node.type}) output {socket.name}")
        index = self.add(node, groups)
        return {"link": [index, socket_key(socket)], "from": socket_type(socket), "to": to_type}
