//! Packing: an asset's `.rtbvh` cache is used when fresh, and rebuilt from the source
//! (then written beside it) when missing, stale or invalid. `rt pack` does this ahead of
//! time; `rt render` does it for whatever it finds out of date.

use super::cache::{self, CacheProblem, PackedMesh};
use super::mesh_bvh::{BuildQuality, MeshBvh};
use crate::asset::{self, AssetError, AssetFiles};
use crate::progress::{self, Meter, MeterSpec};
use crate::scene::Material;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// One distinct asset of a scene, ready for the GPU, however many instances place it.
/// Its geometry is only in `bvh` (triangles in leaf order): a mesh loaded from its cache
/// is never imported.
#[derive(Clone, Debug)]
pub struct LoadedMesh {
    pub path: PathBuf,
    pub bvh: MeshBvh,
    pub materials: Vec<(String, Material)>,
    pub textures: Vec<crate::asset::TextureImage>,
    /// Of the source mesh.
    pub vertex_count: usize,
    pub triangle_count: usize,
    pub provenance: Provenance,
}

/// Where a loaded mesh's BVH came from, and what it cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Provenance {
    /// Read from a fresh `.rtbvh`.
    Cache { load_time: Duration },
    /// Imported and built (the cache was missing or stale, and has been rewritten).
    Packed { build_time: Duration },
    /// Imported and built with no cache: built-in assets, or a cache that could not be written.
    InMemory { build_time: Duration },
}

/// What `rt pack` did for one asset.
#[derive(Clone, Debug)]
pub struct PackReport {
    pub asset: PathBuf,
    pub cache: PathBuf,
    pub outcome: PackOutcome,
}

#[derive(Clone, Debug, PartialEq)]
pub enum PackOutcome {
    UpToDate,
    Packed { reason: String, triangles: u32, time: Duration },
}

impl LoadedMesh {
    fn new(path: &Path, packed: PackedMesh, provenance: Provenance) -> Self {
        warn_if_invisible(path, &packed);
        Self {
            path: path.to_path_buf(),
            bvh: packed.bvh,
            materials: packed.materials,
            textures: packed.textures,
            vertex_count: packed.vertex_count as usize,
            triangle_count: packed.triangle_count as usize,
            provenance,
        }
    }
}

/// The build leaves zero-area triangles out; a mesh of nothing else renders nothing,
/// which must not pass without a word.
fn warn_if_invisible(path: &Path, packed: &PackedMesh) {
    if packed.bvh.triangles.is_empty() && packed.triangle_count > 0 {
        let which = match packed.triangle_count {
            1 => "its only triangle is".to_owned(),
            n => format!("all {n} triangles are"),
        };
        log::warn!("{}: {which} degenerate (zero area): the mesh is invisible", path.display());
    }
}

fn import_and_build(files: &AssetFiles, quality: BuildQuality) -> Result<PackedMesh, AssetError> {
    let mesh = asset::load_mesh(&files.main)?;
    let bvh = MeshBvh::build(&mesh, quality);
    Ok(PackedMesh {
        bvh,
        vertex_count: mesh.positions.len() as u32,
        triangle_count: mesh.indices.len() as u32,
        materials: mesh.materials,
        textures: mesh.textures,
    })
}

/// The asset's BVH from its cache if that is fresh; else imported, built, and the cache
/// rewritten (a cache that cannot be written costs a warning, not the render).
pub fn load_or_pack(path: &Path, quality: BuildQuality) -> Result<LoadedMesh, AssetError> {
    let files = AssetFiles::resolve(path)?;
    let start = Instant::now();
    let Some(cache_path) = files.cache_path() else {
        let packed = import_and_build(&files, quality)?;
        return Ok(LoadedMesh::new(path, packed, Provenance::InMemory { build_time: start.elapsed() }));
    };
    let (source_hash, params_hash) = (cache::source_hash(&files)?, cache::params_hash(quality));
    let problem = match cache::read(&cache_path, source_hash, params_hash) {
        Ok(packed) => return Ok(LoadedMesh::new(path, packed, Provenance::Cache { load_time: start.elapsed() })),
        Err(problem) => problem,
    };
    match problem {
        CacheProblem::Missing => log::info!("{}: no BVH cache yet; packing it", cache_path.display()),
        _ => log::warn!("{}: {problem}; rebuilding it", cache_path.display()),
    }
    let packed = import_and_build(&files, quality)?;
    let build_time = start.elapsed();
    let provenance = match cache::write(&cache_path, &packed, source_hash, params_hash) {
        Ok(()) => Provenance::Packed { build_time },
        Err(e) => {
            log::warn!("{e}; the BVH stays in memory only");
            Provenance::InMemory { build_time }
        }
    };
    Ok(LoadedMesh::new(path, packed, provenance))
}

