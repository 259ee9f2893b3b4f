//! rt scenes as Mitsuba 3 sees them: the one translation that `rt bench compare`, the
//! Mitsuba references of the tests (`tests/refs/make_refs.py`) and
//! `scripts/equal_error.py` all render (the latter two through `rt bench mitsuba-scene`).
//!
//! The result is a Mitsuba scene dictionary as JSON (`mitsuba_scene.py` loads it) beside
//! one PLY per mesh and material, in world space. Each choice makes Mitsuba do rt's work:
//!
//! | rt | Mitsuba 3 |
//! |---|---|
//! | pinhole camera, `fov_y_deg` | `perspective`, `fov_axis = "y"`, look-at with rt's up |
//! | a pixel's samples uniform in it | `hdrfilm` with a `box` filter |
//! | `max_bounces = B` | `max_depth = B + 1` (depth 1: what the camera sees) |
//! | Russian roulette after bounce 3, survival max(throughput) ≤ 0.95 | `rr_depth = 5`, the same rule |
//! | diffuse (two-sided) | `twosided` `diffuse`, reflectance = base × weight |
//! | `reflection` | `conductor`/`roughconductor` (GGX, α = roughness², visible normals), η from F0, k = 0 |
//! | `specular` beside `diffuse` (weights summing to 1) | `blendbsdf` of `diffuse` and an untinted `roughconductor` |
//! | `transmission` | `dielectric`/`roughdielectric` of the same IOR |
//! | `absorption` | interior `homogeneous` medium, albedo 0, with `volpath` |
//! | emission (from both faces) | `area` on the surface turned to face the camera, and on its mirror image 0.01 mm behind it |
//! | interpolated normals | PLY vertex normals (`face_normals = false`) |
//! | `[sky] kind = "uniform"`, `sample_as_light` | `constant`, sampled as a light (refused without `sample_as_light`) |
//!
//! Anything else (textures, lamps, a sun, instances, Cycles' multiscatter lobes, layers)
//! is refused with its name rather than approximated.

use anyhow::{Context, Result, bail};
use glam::{Mat3, Vec3, Vec4Swizzles};
use rt::asset::load_mesh;
use rt::scene::{Material, Microfacet, Projection, Scene, Sky};
use rt::shared_constants::ROULETTE_START;
use serde_json::{Map, Value, json};
use std::path::Path;

/// How far the flipped copy of an emitting surface lies behind it: far enough that
/// Mitsuba's ray offsets never confuse the two, near enough not to show (a copy 0.1 mm
/// away showed as a sliver at a light's silhouette).
const FLIPPED_EMITTER_OFFSET: f32 = 1e-5;

fn rgb(c: [f32; 3]) -> Value {
    json!({ "type": "rgb", "value": c })
}

/// The index of a non-absorbing interface whose normal-incidence reflectance is `f0`.
fn conductor_eta(base: [f32; 3]) -> [f32; 3] {
    base.map(|c| {
        let r = c.clamp(0.0, 0.999_999).sqrt();
        (1.0 + r) / (1.0 - r)
    })
}

/// Why `m` has no Mitsuba counterpart, if it has none.
fn refusal(m: &Material) -> Option<&'static str> {
    let t = &m.textures;
    let layered = m.coat > 0.0 || m.sheen > 0.0 || m.has_thin_film() || m.dielectric_coating().is_some();
    match () {
        _ if t.any() || t.has_alpha() => Some("textures and alpha"),
        _ if !m.node_program.is_empty() || m.mix_material.is_some() => Some("node graphs and mixed materials"),
        _ if layered => Some("coats, sheen, thin films and dielectric coatings"),
        _ if m.anisotropy != 0.0 || m.has_rough_diffuse() => Some("anisotropy and rough diffuse"),
        _ if m.hardness.is_some() => Some("hardness"),
        _ if m.holdout > 0.0 || m.volume_emission.iter().any(|&c| c > 0.0) => Some("holdouts and emitting media"),
        _ => None,
    }
}

