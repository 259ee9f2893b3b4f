//! Semantic checks on the deserialized file, and its conversion into a [`Scene`].

use super::atmosphere;
use super::environment;
use super::light;
use super::parse::{SceneError, Seg, Seg::*, Source, hint};
use super::schema::{self, File, Scale, SkyKind};
use super::{
    InstanceSet, Material, MeshInstance, ObjectInfo, RenderSettings, Scene, ShadowTerminator, Sky, Sphere, Sun,
    WorldGraph,
};
use glam::{Mat3, Mat4, Vec3};
use std::path::Path;

/// Largest sphere radius and centre coordinate, in metres. The shaders square the
/// radius and the distance to the centre in f32, which overflows (and the sphere
/// silently vanishes) beyond about 1.8e19 m; 1e15 m (a tenth of a light year) keeps
/// those squares, and the sums and products of them that light sampling forms, finite.
pub const MAX_SPHERE_EXTENT: f32 = 1e15;

pub(super) fn scene(file: File, src: &Source, base_dir: &Path) -> Result<Scene, SceneError> {
    let render = file.render;
    if let Err((key, message)) = render.check() {
        return Err(src.error(&[Key("render")], key, message));
    }
    let materials = materials(src, file.materials)?;
    let meshes = file.mesh.into_iter().enumerate().map(|(i, m)| mesh(src, i, m, &materials, base_dir));
    let meshes = meshes.collect::<Result<_, _>>()?;
    let spheres = file.sphere.into_iter().enumerate().map(|(i, s)| sphere(src, i, s, &materials));
    let spheres = spheres.collect::<Result<_, _>>()?;
    let lights = file.light.into_iter().enumerate().map(|(i, l)| light::validate(src, i, l));
    let lights = lights.collect::<Result<_, _>>()?;
    let sets = file.instances.into_iter().enumerate().map(|(i, set)| instance_set(src, i, set, &materials, base_dir));
    let instance_sets = sets.collect::<Result<_, _>>()?;
    Ok(Scene {
        origin: src.origin.to_owned(),
        render,
        camera: super::camera::validate(src, file.camera)?,
        sky: sky(src, file.sky, base_dir)?,
        sun: file.sun.map(|s| sun(src, s)).transpose()?,
        materials,
        meshes,
        spheres,
        lights,
        instance_sets,
    })
}

/// The materials in the order the file gives them, each checked.
fn materials(
    src: &Source,
    materials: std::collections::BTreeMap<String, Material>,
) -> Result<Vec<(String, Material)>, SceneError> {
    let mut materials: Vec<(String, Material)> = materials.into_iter().collect();
    materials.sort_by_key(|(name, _)| src.locate(&[Key("materials"), Key(name)]).map(|s| s.start));
    for (name, m) in &materials {
        material(src, &[Key("materials"), Key(name)], m)?;
    }
    Ok(materials)
}

/// An error unless `name` names one of `materials` (`entry`: where in a list it stands).
fn check_material_name(
    src: &Source,
    p: &[Seg],
    key: &str,
    entry: Option<usize>,
    name: &str,
    materials: &[(String, Material)],
) -> Result<(), SceneError> {
    if materials.iter().any(|(m, _)| m == name) {
        return Ok(());
    }
    let names = hint(name, materials.iter().map(|(m, _)| m.as_str()));
    let entry = entry.map_or(String::new(), |j| format!("entry {j}: "));
    Err(src.error(p, key, format!("{entry}`{name}` names no [materials.*] table{names}")))
}

fn mesh(
    src: &Source,
    i: usize,
    m: schema::Mesh,
    materials: &[(String, Material)],
    base_dir: &Path,
) -> Result<MeshInstance, SceneError> {
    let p = [Key("mesh"), Index(i)];
    if m.asset.is_empty() {
        return Err(src.error(&p, "asset", "must name a file or folder, got \"\""));
    }
    let object_to_world = transform(src, &p, &m)?;
    if let Some(name) = &m.material {
        check_material_name(src, &p, "material", None, name, materials)?;
    }
    Ok(MeshInstance {
        object_to_world,
        asset: base_dir.join(&m.asset),
        material: m.material,
        shadow_terminator: ShadowTerminator::validate(
            src,
            &p,
            m.shadow_terminator_geometry_offset,
            m.shadow_terminator_shading_offset,
        )?,
        holdout: m.holdout,
        info: ObjectInfo::validate(src, &p, m.object_color, m.random, m.object_index)?,
        motion: m.motion.as_deref().map(|keys| super::motion::validate_keys(src, &p, keys)).transpose()?,
    })
}

