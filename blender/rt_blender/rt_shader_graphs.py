"""Which inputs of a material's shaders (and of a World's Background) a node graph rt
evaluates drives, and those graphs, for rt_export.py: a Principled's or Diffuse BSDF's
inputs, an Emission's, a Mix Shader's factor with its two shaders, a Background's colour and
strength. The graphs themselves are written by rt_node_graph.GraphWriter.
"""

import json
import os

from .rt_node_graph import FORMAT_VERSION, GraphWriter, Unevaluated
from .rt_node_groups import linked_node

# rt's lobe modules (crates/rt/src/scene/lobe), by the Blender node type each renders: the
# registry's table, which a test of rt keeps equal to it.
with open(os.path.join(os.path.dirname(__file__), "rt_lobes.json"), encoding="utf-8") as table:
    LOBES = {lobe["node"]: lobe for lobe in json.load(table)["lobes"]}

# Shader inputs a graph can drive: rt's material input, the socket's type there.
TARGETS = {
    "BSDF_PRINCIPLED": {"Base Color": "base_color", "Roughness": "roughness", "Metallic": "metallic",
                        "Emission Color": "emission", "Emission Strength": "emission", "Normal": "normal"},
    "BSDF_DIFFUSE": {"Color": "base_color", "Roughness": None, "Normal": "normal"},
    "EMISSION": {"Color": "emission", "Strength": "emission"},
    # A lobe module's colour is the material's base colour.
    **{node: {lobe["color"]: "base_color", "Normal": "normal"} for node, lobe in LOBES.items()},
}
TARGET_TYPES = {"base_color": "RGBA", "roughness": "VALUE", "metallic": "VALUE", "emission": "RGBA",
                "mix_factor": "VALUE", "normal": "VECTOR"}
# Shaders a Mix Shader with a graph-driven factor may mix: each becomes a material of its own.
MIXABLE = {"BSDF_PRINCIPLED", "BSDF_DIFFUSE", "BSDF_GLOSSY", "BSDF_METALLIC", "BSDF_SHEEN", "BSDF_GLASS", "HOLDOUT",
           "EMISSION", *LOBES}
# Shaders an Add Shader may add, each a material of its own of twice its weight: BSDFs (an
# Emission added is exact in one material, rt_shader_nodes.add).
ADDABLE = MIXABLE - {"HOLDOUT", "EMISSION"}
# What a driven socket's own value becomes in the glTF factors: the part the graph scales.
NEUTRAL = {"Metallic": 0.0, "Emission Color": (1.0, 1.0, 1.0, 1.0), "Color": (1.0, 1.0, 1.0, 1.0),
           "Emission Strength": 1.0, "Strength": 1.0}

IMAGE_NODES = {"TEX_IMAGE", "TEX_ENVIRONMENT", "NORMAL_MAP"}


def tree_has_image(tree):
    return any(n.type in IMAGE_NODES or (n.type == "GROUP" and n.node_tree and tree_has_image(n.node_tree))
               for n in tree.nodes)


def contains_image(socket, seen=None):
    """Whether an Image or Environment Texture feeds `socket` (rt_export follows those)."""
    seen = set() if seen is None else seen
    for link in socket.links:
        node = link.from_node
        if node.name in seen:
            continue
        seen.add(node.name)
        if node.type in IMAGE_NODES or (node.type == "GROUP" and node.node_tree and tree_has_image(node.node_tree)):
            return True
        if any(contains_image(s, seen) for s in node.inputs):
            return True
    return False


def drives(node, name):
    """Whether a graph rt evaluates drives input `name` of shader `node`."""
    socket = node.inputs.get(name)
    if socket is None or not socket.is_linked or name not in TARGETS.get(node.type, {}):
        return False
    return TARGETS[node.type][name] is not None and evaluated(socket)


def evaluated(socket):
    """Whether a graph rt evaluates feeds `socket` (linked, no image, every node evaluated)."""
    if not socket.is_linked or contains_image(socket):
        return False
    try:
        GraphWriter().input(socket, ())
    except Unevaluated:
        return False
    return True


def emits(part):
    """Whether shader `part` emits (an Emission shader, a Principled BSDF's emission)."""
    strength = part.inputs.get("Strength" if part.type == "EMISSION" else "Emission Strength")
    return strength is not None and (strength.is_linked or strength.default_value > 0.0)


