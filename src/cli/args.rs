//! The command line's options: the commands and what `rt render` and `rt watch` take.

use super::bench_args::BenchCommand;
use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use rt::VERSION;
use rt::bvh::BuildQuality;
use rt::denoise::DenoiseDevice;
use rt::render::{ImageFormat, Progress, RenderFlags};
use rt::scene::{LightSampler, MAX_IMAGE_SIDE, Microfacet, RoughTransmission, Sampling};
use std::path::PathBuf;

#[derive(Parser)]
#[command(name = "rt", version = VERSION, about = "A physically based GPU path tracer for scenes made in Blender")]
pub(crate) struct Cli {
    /// GPU adapter to use: part of its name, as printed by `rt info`.
    #[arg(long, global = true, env = "RT_ADAPTER")]
    pub(crate) adapter: Option<String>,
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Build the BVH caches (.rtbvh) of assets whose cache is missing or stale.
    Pack {
        /// Asset folders (searched recursively), .rtmesh, .gltf, .glb or .obj files.
        #[arg(required = true)]
        paths: Vec<PathBuf>,
        #[arg(long, value_enum, default_value_t)]
        quality: BuildQuality,
        /// Rebuild even caches that are up to date.
        #[arg(long)]
        force: bool,
    },
    /// Render a scene to a PNG (tone-mapped sRGB) or EXR (linear radiance).
    Render(RenderArgs),
    /// Merge parts that `rt render --sample-range` wrote into the image one render gives,
    /// bit for bit; parts that overlap, leave gaps or come from another render are refused.
    Merge {
        /// The parts (OpenEXR files), in any order.
        #[arg(required = true)]
        parts: Vec<PathBuf>,
        /// Output image: .png or .exr (with the AOV layers if the parts were rendered with --aovs).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Show a scene in a window that re-renders as its files change (or, headless, write frames).
    Watch(WatchArgs),
    /// Print what a scene contains: counts, bounds, BVH statistics, feature set, GPU.
    Info {
        /// Scene file; the built-in Cornell box when omitted.
        scene: Option<PathBuf>,
        #[arg(long, value_enum, default_value_t)]
        quality: BuildQuality,
        /// Print only the files rendering the scene reads (the scene, meshes, materials,
        /// textures, caches, environment image), one absolute path a line.
        #[arg(long)]
        inputs: bool,
    },
    /// Measure performance.
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Check this machine: GPUs and Vulkan drivers, Open Image Denoise, Blender's Python
    /// module, Blender and rt's extension; says what to do about what is missing.
    Doctor,
}

#[derive(Args, Clone)]
pub(crate) struct RenderArgs {
    /// Scene file; the built-in Cornell box when omitted.
    pub(crate) scene: Option<PathBuf>,
    /// Output image: .png or .exr.
    #[arg(short, long, default_value = "render.png")]
    pub(crate) output: PathBuf,
    /// Samples per pixel [default: the scene's].
    #[arg(long)]
    pub(crate) spp: Option<u32>,
    /// Image size as WIDTHxHEIGHT [default: the scene's].
    #[arg(long, value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// Seed of the random numbers: the same seed gives the same image.
    #[arg(long, default_value_t = 0)]
    pub(crate) seed: u32,
    /// Longest path, in bounces: 0 shows emitters and the sky only [default: the scene's].
    #[arg(long)]
    pub(crate) max_bounces: Option<u32>,
    /// Exposure in EV for PNG output [default: the scene's].
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) exposure: Option<f32>,
    /// A transparent film, as Blender's: the background seen by the camera is left out and
    /// the image gets an alpha channel (the share of each pixel the scene covers) [default: the scene's].
    #[arg(long)]
    pub(crate) transparent: bool,
    /// BVH build quality.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) quality: BuildQuality,
    /// How paths find light [default: the scene's].
    #[arg(long, value_enum)]
    pub(crate) sampling: Option<Sampling>,
    /// Candidates per resampled direction with `--sampling seed` [default: the scene's].
    #[arg(long)]
    pub(crate) ris_candidates: Option<u32>,
    /// Model of rough refraction [default: the scene's].
    #[arg(long, value_enum)]
    pub(crate) rough_transmission: Option<RoughTransmission>,
    /// How light sampling picks a lamp or emitter: by power, or down the light tree [default: the scene's].
    #[arg(long, value_enum)]
    pub(crate) light_sampler: Option<LightSampler>,
    /// Model of rough GGX lobes: Cycles' multiscatter GGX, or single scattering as Mitsuba 3 [default: the scene's].
    #[arg(long, value_enum)]
    pub(crate) microfacet: Option<Microfacet>,
    /// Scale every sample down to at most this luminance. Hides fireflies at the
    /// price of bias (bright light goes missing); off by default.
    #[arg(long)]
    pub(crate) clamp: Option<f32>,
    /// Fail (exit status 3) if any sample was non-finite or any ray overflowed the traversal stack.
    #[arg(long)]
    pub(crate) strict: bool,
    /// Samples per pixel in each GPU dispatch [default: as many as keep a dispatch near 80 ms].
    #[arg(long)]
    pub(crate) samples_per_dispatch: Option<u32>,
    /// Invocations each pixel's samples are spread over; the image is the same whatever
    /// the number [default: as many as keep the GPU busy, 1 on a CPU].
    #[arg(long)]
    pub(crate) sample_lanes: Option<u32>,
    /// What stderr shows while rendering: a bar, nothing, or JSON lines for a program
    /// that drives rt (progress, warning, done, error events).
    #[arg(long, value_enum, default_value_t)]
    pub(crate) progress: Progress,
    /// Also write the albedo, normal, depth, position, emission, standard error and sample count per pixel:
    /// the output is then one multi-layer OpenEXR (docs/denoising.md).
    #[arg(long)]
    pub(crate) aovs: bool,
    /// Denoise the image with Open Image Denoise, guided by albedo and normals (with
    /// --aovs, the raw image is kept as the `noisy` layer).
    #[arg(long)]
    pub(crate) denoise: bool,
    /// Where Open Image Denoise runs: auto takes a CUDA GPU when it has one, else the CPU.
    #[arg(long, value_enum, default_value_t, requires = "denoise")]
    pub(crate) denoise_device: DenoiseDevice,
    /// Adaptive sampling: a pixel stops once the relative standard error of its mean
    /// luminance is below this, e.g. 0.01 (0: off) [default: the scene's].
    #[arg(long)]
    pub(crate) noise_threshold: Option<f32>,
    /// Stop after this many seconds with the samples taken so far, as Cycles' Time Limit
    /// [default: none].
    #[arg(long, value_parser = parse_seconds)]
    pub(crate) time_limit: Option<f64>,
    /// While rendering, write the image so far (linear, as an OpenEXR) to this path every
    /// --snapshot-every seconds; with --progress json, a `snapshot` event says so.
    #[arg(long)]
    pub(crate) snapshot: Option<PathBuf>,
    /// Seconds between snapshots.
    #[arg(long, value_parser = parse_seconds, default_value_t = 1.0, requires = "snapshot")]
    pub(crate) snapshot_every: f64,
    /// Also write each AOV as an OpenEXR of its own in this folder (albedo.exr, normal.exr,
    /// depth.exr, error.exr, samples.exr; one-value AOVs in all three channels), for
    /// programs that read plain images (the Blender engine's passes).
    #[arg(long)]
    pub(crate) aov_files: Option<PathBuf>,
    /// Render only samples FIRST..END of each pixel (e.g. 0..256) into a part, an OpenEXR
    /// that `rt merge` adds to the other parts: parts that tile 0..N merge into the image
    /// --spp N gives, bit for bit. Give -o an .exr path.
    #[arg(long, value_parser = rt::render::part::parse_sample_range)]
    pub(crate) sample_range: Option<std::ops::Range<u32>>,
    /// Render frames FIRST..LAST (both included) of an animation: #### in the scene's and
    /// the output's names is the frame number (shot_####.toml → shot_0007.toml). One GPU
    /// start and the pipelines built once serve every frame.
    #[arg(long, value_parser = rt::render::frames::parse_frame_range)]
    pub(crate) frames: Option<std::ops::RangeInclusive<u32>>,
}