fn sphere(src: &Source, i: usize, s: schema::Sphere, materials: &[(String, Material)]) -> Result<Sphere, SceneError> {
    let p = [Key("sphere"), Index(i)];
    let within = format!("within ±{MAX_SPHERE_EXTENT:e} m (rt intersects spheres in f32)");
    src.check(&p, "center", &s.center, &within, |c| c.abs() <= MAX_SPHERE_EXTENT)?;
    let size = format!("positive and at most {MAX_SPHERE_EXTENT:e} m (rt intersects spheres in f32)");
    src.check(&p, "radius", &[s.radius], &size, |r| r > 0.0 && r <= MAX_SPHERE_EXTENT)?;
    if let Some(name) = &s.material {
        check_material_name(src, &p, "material", None, name, materials)?;
    }
    Ok(Sphere { center: s.center.into(), radius: s.radius, material: s.material })
}

fn instance_set(
    src: &Source,
    i: usize,
    set: schema::Instances,
    materials: &[(String, Material)],
    base_dir: &Path,
) -> Result<InstanceSet, SceneError> {
    let p = [Key("instances"), Index(i)];
    for (field, value) in [("asset", &set.asset), ("file", &set.file)] {
        if value.is_empty() {
            return Err(src.error(&p, field, "must name a file or folder, got \"\""));
        }
    }
    for (j, name) in set.materials.iter().enumerate() {
        check_material_name(src, &p, "materials", Some(j), name, materials)?;
    }
    let shadow_terminator = ShadowTerminator::validate(
        src,
        &p,
        set.shadow_terminator_geometry_offset,
        set.shadow_terminator_shading_offset,
    )?;
    Ok(InstanceSet {
        shadow_terminator,
        asset: base_dir.join(&set.asset),
        file: base_dir.join(&set.file),
        materials: set.materials,
        holdout: set.holdout,
        info: ObjectInfo::validate(src, &p, set.object_color, set.random, set.object_index)?,
    })
}

fn sky(src: &Source, sky: Option<schema::Sky>, base_dir: &Path) -> Result<Sky, SceneError> {
    let p = [Key("sky")];
    let Some(sky) = sky else {
        return Ok(Sky::Black);
    };
    if sky.kind != SkyKind::Uniform && sky.color.is_some() {
        return Err(src.error(&p, "color", "only applies to kind = \"uniform\""));
    }
    if !matches!(sky.kind, SkyKind::Uniform | SkyKind::Graph) && sky.sample_as_light.is_some() {
        return Err(src.error(&p, "sample_as_light", "only applies to kind = \"uniform\" or \"graph\""));
    }
    if sky.kind != SkyKind::Graph && sky.graph.is_some() {
        return Err(src.error(&p, "graph", "only applies to kind = \"graph\""));
    }
    if sky.kind != SkyKind::Atmosphere
        && let Some(key) = atmosphere::keys_present(&sky)
    {
        return Err(src.error(&p, key, "only applies to kind = \"atmosphere\""));
    }
    if sky.kind != SkyKind::Environment
        && let Some(key) = environment::keys_present(&sky)
    {
        return Err(src.error(&p, key, "only applies to kind = \"environment\""));
    }
    Ok(match sky.kind {
        SkyKind::Black => Sky::Black,
        SkyKind::Atmosphere => Sky::Atmosphere(atmosphere::validate(src, &p, &sky)?),
        SkyKind::Environment => Sky::Environment(environment::validate(src, &p, &sky, base_dir)?),
        SkyKind::Graph => match sky.graph.as_deref() {
            None | Some("") => return Err(src.error(&p, "graph", "must name the world's node graph (.json)")),
            Some(name) => Sky::Graph(WorldGraph {
                graph: base_dir.join(name),
                sample_as_light: sky.sample_as_light.unwrap_or(true),
            }),
        },
        SkyKind::Uniform => {
            let color = sky.color.unwrap_or([1.0; 3]);
            src.check(&p, "color", &color, "non-negative", |c| c >= 0.0)?;
            Sky::Uniform { color: color.into(), sample_as_light: sky.sample_as_light.unwrap_or(false) }
        }
    })
}

