"""A mesh's named attributes for rt, for rt_export.py: the colour and generic attributes
that the materials' Attribute and Color Attribute nodes read, numbered per mesh and
written into the `.rtmesh` (version 4) as Cycles reads them (docs/shader-nodes.md).

Cycles reads an attribute's values at a triangle's corners and interpolates them: a byte
colour decoded from sRGB per corner, a float colour as it is, a vector or uv map as its
components, an integer or boolean as a value. Blender's `color` of a colour attribute is
already linear, so every kind travels as four floats per corner.
"""

import sys

import numpy as np

from . import rt_node_graph
from .rt_hash import hash_uint, instance_random

# What Cycles reads each of Blender's data types as (rt's `ATTRIBUTE_DATA`, crates/rt/src/asset/node_modes.rs),
# and the property and component count Blender's Python API gives its values by.
DATA = {
    "FLOAT": ("FLOAT", "value", 1, np.float32),
    "INT": ("FLOAT", "value", 1, np.int32),
    "INT8": ("FLOAT", "value", 1, np.int32),
    "BOOLEAN": ("FLOAT", "value", 1, bool),
    "FLOAT2": ("FLOAT2", "vector", 2, np.float32),
    "FLOAT_VECTOR": ("FLOAT3", "vector", 3, np.float32),
    "FLOAT_COLOR": ("FLOAT4", "color", 4, np.float32),
    "BYTE_COLOR": ("FLOAT4", "color", 4, np.float32),
}
# Domains Cycles interpolates over a triangle (edges' attributes it does not read).
DOMAINS = {"POINT", "CORNER", "FACE"}
# The most attributes an `.rtmesh` carries.
MAX_ATTRIBUTES = 15
NODE_TYPES = ("ATTRIBUTE", "VERTEX_COLOR")
# Geometry's Random Per Island, Parametric and Pointiness, which Cycles computes per mesh:
# attributes the exporter makes (rt_node_graph reads those outputs as Attribute nodes of
# these names).
ISLAND = rt_node_graph.ISLAND
PARAMETRIC = rt_node_graph.PARAMETRIC
POINTINESS = rt_node_graph.POINTINESS
MADE = {ISLAND: "FLOAT", PARAMETRIC: "FLOAT3", POINTINESS: "FLOAT"}
# Parametric at a triangle's corners: interpolated, (1 − u − v, u, 0) as Cycles' NODE_GEOM_uv.
PARAMETRIC_CORNERS = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]], np.float32)


def log(message):
    print(f"rt_export: {message}", file=sys.stderr)


def default_color_name(mesh):
    """The colour attribute an unnamed Color Attribute node reads: the mesh's render one."""
    name = getattr(mesh.attributes, "default_color_name", "") or ""
    if not name and len(mesh.color_attributes):
        index = getattr(mesh.color_attributes, "render_color_index", 0)
        name = mesh.color_attributes[max(index, 0)].name
    return name


def readable(mesh, name):
    """The mesh's attribute `name` if Cycles reads it, else None (`True` for those made here)."""
    if name in MADE:
        return True
    attribute = mesh.attributes.get(name) if name else None
    if attribute is None or attribute.domain not in DOMAINS or attribute.data_type not in DATA:
        return None
    return attribute


def attribute_nodes(gltf_materials):
    """The Attribute and Color Attribute nodes of the materials' graphs, with their material."""
    for material in gltf_materials:
        graph = material.get("extras", {}).get("rt_node_graph") or {}
        for node in graph.get("nodes", ()):
            if node["type"] in NODE_TYPES:
                yield material, node


def node_attribute_name(node, default_color):
    settings = node["settings"]
    if node["type"] == "VERTEX_COLOR":
        return settings.get("layer_name") or default_color
    return settings.get("attribute_name", "")


def attributes_read(mesh, gltf_materials):
    """{name: rt's data kind} of the attributes of `mesh` that the materials' graphs read, in
    the order rt numbers them, and the name an unnamed Color Attribute reads."""
    default_color = default_color_name(mesh)
    read = {}
    for material, node in attribute_nodes(gltf_materials):
        name = node_attribute_name(node, default_color)
        attribute = readable(mesh, name)
        if attribute is None or name in read:
            continue
        if len(read) == MAX_ATTRIBUTES:
            log(f"{material['name']}: {node['name']} reads attribute {name!r}; rt carries {MAX_ATTRIBUTES} "
                f"attributes of a mesh and reads it as missing")
            continue
        read[name] = MADE.get(name) or DATA[attribute.data_type][0]
    return read, default_color


def number_attributes(gltf_materials, read, default_color):
    """Gives each Attribute and Color Attribute node of the materials' graphs the number of
    the attribute it reads (`slot`) and its kind (`data`); a node whose attribute the mesh
    lacks (or rt does not carry) gets no number, and reads what Cycles reads then."""
    names = list(read)
    for material, node in attribute_nodes(gltf_materials):
        name = node_attribute_name(node, default_color)
        settings = node["settings"]
        if name in read:
            settings["slot"], settings["data"] = names.index(name), read[name]
            continue
        settings["slot"], settings["data"] = None, "FLOAT"
        log(f"{material['name']}: {node['name']} reads attribute {name!r}, which the mesh does not have "
            f"(or not on points, corners or faces); it reads zero as in Cycles")