/// A positive, finite number of seconds.
pub(crate) fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a positive number of seconds, not {s:?}")),
    }
}

impl RenderArgs {
    /// These arguments for one frame: the scene's and the output's #### filled in.
    pub(crate) fn at_frame(&self, frame: u32) -> Result<Self> {
        let scene = self.scene.as_deref().context("--frames: give the scene file, with #### for the frame number")?;
        Ok(Self {
            scene: Some(rt::render::frames::frame_path(scene, frame, "scene")?),
            output: rt::render::frames::frame_path(&self.output, frame, "-o")?,
            ..self.clone()
        })
    }

    pub(crate) fn flags(&self) -> RenderFlags {
        RenderFlags {
            size: self.size,
            spp: self.sample_range.as_ref().map(|r| r.len() as u32).or(self.spp),
            max_bounces: self.max_bounces,
            exposure: self.exposure,
            transparent: self.transparent,
            sampling: self.sampling,
            ris_candidates: self.ris_candidates,
            rough_transmission: self.rough_transmission,
            light_sampler: self.light_sampler,
            microfacet: self.microfacet,
            seed: self.seed,
            clamp: self.clamp,
            samples_per_dispatch: self.samples_per_dispatch,
            sample_lanes: self.sample_lanes,
            noise_threshold: self.noise_threshold,
            aovs: self.aovs || self.denoise || self.aov_files.is_some(),
        }
    }
}

