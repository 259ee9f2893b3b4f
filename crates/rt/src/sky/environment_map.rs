//! An environment image on the GPU: its constants and its texels with their
//! distribution, group 2 of the integrator (`shaders/environment.wgsl`).

use super::environment::{Distribution, EnvironmentImage, gpu_bytes, gpu_entries};
use crate::gpu::{GpuContext, bind_group};
use crate::layout::GpuEnvironment;
use crate::scene::Environment;
use anyhow::Result;
use glam::{Mat3, Vec3};
use wgpu::util::DeviceExt;

pub struct EnvironmentMap {
    /// What the buffers were made from.
    params: Environment,
    info: GpuEnvironment,
    /// Whether the image has any light in it (else light sampling leaves it out).
    image_emits: bool,
    uniform: wgpu::Buffer,
    /// Group 2 of the integrator.
    pub bind_group: wgpu::BindGroup,
}

/// Rows of the map from rt's world (Y up) to the image's frame: Blender's axes (Z up;
/// rt's (x, y, z) is Blender's (x, −z, y)), then the Mapping node's rotation, XYZ Euler
/// as Blender composes it (Rz · Ry · Rx).
pub fn world_to_image(rotation_deg: Vec3) -> Mat3 {
    let r = rotation_deg * (std::f32::consts::PI / 180.0);
    let rotation = Mat3::from_rotation_z(r.z) * Mat3::from_rotation_y(r.y) * Mat3::from_rotation_x(r.x);
    let to_blender = Mat3::from_cols(Vec3::X, Vec3::Z, -Vec3::Y);
    rotation * to_blender
}

/// The environment's share of light samples: all of them when nothing else emits,
/// else half; none for an image that is black everywhere.
pub fn light_share(emits: bool, other_lights: bool) -> f32 {
    match (emits, other_lights) {
        (false, _) => 0.0,
        (true, false) => 1.0,
        (true, true) => 0.5,
    }
}

impl EnvironmentMap {
    /// Reads the image (halved until the GPU can bind it), builds its distribution and
    /// uploads both; `layout` is the integrator's group 2 layout.
    pub fn new(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, params: &Environment) -> Result<Self> {
        let start = std::time::Instant::now();
        let mut image = EnvironmentImage::read(&params.image)?;
        let read = start.elapsed();
        let max = ctx.device.limits().max_storage_buffer_binding_size;
        while gpu_bytes(image.width, image.height) > max && image.width > 1 {
            log::warn!(
                "{}: {}×{} texels are more than this GPU binds in one buffer: halved",
                params.image.display(),
                image.width,
                image.height
            );
            image = image.halved();
        }
        let distribution = Distribution::new(&image, params.srgb);
        log::debug!(
            "{}: {}×{} texels read in {:.1} ms, distribution built in {:.1} ms",
            params.image.display(),
            image.width,
            image.height,
            read.as_secs_f64() * 1e3,
            (start.elapsed() - read).as_secs_f64() * 1e3
        );
        let data = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("environment"),
            contents: bytemuck::cast_slice(&gpu_entries(&image, &distribution)),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let m = world_to_image(params.rotation_deg);
        let info = GpuEnvironment {
            to_image_x: m.row(0).to_array(),
            width: image.width,
            to_image_y: m.row(1).to_array(),
            height: image.height,
            to_image_z: m.row(2).to_array(),
            strength: params.strength,
            light_share: 0.0,
            importance: u32::from(params.importance_sampling),
            srgb: u32::from(params.srgb),
            _pad: 0,
        };
        let uniform = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("environment constants"),
            contents: bytemuck::bytes_of(&info),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let bind_group = bind_group(ctx, "environment", layout, &[&uniform, &data]);
        let image_emits = distribution.total > 0.0;
        Ok(Self { params: params.clone(), info, image_emits, uniform, bind_group })
    }

    pub fn params(&self) -> &Environment {
        &self.params
    }

    /// Takes a new strength or sampling switch without reading the image again.
    pub fn set_constants(&mut self, ctx: &GpuContext, params: &Environment) {
        self.info.strength = params.strength;
        self.info.importance = u32::from(params.importance_sampling);
        self.params = params.clone();
        ctx.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&self.info));
    }

    /// Shares light samples with the scene's other lights, if it has any.
    pub fn set_other_lights(&mut self, ctx: &GpuContext, other_lights: bool) {
        let share = light_share(self.image_emits && self.info.strength > 0.0, other_lights);
        if share != self.info.light_share {
            self.info.light_share = share;
            ctx.queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&self.info));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_rotation_is_blenders_axes() {
        let m = world_to_image(Vec3::ZERO);
        // rt's up (+Y) is Blender's +Z; rt's −Z (forward) is Blender's +Y.
        assert!((m * Vec3::Y - Vec3::Z).length() < 1e-6);
        assert!((m * -Vec3::Z - Vec3::Y).length() < 1e-6);
        assert!((m * Vec3::X - Vec3::X).length() < 1e-6);
    }

    #[test]
    fn rotation_about_blenders_z_turns_the_horizon() {
        // Blender's Rz(90°) takes its +X to +Y: rt's +X looks up what rt's −Z did.
        let m = world_to_image(Vec3::new(0.0, 0.0, 90.0));
        assert!((m * Vec3::X - Vec3::Y).length() < 1e-6);
    }
}
