//! The scene's GPU buffers and the bind group that exposes them to every program.

use super::GpuContext;
use super::bind::{Binding, bind_group, sequential_layout};
use super::microfacet_tables::microfacet_tables;
use super::readback::read_buffer;
use super::scene_bindings::{SCENE_BINDINGS, SceneData};
use super::textures::TextureStore;
use crate::bvh::SceneGeometry;
use crate::layout::GpuFrame;
use anyhow::{Result, anyhow};
use bytemuck::Pod;
use wgpu::util::DeviceExt;

/// Counters in the statistics buffer (see `STAT_*` in `shaders/common.wgsl`).
pub const STAT_STACK_OVERFLOW: usize = 0;
const STAT_COUNT: usize = 1;

/// The scene group's layout (see `super::scene_bindings`).
pub fn scene_bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    sequential_layout(device, "scene", wgpu::ShaderStages::COMPUTE, SCENE_BINDINGS)
}

/// The atmosphere's group: its parameters and its tables (read-only to render, written by
/// the table passes).
pub const SKY_BINDINGS: [Binding; 2] = [Binding::Uniform, Binding::ReadOnly];

/// The integrator's group 1: accumulation, AOVs, adaptive sampling's counts, the lanes'
/// chunk counters and the exact sums.
pub const ACCUMULATION_BUFFERS: usize = 7;

/// Layout of the atmosphere's group ([`SKY_BINDINGS`], its tables writable to the table passes).
pub fn sky_bind_group_layout(device: &wgpu::Device, tables_writable: bool) -> wgpu::BindGroupLayout {
    let tables = if tables_writable { Binding::ReadWrite } else { SKY_BINDINGS[1] };
    sequential_layout(device, "sky", wgpu::ShaderStages::COMPUTE, &[SKY_BINDINGS[0], tables])
}

/// Layout of group 1: `count` read-write storage buffers (accumulation, or trace rays and hits).
pub fn io_bind_group_layout(device: &wgpu::Device, count: usize) -> wgpu::BindGroupLayout {
    sequential_layout(device, "io", wgpu::ShaderStages::COMPUTE, &vec![Binding::ReadWrite; count])
}

pub struct SceneBuffers {
    data: SceneData,
    pub bind_group: wgpu::BindGroup,
    /// Group 2 of the integrator when the sky is an atmosphere: its parameters and
    /// tables (see `crate::sky`).
    pub sky_bind_group: Option<wgpu::BindGroup>,
}

/// A storage buffer from a slice; never empty, since bindings must have a size.
fn storage<T: Pod + Default>(ctx: &GpuContext, label: &str, data: &[T], extra: wgpu::BufferUsages) -> wgpu::Buffer {
    let one = [T::default()];
    let contents: &[T] = if data.is_empty() { &one } else { data };
    ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::cast_slice(contents),
        usage: wgpu::BufferUsages::STORAGE | extra,
    })
}

/// The geometry's buffers: (top-level nodes, triangles, shading, instances, top-level primitives,
/// spheres, bottom-level nodes, tangents, second uvs, object_settings, motion keys, attributes).
type GeometryBuffers = (
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
);

fn geometry_buffers(ctx: &GpuContext, geometry: &SceneGeometry) -> Result<GeometryBuffers> {
    check_sizes(ctx, geometry)?;
    let none = wgpu::BufferUsages::empty();
    Ok((
        storage(ctx, "nodes", &geometry.nodes, none),
        storage(ctx, "triangles", &geometry.triangles, none),
        storage(ctx, "shading", &geometry.shading, none),
        storage(ctx, "instances", &geometry.instances, none),
        storage(ctx, "tlas primitives", &geometry.tlas_primitives, none),
        storage(ctx, "spheres", &geometry.spheres, none),
        storage(ctx, "wide nodes", &geometry.wide_nodes, none),
        storage(ctx, "tangents", &geometry.tangents, none),
        storage(ctx, "second uvs", &geometry.second_uvs, none),
        storage(ctx, "object_settings", &geometry.object_settings, none),
        storage(ctx, "motion matrices", &geometry.motion_matrices, none),
        storage(ctx, "attributes", &geometry.attributes, none),
    ))
}

/// The lamp table and its header (count and light-sampling shares).
fn lamp_buffers(ctx: &GpuContext, geometry: &SceneGeometry) -> (wgpu::Buffer, wgpu::Buffer) {
    let lamps = storage(ctx, "lamps", &geometry.lamps, wgpu::BufferUsages::empty());
    let info = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("lamp info"),
        contents: bytemuck::bytes_of(&geometry.lamp_info),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    });
    (lamps, info)
}