#[derive(Args)]
pub(crate) struct WatchArgs {
    /// Scene file.
    pub(crate) scene: PathBuf,
    /// No window: refine each state of the scene to --spp and write it to --frames-dir
    /// as frame-NNNN.png (NNNN: the reload's number); stops when FRAMES_DIR/stop appears.
    #[arg(long, requires = "frames_dir")]
    pub(crate) headless: bool,
    /// No window: take commands on standard input and send frames on standard output
    /// (the protocol: docs/live-preview.md, "Streaming to a client"); with --socket, on a Unix socket.
    #[arg(long, conflicts_with = "headless")]
    pub(crate) stream: bool,
    /// With --stream: serve clients one after another on the Unix socket at this path.
    #[arg(long, requires = "stream")]
    pub(crate) socket: Option<PathBuf>,
    /// Where frames (headless), screenshots and watch.log go.
    #[arg(long)]
    pub(crate) frames_dir: Option<PathBuf>,
    /// Samples per pixel each state is refined to [default: the scene's].
    #[arg(long)]
    pub(crate) spp: Option<u32>,
    /// Image size as WIDTHxHEIGHT (headless), or the window's first size [default: the scene's].
    #[arg(long, value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    #[arg(long, default_value_t = 0)]
    pub(crate) seed: u32,
    /// Format of headless frames: png (tone-mapped) or exr (linear).
    #[arg(long, value_enum, default_value = "png")]
    pub(crate) format: ImageFormat,
    /// Stop once the frame of this reload is written (0: the first state's).
    #[arg(long)]
    pub(crate) max_reloads: Option<u32>,
    /// Read shaders from this folder and reload them when they change (alone: the
    /// repository's `crates/rt/shaders`, from its root).
    #[arg(long, value_name = "SHADERS_DIR", num_args = 0..=1, default_missing_value = "crates/rt/shaders")]
    pub(crate) dev: Option<PathBuf>,
    #[arg(long, value_enum, default_value_t)]
    pub(crate) quality: BuildQuality,
    /// Denoise with Open Image Denoise once the image has 4 samples per pixel, again each
    /// time they double: the window shows it (`N` toggles it); headless, each frame is
    /// written denoised and the raw one beside it as frame-NNNN-raw.
    #[arg(long, conflicts_with = "stream")]
    pub(crate) denoise: bool,
    /// Where Open Image Denoise runs: auto takes a CUDA GPU when it has one, else the CPU.
    #[arg(long, value_enum, default_value_t, requires = "denoise")]
    pub(crate) denoise_device: DenoiseDevice,
    /// Adaptive sampling's noise threshold (0: off) [default: the scene's].
    #[arg(long)]
    pub(crate) noise_threshold: Option<f32>,
}

pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or("expected WIDTHxHEIGHT, e.g. 640x480")?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|&n| (1..=MAX_IMAGE_SIDE).contains(&n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("width and height must be whole numbers from 1 to {MAX_IMAGE_SIDE}")),
    }
}