def island_randoms(mesh):
    """Each face's Random Per Island, as Cycles' attr_create_random_per_island makes it: the
    vertices joined along every edge in the mesh's order (Cycles' DisjointSet, union by
    rank), each face the hash of its island's root."""
    parents = list(range(len(mesh.vertices)))
    ranks = [0] * len(mesh.vertices)

    def find(x):
        root = x
        while parents[root] != root:
            root = parents[root]
        while parents[x] != root:
            parents[x], x = root, parents[x]
        return root

    edges = np.empty(len(mesh.edges) * 2, np.int32)
    mesh.edges.foreach_get("vertices", edges)
    for x, y in edges.reshape(-1, 2).tolist():
        x, y = find(x), find(y)
        if x == y:
            continue
        if ranks[x] < ranks[y]:
            x, y = y, x
        parents[y] = x
        if ranks[x] == ranks[y]:
            ranks[x] += 1
    first = np.empty(len(mesh.polygons), np.int32)
    mesh.polygons.foreach_get("loop_start", first)
    corner_vertex = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", corner_vertex)
    return np.array([instance_random(hash_uint(find(v))) for v in corner_vertex[first].tolist()], np.float32)


def welded_vertices(co):
    """Each vertex's stand-in among those at its very position: the lowest index, as Cycles'
    pointiness welds duplicates (its search by coordinate sums ends at the first of them)."""
    _, first, group = np.unique(co, axis=0, return_index=True, return_inverse=True)
    return first[group.ravel()]


def pointiness(mesh):
    """Each vertex's Pointiness as Cycles' attr_create_pointiness makes it: duplicates welded,
    the angle between a vertex's welded normal and the mean direction of its edges over π,
    then the mean of that and its edge neighbours' (a second ring, roughly)."""
    count = len(mesh.vertices)
    co = np.empty(count * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    welded = welded_vertices(co)
    co = co.astype(np.float64)
    normals = np.empty(count * 3, np.float32)
    mesh.vertex_normals.foreach_get("vector", normals)
    normal = np.zeros((count, 3))
    np.add.at(normal, welded, normals.reshape(-1, 3))
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0.0)
    edges = np.empty(len(mesh.edges) * 2, np.int32)
    mesh.edges.foreach_get("vertices", edges)
    edges = welded[edges.reshape(-1, 2)]
    # Each edge once, whichever way round, in the order Blender lists them first.
    _, first = np.unique(np.sort(edges, axis=1), axis=0, return_index=True)
    v0, v1 = edges[np.sort(first)].T
    step = co[v1] - co[v0]
    length = np.linalg.norm(step, axis=1, keepdims=True)
    step = np.divide(step, length, out=np.zeros_like(step), where=length > 0.0)
    along, neighbours = np.zeros((count, 3)), np.zeros(count)
    np.add.at(along, v0, step)
    np.add.at(along, v1, -step)
    np.add.at(neighbours, v0, 1.0)
    np.add.at(neighbours, v1, 1.0)
    mean = along / np.maximum(neighbours, 1.0)[:, None]
    raw = np.arccos(np.clip(np.sum(normal * mean, axis=1), -1.0, 1.0)) / np.pi
    raw[(neighbours == 0) | (welded != np.arange(count))] = 0.0
    blurred = raw.copy()
    np.add.at(blurred, v0, raw[v1])
    np.add.at(blurred, v1, raw[v0])
    blurred /= neighbours + 1.0
    return blurred[welded].astype(np.float32)


def corner_values(mesh, name, corners, corner_vertex, triangle_faces):
    """Attribute `name`'s values at each triangle corner, four floats each."""
    if name == PARAMETRIC:
        return np.tile(PARAMETRIC_CORNERS, (len(triangle_faces), 1))
    if name == ISLAND:
        values = np.zeros((len(mesh.polygons), 4), np.float32)
        values[:, 0] = island_randoms(mesh)
        domain = "FACE"
    elif name == POINTINESS:
        values = np.zeros((len(mesh.vertices), 4), np.float32)
        values[:, 0] = pointiness(mesh)
        domain = "POINT"
    else:
        attribute = mesh.attributes[name]
        _, key, width, dtype = DATA[attribute.data_type]
        raw = np.empty(len(attribute.data) * width, dtype)
        attribute.data.foreach_get(key, raw)
        values = np.zeros((len(attribute.data), 4), np.float32)
        values[:, :width] = raw.reshape(-1, width).astype(np.float32)
        domain = attribute.domain
    if domain == "POINT":
        return values[corner_vertex[corners]]
    if domain == "CORNER":
        return values[corners]
    return np.repeat(values[triangle_faces], 3, axis=0)
