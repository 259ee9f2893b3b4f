"""Exports a Blender scene for rt: one asset folder per mesh (`NAME/NAME.rtmesh` with the
evaluated geometry, `NAME/NAME.gltf` with its materials) and, optionally, a scene TOML
that places them with the camera, the lamps and the sky. Instances that the depsgraph
generates (collections, geometry nodes, particles) go into one `.rtinst` instance file
per distinct mesh (and Shadow Terminator settings of the objects showing it), beside the
scene TOML in `SCENE_instances/`.

Three ways to run it:

  python blender/rt_export.py FILE.blend --out assets/ [--scene scenes/NAME.toml]
      (with the `bpy` module from PyPI, bpy==5.0.1 on Python 3.11)
  blender -b FILE.blend -P blender/rt_export.py -- --out assets/ [--scene ...]
  in the rt extension: File > Export > rt, and an "rt" tab in the 3D view's sidebar
      with "Export now" and "Live export on save".

Blender is Z-up, rt is Y-up: (x, y, z) in Blender is (x, z, -y) in rt, for positions,
normals and object matrices (M_rt = C M_blender C^-1). Every file is written to a
temporary name and renamed into place, and only when its bytes change.

This module is part of the rt_blender extension (this folder, with its manifest);
blender/rt_export.py is the command line, which imports it from here. Shader nodes are
mapped onto rt's material model by rt_shader_nodes.py beside it.
"""

import argparse
import json
import math
import os
import re
import struct
import sys
import time
import zlib

import bpy
import numpy as np
from bpy.app.handlers import persistent
from mathutils import Matrix, Vector

from . import rt_attributes, rt_node_graph, rt_node_groups, rt_shader_graphs, rt_shader_nodes
from .rt_hash import instance_random, lookup3_final
TEXTURE_SOCKETS = rt_shader_nodes.TEXTURE_SOCKETS
linked_node, rgb, socket_value = rt_shader_nodes.linked_node, rt_shader_nodes.rgb, rt_shader_nodes.socket_value
owner_name = rt_shader_nodes.owner_name

RTMESH_MAGIC = b"RTMESH\0\0"
RTMESH_VERSION = 4
RTINST_MAGIC = b"RTINST\0\0"
RTINST_VERSION = 5
RTINST_OWN_MATERIALS = 0xFFFFFFFF
RTINST_MATERIAL_SET = 0x80000000

# Blender (Z up) to rt (Y up): a rotation of -90 degrees about X.
TO_RT = Matrix(((1, 0, 0, 0), (0, 0, 1, 0), (0, -1, 0, 0), (0, 0, 0, 1)))
FROM_RT = TO_RT.inverted()


def log(message):
    print(f"rt_export: {message}", file=sys.stderr)


def write_if_changed(path, data):
    """Atomically replaces `path` with `data` (bytes or str) unless it already holds it.
    Returns whether it wrote."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        with open(path, "rb") as f:
            if f.read() == data:
                return False
    except OSError:
        pass
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    temp = f"{os.path.join(os.path.dirname(path), '.' + os.path.basename(path))}.{os.getpid()}.tmp"
    with open(temp, "wb") as f:
        f.write(data)
    os.replace(temp, path)
    return True


def sanitize(name):
    clean = re.sub(r"[^A-Za-z0-9_-]+", "_", name).strip("_")
    return clean or "mesh"


# --- geometry ---------------------------------------------------------------------


def to_rt(v):
    """(x, y, z) Blender -> (x, z, -y) rt, for an (n, 3) array."""
    return np.stack([v[:, 0], v[:, 2], -v[:, 1]], axis=1)


def mesh_arrays(mesh, material_count, second_uv_map=None, attributes=()):
    """Positions, normals, uvs, tangents (per vertex, rt axes), triangle indices and material
    indices of an evaluated mesh. Corners that share all of them share a vertex. The uvs
    are the map Cycles reads by default (see `default_uv_map`), as they are (a Mapping node
    in front of a texture is that texture's KHR_texture_transform); `second_uv_map`, a
    map's name, adds that map as the second set; `attributes`, names of the mesh's
    attributes, add them in that order (rt_attributes)."""
    mesh.calc_loop_triangles()
    tri_count = len(mesh.loop_triangles)
    corners = np.empty(tri_count * 3, np.int32)
    mesh.loop_triangles.foreach_get("loops", corners)
    materials = np.empty(tri_count, np.int32)
    mesh.loop_triangles.foreach_get("material_index", materials)
    materials = np.clip(materials, 0, max(material_count - 1, 0)).astype(np.uint32)

    loop_count = len(mesh.loops)
    corner_vertex = np.empty(loop_count, np.int32)
    mesh.loops.foreach_get("vertex_index", corner_vertex)
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    normals = np.empty(loop_count * 3, np.float32)
    if hasattr(mesh, "corner_normals"):
        mesh.corner_normals.foreach_get("vector", normals)
    else:  # Blender before 4.1 (3.4 for the screenshots): split normals live on the loops
        mesh.calc_normals_split()
        mesh.loops.foreach_get("normal", normals)

    columns = {"positions": to_rt(co.reshape(-1, 3)[corner_vertex[corners]]),
               "normals": to_rt(normals.reshape(-1, 3)[corners])}
    if len(mesh.uv_layers) > 0:
        columns["uvs"] = corner_uv_array(mesh, default_uv_map(mesh), corners)
        tangents = mesh_tangents(mesh, loop_count)
        if tangents is not None:
            columns["tangents"] = np.concatenate([to_rt(tangents[:, :3]), tangents[:, 3:4]], axis=1)[corners]
        if second_uv_map is not None and second_uv_map in mesh.uv_layers:
            columns["second_uvs"] = corner_uv_array(mesh, second_uv_map, corners)
    if attributes:
        faces = np.empty(tri_count, np.int32)
        mesh.loop_triangles.foreach_get("polygon_index", faces)
        for k, name in enumerate(attributes):
            columns[k] = rt_attributes.corner_values(mesh, name, corners, corner_vertex, faces)
    vertices, indices = shared_vertices(columns)
    arrays = {key: vertices.get(key) for key in ("positions", "normals", "uvs", "tangents", "second_uvs")}
    arrays["attributes"] = [vertices[k] for k in range(len(attributes))]
    return {**arrays, "indices": indices, "materials": materials}


def shared_vertices(columns):
    """({key: per-vertex array}, triangle indices) of per-corner arrays: corners that agree
    on every one of them share a vertex."""
    records = np.ascontiguousarray(np.concatenate(list(columns.values()), axis=1), dtype=np.float32)
    keys = records.view(np.dtype((np.void, records.itemsize * records.shape[1]))).ravel()
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    # Vertices in order of first use, which keeps neighbours near each other in memory.
    order = np.argsort(first)
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    vertices = records[first[order]]
    indices = rank[inverse.ravel()].astype(np.uint32).reshape(-1, 3)
    bounds = np.cumsum([0] + [c.shape[1] for c in columns.values()])
    return {key: vertices[:, bounds[i]:bounds[i + 1]] for i, key in enumerate(columns)}, indices


def default_uv_map(mesh):
    """The name of the uv map Cycles reads where a node names none: the active render
    one. It is rt's first uv set."""
    return next((layer.name for layer in mesh.uv_layers if layer.active_render), mesh.uv_layers[0].name)


def corner_uv_array(mesh, name, corners):
    """The uvs of map `name` at each triangle corner."""
    uvs = np.empty(len(mesh.loops) * 2, np.float32)
    mesh.uv_layers[name].uv.foreach_get("vector", uvs)
    return uvs.reshape(-1, 2)[corners]


def mesh_tangents(mesh, loop_count):
    """Per-corner MikkTSpace tangents and bitangent signs (n, 4) of the first uv set, as
    Cycles computes them for normal maps, or None where Blender cannot compute them."""
    try:
        mesh.calc_tangents(uvmap=default_uv_map(mesh))
    except RuntimeError as e:
        log(f"{mesh.name}: no tangents ({e})")
        return None
    tangents = np.empty(loop_count * 3, np.float32)
    mesh.loops.foreach_get("tangent", tangents)
    signs = np.empty(loop_count, np.float32)
    mesh.loops.foreach_get("bitangent_sign", signs)
    return np.concatenate([tangents.reshape(-1, 3), signs.reshape(-1, 1)], axis=1)


def rtmesh_bytes(arrays):
    """Contract 1: magic, version, flags, counts, then the sections, little-endian."""
    flags = 1 | (2 if arrays["uvs"] is not None else 0) | (4 if arrays.get("tangents") is not None else 0)
    flags |= 8 if arrays.get("second_uvs") is not None else 0
    flags |= len(arrays.get("attributes", ())) << 4
    header = RTMESH_MAGIC + struct.pack(
        "<4I", RTMESH_VERSION, flags, len(arrays["positions"]), len(arrays["indices"])
    )
    sections = [arrays["positions"].astype("<f4"), arrays["normals"].astype("<f4")]
    if arrays["uvs"] is not None:
        sections.append(arrays["uvs"].astype("<f4"))
    if arrays.get("tangents") is not None:
        sections.append(arrays["tangents"].astype("<f4"))
    if arrays.get("second_uvs") is not None:
        sections.append(arrays["second_uvs"].astype("<f4"))
    sections += [values.astype("<f4") for values in arrays.get("attributes", ())]
    sections += [arrays["indices"].astype("<u4"), arrays["materials"].astype("<u4")]
    return header + b"".join(np.ascontiguousarray(s).tobytes() for s in sections)


# --- materials --------------------------------------------------------------------


active_output = rt_node_groups.active_output


def cycles_absorption(volume):
    """Cycles' absorption coefficient (per metre) of a volume shader node."""
    density = float(socket_value(volume, "Density", 1.0))
    color = np.array(rgb(socket_value(volume, "Color", (1, 1, 1))))
    if volume.type == "VOLUME_ABSORPTION":
        return density * np.maximum(1.0 - color, 0.0)
    # Principled Volume: extinction = density (color + absorption), where the absorption
    # part is (1 - color)(1 - sqrt(absorption color)); the scattering part (density * color)
    # has no equivalent in rt and is left out.
    absorption_color = np.array(rgb(socket_value(volume, "Absorption Color", (0, 0, 0))))
    absorption = np.maximum(1.0 - color, 0.0) * np.maximum(1.0 - np.sqrt(np.maximum(absorption_color, 0.0)), 0.0)
    if np.any(color > 0.0) and density > 0.0:
        log(f"{owner_name(volume)}: volume scattering is not rendered by rt; only absorption is exported")
    return density * absorption


def volume_emission(volume):
    if volume.type == "PRINCIPLED_VOLUME":
        strength = float(socket_value(volume, "Emission Strength", 0.0))
        return np.array(rgb(socket_value(volume, "Emission Color", (1, 1, 1)))) * strength
    if volume.type == "EMISSION":
        return np.array(rgb(socket_value(volume, "Color", (1, 1, 1)))) * float(socket_value(volume, "Strength", 1.0))
    return np.zeros(3)


# --- textures ---------------------------------------------------------------------
#
# Image Texture nodes linked into the Principled BSDF become glTF textures: directly, or
# through Separate Color (one channel), Normal Map (Normal) or a Mapping node in front of
# the image (its transform becomes the texture info's KHR_texture_transform, so that two
# textures on one uv map may be tiled differently; the channels packed into one image,
# such as roughness and metallic, share the first one's). Each glTF image is composed from the channels
# that feed it, as the linear values Cycles reads (an sRGB image's codes decoded, a
# Non-Color one's taken as they are), then encoded for its glTF slot (sRGB for base
# colour and emission, linear for the rest) and written as NAME-HASH.png, the hash
# of its pixels, so that an unchanged image is never rewritten. Roughness and Metallic
# images are combined into glTF's metallic-roughness image (G roughness, B metallic).
# What cannot be followed (procedural textures, Mix, Color Ramp ...) is named in a
# warning and the socket's own value is used.

GLTF_WRAP = {"REPEAT": 10497, "EXTEND": 33071, "CLIP": 33071, "MIRROR": 33648}
GLTF_NEAREST = 9728  # a sampler filter: an Image Texture's Closest interpolation
LUMA = np.array([0.2126, 0.7152, 0.0722])


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def srgb_codes(linear):
    """sRGB codes of linear values, inverting Cycles' decoding beyond 1 as well."""
    c = np.maximum(linear, 0.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1.0 / 2.4) - 0.055)


def linear_to_srgb(c):
    """sRGB codes of linear values clamped to [0, 1]: what an 8-bit image holds."""
    return srgb_codes(np.clip(c, 0.0, 1.0))


