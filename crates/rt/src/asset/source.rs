//! Which files an asset path stands for: the file to import, the files it reads
//! besides (materials, buffers), and where its BVH cache lives.

use super::{AssetError, builtin, gltf_buffers, gltf_textures};
use std::path::{Path, PathBuf};

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AssetKind {
    /// An `.rtmesh` and the materials-only glTF beside it.
    RtMesh {
        materials: PathBuf,
    },
    Obj,
    /// `.gltf` or `.glb`.
    Gltf,
}

/// An asset path resolved into its files.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AssetFiles {
    pub kind: AssetKind,
    /// The file the importer opens: the `.rtmesh`, `.obj`, `.gltf` or `.glb`.
    pub main: PathBuf,
}

impl AssetFiles {
    /// `NAME/` (a folder holding `NAME.rtmesh` and `NAME.gltf`), `X.rtmesh` (with `X.gltf`),
    /// `X.obj`, `X.gltf` or `X.glb`. Files are not opened here, but a main file that does
    /// not exist is reported here, with a "did you mean" among its neighbours; a missing
    /// sidecar (`.gltf`, `.mtl`, `.bin`) is reported by whoever reads it.
    pub fn resolve(path: &Path) -> Result<Self, AssetError> {
        if path.is_dir() {
            let Some(name) = path.file_name() else {
                return Err(AssetError::new(path, "an asset folder needs a name (NAME/NAME.rtmesh)"));
            };
            let main = path.join(name).with_extension("rtmesh");
            if !main.is_file() {
                return Err(AssetError::new(
                    path,
                    format!(
                        "asset folder without {} (export it from Blender with blender/rt_export.py)",
                        main.display()
                    ),
                ));
            }
            return Ok(Self::rtmesh(main));
        }
        if !is_builtin(path) && !path.exists() {
            return Err(not_found(path));
        }
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        let kind = match ext.as_deref() {
            Some("rtmesh") => return Ok(Self::rtmesh(path.to_path_buf())),
            Some("obj") => AssetKind::Obj,
            // Built-in assets are OBJ only; glTF reads from disk.
            Some("gltf" | "glb") if !is_builtin(path) => AssetKind::Gltf,
            _ => {
                return Err(AssetError::new(
                    path,
                    "unsupported asset type (expected an asset folder, .rtmesh, .obj, .gltf or .glb)",
                ));
            }
        };
        Ok(Self { kind, main: path.to_path_buf() })
    }

    fn rtmesh(main: PathBuf) -> Self {
        Self { kind: AssetKind::RtMesh { materials: main.with_extension("gltf") }, main }
    }

    /// Where the BVH cache of this asset lives: beside its main file, with the extension
    /// `.rtbvh` (so `NAME/NAME.rtbvh` for a folder). Built-in assets have none.
    pub fn cache_path(&self) -> Option<PathBuf> {
        (!is_builtin(&self.main)).then(|| self.main.with_extension("rtbvh"))
    }

    /// Every file whose bytes the imported mesh depends on, main file first. A file that
    /// is named but missing is listed too: creating it later changes the mesh.
    pub fn source_files(&self) -> Result<Vec<PathBuf>, AssetError> {
        let mut files = vec![self.main.clone()];
        let dir = self.main.parent().unwrap_or(Path::new(""));
        match &self.kind {
            AssetKind::RtMesh { materials } => {
                files.push(materials.clone());
                // A glTF that cannot be read has no images to list; the import reports it.
                let bytes = crate::files::read(materials).ok();
                if let Some(gltf) = bytes.and_then(|b| gltf::Gltf::from_slice(&b).ok()) {
                    files.extend(gltf_textures::image_files(&gltf.document).map(|name| dir.join(name)));
                }
            }
            AssetKind::Obj => {
                let bytes = builtin::read(&self.main).map_err(|e| AssetError::new(&self.main, e.message()))?;
                files.extend(material_libraries(&bytes).map(|name| dir.join(name)));
            }
            AssetKind::Gltf => {
                let bytes = crate::files::read(&self.main).map_err(|e| AssetError::new(&self.main, e.message()))?;
                let gltf = gltf::Gltf::from_slice_without_validation(&bytes)
                    .map_err(|e| AssetError::new(&self.main, format!("cannot read glTF: {e}")))?;
                for buffer in gltf.document.buffers() {
                    if let gltf::buffer::Source::Uri(uri) = buffer.source()
                        && let Ok(Some(file)) = gltf_buffers::buffer_file(dir, uri)
                    {
                        files.push(file);
                    }
                }
                files.extend(gltf_textures::image_files(&gltf.document).map(|name| dir.join(name)));
            }
        }
        Ok(files)
    }
}

