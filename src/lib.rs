//! rt: a physically based GPU path tracer for scenes made in Blender.
//!
//! The pipeline flows down through these modules: `scene` reads the scene file,
//! `asset` imports meshes, `bvh` builds acceleration structures, `gpu` owns the
//! device and the specialised pipelines, `sky` builds the atmosphere's tables,
//! `render` drives progressive rendering and writes images, `bench` measures;
//! `files` is how every one of them reads inputs and writes outputs.

pub mod asset;
pub mod bench;
pub mod bvh;
pub mod denoise;
pub mod doctor;
pub mod files;
pub mod fuzz;
pub mod gpu;
pub mod gpu_struct;
pub mod info;
pub mod layout;
pub mod render;
pub mod scene;
pub mod shared_constants;
pub mod sky;
pub mod watch;
