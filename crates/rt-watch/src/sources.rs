//! The files a scene is made of: what to watch, and the prints that tell whether an
//! asset really changed (an editor that saves the same bytes again changes nothing).

use super::plan::AssetPrints;
use rt::asset::AssetFiles;
use rt::bvh::{asset_paths, cache};
use rt::gpu::shader::built_in_files;
use rt::scene::Scene;
use std::path::{Path, PathBuf};

/// The display shader, read from disk with `--dev` like the path tracer's.
pub const DISPLAY_SHADER: &str = "display.wgsl";

/// BLAKE3 of every asset's source files (the same hash that keys its BVH cache), and
/// of every instance file.
pub fn asset_prints(scene: &Scene) -> AssetPrints {
    let assets = asset_paths(scene).into_iter().map(|path| {
        let print = AssetFiles::resolve(&path).and_then(|f| cache::source_hash(&f)).map_err(|e| e.to_string());
        (path, print)
    });
    let instance_files = scene.instance_sets.iter().map(|s| {
        let print = rt::files::read(&s.file).map(|b| *blake3::hash(&b).as_bytes());
        (s.file.clone(), print.map_err(|e| e.to_string()))
    });
    assets.chain(instance_files).collect()
}

/// The scene file, every asset's source files, every instance file, and with `shaders` the shader files.
pub fn watched_files(scene_path: &Path, scene: &Scene, shaders: Option<&Path>) -> Vec<PathBuf> {
    let mut files = vec![scene_path.to_path_buf()];
    for asset in asset_paths(scene) {
        files.extend(asset_files(&asset));
    }
    files.extend(scene.instance_sets.iter().map(|s| s.file.clone()));
    if let Some(dir) = shaders {
        files.extend(built_in_files().map(|(name, _)| dir.join(name)));
        files.push(dir.join(DISPLAY_SHADER));
    }
    files
}

/// The files an asset reads: the `.rtmesh` and `.gltf` of a folder, an `.obj` and its
/// `.mtl`, a `.gltf` and its `.bin`. An asset that cannot be resolved now (its main
/// file is missing or broken) is watched where its files will appear.
fn asset_files(asset: &Path) -> Vec<PathBuf> {
    if let Ok(files) = AssetFiles::resolve(asset).and_then(|f| f.source_files()) {
        return files;
    }
    match (asset.extension(), asset.file_name()) {
        (None, Some(name)) => {
            let main = asset.join(name);
            vec![main.with_extension("rtmesh"), main.with_extension("gltf")]
        }
        _ => vec![asset.to_path_buf()],
    }
}

/// The file names of `paths`, for a log line: "scene.toml,dragon.rtmesh".
pub fn names(paths: &[PathBuf]) -> String {
    let names: Vec<String> = paths
        .iter()
        .map(|p| p.file_name().map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into()))
        .collect();
    if names.is_empty() { "-".into() } else { names.join(",") }
}