def png_bytes(rgba):
    """An 8-bit RGBA PNG of an (h, w, 4) uint8 array, rows from the top."""
    h, w, _ = rgba.shape
    raw = b"".join(b"\0" + rgba[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


_linear_pixels = {}


def linear_pixels(image):
    """(h, w, 4) float array of the values Cycles reads from `image`, rows from the top."""
    key = (image.name, image.size[0], image.size[1], image.colorspace_settings.name, image.is_dirty)
    if key not in _linear_pixels:
        w, h = image.size
        channels = image.channels
        pixels = np.empty(w * h * channels, np.float32)
        image.pixels.foreach_get(pixels)
        pixels = pixels.reshape(h, w, channels)[::-1]
        if channels < 4:
            grey = np.repeat(pixels[:, :, :1], 3, axis=2) if channels < 3 else pixels[:, :, :3]
            pixels = np.concatenate([grey, np.ones((h, w, 1), np.float32)], axis=2)
        if image.colorspace_settings.name == "sRGB" and not image.is_float:
            pixels = np.concatenate([srgb_to_linear(pixels[:, :, :3]), pixels[:, :, 3:]], axis=2)
        _linear_pixels[key] = pixels
    return _linear_pixels[key]


def mapping_transform(node):
    """A Mapping node (Point) as a 2x3 map of uvs: location + rotation (scale * uv)."""
    if node.vector_type != "POINT":
        return None
    values = {name: node.inputs[name].default_value for name in ("Location", "Rotation", "Scale")}
    if any(node.inputs[name].is_linked for name in values):
        return None
    from mathutils import Euler

    a = np.array(Euler(values["Rotation"], "XYZ").to_matrix()) @ np.diag(values["Scale"])
    return np.concatenate([a[:2, :2], np.array(values["Location"][:2]).reshape(2, 1)], axis=1)


class Channel:
    """One channel that feeds a socket: an Image Texture node's output, one of its
    channels or all three (colour), the uv transform in front of it and the uv map it
    reads ("" for Cycles' default one)."""

    def __init__(self, node, output, component, transform, uv_map=""):
        self.node, self.output, self.component, self.transform = node, output, component, transform
        self.uv_map = uv_map

    def values(self):
        """(h, w, 3) for colour, (h, w) for one channel."""
        pixels = linear_pixels(self.node.image)
        if self.output == "Alpha":
            return pixels[:, :, 3]
        if self.component is None:
            return pixels[:, :, :3]
        if self.component == "luma":
            return pixels[:, :, :3] @ LUMA
        return pixels[:, :, self.component]


# The Principled inputs that take a normal: followed through a Normal Map node into its image.
NORMAL_SOCKETS = ("Normal", "Coat Normal")


def texture_channel(material, node, socket_name, baker=None):
    """The image channel linked into `node.inputs[socket_name]`, or None (then the
    socket's own value is used; a link rt cannot follow is warned about, or, with a
    `baker`, baked into an image)."""
    socket = node.inputs.get(socket_name)
    if socket is None or not socket.is_linked:
        return None
    # Followed through node groups (a texture set's group); a bake reads the socket itself.
    links = rt_node_groups.followed(socket).links
    if not links:
        return None
    link = links[0]
    source, output, component = link.from_node, link.from_socket.name, None
    if source.type == "NORMAL_MAP" and socket_name in NORMAL_SOCKETS:
        inner = source.inputs["Color"]
        if not inner.is_linked:
            return None
        source, output = inner.links[0].from_node, inner.links[0].from_socket.name
        if source.type != "TEX_IMAGE" or source.image is None:
            # A procedural colour into the Normal Map node: the whole normal is what a bake can give.
            source = link.from_node
    if source.type == "SEPARATE_COLOR" and source.mode == "RGB":
        component = {"Red": 0, "Green": 1, "Blue": 2}[output]
        inner = source.inputs["Color"]
        if not inner.is_linked:
            return None
        source, output = inner.links[0].from_node, inner.links[0].from_socket.name
    if source.type != "TEX_IMAGE" or source.image is None:
        if source.type in {"RGB", "VALUE"}:
            return None
        if baker is not None and (socket_name in BAKED_SOCKETS or socket_name == "Normal"):
            baked = baker.bake(material, socket)
            if baked is not None:
                return baked
        fallback = "the coat takes the interpolated normal" if socket_name == "Coat Normal" else "using its own value"
        what = f"{socket_name} is linked to {source.type}, which rt cannot follow; {fallback}"
        log(f"{material.name}: {what}")
        rt_shader_nodes.NOTES.setdefault(material.name, []).append(what)
        return None
    if component is None and output == "Color" and socket.type == "VALUE":
        component = "luma"
    transform = None
    vector = source.inputs["Vector"]
    if vector.is_linked:
        mapping = vector.links[0].from_node
        transform = mapping_transform(mapping) if mapping.type == "MAPPING" else None
        if transform is None and mapping.type != "UVMAP" and mapping.type != "TEX_COORD":
            log(f"{material.name}: {socket_name}'s image coordinates come from {mapping.type}; using the uvs as they are")
    if source.extension == "CLIP":
        log(f"{material.name}: image {source.image.name} clips; rt clamps it to its edge")
    if source.interpolation in {"Cubic", "Smart"}:
        log(f"{material.name}: image {source.image.name}: {source.interpolation} interpolation; rt interpolates linearly")
    return Channel(source, output, component, transform, image_uv_map(source))


def image_uv_map(image_node):
    """The uv map an Image Texture node reads: a UV Map node's, directly or through a
    Mapping node, else "" (Cycles' default map)."""
    vector = image_node.inputs["Vector"]
    source = vector.links[0].from_node if vector.is_linked else None
    if source is not None and source.type == "MAPPING" and source.inputs["Vector"].is_linked:
        source = source.inputs["Vector"].links[0].from_node
    return source.uv_map if source is not None and source.type == "UVMAP" else ""


class Textures:
    """The images and textures of one asset's glTF, built material by material."""

    def __init__(self, base_name, baker=None):
        self.base_name = base_name
        self.baker = baker  # a Baker for links rt cannot follow, or None
        self.images = {}  # file name -> PNG bytes
        self.gltf_images, self.gltf_textures, self.samplers = [], [], []

    def add(self, channels, srgb, image_node):
        """A glTF texture index for an image made of `channels` ([r, g, b, a], each a
        Channel, a (Channel of colour, index) pair or a constant), read as `image_node`
        (an Image Texture node) reads its image: its Extension and its Interpolation."""
        sized = [c[0] if isinstance(c, tuple) else c for c in channels if not isinstance(c, (int, float))]
        h, w = max((c.values().shape[:2] for c in sized), key=lambda s: s[0] * s[1])
        planes = []
        for c in channels:
            if isinstance(c, (int, float)):
                planes.append(np.full((h, w), float(c), np.float32))
                continue
            channel, index = c if isinstance(c, tuple) else (c, None)
            values = channel.values()
            values = values[:, :, index] if index is not None else values
            if values.shape != (h, w):
                # Nearest texel of the largest image's grid.
                ys = np.arange(h) * values.shape[0] // h
                xs = np.arange(w) * values.shape[1] // w
                values = values[ys][:, xs]
            planes.append(values)
        rgba = np.stack(planes, axis=2)
        if srgb:
            rgba[:, :, :3] = linear_to_srgb(rgba[:, :, :3])
        codes = np.round(np.clip(rgba, 0.0, 1.0) * 255.0).astype(np.uint8)
        name = f"{self.base_name}-{blake(codes.tobytes())}.png"
        self.images.setdefault(name, png_bytes(codes))
        if name not in [i["uri"] for i in self.gltf_images]:
            self.gltf_images.append({"uri": name})
        image = [i["uri"] for i in self.gltf_images].index(name)
        wrap = image_node.extension
        sampler = {"wrapS": GLTF_WRAP[wrap], "wrapT": GLTF_WRAP[wrap]}
        if image_node.interpolation == "Closest":
            sampler["magFilter"], sampler["minFilter"] = GLTF_NEAREST, GLTF_NEAREST
        if sampler not in self.samplers:
            self.samplers.append(sampler)
        texture = {"source": image, "sampler": self.samplers.index(sampler)}
        if texture not in self.gltf_textures:
            self.gltf_textures.append(texture)
        return self.gltf_textures.index(texture)


# --- baking (--bake) ----------------------------------------------------------------
#
# A Principled socket fed by what rt cannot follow (procedural textures, Color Ramp,
# Mix ...) is baked with Cycles: the sub-graph feeding it is wired for a moment into an
# Emission shader on the material's output, and an EMIT bake writes its values (linear,
# scalars as grey) into a float image of the chosen size on rt's first uv set (the map
# Cycles reads by default). The image becomes that socket's texture like an Image
# Texture node's would, clamped at its edges. A Normal socket fed by a Bump node or a
# procedural colour into a Normal Map node is baked as Cycles' NORMAL pass in the tangent
# space of that uv set (the material left as it is), which becomes a normal map of
# strength 1. Bakes run before the mesh is evaluated for export, once per material and
# socket, and the node tree is restored afterwards. A mesh seen only as instances
# (collection, geometry-nodes, particle instances) is baked on a stand-in object that
# shows it with each set of materials its instances show, linked into the scene for the
# bake and removed after; geometry made by geometry nodes has no mesh to stand in and
# is warned about.

DEFAULT_BAKE_SIZE = 1024
BAKED_SOCKETS = ("Base Color", "Alpha", "Roughness", "Metallic", "Emission Color")
COLOUR_SOCKETS = ("Base Color", "Emission Color")
BAKE_SAMPLES = 16  # per texel: antialiasing of the procedural pattern within a texel
BAKE_MARGIN = 8  # texels of padding past the uv islands' edges


class BakedImage:
    """Stands for an Image Texture node in a Channel: the baked image's name and edge mode."""

    def __init__(self, name):
        self.name, self.extension, self.interpolation = name, "EXTEND", "Linear"


class BakedChannel(Channel):
    """A socket's baked values: (h, w, 3) linear colour, or one channel of them for a scalar."""

    def __init__(self, name, pixels, colour):
        super().__init__(BakedImage(name), "Color", None if colour else 0, None)
        self.pixels = pixels

    def values(self):
        return self.pixels[:, :, :3] if self.component is None else self.pixels[:, :, self.component]


def principled_surface(material):
    """The Principled BSDF that `gltf_material` reads of a material, or None."""
    if material is None or material.node_tree is None:
        return None
    output = active_output(material.node_tree, "OUTPUT_MATERIAL")
    surface = linked_node(output.inputs["Surface"]) if output else None
    if surface is not None and surface.type not in {"BSDF_PRINCIPLED", "EMISSION"}:
        principled = [n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED"]
        surface = principled[0] if principled else surface
    return surface if surface is not None and surface.type == "BSDF_PRINCIPLED" else None


def needs_bake(socket):
    """Whether `texture_channel` cannot follow what feeds `socket` (through Separate Color
    too, or for Normal a Normal Map node), and no node graph rt evaluates drives it."""
    if rt_shader_graphs.drives(socket.node, socket.name):
        return False
    source = linked_node(socket)
    if source is not None and source.type == "NORMAL_MAP" and socket.name == "Normal":
        source = linked_node(source.inputs["Color"])
        if source is None:
            return False
    if source is not None and source.type == "SEPARATE_COLOR" and source.mode == "RGB":
        source = linked_node(source.inputs["Color"])
    if source is None or source.type in {"RGB", "VALUE"}:
        return False
    return source.type != "TEX_IMAGE" or source.image is None


class Baker:
    """Bakes sockets of one object's materials into images of `size` × `size` texels."""

    def __init__(self, obj, size):
        self.obj, self.size = obj, size  # obj None: only what was baked before (an instance's stand-in is gone)
        self.baked = {}  # (material name, socket name) -> BakedChannel, or None where baking failed

    def prebake(self, materials):
        """Bakes every socket that will need it, before the object's mesh is evaluated for export."""
        for material in materials:
            surface = principled_surface(material)
            for name in BAKED_SOCKETS + ("Normal",) if surface is not None else ():
                if needs_bake(surface.inputs[name]):
                    self.bake(material, surface.inputs[name])

    def bake(self, material, socket):
        if rt_node_groups.in_group(socket):
            # A bake links the socket's source to an Emission in the material's own tree.
            log(f"{material.name}: {socket.name} cannot be baked inside node group {socket.groups[-1].name!r}")
            return None
        key = (material.name, socket.name)
        if key not in self.baked and self.obj is not None:
            self.baked[key] = self._bake(material, socket)
        return self.baked.get(key)

    def _bake(self, material, socket):
        mesh = self.obj.data
        if self.obj.type != "MESH" or not len(mesh.uv_layers):
            log(f"{material.name}: {socket.name} cannot be baked: {self.obj.name} has no uv map")
            return None
        if self.obj.name not in bpy.context.view_layer.objects:
            log(f"{material.name}: {socket.name} cannot be baked: {self.obj.name} is not in the view layer")
            return None
        tree = material.node_tree
        output = active_output(tree, "OUTPUT_MATERIAL")
        surface = output.inputs["Surface"]
        was_on_surface = surface.links[0].from_socket if surface.is_linked else None
        image = bpy.data.images.new(f"rt_bake_{material.name}_{socket.name}", self.size, self.size,
                                    alpha=False, float_buffer=True)
        image.colorspace_settings.name = "Non-Color"  # the values as the shader gives them
        normal = socket.name == "Normal"
        emission = None
        if not normal:
            emission = tree.nodes.new("ShaderNodeEmission")
            emission.inputs["Strength"].default_value = 1.0
            tree.links.new(socket.links[0].from_socket, emission.inputs["Color"])
            tree.links.new(emission.outputs["Emission"], surface)
        target = tree.nodes.new("ShaderNodeTexImage")
        target.image = image
        was_active = tree.nodes.active
        tree.nodes.active = target
        # The bake writes into every material's active image: the object's others get a scratch one.
        scratch = bpy.data.images.new("rt_bake_scratch", 4, 4, float_buffer=True)
        others = []
        for slot in self.obj.material_slots:
            other = slot.material
            if other is None or other == material or other.node_tree is None or other in [o for o, _, _ in others]:
                continue
            node = other.node_tree.nodes.new("ShaderNodeTexImage")
            node.image = scratch
            others.append((other, node, other.node_tree.nodes.active))
            other.node_tree.nodes.active = node
        scene = bpy.context.scene
        layer = bpy.context.view_layer
        saved = (scene.render.engine, scene.cycles.samples, layer.objects.active,
                 [o for o in layer.objects if o.select_get()])
        try:
            scene.render.engine = "CYCLES"
            scene.cycles.samples = BAKE_SAMPLES
            for o in saved[3]:
                o.select_set(False)
            self.obj.select_set(True)
            layer.objects.active = self.obj
            # NORMAL: tangent space of the bake's uv map, +X +Y +Z as RGB, as normal maps are read.
            bpy.ops.object.bake(type="NORMAL" if normal else "EMIT", margin=BAKE_MARGIN, margin_type="EXTEND",
                                use_clear=True, target="IMAGE_TEXTURES", uv_layer=default_uv_map(mesh),
                                normal_space="TANGENT", normal_r="POS_X", normal_g="POS_Y", normal_b="POS_Z")
            pixels = np.empty(self.size * self.size * 4, np.float32)
            image.pixels.foreach_get(pixels)
            pixels = pixels.reshape(self.size, self.size, 4)[::-1].copy()
        except RuntimeError as e:
            log(f"{material.name}: baking {socket.name} failed ({e}); using its own value")
            return None
        finally:
            scene.render.engine, scene.cycles.samples = saved[0], saved[1]
            self.obj.select_set(False)
            for o in saved[3]:
                o.select_set(True)
            layer.objects.active = saved[2]
            for other, node, active in others:
                other.node_tree.nodes.remove(node)
                other.node_tree.nodes.active = active
            tree.nodes.remove(target)
            if emission is not None:
                tree.nodes.remove(emission)
                if was_on_surface is not None:
                    tree.links.new(was_on_surface, surface)
            tree.nodes.active = was_active
            bpy.data.images.remove(image)
            bpy.data.images.remove(scratch)
        log(f"{material.name}: baked {socket.name} ({linked_node(socket).type}) into {self.size}x{self.size} "
            f"texels on uv map {default_uv_map(mesh)!r}")
        return BakedChannel(f"{material.name}-{socket.name}", pixels, normal or socket.name in COLOUR_SOCKETS)


def blake(data):
    import hashlib

    return hashlib.blake2b(data, digest_size=8).hexdigest()


def material_textures(material, surface, out, textures, factors, found):
    """Adds the base textures of a Principled BSDF (`found`: socket name -> Channel or None)
    to glTF material `out`, each with its own Mapping node as its KHR_texture_transform."""
    pbr = out["pbrMetallicRoughness"]
    transformed = lambda info, key, *channels: with_uv_transform(info, material.name, key, channels)  # noqa: E731
    base, alpha = found["Base Color"], found["Alpha"]
    if base is not None or alpha is not None:
        rgb_source = [(base, i) for i in range(3)] if base is not None else [float(v) for v in factors["base"]]
        pbr["baseColorFactor"] = [1.0, 1.0, 1.0, 1.0]
        channels = rgb_source + [alpha if alpha is not None else 1.0]
        info = {"index": textures.add(channels, True, (base or alpha).node), UV_MAP_KEY: (base or alpha).uv_map}
        pbr["baseColorTexture"] = transformed(info, "base colour", base, alpha)
        if alpha is not None:
            # Cycles blends by alpha (stochastically): so does rt with glTF's BLEND.
            out["alphaMode"] = "BLEND"
            out.pop("alphaCutoff", None)
    rough, metal = found["Roughness"], found["Metallic"]
    if rough is not None or metal is not None:
        pbr["metallicRoughnessTexture"] = transformed({"index": textures.add(
            [0.0, rough if rough is not None else factors["roughness"],
             metal if metal is not None else factors["metallic"], 1.0], False, (rough or metal).node),
            UV_MAP_KEY: (rough or metal).uv_map}, "roughness and metallic", rough, metal)
        pbr["roughnessFactor"], pbr["metallicFactor"] = 1.0, 1.0
    if found["Normal"] is not None:
        out["normalTexture"] = normal_map_info(material, surface, "Normal", found["Normal"], textures)
    emission, strength_map = found["Emission Color"], found["Emission Strength"]
    if emission is not None or strength_map is not None:
        strength = factors["strength"]
        colour = [(emission, i) for i in range(3)] if emission is not None else factors["emission"]
        if strength_map is not None:
            # glTF's emission is one texture times a factor: the colour times the strength over
            # its largest value, which becomes the factor's strength.
            strength = float(strength_map.values().max())
            colour = [ScaledChannel(c, strength_map, strength) for c in colour]
        first = emission or strength_map
        info = {"index": textures.add(colour + [1.0], True, first.node), UV_MAP_KEY: first.uv_map}
        out["emissiveTexture"] = transformed(info, "emission", emission, strength_map)
        if strength > 0.0:
            out["emissiveFactor"] = [1.0, 1.0, 1.0]
            out.setdefault("extensions", {})["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}


class ScaledChannel(Channel):
    """A channel of colour (a (Channel, index) pair or a constant) times a strength Channel
    over `scale`, on the larger of the two images' grids (nearest texels)."""

    def __init__(self, colour, strength, scale):
        super().__init__(strength.node, strength.output, strength.component, strength.transform, strength.uv_map)
        self.colour, self.strength, self.scale = colour, strength, max(scale, 1e-12)

    def values(self):
        s = self.strength.values() / self.scale
        if isinstance(self.colour, tuple):
            channel, index = self.colour
            c = channel.values()[:, :, index]
        else:
            c = np.full(s.shape, float(self.colour), np.float32)
        h, w = max(c.shape, s.shape, key=lambda shape: shape[0] * shape[1])
        nearest = lambda v: v[np.arange(h) * v.shape[0] // h][:, np.arange(w) * v.shape[1] // w]  # noqa: E731
        return nearest(c) * nearest(s)
def normal_map_info(material, surface, socket_name, normal, textures):
    """The texture info (with its scale) of the normal map `normal` that feeds socket
    `socket_name` of `surface`, through a Normal Map node or baked."""
    node = surface.inputs[socket_name].links[0].from_node
    mapped = node.type == "NORMAL_MAP" and not isinstance(normal, BakedChannel)
    # A baked normal has the node's strength in it already, in the default map's tangent space.
    strength = float(node.inputs["Strength"].default_value) if mapped else 1.0
    # The Normal Map node's uv map is the one its tangents are of, and the one rt reads the image with.
    uv_map = (node.uv_map if mapped else "") or normal.uv_map
    if normal.uv_map not in ("", uv_map):
        log(f"{material.name}: its {socket_name} map's image reads uv map {normal.uv_map!r} but its Normal Map node "
            f"names {uv_map!r}; rt reads both with {uv_map!r}")
    # Its tangents are the uv map's, whatever the Mapping node does (as in Cycles).
    info = {"index": textures.add([(normal, i) for i in range(3)] + [1.0], False, normal.node),
            "scale": strength, UV_MAP_KEY: uv_map}
    return with_uv_transform(info, material.name, f"{socket_name} map", [normal])


def coat_normal_texture(material, surface, out, textures, channel):
    """KHR_materials_clearcoat's clearcoatNormalTexture of a coated material whose Coat Normal
    is fed by a Normal Map node with an image (`channel`): the base's normal texture where
    the Normal input's Normal Map node is the same one, else its own. Unlinked, the coat
    takes the interpolated normal, as in Cycles, and has none."""
    clearcoat = out["extensions"].get("KHR_materials_clearcoat")
    node = linked_node(surface.inputs["Coat Normal"])
    if clearcoat is None or node is None:
        return
    if node == linked_node(surface.inputs["Normal"]):
        # One Normal Map node feeds both: one texture, read the same way.
        import copy

        if "normalTexture" in out:
            clearcoat["clearcoatNormalTexture"] = copy.deepcopy(out["normalTexture"])
    elif channel is not None:
        clearcoat["clearcoatNormalTexture"] = normal_map_info(material, surface, "Coat Normal", channel, textures)


def channels_of(channels):
    """The Channels among a texture's `channels` (Channels, (Channel, index) pairs, TurnChannels, constants)."""
    for c in channels:
        c = c[0] if isinstance(c, tuple) else c
        c = c.channel if isinstance(c, TurnChannel) else c
        if isinstance(c, Channel):
            yield c


def with_uv_transform(info, material_name, what, channels):
    """Texture info `info` with the Mapping node of its image's `channels` as its
    KHR_texture_transform (none for none). One image packs them: where their Mapping
    nodes differ, the first one's is used, with a warning."""
    transforms = [c.transform for c in channels_of(channels)]
    first = transforms[0] if transforms else None
    if any((t is None) != (first is None) or (t is not None and not np.allclose(t, first)) for t in transforms):
        log(f"{material_name}: the images packed into its {what} texture come through different Mapping nodes; "
            f"rt reads them all through the first one's")
    if first is not None:
        info.setdefault("extensions", {})["KHR_texture_transform"] = gltf_texture_transform(first, material_name, what)
    return info


def gltf_texture_transform(transform, material_name, what):
    """A 2x3 map of Blender uvs (a Mapping node: location + rotation (scale * uv)) as
    KHR_texture_transform, which maps glTF's uvs (v = 1 - Blender's v): the map's 2x2 part
    as rotation * scale (a Mapping node turned about X or Y is not one: its nearest is used,
    with a warning), the offset as Blender's glTF exporter writes it."""
    a, location = np.asarray(transform, np.float64)[:, :2], np.asarray(transform, np.float64)[:, 2]
    rotation = math.atan2(a[1, 0], a[0, 0])
    sin, cos = math.sin(rotation), math.cos(rotation)
    scale = [math.hypot(a[0, 0], a[1, 0]), -sin * a[0, 1] + cos * a[1, 1]]
    fitted = np.array([[cos, -sin], [sin, cos]]) @ np.diag(scale)
    if not np.allclose(fitted, a, atol=1e-6):
        log(f"{material_name}: the Mapping node of its {what} texture is not a rotation about Z with a scale; "
            f"rt uses the nearest that is")
    ext = {"offset": [float(location[0] - scale[1] * sin), float(1.0 - location[1] - scale[1] * cos)],
           "rotation": float(rotation), "scale": [float(scale[0]), float(scale[1])]}
    return ext


def sheen_layer(out, extensions, weight, roughness, tint):
    """The Principled's sheen layer in glTF material `out`: glTF's sheen has no weight, so
    other readers get Blender's exporter's colour and roughness; rt reads its own keys first."""
    extensions["KHR_materials_sheen"] = {"sheenColorFactor": tint, "sheenRoughnessFactor": roughness}
    out["extras"].update({"rt_sheen": weight, "rt_sheen_roughness": roughness, "rt_sheen_tint": tint})


def gltf_material(material, thickness, textures=None, shader=None, weight=1.0):
    """One glTF material (with KHR extensions) from a Blender material; every factor is written, since rt's importer
    applies glTF's defaults to absent ones. Its textures go into `textures`. The surface
    shader is mapped onto rt's model by rt_shader_nodes (which warns about what it cannot
    map). A Mix Shader whose factor a node graph drives is its first shader, with the second
    as another material (`_rt_mix`, see rt_shader_graphs.finish_materials); so is an Add
    Shader of two BSDFs, each of `weight` 2 (its BSDF and emission scaled by it); `shader`
    is the shader to read instead of the output's."""
    name = material.name if material else "default"
    output = active_output(material.node_tree, "OUTPUT_MATERIAL") if material and material.node_tree else None
    top = linked_node(output.inputs["Surface"]) if output else None
    parts = rt_shader_graphs.mix_parts(top) if shader is None else None
    shader = shader or (parts[0] if parts else top)
    weight = rt_shader_graphs.part_weight(top) if parts else weight
    if material is None:
        s = rt_shader_nodes.Surface()
    else:
        if top is shader or parts:
            rt_shader_nodes.NOTES[material.name] = []
        s = rt_shader_nodes.surface(material, shader)
    if weight != 1.0:
        s.emission = [e * weight for e in s.emission]
        s.emission_strength *= weight
    base, metallic, roughness, ior, transmission = s.base, s.metallic, s.roughness, s.ior, s.transmission
    specular_level, specular_tint, alpha = s.specular_level, s.specular_tint, s.alpha
    surface = s.principled
    peak = max(s.emission)
    emission, strength = ([e / peak for e in s.emission], peak) if peak > 0.0 else ([0.0, 0.0, 0.0], 0.0)

    out = {
        "name": name,
        "pbrMetallicRoughness": {
            "baseColorFactor": base + [alpha],
            "metallicFactor": metallic,
            "roughnessFactor": roughness,
        },
    }
    if alpha < 1.0:
        out["alphaMode"] = "BLEND"
    extensions = {
        "KHR_materials_ior": {"ior": ior},
        # Blender's level 0.5 is the unscaled F0 of the IOR, glTF's factor 1; glTF's factor
        # stops at 1, so the level itself goes into extras too. The tint is also the metal's F82 tint.
        "KHR_materials_specular": {
            "specularFactor": min(max(2.0 * specular_level, 0.0), 1.0),
            "specularColorFactor": [min(max(c, 0.0), 1.0) for c in specular_tint],
        },
    }
    out["extras"] = {"rt_specular_ior_level": min(max(specular_level, 0.0), 1.0)}
    diffuse_roughness = min(max(s.diffuse_roughness, 0.0), 1.0)
    if diffuse_roughness > 0.0:
        # Cycles' Oren-Nayar diffuse (Principled's Diffuse Roughness); glTF has no such input.
        out["extras"]["rt_diffuse_roughness"] = diffuse_roughness
    if material is not None and not material.cycles.use_bump_map_correction:
        # Cycles' Bump Map Correction (on by default) of glossy normals on smooth surfaces.
        out["extras"]["rt_bump_map_correction"] = False
    if s.holdout > 0.0:
        # Blender's Holdout shader, or a Mix Shader's share of one.
        out["extras"]["rt_holdout"] = min(s.holdout, 1.0)
    if s.module is not None:
        # A lobe module of rt (the Toon BSDF, ...): its BSDF, weighted by the base colour.
        out["extras"]["rt_lobe"] = s.module
    if s.glossy is not None:
        # Cycles' Glossy BSDF: GGX without Fresnel, tinted by its colour; glTF has no such lobe
        # (its factors above describe a metal of that colour for other readers).
        out["extras"]["rt_glossy_color"] = [max(c, 0.0) for c in s.glossy]
    if weight != 1.0:
        # An Add Shader's BSDF, rendered at half the points: Cycles' closures add past 1.
        out["extras"]["rt_closure_weight"] = weight
    swapped = bool(parts) and parts[2]
    graph = rt_shader_graphs.material_graph(material, shader, rt_shader_graphs.factor_of(top) if parts else None,
                                            swapped) if material else None
    if graph is not None:
        out["extras"]["rt_node_graph"] = graph
    if parts:
        out["_rt_mix"] = gltf_material(material, thickness, textures, shader=parts[1], weight=weight)
        out["_rt_mix"]["name"] = f"{name} (mixed)"
    found, film_range, ior_ranges = {}, None, {}
    if textures is not None and surface is not None:
        # A socket a node graph drives is not followed into a texture (nor baked).
        found = {name: None if rt_shader_graphs.drives(surface, name) else texture_channel(material, surface, name,
                                                                                           textures.baker)
                 for name in TEXTURE_SOCKETS if name != FILM_SOCKET and name not in IOR_SOCKETS}
        # The coat's own normal map (not baked: a Bump node there is warned about), unless it is
        # the Normal input's (see `coat_normal_texture`). Only a coat reads it.
        coated = float(socket_value(surface, "Coat Weight", 0.0)) > 0.0 or found.get("Coat Weight")
        if coated and linked_node(surface.inputs["Coat Normal"]) != linked_node(surface.inputs["Normal"]):
            found["Coat Normal"] = texture_channel(material, surface, "Coat Normal")
        film_range = ranged_texture(material, surface, FILM_SOCKET)
        found[FILM_SOCKET] = film_range[0] if film_range else None
        ior_ranges = {name: ranged_texture(material, surface, name) for name in IOR_SOCKETS}
        if found["Diffuse Roughness"]:
            # The texels are the roughness: its factor is 1.
            out["extras"]["rt_diffuse_roughness"] = 1.0
        if found["Transmission Weight"]:
            transmission = 1.0
        if ior_ranges["IOR"]:
            # The texels' 1 is the factor; their 0 the minimum (`ior_texture`).
            ior = ior_ranges["IOR"][2]
            extensions["KHR_materials_ior"]["ior"] = ior
        if found["Specular IOR Level"]:
            # The texels are the level (glTF's specular is twice it, at most 1, for other readers).
            extensions["KHR_materials_specular"]["specularFactor"] = 1.0
            out["extras"]["rt_specular_ior_level"] = 1.0
    # A socket fed by an image takes its values from it: its factor is 1 (a rotation's, added to, 0).
    value = lambda name, default: (1.0 if found.get(name) else socket_value(surface, name, default))  # noqa: E731
    colour = lambda name: ((1, 1, 1) if found.get(name) else socket_value(surface, name, (1, 1, 1)))  # noqa: E731
    if surface is not None:
        coat = float(value("Coat Weight", 0.0))
        if coat > 0.0:
            coat_roughness = min(max(float(value("Coat Roughness", 0.03)), 0.0), 1.0)
            # glTF's clearcoat (for other readers) has no index or tint: rt reads its own keys first.
            extensions["KHR_materials_clearcoat"] = {
                "clearcoatFactor": min(coat, 1.0),
                "clearcoatRoughnessFactor": coat_roughness,
            }
            out["extras"].update({
                "rt_coat": min(coat, 1.0),
                "rt_coat_roughness": coat_roughness,
                "rt_coat_ior": max(ior_ranges["Coat IOR"][2] if ior_ranges.get("Coat IOR")
                                   else float(socket_value(surface, "Coat IOR", 1.5)), 1.0),
                "rt_coat_tint": [min(max(c, 0.0), 1.0) for c in rgb(colour("Coat Tint"))],
            })
        sheen = float(value("Sheen Weight", 0.0))
        if sheen > 0.0:
            sheen_roughness = min(max(float(value("Sheen Roughness", 0.5)), 0.0), 1.0)
            sheen_tint = [min(max(c, 0.0), 1.0) for c in rgb(colour("Sheen Tint"))]
            sheen_layer(out, extensions, min(sheen, 1.0), sheen_roughness, sheen_tint)
        anisotropy = float(value("Anisotropic", 0.0))
        if anisotropy > 0.0:
            rotation = 0.0 if found.get("Anisotropic Rotation") else socket_value(surface, "Anisotropic Rotation", 0.0)
            rotation = float(rotation) % 1.0
            # glTF's rotation is in radians (Blender's exporter converts so too).
            extensions["KHR_materials_anisotropy"] = {
                "anisotropyStrength": min(anisotropy, 1.0),
                "anisotropyRotation": rotation * 2.0 * math.pi,
            }
            out["extras"].update({
                "rt_anisotropy": min(anisotropy, 1.0),
                "rt_anisotropy_rotation": rotation,
            })
            out["extras"].update(tangent_extras(name, surface.inputs["Tangent"]))
        film = float(socket_value(surface, FILM_SOCKET, 0.0))
        # A film of one thickness: glTF's range collapsed to it (rt reads the maximum); of a
        # texture's, the range its texels map to (the texture is added by `layer_textures`).
        low, high = (film_range[1], film_range[2]) if film_range else (film, film)
        if high > 0.0:
            extensions["KHR_materials_iridescence"] = {
                "iridescenceFactor": 1.0,
                "iridescenceIor": max(ior_ranges["Thin Film IOR"][2] if ior_ranges.get("Thin Film IOR")
                                      else float(socket_value(surface, "Thin Film IOR", 1.33)), 1e-5),
                "iridescenceThicknessMinimum": low,
                "iridescenceThicknessMaximum": high,
            }
    if s.sheen is not None and surface is None:
        sheen_layer(out, extensions, *s.sheen)
    if transmission > 0.0:
        extensions["KHR_materials_transmission"] = {"transmissionFactor": transmission}
    peak = max(emission)
    if strength > 0.0 and peak > 0.0:
        # glTF keeps emissiveFactor in [0, 1]; the rest goes into the strength.
        out["emissiveFactor"] = [c / peak for c in emission]
        extensions["KHR_materials_emissive_strength"] = {"emissiveStrength": strength * peak}

    volume = linked_node(output.inputs["Volume"]) if output else None
    if volume is not None:
        absorption = cycles_absorption(volume) if volume.type in {"VOLUME_ABSORPTION", "PRINCIPLED_VOLUME"} else None
        if absorption is not None and absorption.max() > 0.0:
            # rt reads absorption = -ln(c) / d: with d = 1 / max, every channel of c lies in
            # [1/e, 1], far from where float precision would suffer.
            distance = 1.0 / float(absorption.max())
            color = [math.exp(-a * distance) for a in absorption]
            extensions["KHR_materials_volume"] = {
                "thicknessFactor": thickness,
                "attenuationDistance": distance,
                "attenuationColor": color,
            }
        glow = volume_emission(volume)
        if glow.max() > 0.0:
            out["extras"]["rt_volume_emission"] = [float(g) for g in glow]
    out["extensions"] = extensions
    if textures is not None and surface is not None:
        factors = {"base": base, "roughness": roughness, "metallic": metallic, "strength": s.emission_strength,
                   "emission": [float(c) for c in rgb(socket_value(surface, "Emission Color", (0, 0, 0)))]}
        material_textures(material, surface, out, textures, factors, found)
        layer_textures(out, textures, found)
        ior_texture(out, textures, ior_ranges)
        coat_normal_texture(material, surface, out, textures, found.get("Coat Normal"))
    notes = rt_shader_nodes.NOTES.get(material.name) if material is not None else None
    if notes:
        # What rt renders differently from Cycles, for `rt info` (and the material panel).
        out["extras"]["rt_notes"] = list(dict.fromkeys(notes))
    return out


def tangent_extras(name, socket):
    """rt's `tangent` of a Principled BSDF's Tangent input: a Tangent node, radial about an
    axis or along a uv map (the map's name kept under TANGENT_UV_MAP_KEY for `assign_uv_sets`)."""
    node = linked_node(socket)
    if node is None:
        return {}
    if node.type == "TANGENT" and node.direction_type == "RADIAL":
        return {"rt_tangent": f"radial_{node.axis.lower()}"}
    if node.type == "TANGENT" and node.direction_type == "UV_MAP":
        return {"rt_tangent": "uv", TANGENT_UV_MAP_KEY: node.uv_map}
    log(f"{name}: the Principled BSDF's Tangent input is linked to {node.type}, which rt cannot follow; "
        f"rt uses the radial tangent about Z")
    return {}


class TurnChannel:
    """A channel of rotations (turns), brought into [0, 1): rt adds it to the rotation factor."""

    def __init__(self, channel):
        self.channel = channel

    def values(self):
        return np.mod(self.channel.values(), 1.0)


def layer_textures(out, textures, found):
    """Adds the textures of the coat, sheen, anisotropy, specular tint, diffuse roughness,
    film thickness, transmission and IOR level sockets (`found`, socket name -> Channel or
    None) to glTF material `out`, whose factors for them are 1 (the rotation's 0): the coat's
    as KHR_materials_clearcoat's textures (R weight, G roughness, one image), the specular
    tint's and level's as KHR_materials_specular's colour texture and texture (A), the
    transmission's as KHR_materials_transmission's (R), the film's as KHR_materials_iridescence's
    thickness texture (G, over the range `film_thickness_texture` found), the others in
    rt's extras (sheen: R weight, G roughness; anisotropy: R amount, G rotation; diffuse
    roughness: R)."""
    extensions, extras = out["extensions"], out["extras"]

    def info(channels, srgb, first):
        return with_uv_transform({"index": textures.add(channels, srgb, first.node),
                                  UV_MAP_KEY: first.uv_map}, out["name"], "layer", channels)

    def rgb_of(c):
        return [(c, i) for i in range(3)] + [1.0]

    weight, rough = found.get("Coat Weight"), found.get("Coat Roughness")
    clearcoat = extensions.get("KHR_materials_clearcoat")
    if clearcoat is not None and (weight or rough):
        index = info([weight or 1.0, rough or 1.0, 0.0, 1.0], False, weight or rough)["index"]
        for key, channel in (("clearcoatTexture", weight), ("clearcoatRoughnessTexture", rough)):
            if channel:
                # One image, two texture infos: each reads it through its own channel's Mapping node.
                clearcoat[key] = with_uv_transform({"index": index, UV_MAP_KEY: channel.uv_map}, out["name"], key,
                                                   [channel])
    if clearcoat is not None and found.get("Coat Tint"):
        extras["rt_coat_tint_texture"] = info(rgb_of(found["Coat Tint"]), True, found["Coat Tint"])
    weight, rough = found.get("Sheen Weight"), found.get("Sheen Roughness")
    if "rt_sheen" in extras and (weight or rough):
        extras["rt_sheen_texture"] = info([weight or 1.0, rough or 1.0, 0.0, 1.0], False, weight or rough)
    if "rt_sheen" in extras and found.get("Sheen Tint"):
        extras["rt_sheen_tint_texture"] = info(rgb_of(found["Sheen Tint"]), True, found["Sheen Tint"])
    amount, rotation = found.get("Anisotropic"), found.get("Anisotropic Rotation")
    if "rt_anisotropy" in extras and (amount or rotation):
        extras["rt_anisotropy_texture"] = info(
            [amount or 1.0, TurnChannel(rotation) if rotation else 0.0, 0.0, 1.0], False, amount or rotation)
    tint = found.get("Specular Tint")
    if tint:
        specular = extensions["KHR_materials_specular"]
        specular["specularColorFactor"] = [1.0, 1.0, 1.0]
        specular["specularColorTexture"] = info(rgb_of(tint), True, tint)
    roughness = found.get("Diffuse Roughness")
    if roughness and "rt_diffuse_roughness" in extras:
        extras["rt_diffuse_roughness_texture"] = info([roughness, 0.0, 0.0, 1.0], False, roughness)
    weight = found.get("Transmission Weight")
    if weight and "KHR_materials_transmission" in extensions:
        extensions["KHR_materials_transmission"]["transmissionTexture"] = info([weight, 0.0, 0.0, 1.0], False, weight)
    level = found.get("Specular IOR Level")
    if level:
        # glTF's specular texture is its alpha.
        extensions["KHR_materials_specular"]["specularTexture"] = info([1.0, 1.0, 1.0, level], False, level)
    film = found.get(FILM_SOCKET)
    if film and "KHR_materials_iridescence" in extensions:
        # glTF's thickness texture: G from the minimum (0) to the maximum (1).
        extensions["KHR_materials_iridescence"]["iridescenceThicknessTexture"] = info(
            [0.0, film, 0.0, 1.0], False, film)


def ior_texture(out, textures, ranges):
    """rt's `extras.rt_ior_texture` of the indices fed by images (`ranges`: socket name ->
    (channel, value at 0, value at 1) or None): one image, R the IOR, G the coat's, B the
    film's, each read from its minimum (`rt_ior_minimum`, `rt_coat_ior_minimum`,
    `rt_thin_film_ior_minimum`) at 0 to the material's own index at 1. glTF has no texture
    of an index. The coat's and the film's count only where the material has them."""
    extras = out["extras"]
    present = {"IOR": True, "Coat IOR": "rt_coat" in extras,
               "Thin Film IOR": "KHR_materials_iridescence" in out["extensions"]}
    driven = {name: r for name, r in ranges.items() if r and present[name]}
    if not driven:
        return
    first = next(iter(driven.values()))[0]
    channels = [driven[name][0] if name in driven else 1.0 for name in IOR_SOCKETS] + [1.0]
    extras["rt_ior_texture"] = with_uv_transform({"index": textures.add(channels, False, first.node),
                                                  UV_MAP_KEY: first.uv_map}, out["name"], "index",
                                                 [c for c in channels if isinstance(c, Channel)])
    keys = {"IOR": "rt_ior_minimum", "Coat IOR": "rt_coat_ior_minimum", "Thin Film IOR": "rt_thin_film_ior_minimum"}
    for name, (_, low, _) in driven.items():
        extras[keys[name]] = low


FILM_SOCKET = "Thin Film Thickness"
# The indices, one image's R, G and B (rt's extras.rt_ior_texture), each over its range.
IOR_SOCKETS = rt_shader_nodes.IOR_SOCKETS


def ranged_texture(material, surface, socket_name):
    """An image into a Principled input whose values an image's 0-1 does not reach (Thin
    Film Thickness in nm, the indices): through a Map Range node (linear, float, its bounds
    unlinked) or a Math node multiplying the image by a constant. Returns (channel, value at
    0, value at 1), or None (a link rt cannot follow is warned about; the socket's own value
    is used)."""
    socket = surface.inputs[socket_name]
    if not socket.is_linked:
        return None
    node = socket.links[0].from_node
    if node.type == "MAP_RANGE" and node.data_type == "FLOAT" and node.interpolation_type == "LINEAR":
        bounds = [node.inputs[name] for name in ("From Min", "From Max", "To Min", "To Max")]
        if not any(b.is_linked for b in bounds):
            from_min, from_max, to_min, to_max = (float(b.default_value) for b in bounds)
            channel = texture_channel(material, node, "Value")
            if channel is not None and from_max != from_min:
                slope = (to_max - to_min) / (from_max - from_min)
                return channel, to_min - from_min * slope, to_min + (1.0 - from_min) * slope
    if node.type == "MATH" and node.operation == "MULTIPLY" and not node.inputs[1].is_linked:
        channel = texture_channel(material, node, "Value")
        if channel is not None:
            return channel, 0.0, float(node.inputs[1].default_value)
    log(f"{material.name}: {socket_name} is linked to {node.type}; rt follows an image through a Map Range "
        f"or a Math Multiply node only, and uses the socket's own value")
    return None


def gltf_text(materials, thickness, textures=None):
    used = {ext for m in materials for ext in m.get("extensions", {})}
    if any("extensions" in info for m in materials for _, info in texture_infos(m)):
        used.add("KHR_texture_transform")
    used = sorted(used)
    document = {
        "asset": {"version": "2.0", "generator": "rt_export.py"},
        "extensionsUsed": used,
        "materials": materials,
    }
    if textures is not None and textures.gltf_textures:
        document["images"] = textures.gltf_images
        document["samplers"] = textures.samplers
        document["textures"] = textures.gltf_textures
    return json.dumps(document, indent=1, sort_keys=True) + "\n"


# --- objects ----------------------------------------------------------------------


# The names of the objects the depsgraph being exported shows (see `export_scene`): a
# render depsgraph leaves out what is hidden from renders (and evaluates render-level
# modifiers), the viewport's what the viewport hides. None outside an export: then what
# renders in the current view layer.
_shown = None


# The depsgraph being exported (see `export_scene`), whose evaluated objects' matrices
# count: a preview scene's objects are placed only there.
_depsgraph = None


# {object name: its world matrices over the shutter} of the objects and camera that move in
# the export under way (see `motion_keys`).
_motion = {}


def world_matrix(obj):
    """`obj`'s world matrix in the depsgraph being exported (its own outside an export)."""
    return obj.evaluated_get(_depsgraph).matrix_world if _depsgraph is not None else obj.matrix_world


def shown_objects(depsgraph):
    """The names of the objects `depsgraph` evaluates as visible in its mode."""
    return {o.original.name for o in depsgraph.objects}


def is_shown(obj, scene):
    if _shown is not None:
        return obj.name in _shown
    layer = bpy.context.view_layer if bpy.context.scene == scene else scene.view_layers[0]
    return not obj.hide_render and obj.name in layer.objects


def exported_objects(scene):
    """Mesh objects that render, in name order."""
    return sorted((o for o in scene.objects if o.type == "MESH" and is_shown(o, scene)), key=lambda o: o.name)


def object_slot_materials(obj):
    return [slot.material for slot in obj.material_slots] or [None]


def export_object_mesh(obj, depsgraph, base_name="mesh", bake_size=0):
    """(rtmesh bytes, gltf text, {image file: PNG bytes}, triangle count) of an object's
    evaluated mesh.
    With `bake_size`, links rt cannot follow are baked into images of that size."""
    materials = object_slot_materials(obj)
    textures = Textures(base_name, Baker(obj, bake_size) if bake_size > 0 else None)
    if textures.baker is not None:
        textures.baker.prebake(materials)
        depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        return export_mesh(mesh, materials, textures)
    finally:
        evaluated.to_mesh_clear()


# --- uv sets ----------------------------------------------------------------------
#
# rt carries two uv sets: the map Cycles reads by default (the active render one) and a
# second one, the first other map that some texture of the mesh's materials reads (a UV
# Map node in front of its Image Texture, directly or through a Mapping node). Textures
# name their map under UV_MAP_KEY while the materials are built; once the mesh's second
# set is known it becomes glTF's texCoord (1 for the second set). A normal map reads the
# map its Normal Map node names, in that map's tangent frame (rt makes MikkTSpace's of
# the second set itself); a third map is read as the first, with a warning.

UV_MAP_KEY = "_rt_uv_map"
# The uv map of a Tangent node along a uv map, in a material's extras: rt follows the default one's tangents.
TANGENT_UV_MAP_KEY = "_rt_tangent_uv_map"
TEXTURE_INFOS = ((("pbrMetallicRoughness",), "baseColorTexture"),
                 (("pbrMetallicRoughness",), "metallicRoughnessTexture"),
                 ((), "emissiveTexture"), ((), "normalTexture"),
                 (("extensions", "KHR_materials_clearcoat"), "clearcoatTexture"),
                 (("extensions", "KHR_materials_clearcoat"), "clearcoatRoughnessTexture"),
                 (("extensions", "KHR_materials_clearcoat"), "clearcoatNormalTexture"),
                 (("extensions", "KHR_materials_specular"), "specularColorTexture"),
                 (("extras",), "rt_coat_tint_texture"), (("extras",), "rt_sheen_texture"),
                 (("extras",), "rt_sheen_tint_texture"), (("extras",), "rt_anisotropy_texture"),
                 (("extras",), "rt_diffuse_roughness_texture"),
                 (("extensions", "KHR_materials_iridescence"), "iridescenceThicknessTexture"),
                 (("extensions", "KHR_materials_transmission"), "transmissionTexture"),
                 (("extensions", "KHR_materials_specular"), "specularTexture"),
                 (("extras",), "rt_ior_texture"))


def uv_maps_of(mesh):
    """(the default uv map's name, every map's name) of a mesh; ("", ()) without uvs."""
    if not len(mesh.uv_layers):
        return "", ()
    return default_uv_map(mesh), tuple(layer.name for layer in mesh.uv_layers)


def texture_infos(gltf_material):
    """(glTF key, texture info) of each texture of a glTF material."""
    for path, key in TEXTURE_INFOS:
        holder = gltf_material
        for step in path:
            holder = holder.get(step, {})
        if key in holder:
            yield key, holder[key]


def second_uv_map(uv_maps, gltf_materials):
    """The map rt carries as the second uv set, or None: the first map other than the
    default that a texture reads."""
    default, names = uv_maps
    for material in gltf_materials:
        for _, info in texture_infos(material):
            name = info.get(UV_MAP_KEY, "")
            if name not in ("", default) and name in names:
                return name
    return None


def assign_uv_sets(uv_maps, gltf_materials, second):
    """Copies of the glTF materials whose textures name their uv set as glTF's texCoord:
    1 for the map `second`, else the default (warned about where a texture names another)."""
    import copy

    default, names = uv_maps
    out = copy.deepcopy(gltf_materials)
    for material in out:
        tangent_map = material.get("extras", {}).pop(TANGENT_UV_MAP_KEY, "")
        if tangent_map not in ("", default):
            log(f"{material['name']}: its Tangent node follows uv map {tangent_map!r}; rt follows the tangents of "
                f"the default one ({default!r})")
        for key, info in texture_infos(material):
            name = info.pop(UV_MAP_KEY, "")
            if name in ("", default):
                continue
            if name == second:
                info["texCoord"] = 1
            elif name not in names:
                log(f"{material['name']}: {key} reads uv map {name!r}, which the mesh does not have; "
                    f"rt uses {default!r}")
            else:
                log(f"{material['name']}: {key} reads uv map {name!r}; rt carries two ({default!r} and "
                    f"{second!r}) and uses {default!r}")
    return out


def mesh_thickness(mesh):
    """The thickness of volumes: the mesh's smallest extent (an axis swap keeps it)."""
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    extent = co.max(axis=0) - co.min(axis=0) if len(co) else [1]
    return float(max(min(extent), 1e-3))


def export_mesh(mesh, materials, textures):
    """(rtmesh bytes, gltf text, {image file: PNG bytes}, triangle count) of an evaluated
    mesh shown with `materials`, its images collected by `textures`. The materials come
    first: the uv maps their textures read choose the second uv set."""
    thickness = mesh_thickness(mesh)
    gltf_materials = rt_shader_graphs.finish_materials([gltf_material(m, thickness, textures) for m in materials],
                                                    rt_shader_graphs.texture_space(mesh))
    uv_maps = uv_maps_of(mesh)
    second = second_uv_map(uv_maps, gltf_materials)
    read, default_color = rt_attributes.attributes_read(mesh, gltf_materials)
    rt_attributes.number_attributes(gltf_materials, read, default_color)
    arrays = mesh_arrays(mesh, len(materials), second, list(read))
    gltf = gltf_text(assign_uv_sets(uv_maps, gltf_materials, second), thickness, textures)
    return rtmesh_bytes(arrays), gltf, textures.images, len(arrays["indices"])


def plain_instance(obj):
    """No modifiers and no object-level materials: the object shows its mesh data as it is."""
    return not obj.modifiers and all(slot.link == "DATA" for slot in obj.material_slots)


class Export:
    """One export run: which folder each object's mesh went to."""

    def __init__(self, out_dir):
        self.out_dir = os.path.abspath(out_dir)
        self.folder_of = {}  # object name -> folder name
        self.content = {}  # folder name -> (rtmesh bytes, gltf text)
        self.written = []  # files actually rewritten
        self.triangles = {}
        self.instances = {}  # (folder name, object settings) -> Placements of its instances
        self.view_layer = None  # the view layer whose holdouts the export follows
        self.images = {}  # folder name -> {image file name: PNG bytes}
        self.bake_size = 0  # > 0: bake what rt cannot follow into images of this size

    def instance_counts(self):
        """{folder name: how many instances place it}, whatever their Shadow Terminator settings."""
        counts = {}
        for (folder, _), placed in self.instances.items():
            counts[folder] = counts.get(folder, 0) + len(placed)
        return counts

    def add(self, obj, depsgraph):
        base = sanitize(obj.data.name)
        if plain_instance(obj):
            # Its evaluated mesh is its data's: any plain instance of that data already exported will do.
            for other, folder in self.folder_of.items():
                o = bpy.data.objects.get(other)
                if o is not None and o.data == obj.data and plain_instance(o):
                    self.folder_of[obj.name] = folder
                    return
        rtmesh, gltf, images, triangles = export_object_mesh(obj, depsgraph, base, self.bake_size)
        if triangles == 0:
            # Geometry nodes that output only instances leave the object itself empty.
            return
        self.folder_of[obj.name] = self.store(base, rtmesh, gltf, images, triangles)

    def store(self, base, rtmesh, gltf, images, triangles):
        """The folder holding these bytes: an existing one with the same content, or a new
        one named after `base`."""
        folder = base
        suffix = 1
        while folder in self.content and self.content[folder] != (rtmesh, gltf):
            suffix += 1
            folder = f"{base}_{suffix}"
        if folder not in self.content:
            self.content[folder] = (rtmesh, gltf)
            self.images[folder] = images
            self.triangles[folder] = triangles
            self.write(folder)
        return folder

    def write(self, folder):
        rtmesh, gltf = self.content[folder]
        files = [(folder + ".rtmesh", rtmesh), (folder + ".gltf", gltf)] + sorted(self.images[folder].items())
        for name, data in files:
            path = os.path.join(self.out_dir, folder, name)
            if write_if_changed(path, data):
                self.written.append(path)


# --- instances --------------------------------------------------------------------


def instance_materials(inst):
    """The materials an instance shows: its object's slots (object-linked ones included)
    for collection, particle and linked-duplicate instances; the instanced geometry's
    own for geometry-nodes instances, whose object is the one running the nodes."""
    obj = inst.object
    own, shown = obj.original.data, obj.data.original
    # Compared by name and library: the two references to one mesh need not be one Python object.
    if own is not None and (shown.name, shown.library) == (own.name, own.library):
        return object_slot_materials(obj.original)
    return list(obj.data.materials) or [None]


def rt_rows(matrices):
    """The top three rows of Blender object matrices (an (n, 4, 4) array) in rt's axes,
    row-major, as an (n, 12) array, and which of them rt can invert: finite, with a
    determinant above 1e-6 of the largest that columns of these lengths can have."""
    m = np.asarray(matrices, dtype=np.float64).reshape(-1, 4, 4)
    rows = (np.asarray(TO_RT) @ m @ np.asarray(FROM_RT))[:, :3, :].reshape(-1, 12)
    with np.errstate(all="ignore"):
        linear = m[:, :3, :3]
        lengths = np.prod(np.linalg.norm(linear, axis=1), axis=1)
        finite = np.isfinite(m).all(axis=(1, 2))
        det = np.linalg.det(np.where(finite[:, None, None], linear, 0.0))
        invertible = finite & (np.abs(det) > 1e-6 * lengths)
    return rows, invertible


class InstancedMesh:
    """An evaluated mesh that instances place, exported once: its first instance's
    materials are the asset's own, and an instance showing other materials picks a
    material set of the instance file (slot i shows the set's i-th asset material), the
    asset's .gltf holding every material some instance shows."""

    def __init__(self, mesh, materials, base, baker=None):
        self.base = base
        self.textures = Textures(base, baker)
        self.thickness = mesh_thickness(mesh)
        self.texture_space = rt_shader_graphs.texture_space(mesh)
        self.index = {}  # material name -> index in the asset's materials
        self.exported = []  # glTF materials, the asset's own first
        own = [self.material(m) for m in materials]
        # Material sets shown later use the own materials' second uv set.
        self.uv_maps = uv_maps_of(mesh)
        self.second_uv_map = second_uv_map(self.uv_maps, [self.exported[i] for i in own])
        # So do their attributes.
        self.attributes = rt_attributes.attributes_read(mesh, [self.exported[i] for i in own])
        arrays = mesh_arrays(mesh, len(materials), self.second_uv_map, list(self.attributes[0]))
        self.rtmesh = rtmesh_bytes(arrays)
        self.triangles = len(arrays["indices"])
        self.slots = len(materials)
        self.sets = []  # tuples of asset material indices, one per slot
        self.matrices = []  # Blender matrix of each instance
        self.rows = None  # their rt matrix rows, an (n, 12) array, once invertible ones are kept
        self.codes = []  # each instance's .rtinst material
        self.terminators = []  # each instance's shadow_terminator(object)
        self.infos = []  # each instance's Object Info: (random, r, g, b, a, object index)

    def material(self, m):
        key = m.name if m else ""
        if key not in self.index:
            self.index[key] = len(self.exported)
            self.exported.append(gltf_material(m, self.thickness, self.textures))
        return self.index[key]

    def code_of(self, materials):
        """The .rtinst material of an instance showing `materials`: the asset's own, a
        material set, or None when a set cannot show them (another slot count)."""
        if len(materials) != self.slots:
            return None
        indices = tuple(self.material(m) for m in materials)
        if indices == tuple(range(self.slots)):
            return RTINST_OWN_MATERIALS
        if indices not in self.sets:
            self.sets.append(indices)
        return RTINST_MATERIAL_SET | self.sets.index(indices)

    def gltf(self):
        materials = rt_shader_graphs.finish_materials(self.exported, self.texture_space)
        rt_attributes.number_attributes(materials, *self.attributes)
        materials = assign_uv_sets(self.uv_maps, materials, self.second_uv_map)
        return gltf_text(materials, self.thickness, self.textures)


def instanced_mesh(meshes, obj, materials, bakers=None):
    """(key into `meshes`, .rtinst material) of an instance of `obj` showing `materials`,
    exporting its mesh at its first instance; `meshes[key]` is None for an empty mesh.
    `bakers`: what `prebake_instances` baked, per original mesh."""
    mesh = original_mesh(obj) if bakers else None
    baker = bakers.get(mesh.as_pointer()) if mesh is not None else None
    key = obj.data.as_pointer()
    if key not in meshes:
        meshes[key] = InstancedMesh(obj.data, materials, sanitize(obj.data.name), baker)
    code = meshes[key].code_of(materials) if meshes[key] else RTINST_OWN_MATERIALS
    if code is None:
        # Shown as no material set can show it: another asset folder (same geometry, other materials).
        key = (key, tuple(m.name if m else "" for m in materials))
        if key not in meshes:
            meshes[key] = InstancedMesh(obj.data, materials, sanitize(obj.data.name), baker)
        code = RTINST_OWN_MATERIALS
    if meshes[key] and meshes[key].triangles == 0:
        meshes[key] = None
    return key, code


def exported_instances(depsgraph):
    """The instances of `depsgraph` that rt exports: mesh instances shown in renders."""
    for inst in depsgraph.object_instances:
        obj = inst.object
        if inst.is_instance and obj.type == "MESH" and obj.data is not None and not obj.original.hide_render:
            yield inst


def original_mesh(obj):
    """The mesh data-block an instance's evaluated object shows (its object's own data for
    collection and particle instances, the instanced one's for geometry-nodes instances
    of an object), or None for geometry made by geometry nodes."""
    own, shown = obj.original.data, obj.data
    if own is not None and (shown.name, shown.library) == (own.name, own.library):
        return own
    mesh = shown.original
    return None if mesh.is_evaluated else mesh


def prebake_instances(depsgraph, size):
    """Bakes what rt cannot follow in the materials of meshes that instances show, before
    the instances are exported (a bake changes the scene, which the depsgraph's instance
    iterator must not see): {original mesh pointer: Baker}. Each mesh is baked on a
    stand-in object showing it with each set of materials its instances show."""
    shown = {}  # original mesh pointer -> (mesh, [material lists])
    for inst in exported_instances(depsgraph):
        mesh = original_mesh(inst.object)
        materials = instance_materials(inst)
        if not any(needs_bake(surface.inputs[name]) for surface in map(principled_surface, materials)
                   if surface is not None for name in BAKED_SOCKETS + ("Normal",)):
            continue
        if mesh is None:
            log(f"{inst.object.original.name}: its instances' geometry is made by geometry nodes and has no mesh "
                f"to bake on; their procedural sockets keep their own values")
            continue
        sets = shown.setdefault(mesh.as_pointer(), (mesh, []))[1]
        if materials not in sets:
            sets.append(materials)
    bakers = {}
    for key, (mesh, sets) in shown.items():
        stand_in = bpy.data.objects.new(f"rt_bake_{mesh.name}", mesh)
        bpy.context.scene.collection.objects.link(stand_in)
        bpy.context.view_layer.update()
        baker = Baker(stand_in, size)
        try:
            for materials in sets:
                for slot, material in zip(stand_in.material_slots, materials):
                    slot.link = "OBJECT"
                    slot.material = material
                baker.prebake(materials)
        finally:
            bpy.data.objects.remove(stand_in)
        baker.obj = None
        bakers[key] = baker
    return bakers


def add_instances(export, depsgraph):
    """Every instance that `depsgraph` generates (collection instances, nested ones,
    geometry-nodes instances, particles): each distinct evaluated mesh is exported once,
    and each instance's matrix and material set are kept for its folder. With
    `export.bake_size`, their materials are baked first (`prebake_instances`)."""
    bakers = None
    if export.bake_size > 0:
        bakers = prebake_instances(depsgraph, export.bake_size)
        depsgraph = bpy.context.evaluated_depsgraph_get()
    meshes = {}  # mesh identity (with material names for a set that cannot be) -> InstancedMesh, or None when empty
    resolved = {}  # (object, mesh) identity -> what `instanced_mesh` said for it
    for inst in exported_instances(depsgraph):
        obj = inst.object
        identity = (obj.original.as_pointer(), obj.data.as_pointer())
        if identity not in resolved:
            resolved[identity] = instanced_mesh(meshes, obj, instance_materials(inst), bakers)
        key, code = resolved[identity]
        entry = meshes[key]
        if entry is None:
            continue
        # A copy: the depsgraph reuses the instance's matrix for the next one.
        entry.matrices.append(inst.matrix_world.copy())
        entry.codes.append(code)
        # Cycles takes an instance's holdout from what instances it.
        entry.terminators.append(object_settings(inst.parent or obj, depsgraph.view_layer, obj))
        entry.infos.append((instance_random(inst.random_id),) + tuple(float(c) for c in obj.color)
                           + (int(obj.pass_index),))
    for entry in meshes.values():
        if entry is None or not entry.matrices:
            continue
        rows, invertible = rt_rows(entry.matrices)
        if not invertible.all():
            log(f"{(~invertible).sum()} instances of {entry.base} are scaled to nothing or not finite; left out of the scene")
        entry.rows = rows[invertible]
        entry.codes = [c for c, keep in zip(entry.codes, invertible) if keep]
        entry.terminators = [t for t, keep in zip(entry.terminators, invertible) if keep]
        entry.infos = [t for t, keep in zip(entry.infos, invertible) if keep]
        if not entry.codes:
            continue
        folder = export.store(entry.base, entry.rtmesh, entry.gltf(), entry.textures.images, entry.triangles)
        # An instance file's entry carries one object's Shadow Terminator and holdout settings:
        # instances of objects with other settings go into a file of their own.
        for terminator in sorted(set(entry.terminators)):
            placed = export.instances.setdefault((folder, terminator), Placements(entry.slots))
            placed.add(entry, np.array([t == terminator for t in entry.terminators]))


class Placements:
    """The instances of one asset folder: their matrices, materials and material sets."""

    def __init__(self, slots):
        self.slots = slots
        self.rows = []
        self.codes = []
        self.sets = []
        self.infos = []

    def __len__(self):
        return len(self.codes)

    def add(self, entry, keep):
        """`entry`'s instances where `keep` (a boolean array) is true, its sets renumbered into
        this folder's (a folder with the same bytes has the same materials, in the same order)."""
        for s in entry.sets:
            if s not in self.sets:
                self.sets.append(s)
        renumber = [RTINST_MATERIAL_SET | self.sets.index(s) for s in entry.sets]
        self.rows.append(entry.rows[keep])
        codes = [c for c, k in zip(entry.codes, keep) if k]
        self.infos += [i for i, k in zip(entry.infos, keep) if k]
        self.codes += [c if c == RTINST_OWN_MATERIALS else renumber[c & ~RTINST_MATERIAL_SET] for c in codes]


def rtinst_bytes(placements):
    """The instance file (version 5): magic, version, instance, slot and set counts, no
    motion keys and each instance's Object Info, the material sets, (12 f32, u32) per
    instance, then (random, r, g, b, a as f32, Object Index as u32) per instance."""
    records = np.zeros(len(placements), dtype=[("rows", "<f4", 12), ("material", "<u4")])
    records["rows"] = np.concatenate(placements.rows).astype(np.float32)
    records["material"] = np.asarray(placements.codes, dtype=np.uint32)
    slots = placements.slots if placements.sets else 0
    header = struct.pack("<6I", RTINST_VERSION, len(placements), slots, len(placements.sets), 0, 1)
    sets = np.asarray(placements.sets, dtype="<u4").tobytes()
    infos = np.zeros(len(placements), dtype=[("info", "<f4", 5), ("index", "<u4")])
    infos["info"] = np.asarray([i[:5] for i in placements.infos], dtype=np.float32).reshape(len(placements), 5)
    infos["index"] = np.asarray([i[5] for i in placements.infos], dtype=np.uint32)
    return RTINST_MAGIC + header + sets + records.tobytes() + infos.tobytes()


def instances_toml(export, scene_path):
    """One [[instances]] per folder with instances (and per Shadow Terminator settings of
    their objects), writing its instance file into SCENE_instances/ beside the scene file."""
    scene_dir = os.path.dirname(os.path.abspath(scene_path))
    stem = os.path.splitext(os.path.basename(scene_path))[0]
    text = []
    for folder, terminator in sorted(export.instances):
        placed = export.instances[(folder, terminator)]
        name = folder if terminator[:2] == SHADOW_TERMINATOR_DEFAULTS else f"{folder}_terminator_{fmt(terminator[0])}_{fmt(terminator[1])}"
        name += "_holdout" if terminator[2] else ""
        path = os.path.join(scene_dir, f"{stem}_instances", name + ".rtinst")
        if write_if_changed(path, rtinst_bytes(placed)):
            export.written.append(path)
        asset = os.path.relpath(os.path.join(export.out_dir, folder), scene_dir).replace(os.sep, "/")
        file = os.path.relpath(path, scene_dir).replace(os.sep, "/")
        text.append(f"# {len(placed)} instances\n[[instances]]\nasset = {json.dumps(asset)}\nfile = {json.dumps(file)}\n"
                    f"{object_settings_toml(terminator)}\n")
    return "".join(text)


# --- scene TOML -------------------------------------------------------------------


# Blender's defaults of an object's Shadow Terminator settings (Object > Shading): (Geometry
# Offset, Shading Offset), which are also the scene file's defaults.
SHADOW_TERMINATOR_DEFAULTS = (0.1, 0.0)


def shadow_terminator(obj):
    """(Geometry Offset, Shading Offset) of `obj`, the object's own properties that Cycles
    reads (not the legacy `obj.cycles` ones), to six decimals (Blender keeps them in float)."""
    return (round(float(obj.shadow_terminator_geometry_offset), 6), round(float(obj.shadow_terminator_shading_offset), 6))


def object_settings(obj, view_layer, shading=None):
    """(Geometry Offset, Shading Offset, holdout) of an object: its Shadow Terminator
    settings (those of `shading` if given: an instance's own) and whether it is held out in
    `view_layer` (its own Holdout or its collection's)."""
    return shadow_terminator(shading or obj) + (bool(obj.original.holdout_get(view_layer=view_layer)),)


def object_settings_toml(settings):
    """The scene-file keys of an object's settings other than the defaults."""
    return shadow_terminator_toml(settings[:2]) + ("holdout = true\n" if settings[2] else "")


def object_random(name):
    """Object Info's Random of an object named `name`, as Cycles sets it for an object that
    is not an instance: hash_uint2(hash_string(name), 0) over 2^32 - 1, in float32."""
    h = 0
    for byte in name.encode("utf-8"):
        h = (h * 37 + byte) & 0xFFFFFFFF  # the UTF-8 bytes as unsigned (found against Cycles)
    seed = (0xDEADBEEF + (2 << 2) + 13) & 0xFFFFFFFF
    return instance_random(lookup3_final((seed + h) & 0xFFFFFFFF, seed, seed))


def object_info_toml(obj):
    """The scene-file keys of what Object Info reads of `obj`: its Random, its Object Color
    when not Blender's white and its Object Index (Pass Index) when not 0."""
    color = [float(c) for c in obj.color]
    text = f"random = {fmt(object_random(obj.name))}\n"
    text += f"object_color = {vec(color)}\n" if color != [1.0, 1.0, 1.0, 1.0] else ""
    return text + (f"object_index = {int(obj.pass_index)}\n" if obj.pass_index else "")


def shadow_terminator_toml(terminator):
    """The scene-file keys of Shadow Terminator settings other than the defaults."""
    keys = ("shadow_terminator_geometry_offset", "shadow_terminator_shading_offset")
    return "".join(f"{key} = {fmt(value)}\n" for key, value, default in zip(keys, terminator, SHADOW_TERMINATOR_DEFAULTS)
                   if value != default)


def fmt(x):
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"non-finite value {x} in the scene")
    text = f"{x:.9g}"
    return text if any(c in text for c in ".en") else text + ".0"


def vec(values):
    return "[" + ", ".join(fmt(v) for v in values) + "]"


def render_size(scene):
    """The output's size as Blender makes it: the resolution times the percentage, rounded
    down (103x79 at 50% is 51x39)."""
    r = scene.render
    return (
        max(1, r.resolution_x * r.resolution_percentage // 100),
        max(1, r.resolution_y * r.resolution_percentage // 100),
    )


def focus_distance(cam):
    """Cycles' focus distance: the focus object's distance along the view axis, if any."""
    dof = cam.data.dof
    if dof.focus_object is None:
        return dof.focus_distance
    if dof.focus_subtarget:
        log(f"camera {cam.name}: focus bone {dof.focus_subtarget!r} is ignored; focusing on its object")
    view_axis = world_matrix(cam).to_3x3().col[2].normalized()
    offset = world_matrix(cam).translation - world_matrix(dof.focus_object).translation
    return abs(view_axis.dot(offset))


# Blender's panorama types that rt renders, by their rt `projection`.
PANORAMAS = {
    "EQUIRECTANGULAR": "equirectangular",
    "FISHEYE_EQUIDISTANT": "fisheye_equidistant",
    "FISHEYE_EQUISOLID": "fisheye_equisolid",
    "MIRRORBALL": "mirror_ball",
}


def panorama_lines(cam):
    """The keys of a panoramic camera: its mapping's angles (Blender's radians as degrees)."""
    data = cam.data
    kind = PANORAMAS[data.panorama_type]
    lines = [f"projection = {json.dumps(kind)}"]
    if kind == "equirectangular":
        angles = []
        for name, limit in [("latitude", math.pi / 2), ("longitude", math.pi)]:
            for end in ("min", "max"):
                value = getattr(data, f"{name}_{end}")
                # Blender keeps its ±90° and ±180° in f32, a hair beyond them; it also lets
                # longitudes run past a full turn, which rt keeps to.
                if abs(value) > limit + 1e-6:
                    log(f"camera {cam.name}: {name}_{end} beyond ±{math.degrees(limit):.0f}° is clamped to it")
                value = max(-limit, min(limit, value))
                angles.append(f"{name}_{end}_deg = {fmt(math.degrees(value))}")
        lines += angles
    elif kind.startswith("fisheye"):
        lines.append(f"fisheye_fov_deg = {fmt(math.degrees(data.fisheye_fov))}")
        if kind == "fisheye_equisolid":
            lines.append(f"fisheye_lens_mm = {fmt(data.fisheye_lens)}")
    if data.dof.use_dof:
        # Cycles sizes a panorama's aperture from the camera's (perspective) lens.
        lines.append(f"focal_length_mm = {fmt(data.lens)}")
    return lines


def camera_pose(matrix_world, focus):
    """`position`, `look_at` and `up` lines of a camera at `matrix_world` (Blender's camera
    looks down its local -Z with +Y up), looking at its focus distance."""
    m = TO_RT @ matrix_world
    position = m.translation
    forward = -(m.to_3x3() @ Vector((0, 0, 1))).normalized()
    up = (m.to_3x3() @ Vector((0, 1, 0))).normalized()
    look_at = position + forward * (focus if focus > 0 else 10.0)
    return [f"position = {vec(position)}", f"look_at = {vec(look_at)}", f"up = {vec(up)}"]


def camera_toml(scene):
    """The camera as Cycles sees it: its roll through `up`, projection (perspective,
    orthographic or one of the panoramas of PANORAMAS), sensor, shift, clip planes and
    depth of field (Blender's camera looks down its local -Z with +Y up)."""
    cam = scene.camera
    if cam is None:
        return ""
    data = cam.data
    panoramic = data.type == "PANO" and data.panorama_type in PANORAMAS
    if data.type == "PANO" and not panoramic:
        log(f"camera {cam.name}: the {data.panorama_type} panorama is exported as a perspective camera")
    elif data.type not in {"PERSP", "ORTHO", "PANO"}:
        log(f"camera {cam.name}: {data.type} is exported as a perspective camera")
    focus = focus_distance(cam)
    lines = camera_pose(world_matrix(cam), focus)
    if cam.name in _motion:
        poses = ", ".join("{ " + ", ".join(camera_pose(m, focus)) + " }" for m in _motion[cam.name])
        lines.append(f"motion = [{poses}]")
    if panoramic:
        lines += panorama_lines(cam)
    elif data.type == "ORTHO":
        lines += ['projection = "orthographic"', f"ortho_scale = {fmt(data.ortho_scale)}"]
    else:
        lines.append(f"focal_length_mm = {fmt(data.lens)}")
    lines += [
        f"sensor_fit = {json.dumps(data.sensor_fit.lower())}",
        f"sensor_width_mm = {fmt(data.sensor_width)}",
        f"sensor_height_mm = {fmt(data.sensor_height)}",
        f"shift_x = {fmt(data.shift_x)}",
        f"shift_y = {fmt(data.shift_y)}",
        f"clip_start = {fmt(data.clip_start)}",
    ]
    aspect = (scene.render.pixel_aspect_x, scene.render.pixel_aspect_y)
    if aspect[0] != aspect[1]:
        lines.append(f"pixel_aspect = {vec(aspect)}")
    if data.clip_end > data.clip_start:
        lines.append(f"clip_end = {fmt(data.clip_end)}")
    else:
        log(f"camera {cam.name}: clip_end is not beyond clip_start; exported without a far clip")
    dof = data.dof
    if dof.use_dof:
        # Cycles clamps both to 1e-5 rather than refusing them.
        lines += [
            f"fstop = {fmt(max(dof.aperture_fstop, 1e-5))}",
            f"focus_distance = {fmt(max(focus, 1e-5))}",
            # Cycles renders fewer than 3 blades as a round aperture.
            f"blades = {dof.aperture_blades if dof.aperture_blades >= 3 else 0}",
            f"blade_rotation_deg = {fmt(math.degrees(dof.aperture_rotation))}",
            f"aperture_ratio = {fmt(dof.aperture_ratio)}",
        ]
    return "[camera]\n" + "\n".join(lines) + "\n\n"


def lamps(scene):
    return sorted(
        (o for o in scene.objects if o.type == "LIGHT" and o.data.type in LAMP_TYPES and is_shown(o, scene)),
        key=lambda o: o.name,
    )


def sky_is_atmosphere(scene):
    return sky_toml(scene).startswith('[sky]\nkind = "atmosphere"')


def sun_toml(scene):
    """Under a Sky Texture, the first Sun lamp lights rt's atmosphere as its `[sun]`."""
    suns = [o for o in lamps(scene) if o.data.type == "SUN"]
    if not suns or not sky_is_atmosphere(scene):
        return ""
    sun = suns[0]
    # A sun shines along its local -Z, so the sun itself lies along +Z.
    to_sun = (TO_RT.to_3x3() @ world_matrix(sun).to_3x3() @ Vector((0, 0, 1))).normalized()
    elevation = math.degrees(math.asin(max(-1.0, min(1.0, to_sun.y))))
    azimuth = math.degrees(math.atan2(to_sun.x, to_sun.z))
    diameter = min(max(math.degrees(sun.data.angle), 1e-3), 89.9)
    return (
        f"[sun]\nelevation_deg = {fmt(elevation)}\nazimuth_deg = {fmt(azimuth)}\n"
        f"angular_diameter_deg = {fmt(diameter)}\n\n"
    )


LAMP_TYPES = {"POINT": "point", "SPOT": "spot", "AREA": "area", "SUN": "sun"}


def lamp_area(obj):
    """Cycles' Light::area, by which it divides a lamp's power when "Normalize" is on."""
    data = obj.data
    if data.type in ("POINT", "SPOT"):
        area = 4.0 * math.pi * data.shadow_soft_size**2
        return area if area > 0.0 else 4.0
    if data.type == "AREA":
        size_y = data.size_y if data.shape in ("RECTANGLE", "ELLIPSE") else data.size
        u, v = world_matrix(obj).col[0].to_3d().length, world_matrix(obj).col[1].to_3d().length
        area = u * data.size * v * size_y
        return area * math.pi / 4.0 if data.shape in ("DISK", "ELLIPSE") else area
    half = data.angle / 2.0
    return math.pi * math.sin(half) ** 2 if half > 0.0 else 1.0


def lamp_color(obj):
    """A lamp's colour as Cycles lights with it: times its blackbody Temperature's colour
    (Blender's `temperature_color`, linear) when that is on, and times what its node tree's
    Emission gives when that is constant (`lamp_nodes_factor`)."""
    data = obj.data
    color = list(data.color)
    if getattr(data, "use_temperature", False):
        color = [c * t for c, t in zip(color, data.temperature_color)]
    return [c * f for c, f in zip(color, lamp_nodes_factor(obj))]


def blackbody_color(temperature):
    """Cycles' Blackbody node's colour at `temperature` (K): Blender's own blackbody colour,
    read through a scratch lamp's Temperature."""
    scratch = bpy.data.lights.new("rt blackbody", "POINT")
    try:
        scratch.use_temperature, scratch.temperature = True, temperature
        return [float(c) for c in scratch.temperature_color]
    finally:
        bpy.data.lights.remove(scratch)


def constant_input(socket, colour):
    """The constant an input of a lamp's Emission takes (its own value, or an RGB, Value or
    Blackbody node of constant temperature linked to it), or None when a graph varies it."""
    source = linked_node(socket)
    if source is None:
        value = socket.default_value
    elif (constant := rt_shader_nodes.constant_node_value(source)) is not None:
        value = constant
    elif source.type == "BLACKBODY" and not source.inputs["Temperature"].is_linked:
        value = blackbody_color(source.inputs["Temperature"].default_value)
    else:
        return None
    try:
        values = [float(v) for v in value][:3]
    except TypeError:
        values = [float(value)] * 3
    return values if colour else sum(values) / 3.0


def lamp_nodes_factor(obj):
    """What a lamp's node tree multiplies its light by, as Cycles evaluates it: the Emission
    at its Light Output, Color x Strength, where both are constant; 1 (warned) for a tree rt
    cannot fold (a texture, a falloff, Light Path), 0 for an output left empty."""
    data = obj.data
    if not getattr(data, "use_nodes", False) or data.node_tree is None:
        return [1.0, 1.0, 1.0]
    output = active_output(data.node_tree, "OUTPUT_LIGHT")
    shader = linked_node(output.inputs["Surface"]) if output is not None else None
    if output is not None and shader is None:
        return [0.0, 0.0, 0.0]
    color = constant_input(shader.inputs["Color"], True) if shader and shader.type == "EMISSION" else None
    strength = constant_input(shader.inputs["Strength"], False) if color is not None else None
    if strength is None:
        log(f"light {obj.name}: rt does not render its node tree's graph (only an Emission of constant Color and "
            f"Strength, a Blackbody's or an RGB's): the lamp's own colour and power")
        return [1.0, 1.0, 1.0]
    return [c * strength for c in color]


def light_toml(obj):
    """One lamp as a [[light]]: Blender's units, its matrix with the lamp's local frame kept
    (it shines along local -Z), only the world turned Y-up."""
    data = obj.data
    kind = LAMP_TYPES[data.type]
    for unsupported, what in (
        (not getattr(data, "use_shadow", True), "shadows off"),
        (data.type == "AREA" and data.spread < math.pi - 1e-6, "a spread under 180 degrees"),
    ):
        if unsupported:
            log(f"light {obj.name}: rt does not render {what}")
    power = data.energy * 2.0 ** getattr(data, "exposure", 0.0)
    if not getattr(data, "normalize", True):
        power *= lamp_area(obj)
    lines = [f"# {obj.name}", "[[light]]", f'type = "{kind}"', f"color = {vec(lamp_color(obj))}"]
    lines.append(f"{'strength' if kind == 'sun' else 'power'} = {fmt(power)}")
    if kind in ("point", "spot"):
        lines.append(f"radius = {fmt(data.shadow_soft_size)}")
        lines.append(f"soft_falloff = {'true' if getattr(data, 'use_soft_falloff', True) else 'false'}")
    if kind == "spot":
        lines.append(f"spot_size_deg = {fmt(min(max(math.degrees(data.spot_size), 1.0), 180.0))}")
        lines.append(f"spot_blend = {fmt(data.spot_blend)}")
    if kind == "area":
        lines.append(f'shape = "{data.shape.lower()}"')
        lines.append(f"size = {fmt(data.size)}")
        if data.shape in ("RECTANGLE", "ELLIPSE"):
            lines.append(f"size_y = {fmt(data.size_y)}")
    if kind == "sun":
        lines.append(f"angle_deg = {fmt(math.degrees(data.angle))}")
    if obj.visible_camera:
        lines.append("visible_to_camera = true")
    m = TO_RT @ world_matrix(obj)
    rows = [m[r][c] for r in range(4) for c in range(4)]
    rows[12:16] = [0.0, 0.0, 0.0, 1.0]
    lines.append(f"matrix = {vec(rows)}")
    return "\n".join(lines) + "\n\n"


def lights_toml(scene):
    atmosphere_sun = sun_toml(scene) != ""
    text = []
    for obj in lamps(scene):
        # The first sun is already the atmosphere's `[sun]`.
        if atmosphere_sun and obj.data.type == "SUN":
            atmosphere_sun = False
            continue
        if obj.data.type == "AREA" and abs(world_matrix(obj).to_3x3().determinant()) < 1e-12:
            log(f"light {obj.name}: scaled to nothing; left out of the scene")
            continue
        text.append(light_toml(obj))
    return "".join(text)


def environment_rotation(texture):
    """The rotation (XYZ Euler, degrees) of a Mapping node in front of an Environment
    Texture, as rt applies it to the direction before the lookup."""
    mapping = linked_node(texture.inputs["Vector"])
    if mapping is None or mapping.type == "TEX_COORD":
        return [0.0, 0.0, 0.0]
    if mapping.type != "MAPPING":
        log(f"{owner_name(texture)}: {texture.name}.Vector comes from {mapping.type}; using the view direction")
        return [0.0, 0.0, 0.0]
    from mathutils import Euler

    inputs = mapping.inputs
    if any(inputs[n].is_linked for n in ("Rotation", "Location", "Scale") if n in inputs):
        log(f"{owner_name(mapping)}: {mapping.name} has linked inputs; using their own values")
    rotation = Euler(inputs["Rotation"].default_value, "XYZ")
    if mapping.vector_type == "POINT" and any(abs(c) > 1e-6 for c in inputs["Location"].default_value):
        log(f"{owner_name(mapping)}: {mapping.name}: a Location moves no direction of the world; left out")
    scale = list(inputs["Scale"].default_value) if "Scale" in inputs else [1.0, 1.0, 1.0]
    if max(scale) - min(scale) > 1e-6 * max(abs(c) for c in scale):
        log(f"{owner_name(mapping)}: {mapping.name}: a non-uniform Scale is not supported; left out")
    if mapping.vector_type == "TEXTURE":
        rotation = rotation.to_matrix().inverted().to_euler("XYZ")
    return [math.degrees(a) for a in rotation]


def exr_bytes(rgb):
    """An uncompressed 32-bit float OpenEXR of an (h, w, 3) array, rows from the top. Written
    here because Blender's own writer may store display-encoded values for a generated image."""

    def attribute(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data

    h, w = rgb.shape[:2]
    # Channels in alphabetical order, each FLOAT (2), not linear, sampled 1x1.
    channels = b"".join(c + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    window = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = b"".join(
        [
            struct.pack("<ii", 20000630, 2),
            attribute("channels", "chlist", channels),
            attribute("compression", "compression", b"\0"),
            attribute("dataWindow", "box2i", window),
            attribute("displayWindow", "box2i", window),
            attribute("lineOrder", "lineOrder", b"\0"),
            attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
            attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)),
            attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
            b"\0",
        ]
    )
    planar = np.ascontiguousarray(np.asarray(rgb, np.float32)[:, :, ::-1].transpose(0, 2, 1)).astype("<f4")
    line_bytes = 3 * w * 4
    first = len(header) + 8 * h
    offsets = struct.pack(f"<{h}Q", *(first + y * (8 + line_bytes) for y in range(h)))
    lines = b"".join(struct.pack("<ii", y, line_bytes) + planar[y].tobytes() for y in range(h))
    return header + offsets + lines


LINEAR_COLORSPACES = {"Linear Rec.709", "Non-Color", "Linear", "Linear CIE-XYZ E", "Linear CIE-XYZ D65"}


def environment_image_bytes(image):
    """(bytes, extension, srgb) of an Environment Texture's image. An image whose Color
    Space is sRGB (float ones too) keeps its sRGB codes, which rt interpolates and then
    decodes as Cycles does (`srgb`); other images are the linear values Cycles reads. An
    unmodified .exr or .hdr file goes as it is (packed or on disk), anything else as a
    float EXR."""
    ext = os.path.splitext(image.filepath_raw or image.name)[1].lower()
    srgb = image.colorspace_settings.name == "sRGB" and not image.colorspace_settings.is_data
    linear = image.colorspace_settings.name in LINEAR_COLORSPACES or image.colorspace_settings.is_data
    if ext in {".exr", ".hdr"} and (linear or srgb) and not image.is_dirty:
        if image.packed_file is not None:
            return bytes(image.packed_file.data), ext, srgb
        path = bpy.path.abspath(image.filepath_raw, library=image.library)
        if os.path.isfile(path):
            with open(path, "rb") as f:
                return f.read(), ext, srgb
    pixels = linear_pixels(image)[:, :, :3]
    return exr_bytes(srgb_codes(pixels) if srgb else pixels), ".exr", srgb


def environment_toml(background, texture, export, scene_dir):
    """`[sky] kind = "environment"`: the image copied into the assets folder under a name
    of its content's hash (so an unchanged image is not written again)."""
    strength = float(socket_value(background, "Strength", 1.0))
    rotation = environment_rotation(texture)
    if texture.interpolation != "Linear":
        log(f"{owner_name(texture)}: {texture.name}: {texture.interpolation} interpolation; rt interpolates linearly")
    data, ext, srgb = environment_image_bytes(texture.image)
    stem = sanitize(os.path.splitext(os.path.basename(texture.image.name))[0])
    path = os.path.join(export.out_dir, "environment", f"{stem}-{blake(data)}{ext}")
    if write_if_changed(path, data):
        export.written.append(path)
    image = os.path.relpath(path, scene_dir).replace(os.sep, "/")
    text = f'[sky]\nkind = "environment"\nimage = {json.dumps(image)}\nstrength = {fmt(max(strength, 0.0))}\n'
    if any(abs(a) > 1e-9 for a in rotation):
        text += f"rotation_deg = {vec(rotation)}\n"
    if srgb:
        text += 'color_space = "srgb"\n'
    return text + "\n"


def world_graph_toml(graph, export, scene_dir):
    """`[sky] kind = "graph"`: the World's graph written beside the assets under a name of
    its content's hash."""
    data = json.dumps(graph, indent=1, sort_keys=True).encode("utf-8")
    path = os.path.join(export.out_dir, "world", f"world-{blake(data)}.json")
    if write_if_changed(path, data):
        export.written.append(path)
    graph_path = os.path.relpath(path, scene_dir).replace(os.sep, "/")
    return f'[sky]\nkind = "graph"\ngraph = {json.dumps(graph_path)}\n\n'


def environment_texture(background):
    """The Environment Texture (equirectangular, with an image) behind a Background node, or None."""
    node = linked_node(background.inputs["Color"])
    if node is None or node.type != "TEX_ENVIRONMENT":
        return None
    if node.image is None:
        log(f"{owner_name(node)}: {node.name} has no image; using the Background's colour")
        return None
    if node.projection != "EQUIRECTANGULAR":
        log(f"{owner_name(node)}: {node.name}: {node.projection} projection is not supported; using the Background's colour")
        return None
    return node


def sky_toml(scene, export=None, scene_dir=None):
    """The `[sky]` table; without `export` (only to ask what kind the sky is), an
    environment's image is not written."""
    world = scene.world
    if world is None:
        return '[sky]\nkind = "black"\n\n'
    tree = world.node_tree
    output = active_output(tree, "OUTPUT_WORLD") if tree else None
    background = linked_node(output.inputs["Surface"]) if output else None
    if background is None or background.type != "BACKGROUND":
        color = rgb(world.color)
    else:
        color_source = linked_node(background.inputs["Color"])
        if color_source is not None and color_source.type == "TEX_SKY":
            return '[sky]\nkind = "atmosphere"\n\n'
        texture = environment_texture(background)
        if texture is not None:
            if export is None:
                return '[sky]\nkind = "environment"\n\n'
            return environment_toml(background, texture, export, scene_dir)
        graph = rt_shader_graphs.world_graph(background)
        if graph is not None:
            if export is None:
                return '[sky]\nkind = "graph"\n\n'
            return world_graph_toml(graph, export, scene_dir)
        strength = float(socket_value(background, "Strength", 1.0))
        color = [c * strength for c in rgb(socket_value(background, "Color", (0, 0, 0)))]
    return f'[sky]\nkind = "uniform"\ncolor = {vec(max(c, 0.0) for c in color)}\n\n'


def film_toml(scene):
    """The `[render]` keys of Blender's Film › Transparent and Cycles' Transparent Glass."""
    if not scene.render.film_transparent:
        return ""
    text = "transparent = true\n"
    cycles = getattr(scene, "cycles", None)
    if cycles is not None and cycles.film_transparent_glass:
        roughness = min(max(float(cycles.film_transparent_roughness), 0.0), 1.0)
        text += f"transparent_glass = true\ntransparent_glass_roughness = {fmt(roughness)}\n"
    return text


def rt_rows_of(matrix_world):
    """An object's Blender world matrix as rt's row-major 16 numbers."""
    m = TO_RT @ matrix_world @ FROM_RT
    rows = [m[r][c] for r in range(4) for c in range(4)]
    rows[12:16] = [0.0, 0.0, 0.0, 1.0]
    return rows


# --- motion blur --------------------------------------------------------------------
#
# As Cycles syncs motion (`BlenderSync::sync_motion`): with the render's Motion Blur on, an
# object whose Object > Motion Blur is on is evaluated at 2^(steps-1)·2 + 1 evenly spaced
# times from the shutter's opening to its closing (Motion Steps `steps`; the shutter lasts
# Shutter frames, and starts at, is centred on or ends at the current frame by Position);
# rt interpolates between those keys. Objects that do not move keep no keys.

def motion_steps(obj):
    """How many keys Cycles takes of `obj` over the shutter (0: it is not blurred)."""
    settings = getattr(obj, "cycles", None)
    if settings is None or not settings.use_motion_blur:
        return 0
    return (2 << (max(1, settings.motion_steps) - 1)) + 1


def split_time(t):
    """A frame time as Blender sets it: (frame, subframe)."""
    frame = math.floor(t)
    return frame, t - frame


def shutter_centre(scene):
    """The frame time at the middle of the open shutter, where Cycles evaluates the whole
    scene (what does not blur, lamps, the camera's lens too): the current frame, moved by
    half the shutter when it opens (Position Start) or closes (End) on the frame."""
    render = scene.render
    centre = scene.frame_current + scene.frame_subframe
    return centre + {"START": 0.5, "END": -0.5}.get(render.motion_blur_position, 0.0) * render.motion_blur_shutter


def shutter_times(scene, centre, steps):
    """The `steps` frame times (frame, subframe) from the shutter's opening to its closing."""
    half = 0.5 * scene.render.motion_blur_shutter
    return [split_time(centre + (2.0 * k / (steps - 1) - 1.0) * half) for k in range(steps)]


def motion_keys(scene, objects, centre, frame_set):
    """{object name: its world matrices over the shutter} of the objects (and the camera)
    that move while it is open, evaluated at each time by `frame_set(frame, subframe)`;
    leaves the frame at the shutter's `centre`."""
    movers = [o for o in objects if motion_steps(o) > 0]
    if scene.camera is not None and motion_steps(scene.camera) > 0:
        movers.append(scene.camera)
    by_steps = {}
    for obj in movers:
        steps = motion_steps(obj)
        if obj == scene.camera:
            # rt keeps the camera's keys with each frame's constants: at most 17.
            steps = min(steps, 17)
        by_steps.setdefault(steps, []).append(obj)
    keys = {}
    try:
        for steps, group in by_steps.items():
            for frame, subframe in shutter_times(scene, centre, steps):
                frame_set(frame, subframe)
                for obj in group:
                    keys.setdefault(obj.name, []).append(world_matrix(obj).copy())
    finally:
        frame_set(*split_time(centre))
    return {name: ms for name, ms in keys.items() if any(m != ms[0] for m in ms[1:])}


def scene_toml(scene, export, scene_path, objects):
    width, height = render_size(scene)
    scene_dir = os.path.dirname(os.path.abspath(scene_path))
    text = [
        f"# Exported from Blender by blender/rt_export.py (scene {scene.name!r}).\n\n",
        f"[render]\nwidth = {width}\nheight = {height}\n{film_toml(scene)}\n",
        camera_toml(scene),
        sky_toml(scene, export, scene_dir),
        sun_toml(scene),
        lights_toml(scene),
    ]
    for obj in objects:
        folder = export.folder_of.get(obj.name)
        if folder is None:
            continue
        m = TO_RT @ world_matrix(obj) @ FROM_RT
        if abs(m.to_3x3().determinant()) < 1e-12:
            log(f"{obj.name}: scaled to nothing; left out of the scene")
            continue
        asset = os.path.relpath(os.path.join(export.out_dir, folder), scene_dir).replace(os.sep, "/")
        rows = [m[r][c] for r in range(4) for c in range(4)]
        rows[12:16] = [0.0, 0.0, 0.0, 1.0]
        terminator = object_settings_toml(object_settings(obj, export.view_layer)) + object_info_toml(obj)
        motion = ""
        if obj.name in _motion:
            motion = f"motion = [{', '.join(vec(rt_rows_of(k)) for k in _motion[obj.name])}]\n"
        text.append(f"# {obj.name}\n[[mesh]]\nasset = {json.dumps(asset)}\nmatrix = {vec(rows)}\n{motion}{terminator}\n")
    text.append(instances_toml(export, scene_path))
    return "".join(text).rstrip("\n") + "\n"


# --- the export -------------------------------------------------------------------


def render_modifiers(scene):
    """Sets the scene's modifiers as a render evaluates them (Cycles renders a Subdivision
    Surface's or Multiresolution's render levels, and the modifiers shown in renders); returns
    what puts them back. Objects whose modifiers cannot be set (linked from a library) keep
    the viewport's, with a warning."""
    saved = []
    for obj in scene.objects:
        for modifier in obj.modifiers:
            levels = getattr(modifier, "render_levels", None)
            if modifier.show_viewport == modifier.show_render and getattr(modifier, "levels", levels) == levels:
                continue
            state = (modifier, modifier.show_viewport, getattr(modifier, "levels", None))
            try:
                modifier.show_viewport = modifier.show_render
                if levels is not None:
                    modifier.levels = levels
            except (AttributeError, TypeError, RuntimeError) as e:
                log(f"{obj.name}: modifier {modifier.name} keeps its viewport settings ({e})")
                continue
            saved.append(state)

    def restore():
        for modifier, shown, levels in saved:
            modifier.show_viewport = shown
            if levels is not None:
                modifier.levels = levels
        if saved:
            bpy.context.view_layer.update()

    if saved:
        bpy.context.view_layer.update()
    return restore


def export_scene(scene, out_dir, scene_path=None, only=None, previous=None, bake_size=0, depsgraph=None,
                 frame_set=None, carry=None, motion_blur=True, as_rendered=True):
    """Exports every mesh object `depsgraph` shows into `out_dir`, and the scene TOML to
    `scene_path` if given. F12 passes the render's depsgraph (render visibility and
    render-level modifiers count), the viewport its own (the viewport's); without one,
    the context's depsgraph is evaluated and what renders in the view layer exported.
    With `only` (a set of object names) and the `previous` export, objects outside `only`
    keep the folder they had and are not evaluated. With `bake_size`, sockets fed by what
    rt cannot follow are baked (see `Baker`). With the render's Motion Blur on, the scene is
    exported at the shutter's centre and its moving objects and camera over the shutter,
    each time set by `frame_set(frame, subframe)` (the scene's own by default; F12 passes
    the render engine's, as Cycles does); the frame is set back after, and `motion_blur`
    False leaves it alone (live exports, which run from Blender's update handlers, where
    changing the frame would start another update). With `carry`, the
    export of another frame into the same `out_dir`, meshes go to the folder that already
    holds the same bytes (see `export_frames`). Without a depsgraph, modifiers are evaluated
    as a render evaluates them (`render_modifiers`) unless `as_rendered` is False (live
    exports: they must not change the scene)."""
    global _shown, _depsgraph, _motion
    _shown = shown_objects(depsgraph) if depsgraph is not None else None
    _depsgraph = depsgraph
    # The viewport's live export (a depsgraph without a way to change its frame) stays sharp.
    blur = motion_blur and scene.render.use_motion_blur and (depsgraph is None or frame_set is not None)
    if frame_set is None:
        frame_set = lambda frame, subframe: scene.frame_set(frame, subframe=subframe)  # noqa: E731
    current = (scene.frame_current, scene.frame_subframe)
    shutter = (shutter_centre(scene), frame_set) if blur else None
    restore = render_modifiers(scene) if depsgraph is None and as_rendered else (lambda: None)
    try:
        if depsgraph is None:
            depsgraph = bpy.context.evaluated_depsgraph_get()
        if blur and shutter[0] != current[0] + current[1]:
            frame_set(*split_time(shutter[0]))
        return _export_scene(scene, out_dir, scene_path, (only, previous, carry), bake_size, depsgraph, shutter)
    finally:
        if blur:
            frame_set(*current)
        restore()
        _shown = _depsgraph = None
        _motion = {}


def _export_scene(scene, out_dir, scene_path, earlier, bake_size, depsgraph, shutter):
    only, previous, carry = earlier
    # Images may have been painted or reloaded since the last export.
    _linear_pixels.clear()
    export = Export(out_dir)
    if carry is not None:
        # Frames of one range share their folders: a mesh that has not changed keeps its own.
        export.content, export.images, export.triangles = dict(carry.content), dict(carry.images), dict(carry.triangles)
    export.bake_size = bake_size
    export.view_layer = depsgraph.view_layer
    rt_node_graph.VIEW_LAYER.update(scene=scene, layer=depsgraph.view_layer)
    objects = exported_objects(scene)
    for obj in objects:
        if only is not None and previous is not None and obj.name not in only and obj.name in previous.folder_of:
            folder = previous.folder_of[obj.name]
            export.folder_of[obj.name] = folder
            export.content.setdefault(folder, previous.content[folder])
            export.images.setdefault(folder, previous.images.get(folder, {}))
            continue
        export.add(obj, depsgraph)
    add_instances(export, depsgraph)
    if scene_path:
        global _motion
        if shutter is not None:
            _motion = motion_keys(scene, [o for o in objects if o.name in export.folder_of], *shutter)
        path = bpy.path.abspath(scene_path) if scene_path.startswith("//") else scene_path
        if write_if_changed(path, scene_toml(scene, export, path, objects)):
            export.written.append(path)
    return export


def frame_path(pattern, frame):
    """`pattern` with its run of `#` replaced by the zero-padded frame number (as rt reads
    `--frames`)."""
    start = pattern.find("#")
    if start < 0:
        raise ValueError(f"{pattern}: a frame range needs #### where the frame number goes")
    end = start
    while end < len(pattern) and pattern[end] == "#":
        end += 1
    return f"{pattern[:start]}{frame:0{end - start}d}{pattern[end:]}"


def export_frames(scene, out_dir, scene_pattern, first, last, bake_size=0):
    """Exports frames `first` to `last` (both included) into one `out_dir`, frame N's scene
    to `scene_pattern` with its #### made N, for `rt render PATTERN --frames first..last`.
    Meshes are stored by content: one that does not change from frame to frame is written
    once and keeps its folder (and the BVH cache rt builds there); one that changes gets a
    folder per distinct shape. Returns the last frame's export and the files written."""
    current = (scene.frame_current, scene.frame_subframe)
    export, written = None, []
    try:
        for frame in range(first, last + 1):
            started = time.perf_counter()
            scene.frame_set(frame)
            export = export_scene(scene, out_dir, frame_path(scene_pattern, frame), bake_size=bake_size, carry=export)
            written += export.written
            log(f"frame {frame}: {len(export.written)} files written in {time.perf_counter() - started:.2f} s")
    finally:
        scene.frame_set(current[0], subframe=current[1])
    return export, written


# --- add-on: live export on save -------------------------------------------------

_changes = {"objects": set(), "meshes": set(), "materials": set()}
_last_export = {}  # scene name -> Export


def classify_updates(updates):
    """What a depsgraph's updates changed, by kind: objects moved ("transform"), objects
    whose evaluated mesh ("geometry") or materials ("shading") changed, and the mesh
    data, materials and world edited. Only "geometry", "shading", "meshes" and
    "materials" re-export meshes; everything else lands in the scene file."""
    changes = {"transform": set(), "geometry": set(), "shading": set(), "meshes": set(), "materials": set()}
    changes["world"] = False
    for update in updates:
        original = getattr(update.id, "original", update.id)
        if isinstance(original, bpy.types.Object):
            for kind in ("transform", "geometry", "shading"):
                if getattr(update, f"is_updated_{kind}"):
                    changes[kind].add(original.name)
        elif isinstance(original, bpy.types.Mesh):
            changes["meshes"].add(original.name)
        elif isinstance(original, bpy.types.Material):
            changes["materials"].add(original.name)
        elif isinstance(original, bpy.types.World):
            changes["world"] = True
    return changes


def any_change(changes):
    return any(changes.values())


def add_changes(into, changes):
    """Merges `changes` into `into`, a dict of sets as `_changes` is."""
    into["objects"] |= changes["geometry"] | changes["shading"]
    into["meshes"] |= changes["meshes"]
    into["materials"] |= changes["materials"]


@persistent
def _collect_changes(scene, depsgraph):
    changes = classify_updates(depsgraph.updates)
    add_changes(_changes, changes)
    if any_change(changes) and scene.rt_export.live_edits:
        _export_edit(scene)


def changed_objects(scene, changes=None):
    """Objects whose exported mesh may differ since the last export (by `changes`, a dict
    like `_changes`; by default what changed since the last live export)."""
    changes = _changes if changes is None else changes
    out = set()
    for obj in exported_objects(scene):
        materials = {m.name for m in object_slot_materials(obj) if m is not None}
        if obj.name in changes["objects"] or obj.data.name in changes["meshes"] or materials & changes["materials"]:
            out.add(obj.name)
    return out


def live_export(scene):
    settings = scene.rt_export
    previous = _last_export.get(scene.name)
    only = changed_objects(scene) if previous is not None else None
    scene_path = settings.scene_file if settings.write_scene else None
    # Sharp, as the viewport: a live export runs from handlers, where the frame must not move.
    export = export_scene(scene, bpy.path.abspath(settings.out_dir), scene_path, only, previous, motion_blur=False,
                          as_rendered=False)
    _last_export[scene.name] = export
    for key in _changes:
        _changes[key].clear()
    return export


@persistent
def _export_on_save(_filepath):
    for scene in bpy.data.scenes:
        if scene.rt_export.live:
            export = live_export(scene)
            log(f"live export of {scene.name}: {len(export.written)} files written")


# --- add-on: live export on every edit ---------------------------------------------

# At most one export this often while an edit goes on (an object dragged): the edits in
# between wait, and a timer exports the last of them once the interval has passed.
LIVE_EDIT_INTERVAL_S = 0.1
_edits = {"last_export": -math.inf, "pending": set()}


def _export_edit(scene):
    """An edit of `scene`: exported now, or by the timer when the last export was too recent."""
    wait = _edits["last_export"] + LIVE_EDIT_INTERVAL_S - time.monotonic()
    if wait <= 0:
        _edits["pending"].discard(scene.name)
        _live_edit_export(scene)
        return
    _edits["pending"].add(scene.name)
    if not bpy.app.timers.is_registered(flush_live_edits):
        bpy.app.timers.register(flush_live_edits, first_interval=wait)


def _live_edit_export(scene):
    _edits["last_export"] = time.monotonic()
    export = live_export(scene)
    if export.written:
        log(f"live export of {scene.name}: {len(export.written)} files written")


def flush_live_edits():
    """The timer: exports the scenes whose last edits were held back. Returns None (Blender's
    timers run once then)."""
    for name in sorted(_edits["pending"]):
        scene = bpy.data.scenes.get(name)
        if scene is not None and scene.rt_export.live_edits:
            _live_edit_export(scene)
    _edits["pending"].clear()
    return None


class RtExportSettings(bpy.types.PropertyGroup):
    out_dir: bpy.props.StringProperty(name="Assets", subtype="DIR_PATH", default="//assets/")
    scene_file: bpy.props.StringProperty(name="Scene", subtype="FILE_PATH", default="//scenes/scene.toml")
    write_scene: bpy.props.BoolProperty(name="Write scene file", default=True)
    live: bpy.props.BoolProperty(
        name="Live export on save",
        description="On every save, export the meshes and materials that changed since the last export",
        default=False,
    )
    live_edits: bpy.props.BoolProperty(
        name="Live export on every edit",
        description=(
            "On every edit, export what changed (at most every "
            f"{LIVE_EDIT_INTERVAL_S:g} s while an edit goes on; the last state always lands)"
        ),
        default=False,
    )
    bake: bpy.props.BoolProperty(
        name="Bake procedural sockets",
        description="On Export, bake sockets fed by what rt cannot follow (procedural textures, Color Ramp, Mix ...) "
                    "with Cycles into image textures (live exports leave them as their own values)",
        default=False,
    )
    bake_size: bpy.props.IntProperty(name="Bake size", description="Width and height of each baked image",
                                     default=DEFAULT_BAKE_SIZE, min=1, max=8192)
    frame_range: bpy.props.BoolProperty(
        name="Frame range",
        description="Export every frame from the scene's Frame Start to its End, one scene file each (#### in the "
                    "scene file's name is the frame number); meshes that do not change are written once",
        default=False,
    )

    def bake_texels(self):
        """The `bake_size` argument of `export_scene`: 0 unless baking is on."""
        return self.bake_size if self.bake else 0

    def export(self, scene, out_dir):
        """Exports `scene` into `out_dir` as these settings say: (meshes, files written), or
        raises ValueError for a frame range whose scene file has no ####."""
        scene_path = self.scene_file if self.write_scene else None
        if self.frame_range and scene_path:
            export, written = export_frames(scene, out_dir, scene_path, scene.frame_start, scene.frame_end,
                                            bake_size=self.bake_texels())
            return len(export.content), len(written)
        export = export_scene(scene, out_dir, scene_path, bake_size=self.bake_texels())
        return len(export.content), len(export.written)


def report_export(operator, export):
    """Runs `export` (returning meshes and files written) and reports what it did, or why not."""
    try:
        meshes, written = export()
    except ValueError as e:
        operator.report({"ERROR"}, f"rt: {e}")
        return {"CANCELLED"}
    operator.report({"INFO"}, f"rt: {meshes} meshes, {written} files written")
    return {"FINISHED"}


class RT_OT_export(bpy.types.Operator):
    """Export meshes (.rtmesh + .gltf) and a scene TOML for rt"""

    bl_idname = "export_scene.rt"
    bl_label = "Export rt"
    directory: bpy.props.StringProperty(subtype="DIR_PATH")

    def invoke(self, context, _event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        return report_export(self, lambda: context.scene.rt_export.export(context.scene, self.directory))


class RT_OT_export_now(bpy.types.Operator):
    """Export to the folders set in the rt panel"""

    bl_idname = "rt.export_now"
    bl_label = "Export now"

    def execute(self, context):
        settings = context.scene.rt_export
        export = live_export(context.scene) if settings.live and not settings.frame_range else None
        if export is not None:
            return report_export(self, lambda: (len(export.content), len(export.written)))
        return report_export(self, lambda: settings.export(context.scene, bpy.path.abspath(settings.out_dir)))


class RT_PT_panel(bpy.types.Panel):
    bl_label = "rt"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "rt"

    def draw(self, context):
        settings = context.scene.rt_export
        layout = self.layout
        layout.prop(settings, "out_dir")
        layout.prop(settings, "write_scene")
        row = layout.row()
        row.enabled = settings.write_scene
        row.prop(settings, "scene_file")
        row = layout.row()
        row.enabled = settings.write_scene
        row.prop(settings, "frame_range")
        layout.operator(RT_OT_export_now.bl_idname)
        layout.prop(settings, "bake")
        row = layout.row()
        row.enabled = settings.bake
        row.prop(settings, "bake_size")
        layout.prop(settings, "live")
        layout.prop(settings, "live_edits")


def _menu_entry(self, _context):
    self.layout.operator(RT_OT_export.bl_idname, text="rt (.rtmesh + .gltf + scene)")


CLASSES = (RtExportSettings, RT_OT_export, RT_OT_export_now, RT_PT_panel)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.rt_export = bpy.props.PointerProperty(type=RtExportSettings)
    bpy.types.TOPBAR_MT_file_export.append(_menu_entry)
    bpy.app.handlers.depsgraph_update_post.append(_collect_changes)
    bpy.app.handlers.save_post.append(_export_on_save)


def unregister():
    if bpy.app.timers.is_registered(flush_live_edits):
        bpy.app.timers.unregister(flush_live_edits)
    bpy.app.handlers.save_post.remove(_export_on_save)
    bpy.app.handlers.depsgraph_update_post.remove(_collect_changes)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_entry)
    del bpy.types.Scene.rt_export
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)


# --- command line -----------------------------------------------------------------


def main():
    inside_blender = "--" in sys.argv
    argv = sys.argv[sys.argv.index("--") + 1 :] if inside_blender else sys.argv[1:]
    parser = argparse.ArgumentParser(prog="rt_export.py", description=__doc__.split("\n\n")[0])
    if not inside_blender:
        parser.add_argument("blend", help="the .blend file to export")
    parser.add_argument("--out", required=True, help="folder that receives one asset folder per mesh")
    parser.add_argument("--scene", help="scene TOML to write (asset paths relative to it); with --frames, "
                                        "its #### is each frame's number (shot_####.toml)")
    parser.add_argument("--frames", metavar="A..B",
                        help="export frames A to B (both included), one scene file each, meshes that do not "
                             "change written once")
    parser.add_argument("--bake", action="store_true",
                        help="bake sockets fed by what rt cannot follow (procedural textures, Color Ramp, Mix ...) "
                             "with Cycles into image textures")
    parser.add_argument("--bake-size", type=int, default=DEFAULT_BAKE_SIZE,
                        help=f"width and height of each baked image in texels (default {DEFAULT_BAKE_SIZE})")
    args = parser.parse_args(argv)
    if args.bake_size <= 0:
        parser.error(f"--bake-size must be positive, not {args.bake_size}")
    frames = None
    if args.frames is not None:
        match = re.fullmatch(r"(-?\d+)\.\.(-?\d+)", args.frames)
        if match is None or int(match[1]) > int(match[2]) or not args.scene or "#" not in args.scene:
            parser.error(f"--frames takes A..B (A at most B) with a --scene path holding ####, not {args.frames!r}")
        frames = (int(match[1]), int(match[2]))
    if not inside_blender:
        bpy.ops.wm.open_mainfile(filepath=args.blend)
    bake_size = args.bake_size if args.bake else 0
    if frames is None:
        export = export_scene(bpy.context.scene, args.out, args.scene, bake_size=bake_size)
        written = export.written
    else:
        export, written = export_frames(bpy.context.scene, args.out, args.scene, *frames, bake_size=bake_size)
    for folder in sorted(export.content):
        log(f"{folder}: {export.triangles.get(folder, 0)} triangles")
    log(f"{len(export.content)} meshes, {len(written)} files written")
