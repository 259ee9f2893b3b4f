//! Compute pipelines, built per feature set from the assembled WGSL and cached.

use super::GpuContext;
use super::buffers::{io_bind_group_layout, scene_bind_group_layout, sky_bind_group_layout};
use super::build::compute_pipelines;
use super::node_code;
use super::shader::{Program, ShaderFiles, assemble_from};
use crate::bvh::SceneGeometry;
use crate::scene::{FeatureSet, SkyFeature};
use anyhow::{Result, anyhow};
use std::collections::HashMap;
use std::rc::Rc;

/// The pipelines of one program specialised to one feature set.
pub struct Pipelines {
    /// Entry point name → pipeline.
    pub entries: HashMap<&'static str, wgpu::ComputePipeline>,
}

impl Pipelines {
    pub fn entry(&self, name: &str) -> &wgpu::ComputePipeline {
        &self.entries[name]
    }
}

pub struct PipelineCache {
    pub scene_layout: wgpu::BindGroupLayout,
    pub accumulation_layout: wgpu::BindGroupLayout,
    pub trace_layout: wgpu::BindGroupLayout,
    /// Group 2 of the integrator under an atmosphere.
    pub sky_layout: wgpu::BindGroupLayout,
    files: ShaderFiles,
    built: HashMap<(Program, FeatureSet), Rc<Pipelines>>,
    /// Specialised node code by `FeatureSet::node_code`, as [`Self::learn_node_code`] made it.
    node_code: HashMap<u64, String>,
}

impl PipelineCache {
    pub fn new(ctx: &GpuContext) -> Self {
        Self {
            scene_layout: scene_bind_group_layout(&ctx.device),
            // Means, non-finite counts, lane scratch, AOVs, adaptive sampling's counts, the
            // lanes' chunk counters, exact sums.
            accumulation_layout: io_bind_group_layout(&ctx.device, super::buffers::ACCUMULATION_BUFFERS),
            trace_layout: io_bind_group_layout(&ctx.device, 2),
            sky_layout: sky_bind_group_layout(&ctx.device, false),
            files: ShaderFiles::BuiltIn,
            built: HashMap::new(),
            node_code: HashMap::new(),
        }
    }

    /// Makes the specialised code of `geometry`'s node programs, for the feature sets
    /// that name it (see [`crate::gpu::node_code`]).
    pub fn learn_node_code(&mut self, geometry: &SceneGeometry) {
        if let Some(code) = node_code::of_geometry(geometry) {
            self.node_code.entry(geometry.node_code).or_insert(code);
        }
    }

    /// Forgets the specialised code, and the pipelines built with it, of every node shapes
    /// but `key`'s (the geometry now rendered): each edit of a graph's shape in `rt watch`
    /// or Blender's viewport makes new code, and a long session must not keep them all.
    pub fn keep_node_code(&mut self, key: u64) {
        self.node_code.retain(|k, _| *k == key);
        self.built.retain(|(_, f), _| f.node_code == 0 || f.node_code == key);
    }

    /// How many specialised node codes are kept, and pipelines built.
    pub fn sizes(&self) -> (usize, usize) {
        (self.node_code.len(), self.built.len())
    }

    /// Reads the shaders from `files` from now on, rebuilding every pipeline that was
    /// built. Atomic: if any fails to build, nothing changes and the error says why.
    pub fn reload_shaders(&mut self, ctx: &GpuContext, files: ShaderFiles) -> Result<()> {
        let mut built = HashMap::new();
        for &(program, features) in self.built.keys() {
            built.insert((program, features), Rc::new(self.build(ctx, &files, program, features)?));
        }
        (self.files, self.built) = (files, built);
        Ok(())
    }

    pub fn get(&mut self, ctx: &GpuContext, program: Program, features: FeatureSet) -> Result<Rc<Pipelines>> {
        if let Some(p) = self.built.get(&(program, features)) {
            return Ok(p.clone());
        }
        let p = Rc::new(self.build(ctx, &self.files, program, features)?);
        self.built.insert((program, features), p.clone());
        Ok(p)
    }

    fn build(
        &self,
        ctx: &GpuContext,
        files: &ShaderFiles,
        program: Program,
        features: FeatureSet,
    ) -> Result<Pipelines> {
        let adaptive: &[&'static str] = match features.adaptive {
            true => &["render", "render_lanes", "reduce_lanes", "adaptive_mask"],
            false => &["render", "render_lanes", "reduce_lanes"],
        };
        let (io_layout, entry_names): (&wgpu::BindGroupLayout, &[&'static str]) = match program {
            Program::Integrator => (&self.accumulation_layout, adaptive),
            Program::Trace => (
                &self.trace_layout,
                &["trace", "generate_camera_rays", "generate_diffuse_rays", "generate_through_rays"],
            ),
        };
        let mut source = assemble_from(files, program, &features).map_err(|e| anyhow!(e))?;
        if program == Program::Integrator && features.flag("node_code") == Some(true) {
            let code = self.node_code.get(&features.node_code);
            source.push_str(code.ok_or_else(|| anyhow!("no specialised node code {:x}", features.node_code))?);
        }
        // Only the integrator reads the atmosphere; the trace program never calls the sky.
        let mut groups = vec![&self.scene_layout, io_layout];
        if program == Program::Integrator && matches!(features.sky, SkyFeature::Atmosphere | SkyFeature::Environment) {
            groups.push(&self.sky_layout);
        }
        let what = format!("the {program:?} pipeline for [{features}]");
        let entries = compute_pipelines(ctx, &what, source, &groups, entry_names)?;
        log::debug!("built the {program:?} pipeline for [{features}]");
        Ok(Pipelines { entries })
    }
}
