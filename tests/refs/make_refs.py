#!/usr/bin/env python3
"""Renders rt's validation scenes with Mitsuba 3 into linear EXR references.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1
    apt-get install libllvm19          # for the llvm_ad_rgb variant
    /tmp/mi/bin/python tests/refs/make_refs.py [--spp 8192] [NAME...]

Each `tests/refs/scenes/NAME.toml` (an rt scene) is translated into a Mitsuba
scene and rendered to `tests/refs/NAME.exr`. `tests/mitsuba_validation.rs`
renders the same TOML with rt and compares.

How rt maps to Mitsuba (only what the validation scenes use; anything else is
refused rather than guessed):

| rt                                   | Mitsuba 3                                               |
|--------------------------------------|---------------------------------------------------------|
| `[camera]` fov_y_deg                 | `perspective`, `fov_axis = "y"`, look_at with +Y up     |
| pixel sampling (uniform in a pixel)  | `hdrfilm` with a `box` reconstruction filter            |
| `max_bounces = B`                    | `max_depth = B + 1` (depth 1 = emitters seen directly)  |
| diffuse (two-sided in rt)            | `twosided` + `diffuse`, reflectance = base_color·weight |
| `emission` on a planar mesh (rt emits from both faces) | two `area` emitters: the mesh, and a copy with flipped normals moved 0.01 mm along them, so that each side shows an emitting front (a copy moved further shows as a sliver at the light's silhouette) |
| `emission` on a sphere               | `area` emitter on the sphere                            |
| `reflection`, roughness 0            | `conductor`, η = (1+√F0)/(1−√F0) per channel, k = 0     |
| `reflection`, roughness r            | `roughconductor`, GGX, α = r², same η and k             |
| `specular` (untinted GGX, F = 1)     | `roughconductor` with `material = "none"`, α = r²       |
| diffuse + specular weights (sum 1)   | `blendbsdf`, weight = specular weight                   |
| `transmission`, roughness 0          | `dielectric`, int_ior = ior, ext_ior = 1                |
| `transmission`, roughness r          | `roughdielectric`, GGX, α = r²                          |
| `absorption` σ (per metre)           | interior `homogeneous` medium, albedo 0, σt = σ/max(σ) with scale = max(σ) (Mitsuba wants σt in [0,1]); integrator `volpath` |
| OBJ with `usemtl` groups + `.mtl`    | one `obj` shape per group (Kd, Ke as above)             |
| `[sky] kind = "black"`               | no environment emitter                                  |
| `[sky] kind = "uniform"`             | `constant` emitter                                      |
"""

import argparse
import math
import os
import sys
import tempfile
import tomllib

import mitsuba as mi

HERE = os.path.dirname(os.path.abspath(__file__))


def rgb(v):
    return {"type": "rgb", "value": [float(c) for c in v]}


def material_fields(m):
    base = m.get("base_color", [1.0, 1.0, 1.0])
    weights = [m.get(k, d) for k, d in (("diffuse", 1.0), ("specular", 0.0), ("reflection", 0.0), ("transmission", 0.0))]
    total = sum(weights)
    if total > 1.0:
        weights = [w / total for w in weights]
    return base, weights, m.get("roughness", 0.0), m.get("ior", 1.5)


def conductor_eta(base):
    # Normal-incidence reflectance F0 → index of a non-absorbing interface.
    r = [math.sqrt(min(max(c, 0.0), 0.999999)) for c in base]
    return [(1 + x) / (1 - x) for x in r]


def bsdf(m):
    base, (wd, ws, wr, wt), rough, ior = material_fields(m)
    alpha = rough * rough
    if "hardness" in m:
        raise SystemExit("hardness is not used by the validation scenes")
    lobes = [w > 0 for w in (wd, ws, wr, wt)]
    if lobes == [True, False, False, False]:
        return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb([c * wd for c in base])}}
    if lobes == [False, False, True, False]:
        eta = conductor_eta(base)
        if alpha < 1e-3:
            return {"type": "conductor", "eta": rgb(eta), "k": rgb([0, 0, 0]), "specular_reflectance": rgb([wr] * 3)}
        return {"type": "roughconductor", "distribution": "ggx", "alpha": alpha, "eta": rgb(eta), "k": rgb([0, 0, 0]),
                "specular_reflectance": rgb([wr] * 3), "sample_visible": True}
    if lobes == [False, False, False, True] and wt == 1.0:
        if alpha < 1e-3:
            return {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0, "specular_transmittance": rgb(base)}
        return {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha, "int_ior": ior, "ext_ior": 1.0,
                "specular_transmittance": rgb(base), "sample_visible": True}
    if lobes == [True, True, False, False] and abs(wd + ws - 1.0) < 1e-6:
        glossy = {"type": "roughconductor", "distribution": "ggx", "alpha": alpha, "material": "none", "sample_visible": True}
        return {"type": "twosided", "bsdf": {"type": "blendbsdf", "weight": ws,
                "bsdf_0": {"type": "diffuse", "reflectance": rgb(base)}, "bsdf_1": glossy}}
    raise SystemExit(f"no Mitsuba mapping for material {m}")


def medium(m):
    sigma = m.get("absorption", [0, 0, 0])
    top = max(sigma)
    if top <= 0:
        return None
    return {"type": "homogeneous", "albedo": rgb([0, 0, 0]), "sigma_t": rgb([s / top for s in sigma]), "scale": top}


