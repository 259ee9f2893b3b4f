//! The scene's GPU buffers and the bind group that exposes them to every program.

use super::GpuContext;
use super::layout::GpuFrame;
use crate::bvh::SceneGeometry;
use anyhow::{Result, anyhow};
use bytemuck::Pod;
use wgpu::util::DeviceExt;

/// Counters in the statistics buffer (see `shaders/common.wgsl`).
pub const STAT_STACK_OVERFLOW: usize = 0;
const STAT_COUNT: usize = 4;

/// The scene's buffers in binding order (see `shaders/common.wgsl`), so that a live
/// reload can replace some of them and rebind.
pub struct SceneBuffers {
    pub frame: wgpu::Buffer,
    nodes: wgpu::Buffer,
    triangles: wgpu::Buffer,
    shading: wgpu::Buffer,
    instances: wgpu::Buffer,
    tlas: wgpu::Buffer,
    spheres: wgpu::Buffer,
    materials: wgpu::Buffer,
    pub stats: wgpu::Buffer,
    emitters: wgpu::Buffer,
    lamps: wgpu::Buffer,
    lamp_info: wgpu::Buffer,
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

pub fn scene_bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entry = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    };
    let read = wgpu::BufferBindingType::Storage { read_only: true };
    let mut entries = vec![entry(0, wgpu::BufferBindingType::Uniform)];
    entries.extend((1..=7).map(|b| entry(b, read)));
    entries.push(entry(8, wgpu::BufferBindingType::Storage { read_only: false }));
    entries.push(entry(9, read));
    entries.push(entry(10, read));
    entries.push(entry(11, wgpu::BufferBindingType::Uniform));
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some("scene"), entries: &entries })
}

/// Layout of the atmosphere's group: its parameters (uniform) and its tables
/// (storage, read-only to render, written by the table passes).
pub fn sky_bind_group_layout(device: &wgpu::Device, tables_writable: bool) -> wgpu::BindGroupLayout {
    let entry = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    };
    let tables = wgpu::BufferBindingType::Storage { read_only: !tables_writable };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("sky"),
        entries: &[entry(0, wgpu::BufferBindingType::Uniform), entry(1, tables)],
    })
}

/// Layout of group 1: `count` read-write storage buffers (accumulation, or trace rays and hits).
pub fn io_bind_group_layout(device: &wgpu::Device, count: u32) -> wgpu::BindGroupLayout {
    let entries: Vec<_> = (0..count)
        .map(|binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: false },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some("io"), entries: &entries })
}

impl SceneBuffers {
    pub fn new(ctx: &GpuContext, geometry: &SceneGeometry, layout: &wgpu::BindGroupLayout) -> Result<Self> {
        check_sizes(ctx, geometry)?;
        let none = wgpu::BufferUsages::empty();
        let frame = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("frame"),
            contents: bytemuck::bytes_of(&GpuFrame::default()),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let stats =
            storage(ctx, "stats", &[0u32; STAT_COUNT], wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST);
        let materials = storage(ctx, "materials", &geometry.materials, wgpu::BufferUsages::COPY_DST);
        let emitters = storage(ctx, "emitters", &geometry.emitters, wgpu::BufferUsages::COPY_DST);
        let nodes = storage(ctx, "nodes", &geometry.nodes, none);
        let triangles = storage(ctx, "triangles", &geometry.triangles, none);
        let shading = storage(ctx, "shading", &geometry.shading, none);
        let instances = storage(ctx, "instances", &geometry.instances, none);
        let tlas = storage(ctx, "tlas primitives", &geometry.tlas_primitives, none);
        let spheres = storage(ctx, "spheres", &geometry.spheres, none);
        let (lamps, lamp_info) = lamp_buffers(ctx, geometry);
        let bind_group = bind(
            ctx,
            layout,
            [
                &frame, &nodes, &triangles, &shading, &instances, &tlas, &spheres, &materials, &stats, &emitters,
                &lamps, &lamp_info,
            ],
        );
        Ok(Self {
            frame,
            nodes,
            triangles,
            shading,
            instances,
            tlas,
            spheres,
            materials,
            stats,
            emitters,
            lamps,
            lamp_info,
            bind_group,
            sky_bind_group: None,
        })
    }

