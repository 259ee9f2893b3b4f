//! Acceleration structures: a BVH per mesh (obvhs), converted to the GPU node
//! layout and cached in `.rtbvh` files, and a top level over instances and spheres.

pub mod cache;
mod cache_check;
mod cached_material;
mod cached_texture;
mod mesh_bvh;
mod node;
pub mod pack;
mod scene_geometry;

pub use mesh_bvh::{BuildQuality, MeshBvh};
pub use node::{BvhStats, NODE_LAYOUT, convert_bvh2, stats};
pub use pack::{LoadedMesh, PackOutcome, PackReport, Provenance};
pub use scene_geometry::{SceneGeometry, asset_paths};