def obj_groups(path):
    """Splits an OBJ with `usemtl` groups into one OBJ per material: (file, mtl fields)."""
    folder = os.path.dirname(path)
    mtl, current = {}, None
    positions, groups = [], {}
    with open(path) as f:
        lines = f.read().splitlines()
    for line in lines:
        w = line.split()
        if not w:
            continue
        if w[0] == "mtllib":
            with open(os.path.join(folder, w[1])) as f:
                for l in f.read().splitlines():
                    p = l.split()
                    if p and p[0] == "newmtl":
                        current = mtl.setdefault(p[1], {})
                    elif p and p[0] in ("Kd", "Ke") and current is not None:
                        current[p[0]] = [float(x) for x in p[1:4]]
        elif w[0] == "v":
            positions.append(w[1:4])
        elif w[0] == "usemtl":
            current = w[1]
        elif w[0] == "f":
            groups.setdefault(current, []).append([int(x.split("/")[0]) for x in w[1:]])
    out = []
    tmp = tempfile.mkdtemp(prefix="rt-refs-")
    for name, faces in groups.items():
        file = os.path.join(tmp, f"{name}.obj")
        with open(file, "w") as f:
            for p in positions:
                f.write(f"v {' '.join(p)}\n")
            for face in faces:
                f.write(f"f {' '.join(str(i) for i in face)}\n")
        out.append((file, mtl.get(name, {})))
    return out


def flipped_copy(file, offset=1e-5):
    """A planar OBJ's mirror image: reversed winding, moved `offset` along the new normal."""
    verts, faces = [], []
    with open(file) as f:
        for line in f.read().splitlines():
            w = line.split()
            if w and w[0] == "v":
                verts.append([float(x) for x in w[1:4]])
            elif w and w[0] == "f":
                faces.append([int(x) for x in w[1:]])
    a, b, c = (verts[i - 1] for i in faces[0][:3])
    e1 = [b[k] - a[k] for k in range(3)]
    e2 = [c[k] - a[k] for k in range(3)]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    length = math.sqrt(sum(x * x for x in n))
    shift = [-offset * x / length for x in n]
    out = file[:-4] + "_flipped.obj"
    with open(out, "w") as f:
        for v in verts:
            f.write("v {} {} {}\n".format(*(v[k] + shift[k] for k in range(3))))
        for face in faces:
            f.write(f"f {' '.join(str(i) for i in reversed(face))}\n")
    return out


def translate(scene_path, spp):
    with open(scene_path, "rb") as f:
        s = tomllib.load(f)
    base = os.path.dirname(scene_path)
    r, cam = s["render"], s["camera"]
    materials = s.get("materials", {})
    has_medium = any(medium(m) for m in materials.values())
    d = {
        "type": "scene",
        "integrator": {"type": "volpath" if has_medium else "path", "max_depth": r["max_bounces"] + 1},
        "sensor": {
            "type": "perspective",
            "fov_axis": "y",
            "fov": cam["fov_y_deg"],
            "to_world": mi.ScalarTransform4f().look_at(origin=cam["position"], target=cam["look_at"], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": r["width"], "height": r["height"], "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": spp},
        },
    }
    sky = s.get("sky", {"kind": "black"})
    if sky["kind"] == "uniform":
        d["sky"] = {"type": "constant", "radiance": rgb(sky.get("color", [1, 1, 1]))}
    elif sky["kind"] != "black":
        raise SystemExit(f"no Mitsuba mapping for sky {sky}")
    for i, mesh in enumerate(s.get("mesh", [])):
        if any(k in mesh for k in ("rotate_deg", "translate", "scale", "matrix")):
            raise SystemExit("the validation scenes place meshes untransformed")
        for j, (file, mtl) in enumerate(obj_groups(os.path.normpath(os.path.join(base, mesh["asset"])))):
            m = materials[mesh["material"]] if "material" in mesh else {"base_color": mtl.get("Kd", [1, 1, 1])}
            emission = m.get("emission", mtl.get("Ke", [0, 0, 0]))
            shape = {"type": "obj", "filename": file, "face_normals": True, "bsdf": bsdf(m)}
            d[f"mesh{i}_{j}"] = shape
            if max(emission) > 0:
                shape["emitter"] = {"type": "area", "radiance": rgb(emission)}
                d[f"mesh{i}_{j}_back"] = dict(shape, filename=flipped_copy(file))
    for i, sp in enumerate(s.get("sphere", [])):
        m = materials.get(sp.get("material"), {})
        shape = {"type": "sphere", "center": sp["center"], "radius": sp["radius"], "bsdf": bsdf(m)}
        if medium(m):
            shape["interior"] = medium(m)
        if max(m.get("emission", [0, 0, 0])) > 0:
            shape["emitter"] = {"type": "area", "radiance": rgb(m["emission"])}
        d[f"sphere{i}"] = shape
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=8192)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("names", nargs="*")
    args = ap.parse_args()
    mi.set_variant(args.variant)
    scenes = os.path.join(HERE, "scenes")
    names = args.names or sorted(n[:-5] for n in os.listdir(scenes) if n.endswith(".toml"))
    for name in names:
        scene = mi.load_dict(translate(os.path.join(scenes, f"{name}.toml"), args.spp))
        image = mi.render(scene, spp=args.spp, seed=1)
        out = os.path.join(HERE, f"{name}.exr")
        mi.util.write_bitmap(out, image)
        print(f"{name}: {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