    /// Replaces the geometry (nodes, triangles, instances, spheres) and the material
    /// table with `geometry`'s: after an asset or the placement of meshes changed.
    pub fn replace_geometry(
        &mut self,
        ctx: &GpuContext,
        geometry: &SceneGeometry,
        layout: &wgpu::BindGroupLayout,
    ) -> Result<()> {
        check_sizes(ctx, geometry)?;
        let none = wgpu::BufferUsages::empty();
        self.nodes = storage(ctx, "nodes", &geometry.nodes, none);
        self.triangles = storage(ctx, "triangles", &geometry.triangles, none);
        self.shading = storage(ctx, "shading", &geometry.shading, none);
        self.instances = storage(ctx, "instances", &geometry.instances, none);
        self.tlas = storage(ctx, "tlas primitives", &geometry.tlas_primitives, none);
        self.spheres = storage(ctx, "spheres", &geometry.spheres, none);
        self.materials = storage(ctx, "materials", &geometry.materials, wgpu::BufferUsages::COPY_DST);
        self.emitters = storage(ctx, "emitters", &geometry.emitters, wgpu::BufferUsages::COPY_DST);
        (self.lamps, self.lamp_info) = lamp_buffers(ctx, geometry);
        self.rebind(ctx, layout);
        Ok(())
    }

    /// Uploads `geometry`'s material table and emitter table (emission decides which
    /// triangles are lights), in place when their sizes are unchanged.
    pub fn replace_materials(&mut self, ctx: &GpuContext, geometry: &SceneGeometry, layout: &wgpu::BindGroupLayout) {
        let same_size = self.materials.size() == size_of_nonempty(&geometry.materials)
            && self.emitters.size() == size_of_nonempty(&geometry.emitters);
        // Whether there are emitters changes the lamps' share of light samples.
        ctx.queue.write_buffer(&self.lamp_info, 0, bytemuck::bytes_of(&geometry.lamp_info));
        if same_size {
            write_nonempty(ctx, &self.materials, &geometry.materials);
            write_nonempty(ctx, &self.emitters, &geometry.emitters);
        } else {
            self.materials = storage(ctx, "materials", &geometry.materials, wgpu::BufferUsages::COPY_DST);
            self.emitters = storage(ctx, "emitters", &geometry.emitters, wgpu::BufferUsages::COPY_DST);
            self.rebind(ctx, layout);
        }
    }

    fn rebind(&mut self, ctx: &GpuContext, layout: &wgpu::BindGroupLayout) {
        let buffers = [
            &self.frame,
            &self.nodes,
            &self.triangles,
            &self.shading,
            &self.instances,
            &self.tlas,
            &self.spheres,
            &self.materials,
            &self.stats,
            &self.emitters,
            &self.lamps,
            &self.lamp_info,
        ];
        self.bind_group = bind(ctx, layout, buffers);
    }

    pub fn write_frame(&self, ctx: &GpuContext, frame: &GpuFrame) {
        ctx.queue.write_buffer(&self.frame, 0, bytemuck::bytes_of(frame));
    }

    /// Reads the counters and zeroes them.
    pub fn take_stats(&self, ctx: &GpuContext) -> Result<[u32; STAT_COUNT]> {
        let values: Vec<u32> = read_buffer(ctx, &self.stats)?;
        ctx.queue.write_buffer(&self.stats, 0, bytemuck::cast_slice(&[0u32; STAT_COUNT]));
        let mut out = [0; STAT_COUNT];
        out.copy_from_slice(&values[..STAT_COUNT]);
        Ok(out)
    }
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

fn check_sizes(ctx: &GpuContext, geometry: &SceneGeometry) -> Result<()> {
    let max = ctx.device.limits().max_storage_buffer_binding_size;
    let sizes = [
        ("BVH nodes", std::mem::size_of_val(geometry.nodes.as_slice())),
        ("triangles", std::mem::size_of_val(geometry.triangles.as_slice())),
    ];
    for (what, bytes) in sizes {
        if bytes as u64 > max {
            return Err(anyhow!(
                "the scene's {what} take {} MiB; this GPU binds at most {} MiB per buffer",
                bytes >> 20,
                max >> 20
            ));
        }
    }
    Ok(())
}

/// The scene bind group: binding i is the i-th buffer.
fn bind(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, buffers: [&wgpu::Buffer; 12]) -> wgpu::BindGroup {
    let entries: Vec<_> = buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
        .collect();
    ctx.device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some("scene"), layout, entries: &entries })
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

/// Copies a buffer (with COPY_SRC usage) back to the host.
pub fn read_buffer<T: Pod>(ctx: &GpuContext, buffer: &wgpu::Buffer) -> Result<Vec<T>> {
    let size = buffer.size();
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    ctx.wait()?;
    rx.recv()?.map_err(|e| anyhow!("could not read a GPU buffer back: {e}"))?;
    let view = slice.get_mapped_range().map_err(|e| anyhow!("could not map a GPU buffer: {e}"))?;
    let data = bytemuck::pod_collect_to_vec(&view);
    Ok(data)
}