fn sun(src: &Source, s: schema::Sun) -> Result<Sun, SceneError> {
    let p = [Key("sun")];
    src.check(&p, "elevation_deg", &[s.elevation_deg], "in [-90, 90]", |e| e.abs() <= 90.0)?;
    src.finite(&p, "azimuth_deg", &[s.azimuth_deg])?;
    let d = s.angular_diameter_deg;
    src.check(&p, "angular_diameter_deg", &[d], "in (0, 90)", |d| d > 0.0 && d < 90.0)?;
    if let Some(r) = &s.radiance {
        src.check(&p, "radiance", r, "non-negative", |c| c >= 0.0)?;
    }
    Ok(Sun {
        elevation_deg: s.elevation_deg,
        azimuth_deg: s.azimuth_deg,
        angular_diameter_deg: d,
        radiance: s.radiance.map(Vec3::from),
    })
}

fn material(src: &Source, p: &[Seg], m: &Material) -> Result<(), SceneError> {
    let non_negative: [(&str, &[f32]); 8] = [
        ("base_color", &m.base_color),
        ("diffuse", &[m.diffuse]),
        ("specular", &[m.specular]),
        ("reflection", &[m.reflection]),
        ("transmission", &[m.transmission]),
        ("emission", &m.emission),
        ("absorption", &m.absorption),
        ("volume_emission", &m.volume_emission),
    ];
    for (field, values) in non_negative {
        src.check(p, field, values, "non-negative", |v| v >= 0.0)?;
    }
    src.check(p, "ior", &[m.ior], "at least 1", |ior| ior >= 1.0)?;
    src.check(p, "roughness", &[m.roughness], "in [0, 1]", |r| (0.0..=1.0).contains(&r))?;
    src.check(p, "diffuse_roughness", &[m.diffuse_roughness], "in [0, 1]", |r| (0.0..=1.0).contains(&r))?;
    src.check(p, "specular_tint", &m.specular_tint, "in [0, 1]", |t| (0.0..=1.0).contains(&t))?;
    src.check(p, "specular_ior_level", &[m.specular_ior_level], "in [0, 1]", |l| (0.0..=1.0).contains(&l))?;
    src.check(p, "coat", &[m.coat], "in [0, 1]", |c| (0.0..=1.0).contains(&c))?;
    src.check(p, "coat_roughness", &[m.coat_roughness], "in [0, 1]", |r| (0.0..=1.0).contains(&r))?;
    src.check(p, "coat_ior", &[m.coat_ior], "at least 1", |ior| ior >= 1.0)?;
    src.check(p, "coat_tint", &m.coat_tint, "in [0, 1]", |t| (0.0..=1.0).contains(&t))?;
    src.check(p, "sheen", &[m.sheen], "in [0, 1]", |s| (0.0..=1.0).contains(&s))?;
    src.check(p, "sheen_roughness", &[m.sheen_roughness], "in [0, 1]", |r| (0.0..=1.0).contains(&r))?;
    src.check(p, "sheen_tint", &m.sheen_tint, "in [0, 1]", |t| (0.0..=1.0).contains(&t))?;
    src.check(p, "anisotropy", &[m.anisotropy], "in [0, 1]", |a| (0.0..=1.0).contains(&a))?;
    src.check(p, "anisotropy_rotation", &[m.anisotropy_rotation], "in [0, 1]", |r| (0.0..=1.0).contains(&r))?;
    // Blender's Thin Film Thickness stops at 100 µm.
    src.check(p, "thin_film_thickness", &[m.thin_film_thickness], "in [0, 100000] (nm)", |t| {
        (0.0..=100_000.0).contains(&t)
    })?;
    src.check(p, "thin_film_ior", &[m.thin_film_ior], "at least 1", |ior| ior >= 1.0)?;
    src.check(p, "thin_film_weight", &[m.thin_film_weight], "in [0, 1]", |w| (0.0..=1.0).contains(&w))?;
    src.check(p, "holdout", &[m.holdout], "in [0, 1]", |h| (0.0..=1.0).contains(&h))?;
    src.check(p, "closure_weight", &[m.closure_weight], "in [0, 16]", |w| (0.0..=16.0).contains(&w))?;
    if m.specular_ior_level > 0.0 && m.specular > 0.0 {
        return Err(src.error(
            p,
            "specular_ior_level",
            "excludes `specular` (the coating is the diffuse's own glossy layer)",
        ));
    }
    if let Some(h) = m.hardness {
        src.check(p, "hardness", &[h], "positive", |h| h > 0.0)?;
    }
    Ok(())
}

