//! Evaluates the atmosphere's real WGSL on the GPU for chosen rays: the
//! integrator's module for a sky-only atmosphere scene, plus an entry point that
//! calls its functions (`PROBE_WGSL`). The scene's tables and frame are rt's own.

use rt::bvh::BuildQuality;
use rt::gpu::read_buffer;
use rt::gpu::shader::{Program, assemble};
use rt::layout::GpuFrame;
use rt::render::Session;
use std::time::{Duration, Instant};
use wgpu::util::DeviceExt;

/// What the probe computes for a query (see `PROBE_WGSL`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum Kind {
    /// Sky radiance, averaged over `param` evenly spread jitters: a converged render.
    Sky = 0,
    /// `atmosphere_sky_radiance`, as the integrator calls it (one hashed jitter).
    SkyHook = 1,
    /// `atmosphere_transmittance_to_space`.
    TransmittanceHook = 2,
    /// `multiple_scattering(h = origin.x, μs = origin.y)`.
    MultipleScattering = 3,
    /// `transmittance_to_space(h = origin.x, μ = origin.y)`.
    Transmittance = 4,
    /// `atmosphere_segment` over `param` metres: radiance, then transmittance.
    Segment = 5,
    /// `ground_sky_irradiance(μs = origin.x)`.
    GroundSky = 6,
    /// `sun_radiance_at` (limb darkening and transmittance).
    SunDisk = 7,
    /// `scattering_plane(param, h = origin.x, μs = origin.y)`: L₂, L₃, L₄, Ψ.
    ScatteringPlane = 8,
}

/// How the march takes light scattered more than once (see `VARIANTS_WGSL`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum Variant {
    /// rt's: L₂ + L₃ + L₄ / (1 − c), c = L₄/L₃; the ground's E₁ + E₂ + E₃ / (1 − c).
    Built = 0,
    /// The orders up to n, explicitly (1 to 4): nothing beyond.
    Orders1 = 1,
    Orders2 = 2,
    Orders3 = 3,
    Orders4 = 4,
    /// The seed's closure from the second order: L₂ / (1 − c), c = L₃/L₂.
    SecondOrderClosure = 5,
    /// rt's, with the ratio taken an order earlier: c = L₃/L₂.
    EarlierRatio = 6,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Query {
    pub origin: [f32; 3],
    pub param: f32,
    pub direction: [f32; 3],
    pub kind: u32,
    pub variant: u32,
    pub _pad: [u32; 3],
}

impl Query {
    pub fn new(kind: Kind, origin: [f32; 3], direction: [f32; 3], param: f32) -> Self {
        Self { origin, param, direction, kind: kind as u32, variant: Variant::Built as u32, _pad: [0; 3] }
    }

    pub fn with(self, variant: Variant) -> Self {
        Self { variant: variant as u32, ..self }
    }
}

/// The march's look-ups of Ψ and of the ground's sky irradiance, switched by variant.
const VARIANTS_WGSL: &str = r#"
var<private> probe_variant: u32;

fn probe_ratio(a: vec3f, b: vec3f) -> vec3f {
    return min(select(b / a, vec3f(1.0), a <= vec3f(0.0)), vec3f(0.9));
}

fn probe_multiple_scattering(h: f32, mu_s: f32) -> vec3f {
    let l2 = scattering_plane(0u, h, mu_s);
    let l3 = scattering_plane(1u, h, mu_s);
    let l4 = scattering_plane(2u, h, mu_s);
    switch probe_variant {
        case 1u: { return vec3f(0.0); }
        case 2u: { return l2; }
        case 3u: { return l2 + l3; }
        case 4u: { return l2 + l3 + l4; }
        case 5u: { return l2 / (1.0 - probe_ratio(l2, l3)); }
        case 6u: { return l2 + l3 + l4 / (1.0 - probe_ratio(l2, l3)); }
        default: { return scattering_plane(3u, h, mu_s); }
    }
}

fn probe_ground_sky(mu_s: f32) -> vec3f {
    let e1 = ground_row(0u, mu_s);
    let e2 = ground_row(1u, mu_s);
    let e3 = ground_row(2u, mu_s);
    let c32 = probe_ratio(scattering_plane(0u, 0.0, mu_s), scattering_plane(1u, 0.0, mu_s));
    switch probe_variant {
        case 1u: { return vec3f(0.0); }
        case 2u: { return e1; }
        case 3u: { return e1 + e2; }
        case 4u: { return e1 + e2 + e3; }
        case 5u: { return e1 + e2 / (1.0 - c32); }
        case 6u: { return e1 + e2 + e3 / (1.0 - c32); }
        default: { return e1 + ground_row(3u, mu_s); }
    }
}
"#;

/// The rendering functions these replace.
const VARIANT_PATCHES: [(&str, &str); 2] = [
    (
        "return scattering_plane(3u, h, mu_s) * atmosphere.multiple_scattering;",
        "return probe_multiple_scattering(h, mu_s) * atmosphere.multiple_scattering;",
    ),
    (
        "return ground_row(0u, mu_s) + ground_row(3u, mu_s) * atmosphere.multiple_scattering;",
        "return probe_ground_sky(mu_s);",
    ),
];

const PROBE_WGSL: &str = r#"
struct ProbeQuery { origin: vec3f, param: f32, direction: vec3f, kind: u32, variant: u32 }
@group(1) @binding(1) var<storage, read> probe_queries: array<ProbeQuery>;

