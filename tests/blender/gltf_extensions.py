"""Writes a glTF file with KHR_materials_sheen and KHR_materials_anisotropy (no rt extras),
imports it with Blender's own glTF importer and exports the result with
blender/rt_export.py, into the folder given as the first argument, for
tests/blender_gltf_extensions.rs: `source.gltf`, `report.json` (the Principled inputs
Blender's importer set per material) and the export in `assets/` and `scene.toml`."""

import base64
import json
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "cycles"))
out = sys.argv[1]
sys.argv = sys.argv[:1]
import make_texture_refs as refs  # noqa: E402
from cycles_reference import rt_export  # noqa: E402

bpy = refs.bpy
MATERIALS = [
    ("sheen_anisotropy", {
        "KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.5, 0.25], "sheenRoughnessFactor": 0.7},
        "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": -1.0},
    }),
    ("defaults", {"KHR_materials_sheen": {}, "KHR_materials_anisotropy": {}}),
]
triangle = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
document = {
    "asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_materials_sheen", "KHR_materials_anisotropy"],
    "buffers": [{"byteLength": len(triangle),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(triangle).decode()}],
    "bufferViews": [{"buffer": 0, "byteLength": len(triangle)}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "materials": [{"name": name, "extensions": ext} for name, ext in MATERIALS],
    "meshes": [{"name": name, "primitives": [{"attributes": {"POSITION": 0}, "material": i}]}
               for i, (name, _) in enumerate(MATERIALS)],
    "nodes": [{"name": name, "mesh": i, "translation": [2.0 * i, 0, 0]} for i, (name, _) in enumerate(MATERIALS)],
    "scenes": [{"nodes": list(range(len(MATERIALS)))}],
    "scene": 0,
}
os.makedirs(out, exist_ok=True)
source = os.path.join(out, "source.gltf")
with open(source, "w") as f:
    json.dump(document, f)

scene = refs.reset()
bpy.ops.import_scene.gltf(filepath=source)
report = {}
for name, _ in MATERIALS:
    bsdf = next(n for n in bpy.data.materials[name].node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    value = lambda socket: bsdf.inputs[socket].default_value  # noqa: E731
    report[name] = {
        "sheen": value("Sheen Weight"),
        "sheen_tint": list(value("Sheen Tint"))[:3],
        "sheen_roughness": value("Sheen Roughness"),
        "anisotropy": value("Anisotropic"),
        "anisotropy_rotation": value("Anisotropic Rotation"),
        "tangent_linked": bsdf.inputs["Tangent"].is_linked,
    }
refs.camera(scene, (0.0, -12.0, 0.0), (0.0, 0.0, 0.0), 30.0)
rt_export.export_scene(scene, os.path.join(out, "assets"), os.path.join(out, "scene.toml"))
with open(os.path.join(out, "report.json"), "w") as f:
    json.dump(report, f, indent=1)
