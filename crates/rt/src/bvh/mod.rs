//! Acceleration structures: a compressed 8-wide BVH per mesh (obvhs), converted to the
//! GPU node layout and cached in `.rtbvh` files, and a binary top level over instances
//! and spheres.

mod binned_build;
pub mod cache;
mod cache_check;
mod cached_material;
mod cached_texture;
mod emitter_table;
mod light_bounds;
pub mod light_tree;
mod lights;
mod mesh_bvh;
mod node;
pub mod node_table;
pub mod pack;
mod placement;
mod scene_geometry;
mod scene_lights;
mod top_level;
mod wide_node;
mod world_graph;

pub use mesh_bvh::{BuildQuality, MeshBvh};
pub use node::{BvhStats, convert_bvh2, stats};
pub use pack::{LoadedMesh, PackOutcome, PackReport, Provenance};
pub use placement::object_to_world;
pub use scene_geometry::{SceneGeometry, asset_paths};
pub use wide_node::NODE_LAYOUT;