/// Packs one asset unless its cache is fresh (or `force`). Built-in assets have no cache.
pub fn pack(path: &Path, quality: BuildQuality, force: bool) -> Result<PackReport, AssetError> {
    let files = AssetFiles::resolve(path)?;
    let cache_path = files.cache_path().ok_or_else(|| AssetError::new(path, "built-in assets are not cached"))?;
    let (source_hash, params_hash) = (cache::source_hash(&files)?, cache::params_hash(quality));
    let report = |outcome| PackReport { asset: path.to_path_buf(), cache: cache_path.clone(), outcome };
    // Even an up-to-date cache clears what a killed packer left beside it.
    crate::files::output::remove_stale_temporaries(&cache_path);
    let reason = match force {
        true => "forced".to_owned(),
        false => match cache::read(&cache_path, source_hash, params_hash) {
            Ok(_) => return Ok(report(PackOutcome::UpToDate)),
            Err(problem) => problem.to_string(),
        },
    };
    let start = Instant::now();
    let packed = import_and_build(&files, quality)?;
    warn_if_invisible(path, &packed);
    cache::write(&cache_path, &packed, source_hash, params_hash)?;
    Ok(report(PackOutcome::Packed { reason, triangles: packed.triangle_count, time: start.elapsed() }))
}

/// `f` over `items` on every core, results in `items`' order; `bar` advances per item.
pub fn parallel_map<T: Sync, R: Send>(items: &[T], bar: &dyn Meter, f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(items.len()).max(1);
    let next = AtomicUsize::new(0);
    let mut results: Vec<(usize, R)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(item) = items.get(i) else { break };
                        done.push((i, f(item)));
                        bar.inc(1);
                    }
                    done
                })
            })
            .collect();
        // A worker only panics on a bug in rt; let it surface as one.
        workers.into_iter().flat_map(|w| w.join().unwrap_or_else(|p| std::panic::resume_unwind(p))).collect()
    });
    results.sort_by_key(|(i, _)| *i);
    results.into_iter().map(|(_, r)| r).collect()
}

/// A meter over `len` assets, labelled `what`.
pub fn asset_bar(len: usize, what: &str) -> Box<dyn Meter> {
    progress::meter(&MeterSpec { label: what, unit: "assets", total: len as u64, time_left: false })
}

/// [`load_or_pack`] for each path, in parallel.
pub fn load_or_pack_all(paths: &[PathBuf], quality: BuildQuality) -> Result<Vec<LoadedMesh>, AssetError> {
    let bar = asset_bar(paths.len(), "loading BVHs");
    let meshes = parallel_map(paths, bar.as_ref(), |p| load_or_pack(p, quality));
    bar.finish();
    meshes.into_iter().collect()
}

/// Each asset imported and its BVH built at `quality`, in parallel, in memory only.
pub fn build_all_in_memory(paths: &[PathBuf], quality: BuildQuality) -> Result<Vec<LoadedMesh>, AssetError> {
    let meshes = parallel_map(paths, progress::hidden().as_ref(), |path| {
        let start = Instant::now();
        let packed = import_and_build(&AssetFiles::resolve(path)?, quality)?;
        Ok(LoadedMesh::new(path, packed, Provenance::InMemory { build_time: start.elapsed() }))
    });
    meshes.into_iter().collect()
}

/// The assets under `roots`: each root that is a file, and in each folder (recursively,
/// hidden ones skipped) every `.rtmesh` (named by its folder `NAME/` when that holds
/// `NAME.rtmesh`), `.obj`, `.glb`, and `.gltf` that is not an `.rtmesh`'s materials.
pub fn find_assets(roots: &[PathBuf]) -> Result<Vec<PathBuf>, AssetError> {
    let mut found = Vec::new();
    for root in roots {
        if root.is_dir() {
            walk(root, &mut found)?;
        } else {
            found.push(root.clone());
        }
    }
    let mut seen = std::collections::HashSet::new();
    found.retain(|p| seen.insert(AssetFiles::resolve(p).map(|f| f.main).unwrap_or_else(|_| p.clone())));
    Ok(found)
}

fn walk(dir: &Path, found: &mut Vec<PathBuf>) -> Result<(), AssetError> {
    let read = std::fs::read_dir(dir).map_err(|e| AssetError::new(dir, format!("cannot list: {e}")))?;
    let mut entries: Vec<PathBuf> = read.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if name.starts_with('.') {
            continue;
        }
        // Symbolic links to folders are not followed: they could loop.
        if path.is_symlink() && path.is_dir() {
            continue;
        }
        if path.is_dir() {
            walk(&path, found)?;
            continue;
        }
        // A FIFO would block its reader forever, a device never ends: neither is an asset.
        match std::fs::metadata(&path) {
            Ok(m) if m.is_file() => {}
            Ok(m) => {
                log::warn!("{}: skipped: {}, not a file", path.display(), crate::files::input::describe(m.file_type()));
                continue;
            }
            // A dangling link or a file that vanished: there is nothing to pack.
            Err(_) => continue,
        }
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("rtmesh") if path.parent().and_then(Path::file_name) == path.file_stem() => {
                found.push(dir.to_path_buf())
            }
            Some("rtmesh" | "obj" | "glb") => found.push(path),
            Some("gltf") if !path.with_extension("rtmesh").is_file() => found.push(path),
            _ => {}
        }
    }
    Ok(())
}