/// The BSDF of `m` as Mitsuba's plugins compose it.
fn bsdf(name: &str, m: &Material) -> Result<Value> {
    if let Some(what) = refusal(m) {
        bail!("material {name}: {what} are not compared with Mitsuba");
    }
    let [wd, ws, wr, wt] = m.lobe_weights();
    let alpha = m.alpha();
    let rough = alpha >= 1e-3;
    let base = m.base_color;
    let conductor = |eta: Option<[f32; 3]>, weight: f32| {
        let mut c = Map::new();
        c.insert("type".into(), json!(if rough { "roughconductor" } else { "conductor" }));
        match eta {
            Some(eta) => c.extend([("eta".into(), rgb(eta)), ("k".into(), rgb([0.0; 3]))]),
            None => _ = c.insert("material".into(), json!("none")),
        }
        c.insert("specular_reflectance".into(), rgb([weight; 3]));
        if rough {
            c.extend([("distribution".into(), json!("ggx")), ("alpha".into(), json!(alpha))]);
            c.insert("sample_visible".into(), json!(true));
        }
        Value::Object(c)
    };
    let two_sided = |b: Value| json!({ "type": "twosided", "bsdf": b });
    let lobes = [wd > 0.0, ws > 0.0, wr > 0.0, wt > 0.0];
    Ok(match lobes {
        [true, false, false, false] => {
            two_sided(json!({ "type": "diffuse", "reflectance": rgb(base.map(|c| c * wd)) }))
        }
        [false, false, true, false] => two_sided(conductor(Some(conductor_eta(base)), wr)),
        [false, false, false, true] if wt == 1.0 => {
            let mut d = json!({ "type": if rough { "roughdielectric" } else { "dielectric" },
                "int_ior": m.ior, "ext_ior": 1.0, "specular_transmittance": rgb(base) });
            if rough {
                d["distribution"] = json!("ggx");
                d["alpha"] = json!(alpha);
                d["sample_visible"] = json!(true);
            }
            d
        }
        [true, true, false, false] if (wd + ws - 1.0).abs() < 1e-6 => two_sided(json!({
            "type": "blendbsdf", "weight": ws,
            "bsdf_0": { "type": "diffuse", "reflectance": rgb(base) },
            "bsdf_1": conductor(None, 1.0),
        })),
        _ => bail!("material {name}: this mix of lobes {lobes:?} has no Mitsuba counterpart"),
    })
}

/// Mitsuba's `homogeneous` wants σt in [0, 1]: the largest component goes to `scale`.
fn medium(m: &Material) -> Option<Value> {
    let top = m.absorption.iter().copied().fold(0.0, f32::max);
    (top > 0.0).then(|| {
        json!({ "type": "homogeneous", "albedo": rgb([0.0; 3]), "sigma_t": rgb(m.absorption.map(|s| s / top)), "scale": top })
    })
}

/// A shape's dictionary: its BSDF, its medium, and its emitter if it emits.
fn shape(mut shape: Value, name: &str, m: &Material) -> Result<Value> {
    shape["bsdf"] = bsdf(name, m)?;
    if let Some(medium) = medium(m) {
        shape["interior"] = medium;
    }
    if m.is_emissive() {
        shape["emitter"] = json!({ "type": "area", "radiance": rgb(m.emission) });
    }
    Ok(shape)
}

/// Writes a binary little-endian PLY, with vertex normals if given.
fn write_ply(path: &Path, positions: &[Vec3], normals: Option<&[Vec3]>, triangles: &[[u32; 3]]) -> Result<()> {
    let normal_header =
        if normals.is_some() { "property float nx\nproperty float ny\nproperty float nz\n" } else { "" };
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\n{normal_header}element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        positions.len(),
        triangles.len()
    )
    .into_bytes();
    for (i, p) in positions.iter().enumerate() {
        out.extend(p.to_array().iter().flat_map(|c| c.to_le_bytes()));
        if let Some(n) = normals {
            out.extend(n[i].to_array().iter().flat_map(|c| c.to_le_bytes()));
        }
    }
    for t in triangles {
        out.push(3);
        out.extend(t.iter().flat_map(|&i| (i as i32).to_le_bytes()));
    }
    std::fs::write(path, out).with_context(|| format!("writing {}", path.display()))
}

/// Emitting triangles as two one-sided sheets, so that Mitsuba's one-sided emitters emit
/// from both faces as rt's do: each triangle turned to face `eye` (the camera) where rt
/// has it, so that the light seen directly keeps rt's outline exactly, and its mirror
/// image moved away from the camera along its own normal.
fn two_sided(positions: &[Vec3], triangles: &[[u32; 3]], eye: Vec3) -> [(Vec<Vec3>, Vec<[u32; 3]>); 2] {
    let (mut front, mut back) = (Vec::with_capacity(3 * triangles.len()), Vec::with_capacity(3 * triangles.len()));
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        let (a, b, c, n) = if n.dot(eye - a) >= 0.0 { (a, b, c, n) } else { (a, c, b, -n) };
        let shift = -n * FLIPPED_EMITTER_OFFSET;
        front.extend([a, b, c]);
        back.extend([a + shift, c + shift, b + shift]);
    }
    let faces: Vec<[u32; 3]> = (0..triangles.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    [(front, faces.clone()), (back, faces)]
}