/// Object to world: either `matrix` (row-major), or
/// `T(translate) * Rz * Ry * Rx * S(scale)` — scale first, then rotate about X, then Y,
/// then Z (each by `rotate_deg` in degrees, right-handed), then translate.
fn transform(src: &Source, p: &[Seg], m: &schema::Mesh) -> Result<Mat4, SceneError> {
    if let Some(rows) = &m.matrix {
        if m.rotate_deg.is_some() || m.translate.is_some() || m.scale.is_some() {
            return Err(src.error(p, "matrix", "excludes rotate_deg, translate and scale"));
        }
        return matrix(src, p, rows);
    }
    let r = m.rotate_deg.unwrap_or_default();
    let t = m.translate.unwrap_or_default();
    let s = m.scale.map_or([1.0; 3], Scale::axes);
    src.finite(p, "rotate_deg", &r)?;
    src.finite(p, "translate", &t)?;
    src.check(p, "scale", &s, "non-zero", |s| s != 0.0)?;
    Ok(Mat4::from_translation(t.into())
        * Mat4::from_rotation_z(r[2].to_radians())
        * Mat4::from_rotation_y(r[1].to_radians())
        * Mat4::from_rotation_x(r[0].to_radians())
        * Mat4::from_scale(s.into()))
}

/// The largest image side a render may ask for.
pub const MAX_IMAGE_SIDE: u32 = 16384;

impl RenderSettings {
    /// The rules every `[render]` value obeys, whether it comes from the scene file or a
    /// flag: on a violation, the key and what is wrong.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        for (key, size) in [("width", self.width), ("height", self.height)] {
            if !(1..=MAX_IMAGE_SIDE).contains(&size) {
                return Err((key, format!("must be in 1..={MAX_IMAGE_SIDE}, got {size}")));
            }
        }
        if self.spp == 0 {
            return Err(("spp", "must be at least 1, got 0".into()));
        }
        if !self.exposure.is_finite() {
            return Err(("exposure", format!("must be finite, got {}", self.exposure)));
        }
        if !(1..=64).contains(&self.ris_candidates) {
            return Err(("ris_candidates", format!("must be in 1..=64, got {}", self.ris_candidates)));
        }
        if !(self.noise_threshold.is_finite() && (0.0..1.0).contains(&self.noise_threshold)) {
            return Err(("noise_threshold", format!("must be in [0, 1) (0: off), got {}", self.noise_threshold)));
        }
        if !(0.0..=1.0).contains(&self.transparent_glass_roughness) {
            let r = self.transparent_glass_roughness;
            return Err(("transparent_glass_roughness", format!("must be in [0, 1], got {r}")));
        }
        if self.adaptive_min_samples < 2 {
            return Err(("adaptive_min_samples", format!("must be at least 2, got {}", self.adaptive_min_samples)));
        }
        Ok(())
    }
}

/// A row-major `matrix` key: finite, affine and invertible.
pub(super) fn matrix(src: &Source, p: &[Seg], rows: &[f32; 16]) -> Result<Mat4, SceneError> {
    matrix_of(src, p, "matrix", rows)
}

/// A row-major matrix under the key `field` (see [`matrix`]).
pub(super) fn matrix_of(src: &Source, p: &[Seg], field: &str, rows: &[f32; 16]) -> Result<Mat4, SceneError> {
    src.finite(p, field, rows)?;
    if rows[12..] != [0.0, 0.0, 0.0, 1.0] {
        let last = &rows[12..];
        return Err(src.error(p, field, format!("last row must be [0, 0, 0, 1], got {last:?}")));
    }
    let matrix = Mat4::from_cols_array(rows).transpose();
    let [a, b, c] = [matrix.x_axis, matrix.y_axis, matrix.z_axis].map(|v| v.truncate());
    // Relative to the largest determinant columns of these lengths can have, so that
    // a uniform millimetre scale passes and a nearly flat matrix does not.
    let det = Mat3::from_cols(a, b, c).determinant().abs();
    if det <= 1e-6 * a.length() * b.length() * c.length() {
        return Err(src.error(p, field, "must be invertible"));
    }
    Ok(matrix)
}
