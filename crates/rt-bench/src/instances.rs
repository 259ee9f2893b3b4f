//! `rt bench instances`: how the top level scales with the number of instances. For
//! each count, a field of that many instances of one 10,000-triangle sphere (random
//! scale and turn, on a square grid) is written as an OBJ and an `.rtinst` file, loaded
//! as any scene is, and measured: the top level's build time, the GPU memory of the
//! meshes and of the instances with their top level, and the camera, diffuse and path
//! rates from a camera standing at the field's edge, looking across it as a person
//! looks into a forest (near instances large, far ones smaller than a pixel).

use super::compare::rate;
use super::throughput::{ThroughputOptions, measure};
use anyhow::{Context, Result, bail};
use glam::{Mat4, Quat, Vec3};
use indicatif::ProgressBar;
use rt::asset::rtinst::{self, InstanceRecord, MaterialSets};
use rt::bvh::{BuildQuality, SceneGeometry};
use rt::gpu::GpuContext;
use rt::render::{Session, human};
use std::fmt::Write as _;
use std::path::Path;

/// Metres between neighbouring instances (the sphere's radius is 1).
const SPACING: f32 = 2.5;

#[derive(Clone, Debug)]
pub struct InstanceScaleOptions {
    pub counts: Vec<usize>,
    pub size: (u32, u32),
    pub runs: u32,
    pub spp: u32,
}

/// A UV sphere of radius 1 with `rings` × `segments` quads (the poles' rings as
/// triangles): 9,800 triangles for 50 × 100.
fn sphere_obj(rings: u32, segments: u32) -> String {
    let mut obj = String::from("# rt bench instances: a UV sphere\n");
    for r in 1..rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            let (x, y, z) = (theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            let _ = writeln!(obj, "v {x} {y} {z}");
        }
    }
    let _ = writeln!(obj, "v 0 1 0\nv 0 -1 0");
    let ring = |r: u32, s: u32| 1 + (r - 1) * segments + s % segments;
    let (top, bottom) = ((rings - 1) * segments + 1, (rings - 1) * segments + 2);
    for s in 0..segments {
        let _ = writeln!(obj, "f {top} {} {}", ring(1, s + 1), ring(1, s));
        let _ = writeln!(obj, "f {bottom} {} {}", ring(rings - 1, s), ring(rings - 1, s + 1));
        for r in 1..rings - 1 {
            let (a, b, c, d) = (ring(r, s), ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s));
            let _ = writeln!(obj, "f {a} {b} {c}\nf {a} {c} {d}");
        }
    }
    obj
}

/// Instances along a side of the square grid of `count`.
fn side(count: usize) -> usize {
    (count as f64).sqrt().ceil() as usize
}

/// Half the width of the grid of `count`, in metres.
fn half_width(count: usize) -> f32 {
    side(count) as f32 * SPACING / 2.0
}

/// `count` instances on a square grid centred on the origin, each scaled by 0.6–1.2 and
/// turned about the vertical by a hash of its index.
fn field(count: usize) -> Vec<InstanceRecord> {
    let (side, half) = (side(count), half_width(count));
    (0..count)
        .map(|k| {
            let h = (k as u32).wrapping_mul(2_654_435_761) as f32 / u32::MAX as f32;
            let (i, j) = ((k % side) as f32, (k / side) as f32);
            let m = Mat4::from_scale_rotation_translation(
                Vec3::splat(0.6 + 0.6 * h),
                Quat::from_rotation_y(std::f32::consts::TAU * h),
                Vec3::new(i * SPACING - half, 1.0, j * SPACING - half),
            );
            InstanceRecord::new(&m, 0)
        })
        .collect()
}