fn light_tree_buffers(ctx: &GpuContext, geometry: &SceneGeometry) -> (wgpu::Buffer, wgpu::Buffer) {
    let none = wgpu::BufferUsages::empty();
    let tree = &geometry.light_tree;
    (storage(ctx, "light tree nodes", &tree.nodes, none), storage(ctx, "light tree trails", &tree.trails, none))
}

fn texture_buffers(ctx: &GpuContext, geometry: &SceneGeometry) -> (wgpu::Buffer, wgpu::Buffer) {
    let max = ctx.device.limits().max_storage_buffer_binding_size;
    let store = TextureStore::pack(geometry.textures(), max);
    let none = wgpu::BufferUsages::empty();
    (storage(ctx, "textures", &store.table, none), storage(ctx, "texels", &store.texels, none))
}

fn material_buffers(ctx: &GpuContext, geometry: &SceneGeometry) -> (wgpu::Buffer, wgpu::Buffer, wgpu::Buffer) {
    let writable = wgpu::BufferUsages::COPY_DST;
    (
        storage(ctx, "materials", &geometry.materials, writable),
        storage(ctx, "emitters", &geometry.emitters, writable),
        storage(ctx, "node programs", &geometry.node_programs, writable),
    )
}

impl SceneBuffers {
    pub fn new(ctx: &GpuContext, geometry: &SceneGeometry, layout: &wgpu::BindGroupLayout) -> Result<Self> {
        let (
            nodes,
            triangles,
            shading,
            instances,
            tlas_primitives,
            spheres,
            wide_nodes,
            tangent_frames,
            second_uvs,
            object_settings,
            motion_matrices,
            attributes,
        ) = geometry_buffers(ctx, geometry)?;
        let (materials, emitters, node_programs) = material_buffers(ctx, geometry);
        let frame = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("frame"),
            contents: bytemuck::bytes_of(&GpuFrame::default()),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let counters = wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
        let stats = storage(ctx, "stats", &[0u32; STAT_COUNT], counters);
        let (lamps, lamp_info) = lamp_buffers(ctx, geometry);
        let (textures, texels) = texture_buffers(ctx, geometry);
        let (light_tree_nodes, light_tree_trails) = light_tree_buffers(ctx, geometry);
        let data = SceneData {
            frame,
            nodes,
            triangles,
            shading,
            instances,
            tlas_primitives,
            spheres,
            materials,
            stats,
            emitters,
            lamps,
            lamp_info,
            wide_nodes,
            textures,
            texels,
            light_tree_nodes,
            light_tree_trails,
            tangent_frames,
            microfacet_tables: storage(ctx, "microfacet tables", &microfacet_tables(), wgpu::BufferUsages::empty()),
            second_uvs,
            object_settings,
            node_programs,
            motion_matrices,
            attributes,
        };
        let bind_group = bind_group(ctx, "scene", layout, &data.bindings());
        Ok(Self { data, bind_group, sky_bind_group: None })
    }

    /// Replaces the geometry (nodes, triangles, instances, spheres) and the material
    /// table with `geometry`'s: after an asset or the placement of meshes changed.
    pub fn replace_geometry(
        &mut self,
        ctx: &GpuContext,
        geometry: &SceneGeometry,
        layout: &wgpu::BindGroupLayout,
    ) -> Result<()> {
        let d = &mut self.data;
        (
            d.nodes,
            d.triangles,
            d.shading,
            d.instances,
            d.tlas_primitives,
            d.spheres,
            d.wide_nodes,
            d.tangent_frames,
            d.second_uvs,
            d.object_settings,
            d.motion_matrices,
            d.attributes,
        ) = geometry_buffers(ctx, geometry)?;
        (d.materials, d.emitters, d.node_programs) = material_buffers(ctx, geometry);
        (d.lamps, d.lamp_info) = lamp_buffers(ctx, geometry);
        (d.textures, d.texels) = texture_buffers(ctx, geometry);
        (d.light_tree_nodes, d.light_tree_trails) = light_tree_buffers(ctx, geometry);
        self.bind_group = bind_group(ctx, "scene", layout, &self.data.bindings());
        Ok(())
    }

