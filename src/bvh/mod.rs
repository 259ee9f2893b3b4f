//! Acceleration structures: a BVH per mesh (obvhs), converted to the GPU node
//! layout, and a top level over instances and spheres.

mod mesh_bvh;
mod node;
mod scene_geometry;

pub use mesh_bvh::{BuildQuality, MeshBvh};
pub use node::{BvhStats, NODE_LAYOUT, convert_bvh2, stats};
pub use scene_geometry::{LoadedMesh, SceneGeometry};