fn scene_text(count: usize) -> String {
    let half = half_width(count);
    format!(
        "[render]\nmax_bounces = 4\n\n[camera]\nposition = [0.0, 12.0, {}]\nlook_at = [0.0, 0.0, {}]\nfov_y_deg = 50.0\n\n\
         [sky]\nkind = \"uniform\"\ncolor = [0.9, 0.95, 1.0]\n\n[materials.clay]\nbase_color = [0.6, 0.5, 0.4]\n\n\
         [[mesh]]\nasset = \"ground.obj\"\nmaterial = \"clay\"\n\n\
         [[instances]]\nasset = \"sphere.obj\"\nfile = \"field.rtinst\"\nmaterials = [\"clay\"]\n",
        -half - 5.0,
        -half + 40.0
    )
}

fn ground_obj(count: usize) -> String {
    let h = half_width(count) + 10.0;
    format!("v {} 0 {}\nv {h} 0 {}\nv {h} 0 {h}\nv {} 0 {h}\nf 1 3 2\nf 1 4 3\n", -h, -h, -h, -h)
}

/// One table row: the field of `count` written in `dir`, loaded, built and measured.
fn row(
    ctx: &GpuContext,
    dir: &Path,
    count: usize,
    options: &InstanceScaleOptions,
    bar: &ProgressBar,
) -> Result<String> {
    let dir = &dir.join(count.to_string());
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))
    };
    write("sphere.obj", &sphere_obj(50, 100))?;
    write("ground.obj", &ground_obj(count))?;
    rtinst::write(&dir.join("field.rtinst"), &field(count), &MaterialSets::default())?;
    let scene_path = dir.join("field.toml");
    write("field.toml", &scene_text(count))?;
    let scene = rt::scene::load(&scene_path)?;
    let geometry = SceneGeometry::build(&scene, BuildQuality::default())?;
    let (meshes, top) = (geometry.mesh_bytes(), geometry.top_level_bytes());
    let build_ms = geometry.tlas_build_time.as_secs_f64() * 1e3;
    let mut session = Session::with_geometry(ctx, scene, geometry)?;
    let t = ThroughputOptions { size: options.size, runs: options.runs, spp: options.spp, lanes: None, rays: true };
    let figures = measure(&mut session, &t, bar)?;
    Ok(format!(
        "| {count} | {build_ms:.1} | {:.1} + {:.1} | {:.1} | {} | {} | {} |",
        meshes as f64 / 1048576.0,
        top as f64 / 1048576.0,
        top as f64 / count as f64,
        rate(figures.camera_rays_per_s()),
        rate(figures.diffuse_rays_per_s()),
        human(figures.paths_per_s()),
    ))
}

pub fn instances(options: &InstanceScaleOptions, adapter: Option<&str>) -> Result<()> {
    if options.counts.is_empty() || options.counts.contains(&0) {
        bail!("--counts: give one or more instance counts, each at least 1");
    }
    let ctx = GpuContext::new(adapter)?;
    println!("GPU      {}", ctx.describe());
    println!(
        "field    instances of a 9,800-triangle sphere, {}x{}, {} spp per dispatch, up to 4 bounces, median of {} runs",
        options.size.0,
        options.size.1,
        options.spp,
        options.runs.max(1)
    );
    // The field's files can be large (64 bytes per instance): never left behind.
    let scratch = rt::files::ScratchDir::new("bench-instances").context("cannot make a scratch folder")?;
    let dir = scratch.path();
    let bar = ProgressBar::new(options.counts.len() as u64 * 2 * (options.runs.max(1) as u64 + 1));
    let mut rows = Vec::new();
    let mut outcome = Ok(());
    for &count in &options.counts {
        match row(&ctx, dir, count, options, &bar) {
            Ok(r) => rows.push(r),
            Err(e) => {
                outcome = Err(e.context(format!("{count} instances")));
                break;
            }
        }
    }
    bar.finish_and_clear();
    drop(scratch);
    println!(
        "\n| instances | top-level build ms | GPU MiB (meshes + instances and top level) | bytes/instance | camera rays/s | diffuse rays/s | paths/s |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!("{r}");
    }
    outcome
}