    /// Uploads `geometry`'s material table and emitter table (emission decides which
    /// triangles are lights), in place when their sizes are unchanged.
    pub fn replace_materials(&mut self, ctx: &GpuContext, geometry: &SceneGeometry, layout: &wgpu::BindGroupLayout) {
        let d = &mut self.data;
        // A value edited in a node graph changes a program's constants, not its size.
        let same_size = d.materials.size() == size_of_nonempty(&geometry.materials)
            && d.emitters.size() == size_of_nonempty(&geometry.emitters)
            && d.node_programs.size() == size_of_nonempty(&geometry.node_programs);
        // Whether there are emitters changes the lamps' share of light samples.
        ctx.queue.write_buffer(&d.lamp_info, 0, bytemuck::bytes_of(&geometry.lamp_info));
        if same_size {
            write_nonempty(ctx, &d.materials, &geometry.materials);
            write_nonempty(ctx, &d.emitters, &geometry.emitters);
            write_nonempty(ctx, &d.node_programs, &geometry.node_programs);
        } else {
            (d.materials, d.emitters, d.node_programs) = material_buffers(ctx, geometry);
        }
        // Emission decides which triangles the light tree holds, and their power.
        (d.light_tree_nodes, d.light_tree_trails) = light_tree_buffers(ctx, geometry);
        self.bind_group = bind_group(ctx, "scene", layout, &self.data.bindings());
    }

    pub fn write_frame(&self, ctx: &GpuContext, frame: &GpuFrame) {
        ctx.queue.write_buffer(&self.data.frame, 0, bytemuck::bytes_of(frame));
    }

    /// Reads the counters and zeroes them.
    pub fn take_stats(&self, ctx: &GpuContext) -> Result<[u32; STAT_COUNT]> {
        let values: Vec<u32> = read_buffer(ctx, &self.data.stats)?;
        ctx.queue.write_buffer(&self.data.stats, 0, bytemuck::cast_slice(&[0u32; STAT_COUNT]));
        let mut out = [0; STAT_COUNT];
        out.copy_from_slice(&values[..STAT_COUNT]);
        Ok(out)
    }
}

/// Refuses data of `bytes` that one storage binding of at most `max` bytes cannot hold,
/// saying what it is (`what`: "the scene's instances") and both sizes.
pub fn check_binding(what: &str, bytes: u64, max: u64) -> Result<()> {
    if bytes > max {
        return Err(anyhow!(
            "{what} take {:.1} MiB ({bytes} bytes); this GPU binds at most {:.1} MiB ({max} bytes) per buffer",
            bytes as f64 / 1048576.0,
            max as f64 / 1048576.0
        ));
    }
    Ok(())
}

fn check_sizes(ctx: &GpuContext, geometry: &SceneGeometry) -> Result<()> {
    let max = ctx.device.limits().max_storage_buffer_binding_size;
    let sizes = [
        ("top-level BVH nodes", std::mem::size_of_val(geometry.nodes.as_slice())),
        ("mesh BVH nodes", std::mem::size_of_val(geometry.wide_nodes.as_slice())),
        ("triangles", std::mem::size_of_val(geometry.triangles.as_slice())),
        ("triangle shading", std::mem::size_of_val(geometry.shading.as_slice())),
        ("triangle tangents", std::mem::size_of_val(geometry.tangents.as_slice())),
        ("second uvs", std::mem::size_of_val(geometry.second_uvs.as_slice())),
        ("attributes", std::mem::size_of_val(geometry.attributes.as_slice())),
        ("instances", std::mem::size_of_val(geometry.instances.as_slice())),
        ("instance settings", std::mem::size_of_val(geometry.object_settings.as_slice())),
        ("motion matrices", std::mem::size_of_val(geometry.motion_matrices.as_slice())),
        ("emitters", std::mem::size_of_val(geometry.emitters.as_slice())),
        ("node programs", std::mem::size_of_val(geometry.node_programs.as_slice())),
        ("light tree nodes", std::mem::size_of_val(geometry.light_tree.nodes.as_slice())),
    ];
    for (what, bytes) in sizes {
        check_binding(&format!("the scene's {what}"), bytes as u64, max)?;
    }
    Ok(())
}

/// The size [`storage`] gives a buffer for `data`.
fn size_of_nonempty<T: Pod + Default>(data: &[T]) -> u64 {
    (std::mem::size_of::<T>() * data.len().max(1)) as u64
}

fn write_nonempty<T: Pod + Default>(ctx: &GpuContext, buffer: &wgpu::Buffer, data: &[T]) {
    let one = [T::default()];
    let contents: &[T] = if data.is_empty() { &one } else { data };
    ctx.queue.write_buffer(buffer, 0, bytemuck::cast_slice(contents));
}