def mix_parts(shader):
    """(first, second, swapped) shaders of a Mix Shader whose Fac a graph drives, or whose
    constant Fac mixes shaders that no one parameter set holds (`exactly_mixed`), or of an
    Add Shader of two BSDFs (`ADDABLE`), whose shaders rt renders one by one (none with a
    Normal input linked, at most one emitting), or None. Each shading point is then one of
    the two, picked by the factor: Cycles' closures weighted by it; an Add Shader's are a Mix
    of factor ½, each of weight 2 (`factor_of`, `part_weight`). The emitting one comes
    first, so that the material its triangles name is the one light sampling finds
    (`swapped`: it was the second, and the factor is 1 − Fac)."""
    if shader is None or shader.type not in {"MIX_SHADER", "ADD_SHADER"}:
        return None
    if shader.type == "ADD_SHADER":
        parts = tuple(linked_node(s) for s in shader.inputs if s.type == "SHADER")
        if any(part is None or part.type not in ADDABLE for part in parts):
            return None
    else:
        parts = (linked_node(shader.inputs[1]), linked_node(shader.inputs[2]))
        fac = shader.inputs["Fac"]
        if not (evaluated(fac) or (not fac.is_linked and 0.0 < fac.default_value < 1.0 and not exactly_mixed(parts))):
            return None
    for part in parts:
        if part is None or part.type not in MIXABLE or part.mute:
            return None
        normal = part.inputs.get("Normal")
        if normal is not None and normal.is_linked:
            return None
    if emits(parts[0]) and emits(parts[1]):
        return None
    if emits(parts[1]):
        return parts[1], parts[0], True
    return parts[0], parts[1], False


def factor_of(shader):
    """What picks a mixed shader's second part (`mix_parts`): a Mix Shader's Fac socket, ½
    for an Add Shader."""
    return shader.inputs["Fac"] if shader.type == "MIX_SHADER" else 0.5


def part_weight(shader):
    """What each part of a mixed shader is scaled by: 2 for an Add Shader's (each is picked at
    half the points), 1 for a Mix Shader's (its factor weighs them)."""
    return 2.0 if shader.type == "ADD_SHADER" else 1.0


def exactly_mixed(parts):
    """Whether rt_shader_nodes.mixed mixes shaders `parts` into one parameter set exactly:
    a holdout, a transparent or an emission beside another shader, or two diffuse ones."""
    kinds = {p.type if p is not None else None for p in parts}
    return bool(kinds & {"HOLDOUT", "BSDF_TRANSPARENT", "EMISSION", None}) or kinds == {"BSDF_DIFFUSE"}


def material_graph(material, shader, mix_factor=None, swapped=False):
    """`extras.rt_node_graph` for the shader linked to `material`'s output (or one of a Mix
    Shader's, whose factor socket `mix_factor` drives the choice between them, 1 − it when
    its shaders are `swapped`), or None."""
    if shader is None or (shader.type not in TARGETS and mix_factor is None):
        return None
    writer = GraphWriter(material)
    outputs = {}
    for name, target in TARGETS.get(shader.type, {}).items():
        if target is not None and drives(shader, name):
            value = writer.input(shader.inputs[name], (), TARGET_TYPES[target])
            # The glTF keeps the factors the graph scales: both parts of an emission driven
            # are their product, a strength alone scales the colour there.
            outputs[target] = writer.product(outputs[target], value) if target in outputs else value
    if mix_factor is not None:
        # A number: an Add Shader's ½.
        outputs["mix_factor"] = ({"value": mix_factor} if isinstance(mix_factor, float)
                                 else writer.input(mix_factor, (), "VALUE"))
        if swapped:
            writer.nodes.append({"name": f"rt one minus {len(writer.nodes)}", "type": "MATH",
                                 "settings": {"operation": "SUBTRACT", "use_clamp": False},
                                 "inputs": {"Value": {"value": 1.0}, "Value_001": outputs["mix_factor"]}})
            outputs["mix_factor"] = {"link": [len(writer.nodes) - 1, "Value"], "from": "VALUE", "to": "VALUE"}
    if not outputs:
        return None
    return {"version": FORMAT_VERSION, "nodes": writer.nodes, "outputs": outputs}


def world_graph(background):
    """The graph of a World's Background whose Color or Strength a graph rt evaluates drives
    (and nothing it does not), or None: its `emission` is the colour times the strength.
    A World's Generated and Object coordinates are the direction itself (Cycles'
    `shader_setup_from_background`): a texture space of centre and half-size 1/2."""
    sockets = (background.inputs["Color"], background.inputs["Strength"])
    linked = [s for s in sockets if s.is_linked]
    if not linked or not all(evaluated(s) for s in linked):
        return None
    writer = GraphWriter()
    emission = writer.product(writer.input(sockets[0], (), "RGBA"), writer.input(sockets[1], (), "VALUE"))
    return {"version": FORMAT_VERSION, "nodes": writer.nodes, "outputs": {"emission": emission},
            "texture_space": {"location": [0.5, 0.5, 0.5], "size": [0.5, 0.5, 0.5]}}


def texture_space(mesh):
    """A mesh's texture space, which Generated coordinates are relative to."""
    return {"location": [float(v) for v in mesh.texspace_location], "size": [float(v) for v in mesh.texspace_size]}


def finish_materials(materials, space):
    """The glTF materials of one mesh, made final: each Mix Shader's second material
    (`_rt_mix`) appended and named by the first's `rt_mix_material`, and every graph given
    the mesh's texture space `space`."""
    for m in list(materials):
        second = m.pop("_rt_mix", None)
        if second is not None:
            m["extras"]["rt_mix_material"] = len(materials)
            materials.append(second)
    for m in materials:
        graph = m.get("extras", {}).get("rt_node_graph")
        if graph is not None:
            graph["texture_space"] = space
    return materials