/// A path that does not exist, with a "did you mean" among the names beside it.
fn not_found(path: &Path) -> AssetError {
    AssetError::new(path, format!("no such file or folder{}", sibling_hint(path)))
}

/// "; did you mean `dragon`?" among the names beside a path that does not exist.
fn sibling_hint(path: &Path) -> String {
    let (Some(name), Some(dir)) = (path.file_name(), path.parent()) else { return String::new() };
    let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    let Ok(entries) = std::fs::read_dir(dir) else { return String::new() };
    let mut siblings: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('.'))
        .collect();
    siblings.sort();
    let hint = crate::scene::did_you_mean(&name.to_string_lossy(), siblings.iter().map(String::as_str));
    // A list of every file in the folder helps nobody; only a near name does.
    if hint.contains("did you mean") { hint } else { String::new() }
}

fn is_builtin(path: &Path) -> bool {
    path.starts_with(crate::scene::BUILTIN_PREFIX)
}

/// The `mtllib` names of an OBJ, as tobj reads them: the rest of the line, trimmed.
fn material_libraries(obj: &[u8]) -> impl Iterator<Item = String> + '_ {
    obj.split(|&b| b == b'\n').filter_map(|line| {
        let line = String::from_utf8_lossy(line);
        let rest = line.trim_start().strip_prefix("mtllib")?;
        (rest.starts_with(char::is_whitespace) && !rest.trim().is_empty()).then(|| rest.trim().to_owned())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::fixture::TempDir;

    #[test]
    fn resolves_folders_files_and_cache_paths() {
        let dir = TempDir::new("resolve_assets");
        let main = dir.write("dragon/dragon.rtmesh", "");
        let folder = main.parent().expect("folder").to_path_buf();
        let files = AssetFiles::resolve(&folder).expect("folder asset");
        assert_eq!(files.main, main);
        assert_eq!(files.kind, AssetKind::RtMesh { materials: folder.join("dragon.gltf") });
        assert_eq!(files.cache_path(), Some(folder.join("dragon.rtbvh")));
        assert_eq!(AssetFiles::resolve(&main).expect("file"), files);

        let foo = dir.write("a/foo.obj", "");
        let obj = AssetFiles::resolve(&foo).expect("obj");
        assert_eq!(obj.cache_path(), Some(foo.with_extension("rtbvh")));
        let message = AssetFiles::resolve(&foo.with_file_name("fo.obj")).expect_err("missing").to_string();
        assert!(message.ends_with("fo.obj: no such file or folder; did you mean `foo.obj`?"), "{message}");
        let builtin = AssetFiles::resolve(Path::new("<built-in>/assets/bunny/bunny.obj")).expect("built-in");
        assert_eq!(builtin.cache_path(), None);

        let empty = dir.write("empty/readme.txt", "");
        let message = AssetFiles::resolve(empty.parent().expect("folder")).expect_err("no rtmesh").to_string();
        assert!(message.contains("empty.rtmesh"), "{message}");
    }

    #[test]
    fn source_files_include_sidecars() {
        let dir = TempDir::new("source_files");
        let obj = dir.write("m.obj", "mtllib my lib.mtl\nv 0 0 0\nmtllibx nope\n");
        let files = AssetFiles::resolve(&obj).expect("obj").source_files().expect("files");
        assert_eq!(files, [obj.clone(), obj.with_file_name("my lib.mtl")]);

        let gltf = dir.write(
            "m.gltf",
            r#"{ "asset": { "version": "2.0" }, "buffers": [
                { "byteLength": 4, "uri": "data%20bin.bin" },
                { "byteLength": 1, "uri": "data:application/octet-stream;base64,AA==" }] }"#,
        );
        let files = AssetFiles::resolve(&gltf).expect("gltf").source_files().expect("files");
        assert_eq!(files, [gltf.clone(), gltf.with_file_name("data bin.bin")]);
    }
}
