//! rt: a physically based GPU path tracer for scenes made in Blender — the renderer.
//!
//! The pipeline flows down through these modules: `scene` reads the scene file,
//! `asset` imports meshes, `bvh` builds acceleration structures, `gpu` owns the
//! device and the specialised pipelines, `sky` builds the atmosphere's tables,
//! `render` drives progressive rendering and writes images; `files` is how every one
//! of them reads inputs and writes outputs, and `progress` how long work says how far
//! it has come. The live viewer (`rt-watch`) and the benchmarks (`rt-bench`) are crates
//! of their own above this one: nothing here draws a window or a terminal.

pub mod asset;
pub mod bvh;
pub mod denoise;
pub mod doctor;
pub mod files;
pub mod fuzz;
pub mod gpu;
pub mod gpu_struct;
pub mod info;
pub mod layout;
pub mod progress;
pub mod render;
pub mod scene;
pub mod shared_constants;
pub mod sky;

/// rt's version and the commit it was built from ("unknown" outside a git checkout),
/// with "+changes" when the work tree differed from it: `rt --version`, `rt doctor`.
pub const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), " (commit ", env!("RT_COMMIT"), ")");
