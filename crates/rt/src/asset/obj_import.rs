//! Wavefront OBJ import through tobj, with `.mtl` materials.
//!
//! | MTL            | rt material                                             |
//! |----------------|---------------------------------------------------------|
//! | `Kd`           | `base_color`                                            |
//! | `Ke`           | `emission`                                              |
//! | `Ni`           | `ior`                                                   |
//! | `d` (or `Tr`)  | `transmission = 1 - d` (`= Tr`), `diffuse = 1 - transmission` |
//!
//! Anything else keeps [`Material::default`]'s value (white diffuse).

use super::{AssetError, MeshData, builtin};
use crate::scene::Material;
use std::cell::RefCell;
use std::io::BufRead;
use std::path::Path;

/// Loads an OBJ file and the material libraries (`mtllib`) it names.
pub fn load(path: &Path) -> Result<MeshData, AssetError> {
    let bytes = builtin::read(path).map_err(|e| AssetError::new(path, e.message()))?;
    let dir = path.parent().unwrap_or(Path::new(""));
    // tobj's loader callback can only return its own error codes, so the
    // precise message waits here.
    let mtl_error = RefCell::new(None);
    let mesh = parse(path, &bytes, |mtl: &Path| {
        let mtl_path = dir.join(mtl);
        let text = match builtin::read(&mtl_path) {
            Ok(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
            Err(e) if e.is_not_found() => {
                log::warn!("{}: material library {e}; using a default material", path.display());
                return Err(tobj::LoadError::OpenFileFailed);
            }
            // A FIFO or device named as a library is a mistake to report, not to skip.
            Err(e) => {
                mtl_error.replace(Some(AssetError::new(&mtl_path, e.message())));
                return Err(tobj::LoadError::OpenFileFailed);
            }
        };
        check_colours(&text)
            .and_then(|()| {
                tobj::load_mtl_buf(&mut text.as_bytes()).map_err(|e| format!("cannot parse material library: {e}"))
            })
            .map_err(|message| {
                mtl_error.replace(Some(AssetError::new(&mtl_path, message)));
                tobj::LoadError::MaterialParseError
            })
    });
    match mtl_error.into_inner() {
        Some(e) => Err(e),
        None => mesh,
    }
}

/// tobj panics on a colour with fewer than three numbers; refuse those first.
fn check_colours(text: &str) -> Result<(), String> {
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if let Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next()
            && words.count() < 3
        {
            return Err(format!("line {}: `{key}` needs three numbers", n + 1));
        }
    }
    Ok(())
}

fn parse(
    path: &Path,
    bytes: &[u8],
    material_loader: impl Fn(&Path) -> tobj::MTLLoadResult,
) -> Result<MeshData, AssetError> {
    let options = tobj::LoadOptions { triangulate: true, single_index: true, ..Default::default() };
    let mut reader = bytes;
    let (models, materials) = tobj::load_obj_buf(&mut reader, &options, material_loader)
        .map_err(|e| AssetError::new(path, describe_load_error(bytes, e)))?;
    // A missing library was already reported as a warning; its triangles fall back to
    // the default material below.
    let materials = materials.unwrap_or_default();

    let mut mesh = MeshData { normals: Some(Vec::new()), uvs: Some(Vec::new()), ..Default::default() };
    for m in &materials {
        mesh.materials.push((m.name.clone(), map_material(m).map_err(|e| AssetError::new(path, e))?));
    }

    let mut default_id = None;
    let (mut any_normals, mut any_uvs) = (false, false);
    for model in &models {
        let m = &model.mesh;
        let base = mesh.positions.len() as u32;
        let vertex_count = m.positions.len() / 3;
        mesh.positions.extend(m.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        if u32::try_from(mesh.positions.len()).is_err() {
            return Err(AssetError::new(path, "more than 2^32 vertices"));
        }
        // With `single_index`, tobj gives every vertex a normal only if every face
        // corner named one; a partial set cannot be matched to vertices.
        any_normals |= !m.normals.is_empty();
        any_uvs |= !m.texcoords.is_empty();
        if m.normals.len() == vertex_count * 3 {
            if let Some(n) = &mut mesh.normals {
                n.extend(m.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
            }
        } else {
            mesh.normals = None;
        }
        if m.texcoords.len() == vertex_count * 2 {
            if let Some(uv) = &mut mesh.uvs {
                uv.extend(m.texcoords.chunks_exact(2).map(|t| [t[0], t[1]]));
            }
        } else {
            mesh.uvs = None;
        }

        let material = match m.material_id.filter(|&id| id < materials.len()) {
            Some(id) => id as u32,
            None => *default_id.get_or_insert_with(|| {
                mesh.materials.push(("default".into(), Material::default()));
                (mesh.materials.len() - 1) as u32
            }),
        };
        for tri in m.indices.chunks_exact(3) {
            mesh.indices.push([base + tri[0], base + tri[1], base + tri[2]]);
            mesh.material_ids.push(material);
        }
    }
    if (mesh.normals.is_none() && any_normals) || (mesh.uvs.is_none() && any_uvs) {
        log::warn!("{}: normals or texture coordinates are missing on some faces; dropped them all", path.display());
    }
    if default_id.is_some() && !materials.is_empty() {
        log::warn!("{}: some faces have no known material; using a default one", path.display());
    }
    Ok(mesh)
}

fn map_material(m: &tobj::Material) -> Result<Material, String> {
    let defaults = Material::default();
    let transparency = match (m.dissolve, m.unknown_param.get("Tr")) {
        (Some(d), _) => 1.0 - d,
        (None, Some(tr)) => {
            tr.trim().parse::<f32>().map_err(|_| format!("material `{}`: `Tr {tr}` is not a number", m.name))?
        }
        (None, None) => 0.0,
    };
    let transmission = transparency.clamp(0.0, 1.0);
    Ok(Material {
        base_color: m.diffuse.unwrap_or(defaults.base_color),
        emission: m.emissive.unwrap_or(defaults.emission),
        ior: m.optical_density.unwrap_or(defaults.ior),
        transmission,
        diffuse: 1.0 - transmission,
        ..defaults
    })
}

/// tobj's errors name no line; for the ones a user can fix by finding a face,
/// find the first face that refers past the end of its vertex data.
fn describe_load_error(bytes: &[u8], e: tobj::LoadError) -> String {
    use tobj::LoadError::{FaceNormalOutOfBounds, FaceTexCoordOutOfBounds, FaceVertexOutOfBounds};
    if !matches!(e, FaceVertexOutOfBounds | FaceTexCoordOutOfBounds | FaceNormalOutOfBounds) {
        return format!("cannot parse OBJ: {e}");
    }
    const KINDS: [(&str, &str, &str); 3] =
        [("v", "vertex", "vertices"), ("vt", "texture coordinate", "texture coordinates"), ("vn", "normal", "normals")];
    let lines: Vec<String> = bytes.lines().map_while(Result::ok).collect();
    let mut totals = [0i64; 3];
    for line in &lines {
        let key = line.split_whitespace().next();
        if let Some(k) = KINDS.iter().position(|&(tag, _, _)| Some(tag) == key) {
            totals[k] += 1;
        }
    }
    let mut seen = [0i64; 3];
    for (n, line) in lines.iter().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("f") => {}
            key => {
                if let Some(k) = KINDS.iter().position(|&(tag, _, _)| Some(tag) == key) {
                    seen[k] += 1;
                }
                continue;
            }
        }
        let corners: Vec<&str> = words.collect();
        let face = if corners.len() == 3 { "triangle" } else { "polygon" };
        for corner in &corners {
            for (k, field) in corner.split('/').enumerate().take(3) {
                let Ok(index) = field.parse::<i64>() else {
                    continue;
                };
                // Negative indices count back from the latest element, positive ones
                // from the first; 0 is never valid.
                let resolved = if index < 0 { seen[k] + index + 1 } else { index };
                if resolved < 1 || resolved > totals[k] {
                    let (_, one, many) = KINDS[k];
                    return format!(
                        "line {}: {face} refers to {one} {index} but there are only {} {many}",
                        n + 1,
                        totals[k]
                    );
                }
            }
        }
    }
    format!("cannot parse OBJ: {e}")
}