@compute @workgroup_size(64)
fn probe(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= arrayLength(&probe_queries) {
        return;
    }
    let q = probe_queries[id.x];
    probe_variant = q.variant;
    var a = vec3f(0.0);
    var b = vec3f(0.0);
    switch q.kind {
        case 0u: {
            let n = u32(q.param);
            let ray = world_ray(q.origin, q.direction);
            for (var k = 0u; k < n; k++) {
                a += atmosphere_sky(ray, (f32(k) + 0.5) / f32(n));
            }
            a /= f32(n);
        }
        case 1u: { a = atmosphere_sky_radiance(q.origin, q.direction); }
        case 2u: { a = atmosphere_transmittance_to_space(q.origin, q.direction); }
        case 3u: { a = multiple_scattering(q.origin.x, q.origin.y); }
        case 4u: { a = transmittance_to_space(q.origin.x, q.origin.y); }
        case 5u: {
            let s = atmosphere_segment(q.origin, q.direction, q.param);
            a = s.radiance;
            b = s.transmittance;
        }
        case 6u: { a = ground_sky_irradiance(q.origin.x); }
        case 7u: { a = sun_radiance_at(q.origin, q.direction); }
        case 8u: { a = scattering_plane(u32(q.param), q.origin.x, q.origin.y); }
        default: {}
    }
    accumulation[2u * id.x] = vec4f(a, 0.0);
    accumulation[2u * id.x + 1u] = vec4f(b, 0.0);
}
"#;

/// A query's two outputs (see `Kind`).
pub type Outputs = ([f32; 3], [f32; 3]);

pub struct Probe {
    pub renderer: Session<'static>,
    pub frame: GpuFrame,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// A sky-only scene with an atmosphere of these extra `[sky]` keys and a sun.
pub fn scene_text(sky_keys: &str) -> String {
    format!("[sky]\nkind = \"atmosphere\"\n{sky_keys}\n[sun]\nelevation_deg = 10.0\nazimuth_deg = 90.0\n")
}

impl Probe {
    /// `patches` replace text in the assembled WGSL (each must be found): variants for measurements.
    pub fn new(sky_keys: &str, patches: &[(&str, &str)]) -> Self {
        let ctx = crate::common::gpu();
        let scene = crate::common::scene_from(&scene_text(sky_keys));
        let renderer = Session::open(ctx, scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
        let mut source = assemble(Program::Integrator, &renderer.features()) + VARIANTS_WGSL + PROBE_WGSL;
        for (from, to) in VARIANT_PATCHES.iter().chain(patches) {
            assert!(source.contains(from), "patch target {from:?} not in the shader");
            source = source.replace(from, to);
        }
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("probe"),
            entries: &[storage(0, false), storage(1, true)],
        });
        let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("probe"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let p = &renderer.pipeline_cache();
        let pipeline_layout = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("probe"),
            bind_group_layouts: &[Some(&p.scene_layout), Some(&layout), Some(&p.sky_layout)],
            immediate_size: 0,
        });
        let pipeline = ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("probe"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("probe"),
            compilation_options: Default::default(),
            cache: None,
        });
        let frame = renderer.frame();
        Self { renderer, frame, pipeline, layout }
    }

    /// The sun at this elevation, towards +X.
    pub fn set_sun(&mut self, elevation_deg: f64) {
        let e = elevation_deg.to_radians();
        self.frame.sun_direction = [e.cos() as f32, e.sin() as f32, 0.0];
    }

    /// March steps per ray (the tables stay as they are).
    pub fn set_steps(&mut self, steps: u32) {
        let rt::scene::Sky::Atmosphere(mut params) = self.renderer.scene().sky.clone() else { panic!("an atmosphere") };
        params.steps = steps;
        let rebuilt = self.renderer.set_atmosphere(&params).unwrap_or_else(|e| panic!("{e:#}"));
        assert!(!rebuilt, "the step count rebuilt the tables");
    }

    /// Solar irradiance above the atmosphere, as the GPU computes it.
    pub fn irradiance(&self) -> f64 {
        self.frame.sun_radiance[0] as f64 * 2.0 * std::f64::consts::PI * self.frame.sun_one_minus_cos as f64
    }

    /// Pairs of outputs per query, and the GPU time the dispatch took.
    pub fn run(&self, queries: &[Query]) -> (Vec<Outputs>, Duration) {
        let ctx = crate::common::gpu();
        self.renderer.buffers().write_frame(ctx, &self.frame);
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
        let input = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("probe queries"),
            contents: bytemuck::cast_slice(queries),
            usage,
        });
        let output = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("probe output"),
            size: (queries.len() * 32) as u64,
            usage,
            mapped_at_creation: false,
        });
        let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("probe"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: output.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: input.as_entire_binding() },
            ],
        });
        let sky = self.renderer.buffers().sky_bind_group.as_ref().expect("an atmosphere");
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.renderer.buffers().bind_group, &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.set_bind_group(2, sky, &[]);
            pass.dispatch_workgroups((queries.len() as u32).div_ceil(64), 1, 1);
        }
        let start = Instant::now();
        ctx.queue.submit([encoder.finish()]);
        ctx.wait().expect("GPU");
        let took = start.elapsed();
        let values: Vec<[f32; 4]> = read_buffer(ctx, &output).expect("read back");
        let pairs = values.chunks(2).map(|c| ([c[0][0], c[0][1], c[0][2]], [c[1][0], c[1][1], c[1][2]])).collect();
        (pairs, took)
    }
}