/// The meshes' shapes, one per mesh and material (and a flipped copy of each emitter),
/// their PLY files written into `dir`.
fn mesh_shapes(scene: &Scene, dir: &Path, shapes: &mut Map<String, Value>) -> Result<()> {
    for (i, mesh) in scene.meshes.iter().enumerate() {
        let data = load_mesh(&mesh.asset)?;
        let to_world = mesh.object_to_world;
        let normal_to_world = Mat3::from_mat4(to_world).inverse().transpose();
        let positions: Vec<Vec3> =
            data.positions.iter().map(|&p| (to_world * Vec3::from(p).extend(1.0)).xyz()).collect();
        let normals: Option<Vec<Vec3>> = data
            .normals
            .as_ref()
            .map(|n| n.iter().map(|&n| (normal_to_world * Vec3::from(n)).normalize_or_zero()).collect());
        for (m, (own_name, own)) in data.materials.iter().enumerate() {
            let triangles: Vec<[u32; 3]> = data
                .indices
                .iter()
                .zip(&data.material_ids)
                .filter(|&(_, &id)| id as usize == m)
                .map(|(t, _)| *t)
                .collect();
            if triangles.is_empty() {
                continue;
            }
            let (name, material) = match &mesh.material {
                Some(name) => (name.as_str(), scene_material(scene, name)?),
                None => (own_name.as_str(), own),
            };
            let ply = dir.join(format!("mesh{i}_{m}.ply"));
            if !material.is_emissive() {
                write_ply(&ply, &positions, normals.as_deref(), &triangles)?;
                let plain = json!({ "type": "ply", "filename": ply, "face_normals": normals.is_none() });
                shapes.insert(format!("mesh{i}_{m}"), shape(plain, name, material)?);
                continue;
            }
            let [front, back] = two_sided(&positions, &triangles, scene.camera.position);
            let back_ply = dir.join(format!("mesh{i}_{m}_flipped.ply"));
            for ((vertices, faces), (key, file)) in [front, back].iter().zip([("", &ply), ("_flipped", &back_ply)]) {
                write_ply(file, vertices, None, faces)?;
                let plain = json!({ "type": "ply", "filename": file, "face_normals": true });
                shapes.insert(format!("mesh{i}_{m}{key}"), shape(plain, name, material)?);
            }
        }
    }
    Ok(())
}

fn scene_material<'a>(scene: &'a Scene, name: &str) -> Result<&'a Material> {
    scene.material_index(name).map(|i| &scene.materials[i].1).with_context(|| format!("no material {name}"))
}

/// What the scene has that Mitsuba would render differently, if anything.
fn unsupported(scene: &Scene) -> Option<&'static str> {
    let cam = &scene.camera;
    let pinhole = !matches!(cam.projection, Projection::Orthographic { .. } | Projection::Panoramic { .. })
        && cam.depth_of_field.is_none()
        && cam.shift == glam::Vec2::ZERO;
    match () {
        _ if scene.sun.is_some() => Some("a sun"),
        _ if !scene.lights.is_empty() => Some("a lamp"),
        _ if !scene.instance_sets.is_empty() => Some("an [[instances]] set"),
        _ if !pinhole => Some("a camera other than a centred pinhole"),
        _ if scene.render.microfacet != Microfacet::Single => {
            Some("Cycles' multiscatter lobes (set microfacet = \"single\")")
        }
        _ if scene.render.transparent => Some("a transparent film"),
        _ => None,
    }
}

