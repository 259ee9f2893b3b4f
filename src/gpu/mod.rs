//! The GPU side: device setup, host mirrors of GPU structs, shader assembly
//! per feature set, scene buffers and the pipelines that use them.

mod buffers;
mod context;
pub mod layout;
mod pipelines;
pub mod shader;
mod timer;

pub use buffers::{STAT_STACK_OVERFLOW, SceneBuffers, read_buffer, sky_bind_group_layout};
pub use context::{GpuContext, ensure_runtime_dir};
pub use pipelines::{PipelineCache, Pipelines};
pub use timer::GpuTimer;
