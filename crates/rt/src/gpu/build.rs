//! Building GPU objects whose creation can fail validation (shaders, pipelines):
//! inside an error scope, so that a bad shader is an error naming it, never a panic
//! in wgpu's uncaptured-error handler.

use super::GpuContext;
use anyhow::{Result, anyhow};
use std::collections::HashMap;

/// Runs `build` in a validation error scope; `what` names it in the error.
pub fn validated<T>(ctx: &GpuContext, what: &str, build: impl FnOnce() -> T) -> Result<T> {
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let built = build();
    match pollster::block_on(scope.pop()) {
        Some(e) => Err(anyhow!("building {what} failed: {e}")),
        None => Ok(built),
    }
}

/// The compute pipelines of one WGSL module, one per entry point, over the bind
/// group layouts `groups` (group i is `groups[i]`).
pub fn compute_pipelines(
    ctx: &GpuContext,
    what: &str,
    source: String,
    groups: &[&wgpu::BindGroupLayout],
    entries: &[&'static str],
) -> Result<HashMap<&'static str, wgpu::ComputePipeline>> {
    validated(ctx, what, || {
        let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(what),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let groups: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().copied().map(Some).collect();
        let layout = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(what),
            bind_group_layouts: &groups,
            immediate_size: 0,
        });
        entries
            .iter()
            .map(|&name| {
                let pipeline = ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(name),
                    layout: Some(&layout),
                    module: &module,
                    entry_point: Some(name),
                    compilation_options: Default::default(),
                    cache: None,
                });
                (name, pipeline)
            })
            .collect()
    })
}
