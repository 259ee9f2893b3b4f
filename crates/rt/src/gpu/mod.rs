//! The GPU side: device setup, shader assembly per feature set, scene buffers and
//! the pipelines that use them. The GPU structs are declared in `crate::layout`.

mod bind;
mod buffers;
mod build;
mod context;
#[cfg(test)]
mod layout_check;
mod microfacet_tables;
pub mod node_code;
mod pipelines;
mod readback;
mod scene_bindings;
pub mod shader;
mod textures;
mod timer;

pub use bind::{Binding, bind_group, sequential_layout};
pub use buffers::{STAT_STACK_OVERFLOW, SceneBuffers, check_binding, sky_bind_group_layout};
pub use build::{compute_pipelines, validated};
pub use context::{GpuContext, adapter_names, ensure_runtime_dir};
pub use pipelines::{PipelineCache, Pipelines};
pub use readback::{Readback, read_buffer};
pub use timer::{GpuTimer, median, ms};