/// The Mitsuba scene of `scene` at `size`, rendered with `spp` samples per pixel, its
/// PLY files written into `dir` (which must exist).
pub fn translate(scene: &Scene, size: (u32, u32), spp: u32, dir: &Path) -> Result<Value> {
    if let Some(what) = unsupported(scene) {
        bail!("{}: {what} is not compared with Mitsuba", scene.origin);
    }
    let mut d = Map::new();
    let has_medium = scene.materials.iter().any(|(_, m)| m.has_medium());
    d.insert("type".into(), json!("scene"));
    // rt's Russian roulette starts after bounce ROULETTE_START: Mitsuba's depth counts one
    // more vertex, and decides after the vertex it counts.
    d.insert(
        "integrator".into(),
        json!({ "type": if has_medium { "volpath" } else { "path" },
                "max_depth": scene.render.max_bounces + 1, "rr_depth": ROULETTE_START + 2 }),
    );
    let cam = &scene.camera;
    let (width, height) = size;
    let fov_y_deg = 2.0 * cam.view_plane(width, height).half_extent.y.atan().to_degrees();
    let (_, up, _) = cam.basis();
    d.insert(
        "sensor".into(),
        json!({
            "type": "perspective", "fov_axis": "y", "fov": fov_y_deg,
            "to_world": { "look_at": { "origin": cam.position.to_array(), "target": cam.look_at.to_array(), "up": up.to_array() } },
            "film": { "type": "hdrfilm", "width": width, "height": height, "rfilter": { "type": "box" }, "pixel_format": "rgb" },
            "sampler": { "type": "independent", "sample_count": spp },
        }),
    );
    match &scene.sky {
        Sky::Black => {}
        Sky::Uniform { color, sample_as_light: true } => {
            _ = d.insert("sky".into(), json!({ "type": "constant", "radiance": rgb(color.to_array()) }))
        }
        Sky::Uniform { .. } => bail!(
            "{}: a uniform sky that is not sampled as a light (Mitsuba samples it: set `sample_as_light = true` under [sky])",
            scene.origin
        ),
        _ => bail!("{}: a sky other than black or uniform is not compared with Mitsuba", scene.origin),
    }
    mesh_shapes(scene, dir, &mut d)?;
    let default = Material::default();
    for (i, sphere) in scene.spheres.iter().enumerate() {
        let (name, material) = match &sphere.material {
            Some(name) => (name.as_str(), scene_material(scene, name)?),
            None => ("default", &default),
        };
        let plain = json!({ "type": "sphere", "center": sphere.center.to_array(), "radius": sphere.radius });
        d.insert(format!("sphere{i}"), shape(plain, name, material)?);
    }
    Ok(Value::Object(d))
}

/// `rt bench mitsuba-scene`: the translation of `scene` at `size` (its own by default)
/// written as `out/scene.json`, beside its PLY files.
pub fn write(scene: &Scene, size: Option<(u32, u32)>, out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let size = size.unwrap_or((scene.render.width, scene.render.height));
    let d = translate(scene, size, scene.render.spp, out)?;
    let path = out.join("scene.json");
    std::fs::write(&path, serde_json::to_string_pretty(&d)?).with_context(|| format!("writing {}", path.display()))?;
    println!("{}", path.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scene of the repository (this crate is its `crates/rt-bench`).
    fn scene(path: &str) -> Scene {
        rt::scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(path))
            .unwrap_or_else(|e| panic!("{e}"))
    }

    fn folder(name: &str) -> std::path::PathBuf {
        // A folder of its own: another user's files in the shared temporary folder cannot
        // be overwritten (nor should they be).
        let dir = std::env::temp_dir().join(format!("rt-mitsuba-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn cornell_box_translates_with_its_two_sided_lamp_and_bounces() {
        let scene = scene("tests/refs/scenes/cornell_diffuse.toml");
        let dir = folder("cornell");
        let d = translate(&scene, (64, 48), 4, &dir).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(d["integrator"]["max_depth"], scene.render.max_bounces + 1);
        assert_eq!(d["integrator"]["rr_depth"], 5);
        assert!((d["sensor"]["fov"].as_f64().unwrap() - 36.0).abs() < 1e-4);
        let shapes: Vec<&str> = d.as_object().unwrap().keys().map(String::as_str).collect();
        let emitters: Vec<&&str> = shapes.iter().filter(|k| d[**k].get("emitter").is_some()).collect();
        // The ceiling lamp and its flipped copy.
        assert_eq!(emitters.len(), 2, "{shapes:?}");
        assert!(emitters.iter().any(|k| k.ends_with("_flipped")), "{emitters:?}");
        assert_eq!(shapes.iter().filter(|k| k.starts_with("sphere")).count(), 2);
        assert!(d.get("sky").is_none());
    }

    #[test]
    fn what_mitsuba_would_render_differently_is_refused_by_name() {
        let dir = folder("refused");
        let mut scene = scene("tests/refs/scenes/cornell_diffuse.toml");
        scene.materials[0].1.sheen = 1.0;
        let e = translate(&scene, (8, 8), 1, &dir).unwrap_err().to_string();
        assert!(e.contains(&scene.materials[0].0) && e.contains("sheen"), "{e}");
        let sunny =
            rt::scene::parse("[sun]\nelevation_deg = 30.0\nazimuth_deg = 0.0\n", "sunny.toml", Path::new(".")).unwrap();
        let e = translate(&sunny, (8, 8), 1, &dir).unwrap_err().to_string();
        assert!(e.contains("sunny.toml") && e.contains("a sun"), "{e}");
        let sky = rt::scene::parse(
            "[render]\nmicrofacet = \"single\"\n[sky]\nkind = \"uniform\"\n",
            "sky.toml",
            Path::new("."),
        )
        .unwrap();
        let e = translate(&sky, (8, 8), 1, &dir).unwrap_err().to_string();
        let _ = std::fs::remove_dir_all(&dir);
        assert!(e.contains("sky.toml") && e.contains("sample_as_light"), "{e}");
    }
}