#[cfg(test)]
mod tests {
    use crate::asset::fixture::TempDir;
    use crate::asset::load_mesh;
    use crate::scene::Material;

    const CUBE: &str = "mtllib cube.mtl
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
f 1 4 3 2
usemtl red
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
usemtl lamp
f 2 3 7 6
usemtl glass
f 1 5 8 4
";

    const MTL: &str = "newmtl red
Kd 0.8 0.1 0.1
newmtl lamp
Kd 0.5 0.5 0.5
Ke 10 9 8
newmtl glass
Ni 1.45
Tr 0.75
";

    #[test]
    fn obj_cube_with_materials() {
        let dir = TempDir::new("obj_cube_with_materials");
        dir.write("cube.mtl", MTL);
        let mesh = load_mesh(&dir.write("cube.obj", CUBE)).expect("cube loads");
        assert_eq!(mesh.indices.len(), 12);
        assert!(mesh.normals.is_none() && mesh.uvs.is_none());

        let names: Vec<&str> = mesh.materials.iter().map(|(n, _)| n.as_str()).collect();
        // The face before any `usemtl` gets a default material after the file's own.
        assert_eq!(names, ["red", "lamp", "glass", "default"]);
        let count = |id| mesh.material_ids.iter().filter(|&&m| m == id).count();
        assert_eq!([count(0), count(1), count(2), count(3)], [6, 2, 2, 2]);

        let [red, lamp, glass, default] = [0, 1, 2, 3].map(|i| &mesh.materials[i].1);
        assert_eq!(red, &Material { base_color: [0.8, 0.1, 0.1], ..Material::default() });
        assert_eq!(lamp.emission, [10.0, 9.0, 8.0]);
        assert_eq!(lamp.base_color, [0.5; 3]);
        assert_eq!((glass.transmission, glass.diffuse, glass.ior), (0.75, 0.25, 1.45));
        assert_eq!(default, &Material::default());
    }

    #[test]
    fn obj_missing_mtl_uses_a_default_material() {
        let dir = TempDir::new("obj_missing_mtl");
        let mesh = load_mesh(&dir.write("cube.obj", CUBE)).expect("loads without its .mtl");
        assert_eq!(mesh.materials, [("default".to_string(), Material::default())]);
        assert!(mesh.material_ids.iter().all(|&m| m == 0));
    }

    #[test]
    fn obj_bad_mtl_names_the_mtl_and_line() {
        let dir = TempDir::new("obj_bad_mtl");
        dir.write("cube.mtl", "newmtl red\nKd 0.8\n");
        let message = load_mesh(&dir.write("cube.obj", CUBE)).expect_err("short Kd").to_string();
        assert!(message.contains("cube.mtl: line 2: `Kd` needs three numbers"), "{message}");
    }

    #[test]
    fn obj_keeps_normals_and_uvs() {
        let dir = TempDir::new("obj_normals_uvs");
        let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n";
        let mesh = load_mesh(&dir.write("tri.obj", obj)).expect("loads");
        assert_eq!(mesh.normals, Some(vec![[0.0, 0.0, 1.0]; 3]));
        assert_eq!(mesh.uvs, Some(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]));
    }
}
