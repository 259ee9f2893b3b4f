//! The `rt` command line: parses arguments, calls the library, maps errors to exit codes:
//! 0 success, 1 a bad input or a failed render, 2 a usage error (clap's), 3 a render that
//! `--strict` found dropping samples or rays.

use anyhow::{Context, Result, bail};
use clap::{Args, Parser, Subcommand};
use rt::bvh::SceneGeometry;
use rt::bvh::{BuildQuality, PackOutcome, PackReport};
use rt::denoise::{DenoiseDevice, Denoiser};
use rt::gpu::GpuContext;
use rt::gpu::PipelineCache;
use rt::render::RenderReport;
use rt::render::part::PartRequest;
use rt::render::{
    DroppedSamples, Image, ImageFormat, Progress, RenderFlags, RenderRequest, Session, aov_channels, check_output,
    human, image_format, json_event, write_image, write_layered_exr,
};
use rt::scene::{self, LightSampler, MAX_IMAGE_SIDE, Microfacet, RoughTransmission, Sampling, Scene};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The version and the commit rt was built from.
const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), " (commit ", env!("RT_COMMIT"), ")");

/// The exit status of a render that `--strict` rejects.
const EXIT_STRICT: u8 = 3;

#[derive(Parser)]
#[command(name = "rt", version = VERSION, about = "A physically based GPU path tracer for scenes made in Blender")]
struct Cli {
    /// GPU adapter to use: part of its name, as printed by `rt info`.
    #[arg(long, global = true, env = "RT_ADAPTER")]
    adapter: Option<String>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
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
struct RenderArgs {
    /// Scene file; the built-in Cornell box when omitted.
    scene: Option<PathBuf>,
    /// Output image: .png or .exr.
    #[arg(short, long, default_value = "render.png")]
    output: PathBuf,
    /// Samples per pixel [default: the scene's].
    #[arg(long)]
    spp: Option<u32>,
    /// Image size as WIDTHxHEIGHT [default: the scene's].
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Seed of the random numbers: the same seed gives the same image.
    #[arg(long, default_value_t = 0)]
    seed: u32,
    /// Longest path, in bounces: 0 shows emitters and the sky only [default: the scene's].
    #[arg(long)]
    max_bounces: Option<u32>,
    /// Exposure in EV for PNG output [default: the scene's].
    #[arg(long, allow_hyphen_values = true)]
    exposure: Option<f32>,
    /// A transparent film, as Blender's: the background seen by the camera is left out and
    /// the image gets an alpha channel (the share of each pixel the scene covers) [default: the scene's].
    #[arg(long)]
    transparent: bool,
    /// BVH build quality.
    #[arg(long, value_enum, default_value_t)]
    quality: BuildQuality,
    /// How paths find light [default: the scene's].
    #[arg(long, value_enum)]
    sampling: Option<Sampling>,
    /// Candidates per resampled direction with `--sampling seed` [default: the scene's].
    #[arg(long)]
    ris_candidates: Option<u32>,
    /// Model of rough refraction [default: the scene's].
    #[arg(long, value_enum)]
    rough_transmission: Option<RoughTransmission>,
    /// How light sampling picks a lamp or emitter: by power, or down the light tree [default: the scene's].
    #[arg(long, value_enum)]
    light_sampler: Option<LightSampler>,
    /// Model of rough GGX lobes: Cycles' multiscatter GGX, or single scattering as Mitsuba 3 [default: the scene's].
    #[arg(long, value_enum)]
    microfacet: Option<Microfacet>,
    /// Scale every sample down to at most this luminance. Hides fireflies at the
    /// price of bias (bright light goes missing); off by default.
    #[arg(long)]
    clamp: Option<f32>,
    /// Fail (exit status 3) if any sample was non-finite or any ray overflowed the traversal stack.
    #[arg(long)]
    strict: bool,
    /// Samples per pixel in each GPU dispatch [default: as many as keep a dispatch near 80 ms].
    #[arg(long)]
    samples_per_dispatch: Option<u32>,
    /// Invocations each pixel's samples are spread over; the image is the same whatever
    /// the number [default: as many as keep the GPU busy, 1 on a CPU].
    #[arg(long)]
    sample_lanes: Option<u32>,
    /// What stderr shows while rendering: a bar, nothing, or JSON lines for a program
    /// that drives rt (progress, warning, done, error events).
    #[arg(long, value_enum, default_value_t)]
    progress: Progress,
    /// Also write the albedo, normal, depth, position, emission, standard error and sample count per pixel:
    /// the output is then one multi-layer OpenEXR (docs/denoising.md).
    #[arg(long)]
    aovs: bool,
    /// Denoise the image with Open Image Denoise, guided by albedo and normals (with
    /// --aovs, the raw image is kept as the `noisy` layer).
    #[arg(long)]
    denoise: bool,
    /// Where Open Image Denoise runs: auto takes a CUDA GPU when it has one, else the CPU.
    #[arg(long, value_enum, default_value_t, requires = "denoise")]
    denoise_device: DenoiseDevice,
    /// Adaptive sampling: a pixel stops once the relative standard error of its mean
    /// luminance is below this, e.g. 0.01 (0: off) [default: the scene's].
    #[arg(long)]
    noise_threshold: Option<f32>,
    /// Stop after this many seconds with the samples taken so far, as Cycles' Time Limit
    /// [default: none].
    #[arg(long, value_parser = parse_seconds)]
    time_limit: Option<f64>,
    /// While rendering, write the image so far (linear, as an OpenEXR) to this path every
    /// --snapshot-every seconds; with --progress json, a `snapshot` event says so.
    #[arg(long)]
    snapshot: Option<PathBuf>,
    /// Seconds between snapshots.
    #[arg(long, value_parser = parse_seconds, default_value_t = 1.0, requires = "snapshot")]
    snapshot_every: f64,
    /// Also write each AOV as an OpenEXR of its own in this folder (albedo.exr, normal.exr,
    /// depth.exr, error.exr, samples.exr; one-value AOVs in all three channels), for
    /// programs that read plain images (the Blender engine's passes).
    #[arg(long)]
    aov_files: Option<PathBuf>,
    /// Render only samples FIRST..END of each pixel (e.g. 0..256) into a part, an OpenEXR
    /// that `rt merge` adds to the other parts: parts that tile 0..N merge into the image
    /// --spp N gives, bit for bit. Give -o an .exr path.
    #[arg(long, value_parser = rt::render::part::parse_sample_range)]
    sample_range: Option<std::ops::Range<u32>>,
    /// Render frames FIRST..LAST (both included) of an animation: #### in the scene's and
    /// the output's names is the frame number (shot_####.toml → shot_0007.toml). One GPU
    /// start and the pipelines built once serve every frame.
    #[arg(long, value_parser = rt::render::frames::parse_frame_range)]
    frames: Option<std::ops::RangeInclusive<u32>>,
}

/// A positive, finite number of seconds.
fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a positive number of seconds, not {s:?}")),
    }
}

impl RenderArgs {
    /// These arguments for one frame: the scene's and the output's #### filled in.
    fn at_frame(&self, frame: u32) -> Result<Self> {
        let scene = self.scene.as_deref().context("--frames: give the scene file, with #### for the frame number")?;
        Ok(Self {
            scene: Some(rt::render::frames::frame_path(scene, frame, "scene")?),
            output: rt::render::frames::frame_path(&self.output, frame, "-o")?,
            ..self.clone()
        })
    }

    fn flags(&self) -> RenderFlags {
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
struct WatchArgs {
    /// Scene file.
    scene: PathBuf,
    /// No window: refine each state of the scene to --spp and write it to --frames-dir
    /// as frame-NNNN.png (NNNN: the reload's number); stops when FRAMES_DIR/stop appears.
    #[arg(long, requires = "frames_dir")]
    headless: bool,
    /// No window: take commands on standard input and send frames on standard output
    /// (the protocol: docs/live-preview.md, "Streaming to a client"); with --socket, on a Unix socket.
    #[arg(long, conflicts_with = "headless")]
    stream: bool,
    /// With --stream: serve clients one after another on the Unix socket at this path.
    #[arg(long, requires = "stream")]
    socket: Option<PathBuf>,
    /// Where frames (headless), screenshots and watch.log go.
    #[arg(long)]
    frames_dir: Option<PathBuf>,
    /// Samples per pixel each state is refined to [default: the scene's].
    #[arg(long)]
    spp: Option<u32>,
    /// Image size as WIDTHxHEIGHT (headless), or the window's first size [default: the scene's].
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    #[arg(long, default_value_t = 0)]
    seed: u32,
    /// Format of headless frames: png (tone-mapped) or exr (linear).
    #[arg(long, value_enum, default_value = "png")]
    format: ImageFormat,
    /// Stop once the frame of this reload is written (0: the first state's).
    #[arg(long)]
    max_reloads: Option<u32>,
    /// Read shaders from this folder and reload them when they change.
    #[arg(long, value_name = "SHADERS_DIR", num_args = 0..=1, default_missing_value = "shaders")]
    dev: Option<PathBuf>,
    #[arg(long, value_enum, default_value_t)]
    quality: BuildQuality,
    /// Denoise with Open Image Denoise once the image has 4 samples per pixel, again each
    /// time they double: the window shows it (`N` toggles it); headless, each frame is
    /// written denoised and the raw one beside it as frame-NNNN-raw.
    #[arg(long, conflicts_with = "stream")]
    denoise: bool,
    /// Where Open Image Denoise runs: auto takes a CUDA GPU when it has one, else the CPU.
    #[arg(long, value_enum, default_value_t, requires = "denoise")]
    denoise_device: DenoiseDevice,
    /// Adaptive sampling's noise threshold (0: off) [default: the scene's].
    #[arg(long)]
    noise_threshold: Option<f32>,
}

#[derive(Subcommand)]
enum BenchCommand {
    /// Rays/s of camera and diffuse-bounce rays through the BVH alone, and paths/s of the integrator.
    Throughput {
        /// Scene file; the built-in Cornell box when omitted.
        scene: Option<PathBuf>,
        #[arg(long, value_parser = parse_size, default_value = "1024x720")]
        size: (u32, u32),
        /// Timed repetitions of each measurement (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: u32,
        /// Samples per pixel per integrator dispatch.
        #[arg(long, default_value_t = 4)]
        spp: u32,
        /// Lanes each pixel's samples are spread over [default: the renderer's choice].
        #[arg(long)]
        sample_lanes: Option<u32>,
    },
    /// How the top level scales: fields of N instances of a 9,800-triangle sphere, with
    /// the top level's build time, GPU memory per instance and rays/s through the field.
    Instances {
        /// Instance counts, comma-separated.
        #[arg(long, value_delimiter = ',', default_value = "1000,100000,1000000")]
        counts: Vec<usize>,
        #[arg(long, value_parser = parse_size, default_value = "1024x720")]
        size: (u32, u32),
        /// Timed repetitions of each measurement (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: u32,
        /// Samples per pixel per integrator dispatch.
        #[arg(long, default_value_t = 4)]
        spp: u32,
    },
    /// rt beside Mitsuba 3 (through its Python API, when importable) on the same scenes in
    /// one run, like for like: one translation, the same estimator settings and warm-up,
    /// both clocks, and the images compared before any ratio is printed.
    Compare {
        /// Scenes to compare at --size [default: the held-in set: the Cornell box at 9 and
        /// 65 path vertices, at 128x128 and 1024x1024, and the dragon in clay with trace rates].
        scenes: Vec<PathBuf>,
        #[arg(long, value_parser = parse_size, default_value = "1024x720")]
        size: (u32, u32),
        /// Samples per pixel of each render of the given scenes.
        #[arg(long, default_value_t = 16)]
        spp: u32,
        /// Timed renders of each case (the median is reported; the first two images of each
        /// renderer are compared).
        #[arg(long, default_value_t = 5)]
        runs: u32,
        /// Mitsuba's sampler: independent, stratified, multijitter, orthogonal, ldsampler.
        #[arg(long, default_value = "independent")]
        sampler: String,
        /// The Python that imports `mitsuba`.
        #[arg(long, env = "RT_MITSUBA_PYTHON", default_value = "python3")]
        python: String,
        /// Mitsuba variant [default: cuda_ad_rgb, else llvm_ad_rgb].
        #[arg(long)]
        variant: Option<String>,
    },
    /// Writes the Mitsuba 3 scene that `rt bench compare` renders for SCENE: OUT/scene.json
    /// (a dictionary for `mi.load_dict`, loaded by `src/bench/mitsuba_scene.py`) and its
    /// meshes as PLY files. The Mitsuba references of the tests are rendered from it.
    MitsubaScene {
        scene: PathBuf,
        /// The folder to write into (created if missing).
        #[arg(short, long)]
        out: PathBuf,
        /// Image size [default: the scene's].
        #[arg(long, value_parser = parse_size)]
        size: Option<(u32, u32)>,
    },
    /// Error and time of the atmosphere's march steps and table sizes, against
    /// far finer settings, on a scene whose sky is an atmosphere.
    Sky {
        scene: PathBuf,
        #[arg(long, value_parser = parse_size, default_value = "160x90")]
        size: (u32, u32),
        /// Samples per pixel of each render.
        #[arg(long, default_value_t = 4)]
        spp: u32,
    },
    /// `rt watch` latency: file written → first frame of the new state, for a camera move,
    /// a material change and a re-export of a mesh.
    WatchLatency {
        /// The asset folder to re-export (copied to a temporary folder first).
        #[arg(long, default_value = "assets/dragon")]
        asset: PathBuf,
        #[arg(long, value_parser = parse_size, default_value = "320x240")]
        size: (u32, u32),
        /// Edits of each kind (the median is reported).
        #[arg(long, default_value_t = 3)]
        runs: u32,
    },
    /// `rt watch --stream` latency: camera command written → first frame that shows it,
    /// read by a client on the pipes; and a frame's time through the pipe.
    StreamLatency {
        /// Scene file [default: watch-latency's scene around --asset].
        #[arg(long)]
        scene: Option<PathBuf>,
        #[arg(long, default_value = "assets/dragon")]
        asset: PathBuf,
        #[arg(long, value_parser = parse_size, default_value = "320x240")]
        size: (u32, u32),
        /// Camera commands (the median and the worst are reported).
        #[arg(long, default_value_t = 10)]
        runs: u32,
    },
    /// How long the first image of a scene takes, each step of a fresh process timed: cold
    /// (the driver's shader cache empty) and warm (filled by the cold run).
    FirstPixel {
        /// Scene file; the built-in Cornell box when omitted.
        scene: Option<PathBuf>,
        #[arg(long, value_parser = parse_size, default_value = "1024x720")]
        size: (u32, u32),
        /// Run as the measured process (the bench starts itself with this).
        #[arg(long, hide = true)]
        child: bool,
    },
    /// Milliseconds per frame of Open Image Denoise on each device it has (CUDA, CPU): a
    /// rendered frame with albedo and normal AOVs, denoised as `rt render --denoise` does.
    Denoise {
        /// Scene file of the frame; the built-in Cornell box when omitted.
        scene: Option<PathBuf>,
        #[arg(long, value_parser = parse_size, default_value = "1024x720")]
        size: (u32, u32),
        /// Timed runs per device after a first, untimed-in-the-median one.
        #[arg(long, default_value_t = 10)]
        runs: u32,
        /// Samples per pixel of the frame.
        #[arg(long, default_value_t = 4)]
        spp: u32,
    },
    /// Error against a converged reference beside the time it cost, for every knob
    /// that trades accuracy for time; writes report.md, CSV files and plots.
    Accuracy(AccuracyArgs),
    /// Time per sample of the pipeline specialised to the scene, of the all-features
    /// pipeline, and with each absent effect forced on.
    Effects {
        /// Scene file; the built-in Cornell box when omitted.
        scene: Option<PathBuf>,
        /// Image size [default: 160x120 on a CPU adapter, 320x240 on a GPU].
        #[arg(long, value_parser = parse_size)]
        size: Option<(u32, u32)>,
        /// Samples per pixel of each timed render.
        #[arg(long, default_value_t = 16)]
        spp: u32,
        /// Timed renders per pipeline (the median is reported).
        #[arg(long, default_value_t = 5)]
        repeats: u32,
    },
    /// Fireflies per sampling strategy: the share of energy in the brightest 0.01 % of
    /// samples and the noise of pixel means across seeds, also with a (biased) clamp.
    Fireflies(FireflyArgs),
    /// The headline tables for the bundled scenes: fastest setting to 1 % RMSE, speed-up
    /// of the specialised pipeline, fireflies. Run from the repository root.
    Headline {
        /// Folder of the reports (one per scene) and of headline.md.
        #[arg(long, default_value = "out/bench")]
        out: PathBuf,
        /// Image size [default: 160x120 on a CPU adapter, 320x240 on a GPU].
        #[arg(long, value_parser = parse_size)]
        size: Option<(u32, u32)>,
        /// Samples-per-pixel levels of the accuracy sweeps [default: by adapter].
        #[arg(long, value_delimiter = ',')]
        spp: Option<Vec<u32>>,
        /// Samples per pixel of the references [default: by adapter].
        #[arg(long)]
        reference_spp: Option<u32>,
        /// Rewrite the headline section of docs/benchmarks.md with the tables.
        #[arg(long, alias = "readme")]
        docs: bool,
    },
}

#[derive(Args)]
struct AccuracyArgs {
    /// Scene file; the built-in Cornell box when omitted.
    scene: Option<PathBuf>,
    /// Knob to sweep (repeatable) [default: all]: spp, max-bounces, sampling,
    /// light-sampler, ris-candidates, rough-glass, bvh-quality, samples-per-dispatch,
    /// denoise, adaptive, clean-image.
    #[arg(long = "knob")]
    knobs: Vec<String>,
    /// Folder of the report [default: out/bench/SCENE].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Folder of cached references [default: OUT/reference].
    #[arg(long)]
    cache: Option<PathBuf>,
    /// Image size [default: 160x120 on a CPU adapter, 320x240 on a GPU].
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Samples-per-pixel levels, at least three [default: 1,4,16 on a CPU adapter, 16,64,256,1024 on a GPU].
    #[arg(long, value_delimiter = ',')]
    spp: Option<Vec<u32>>,
    /// Timed renders per level, each with its own seed [default: 2 on a CPU adapter, 3 on a GPU].
    #[arg(long)]
    repeats: Option<u32>,
    /// Samples per pixel of the reference [default: 256 on a CPU adapter, 16384 on a GPU].
    #[arg(long)]
    reference_spp: Option<u32>,
    /// Error to reach, as a relative RMSE in percent of the reference's mean radiance.
    #[arg(long, default_value_t = 1.0)]
    target_percent: f64,
    /// SSIM to reach, the perceptual view (of the display transform's luma; 1: the reference).
    #[arg(long, default_value_t = 0.99)]
    target_ssim: f64,
    /// Time budget of the equal-time view [default: the scene defaults at the highest level].
    #[arg(long)]
    budget_ms: Option<f64>,
}

#[derive(Args)]
struct FireflyArgs {
    /// Scene file; the built-in Cornell box when omitted (try scenes/specular_pillars.toml).
    scene: Option<PathBuf>,
    /// Image size [default: 160x120 on a CPU adapter, 320x240 on a GPU].
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Samples per pixel of each seed's image.
    #[arg(long, default_value_t = 16)]
    samples: u32,
    /// Independent images per strategy.
    #[arg(long, default_value_t = 8)]
    seeds: u32,
    /// Clamp luminance of the clamped rows [default: ten times the NEE image's mean].
    #[arg(long)]
    clamp: Option<f32>,
    /// Also write the table to this Markdown file.
    #[arg(long)]
    out: Option<PathBuf>,
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or("expected WIDTHxHEIGHT, e.g. 640x480")?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|&n| (1..=MAX_IMAGE_SIDE).contains(&n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("width and height must be whole numbers from 1 to {MAX_IMAGE_SIDE}")),
    }
}

fn load_scene(path: Option<&Path>) -> Result<Scene> {
    Ok(match path {
        Some(p) => scene::load(p)?,
        None => scene::default_scene()?,
    })
}

/// `--strict` found dropped samples or rays: a finished render, but not a clean one.
#[derive(Debug, thiserror::Error)]
#[error("--strict: the render dropped samples or rays ({0})")]
struct StrictFinding(DroppedSamples);

fn render(args: RenderArgs, adapter: Option<&str>) -> Result<()> {
    check_output(&args.output)?;
    check_sample_range(&args)?;
    let json = args.progress == Progress::Json;
    // With JSON progress, stderr holds JSON lines only.
    let say = |line: String| {
        if !json {
            eprintln!("{line}");
        }
    };
    if args.aovs && image_format(&args.output)? != ImageFormat::Exr {
        bail!("--aovs: AOVs are written as one multi-layer OpenEXR; give -o an .exr path");
    }
    if let Some(snapshot) = &args.snapshot
        && image_format(snapshot)? != ImageFormat::Exr
    {
        bail!("--snapshot: snapshots are linear OpenEXR images; give an .exr path");
    }
    // Before any rendering: a missing denoiser is known at once.
    let mut denoiser = match args.denoise {
        true => Some(Denoiser::new(args.denoise_device).context("--denoise")?),
        false => None,
    };
    if let Some(denoiser) = &denoiser {
        say(format!("denoising with Open Image Denoise on {}", denoiser.describe()));
    }
    let frames = match args.frames.clone() {
        Some(frames) => frames.map(|f| args.at_frame(f)).collect::<Result<Vec<_>>>()?,
        None => vec![args],
    };
    // With --frames, every frame's scene is there before the first is rendered (what else
    // is wrong with one is said when it is read).
    for frame in frames.iter().skip(1) {
        if let Some(scene) = &frame.scene
            && std::fs::metadata(scene).is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound)
        {
            bail!("{}: no such scene file (a frame of --frames)", scene.display());
        }
    }
    // The first scene is read and the flags checked before the GPU starts: a mistake is said at once.
    let mut first = Some(scene_and_request(&frames[0])?);
    let ctx = GpuContext::new(adapter)?;
    say(format!("GPU: {}", ctx.describe()));
    let mut pipelines = None;
    for frame in &frames {
        let scene_request = match first.take() {
            Some(first) => first,
            None => scene_and_request(frame)?,
        };
        pipelines = Some(render_frame(frame, &ctx, scene_request, denoiser.as_mut(), pipelines.take(), &say)?);
    }
    Ok(())
}

/// The scene `args` names, with the flags written into it, and the request they make.
fn scene_and_request(args: &RenderArgs) -> Result<(Scene, RenderRequest)> {
    let mut scene = load_scene(args.scene.as_deref())?;
    let request = RenderRequest {
        progress: args.progress,
        exact_sums: true,
        first_sample: args.sample_range.as_ref().map_or(0, |r| r.start),
        ..args.flags().apply(&mut scene)?
    };
    Ok((scene, request))
}

/// One image of `rt render` (a frame of `--frames`), with the pipelines built so far;
/// returns them, for the next frame.
fn render_frame(
    args: &RenderArgs,
    ctx: &GpuContext,
    (scene, request): (Scene, RenderRequest),
    denoiser: Option<&mut Denoiser>,
    pipelines: Option<PipelineCache>,
    say: &dyn Fn(String),
) -> Result<PipelineCache> {
    let json = args.progress == Progress::Json;
    let exposure = scene.render.exposure;
    let origin = scene.origin.clone();
    let geometry = SceneGeometry::build(&scene, args.quality)?;
    let pipelines = pipelines.unwrap_or_else(|| PipelineCache::new(ctx));
    let mut session = Session::with_pipelines(ctx, scene, geometry, pipelines)?;
    say(format!("{origin}: features [{}]", session.features()));
    if args.sample_range.is_some() {
        check_part_request(&session, &request)?;
    }
    if let Some(tables) = session.atmosphere() {
        say(format!("atmosphere tables built in {:.1} ms", tables.build_time.as_secs_f64() * 1e3));
    }
    let time_limit = args.time_limit.map(std::time::Duration::from_secs_f64);
    let mut snapshots = Snapshots::new(args.snapshot.as_deref(), args.snapshot_every, json);
    let (image, report) = session.render_with(&request, None, time_limit, |s| snapshots.after_step(s))?;
    if let Some(samples) = args.sample_range.clone() {
        let part = PartRequest { path: &args.output, samples, exposure, aov_layers: args.aovs };
        rt::render::part::save(&session, &part)?;
        say(format!("wrote {} (samples {:?} of each pixel)", args.output.display(), part.samples));
        return Ok(session.into_pipelines());
    }
    write_outputs(args, &session, &image, denoiser, exposure, say)?;
    say(format!(
        "wrote {} ({}x{}, {} spp) in {:.2} s: {}samples/s",
        args.output.display(),
        request.width,
        request.height,
        report.samples_per_pixel,
        report.elapsed.as_secs_f64(),
        human(report.samples_per_second)
    ));
    report_end(args, &report)?;
    Ok(session.into_pipelines())
}

/// What a finished render says last: its dropped samples (an error with `--strict`), and
/// with JSON progress the `done` event.
fn report_end(args: &RenderArgs, report: &RenderReport) -> Result<()> {
    let json = args.progress == Progress::Json;
    if !report.dropped.is_clean() {
        match json {
            true => {
                eprintln!("{}", json_event("warning", serde_json::json!({ "message": report.dropped.to_string() })))
            }
            false => eprintln!("warning: {}", report.dropped),
        }
        if args.strict {
            return Err(StrictFinding(report.dropped.clone()).into());
        }
    }
    if json {
        let fields = serde_json::json!({
            "file": args.output,
            "seconds": report.elapsed.as_secs_f64(),
            "spp": report.samples_per_pixel,
        });
        eprintln!("{}", json_event("done", fields));
    }
    Ok(())
}

/// Writes what `rt render` was asked for: the image, denoised or not, with or without its
/// AOV layers, and the AOV files.
fn write_outputs(
    args: &RenderArgs,
    session: &Session,
    image: &Image,
    denoiser: Option<&mut Denoiser>,
    exposure: f32,
    say: &dyn Fn(String),
) -> Result<()> {
    let aovs = if session.request().aovs { Some(session.aovs()?) } else { None };
    let denoised = match (denoiser, &aovs) {
        (Some(denoiser), Some(aovs)) => {
            let start = std::time::Instant::now();
            let clean = denoiser.denoise(image, aovs)?;
            let took = start.elapsed().as_secs_f64();
            say(format!("denoised with Open Image Denoise ({} device) in {took:.2} s", denoiser.device()));
            Some(clean)
        }
        _ => None,
    };
    if let (Some(dir), Some(aovs)) = (&args.aov_files, &aovs) {
        write_aov_files(dir, image, aovs)?;
    }
    match (&aovs, denoised) {
        (Some(aovs), denoised) if args.aovs => {
            let channels = aov_channels(image, aovs, denoised.as_deref());
            write_layered_exr(&args.output, image.width, image.height, channels)
        }
        (_, Some(clean)) => write_image(&Image { pixels: clean, ..image.clone() }, &args.output, exposure),
        _ => write_image(image, &args.output, exposure),
    }
}

/// Refuses a part the session cannot make: one under adaptive sampling, or one whose exact
/// sums do not fit the GPU.
fn check_part_request(session: &Session, request: &RenderRequest) -> Result<()> {
    if request.adaptive() {
        bail!(
            "--sample-range: adaptive sampling stops pixels by all the samples before, so it cannot be split; \
             add --noise-threshold 0"
        );
    }
    let aovs = request.aovs || session.features().has_alpha();
    rt::render::check_exact_sums(session.ctx(), request.width, request.height, aovs).context("--sample-range")
}

/// Refuses what a part of a render cannot hold: it is the samples' sums, finished by `rt merge`.
fn check_sample_range(args: &RenderArgs) -> Result<()> {
    let Some(range) = &args.sample_range else { return Ok(()) };
    let refused = [
        (args.spp.is_some(), "--spp (the range says which samples)"),
        (args.denoise, "--denoise (denoise the merged image)"),
        (args.time_limit.is_some(), "--time-limit (a part holds all of its samples)"),
        (args.snapshot.is_some(), "--snapshot"),
        (args.aov_files.is_some(), "--aov-files"),
    ];
    if let Some((_, what)) = refused.iter().find(|(given, _)| *given) {
        bail!("--sample-range {}..{}: a part cannot take {what}", range.start, range.end);
    }
    if image_format(&args.output)? != ImageFormat::Exr {
        bail!("--sample-range: a part is an OpenEXR that `rt merge` reads; give -o an .exr path");
    }
    Ok(())
}

/// `rt merge`: the parts' sums added, written as `rt render` writes its image.
fn merge(parts: &[PathBuf], output: &Path) -> Result<()> {
    check_output(output)?;
    let merged = rt::render::part::merge(parts)?;
    for warning in &merged.warnings {
        log::warn!("{warning}");
    }
    let (image, aovs) = merged.image();
    let header = &merged.header;
    match aovs {
        Some(aovs) if header.aov_layers => {
            write_layered_exr(output, image.width, image.height, aov_channels(&image, &aovs, None))?
        }
        _ => write_image(&image, output, header.exposure)?,
    }
    let parts = match parts.len() {
        1 => "1 part".to_string(),
        n => format!("{n} parts"),
    };
    eprintln!("wrote {} ({}x{}, {} spp from {parts})", output.display(), image.width, image.height, merged.spp);
    Ok(())
}

/// `--aov-files DIR`: each AOV as a plain OpenEXR of its own.
fn write_aov_files(dir: &Path, image: &Image, aovs: &rt::render::Aovs) -> Result<()> {
    rt::files::check_folder(dir).context("--aov-files")?;
    let grey = |values: Vec<f32>| values.into_iter().map(|v| [v; 3]).collect::<Vec<_>>();
    let files = [
        ("albedo", aovs.albedo.clone()),
        ("normal", aovs.normal.clone()),
        ("depth", grey(aovs.depth.clone())),
        ("position", aovs.position.clone()),
        ("emission", aovs.emission.clone()),
        ("diffuse_color", aovs.diffuse_color.clone()),
        ("error", grey(image.std_error.clone())),
        ("samples", grey(image.sample_counts.iter().map(|&n| n as f32).collect())),
    ];
    for (name, pixels) in files {
        write_image(&Image { pixels, alpha: None, ..image.clone() }, &dir.join(format!("{name}.exr")), 0.0)?;
    }
    Ok(())
}

/// `--snapshot`: the image so far, written every so often while rendering.
struct Snapshots<'a> {
    path: Option<&'a Path>,
    every: std::time::Duration,
    json: bool,
    last: std::time::Instant,
}

impl<'a> Snapshots<'a> {
    fn new(path: Option<&'a Path>, every: f64, json: bool) -> Self {
        let every = std::time::Duration::from_secs_f64(every);
        Self { path, every, json, last: std::time::Instant::now() }
    }

    fn after_step(&mut self, session: &Session) -> Result<()> {
        let Some(path) = self.path.filter(|_| self.last.elapsed() >= self.every && !session.converged()) else {
            return Ok(());
        };
        let image = session.image()?;
        write_image(&image, path, 0.0)?;
        if self.json {
            let fields = serde_json::json!({ "file": path, "spp": image.samples });
            eprintln!("{}", json_event("snapshot", fields));
        }
        self.last = std::time::Instant::now();
        Ok(())
    }
}

fn watch(args: WatchArgs, adapter: Option<&str>) -> Result<()> {
    // Before any GPU or window: a missing denoiser is known at once, as with `rt render`.
    let denoiser = match args.denoise {
        true => Some(Denoiser::new(args.denoise_device).context("--denoise")?),
        false => None,
    };
    let options = rt::watch::WatchOptions {
        scene: args.scene,
        quality: args.quality,
        shader_dir: args.dev,
        frames_dir: args.frames_dir,
        flags: RenderFlags {
            spp: args.spp,
            size: args.size,
            seed: args.seed,
            noise_threshold: args.noise_threshold,
            aovs: args.denoise,
            ..Default::default()
        },
        format: args.format,
        max_reloads: args.max_reloads,
    };
    if args.stream {
        let ctx = GpuContext::new(adapter)?;
        eprintln!("GPU: {}", ctx.describe());
        rt::watch::stream::run(&ctx, &options, args.socket.as_deref())
    } else if args.headless {
        let ctx = GpuContext::new(adapter)?;
        eprintln!("GPU: {}", ctx.describe());
        rt::watch::run_headless(&ctx, &options, None, denoiser)
    } else {
        rt::watch::run_window(adapter, options, denoiser)
    }
}

fn bench_accuracy(args: AccuracyArgs, adapter: Option<&str>) -> Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let stem = args.scene.as_deref().and_then(Path::file_stem).map_or("cornell_box".into(), |s| s.to_string_lossy());
    let options = rt::bench::AccuracyOptions {
        knobs: args.knobs,
        out: args.out.unwrap_or_else(|| Path::new("out/bench").join(&*stem)),
        cache: args.cache,
        size: args.size,
        levels: args.spp,
        repeats: args.repeats,
        reference_spp: args.reference_spp,
        reference_bounces: None,
        target: Some(args.target_percent / 100.0),
        target_ssim: Some(args.target_ssim),
        budget_seconds: args.budget_ms.map(|ms| ms / 1e3),
        progress: true,
    };
    rt::bench::commands::accuracy(&scene, &options, adapter)
}

fn pack(paths: &[PathBuf], quality: BuildQuality, force: bool) -> Result<()> {
    let assets = rt::bvh::pack::find_assets(paths)?;
    if assets.is_empty() {
        bail!("no assets (asset folders, .rtmesh, .gltf, .glb or .obj files) under the given paths");
    }
    let bar = rt::bvh::pack::asset_bar(assets.len(), "packing");
    let results = rt::bvh::pack::parallel_map(&assets, &bar, |a| rt::bvh::pack::pack(a, quality, force));
    bar.finish_and_clear();
    let mut failures = 0;
    for result in results {
        match result {
            Ok(PackReport { asset, outcome: PackOutcome::UpToDate, .. }) => println!("{}: up to date", asset.display()),
            Ok(PackReport { asset, cache, outcome: PackOutcome::Packed { reason, triangles, time } }) => println!(
                "{}: packed {triangles} triangles in {:.1?} into {} ({reason})",
                asset.display(),
                time,
                cache.display()
            ),
            Err(e) => {
                eprintln!("error: {e}");
                failures += 1;
            }
        }
    }
    if failures > 0 {
        bail!("{failures} of {} assets failed to pack", assets.len());
    }
    Ok(())
}

/// Runs one of `rt bench`'s measurements.
fn bench(command: BenchCommand, adapter: Option<&str>) -> Result<()> {
    match command {
        BenchCommand::Throughput { scene, size, runs, spp, sample_lanes } => {
            let options = rt::bench::ThroughputOptions { size, runs, spp, lanes: sample_lanes, rays: true };
            load_scene(scene.as_deref()).and_then(|s| rt::bench::throughput(s, &options, adapter))
        }
        BenchCommand::Instances { counts, size, runs, spp } => {
            rt::bench::instances(&rt::bench::InstanceScaleOptions { counts, size, runs, spp }, adapter)
        }
        BenchCommand::Compare { scenes, size, spp, runs, sampler, python, variant } => {
            let root = PathBuf::new();
            let options = rt::bench::CompareOptions { scenes, size, spp, runs, python, variant, sampler, root };
            rt::bench::compare(&options, adapter)
        }
        BenchCommand::MitsubaScene { scene, out, size } => {
            load_scene(Some(&scene)).and_then(|s| rt::bench::mitsuba_scene::write(&s, size, &out))
        }
        BenchCommand::Sky { scene, size, spp } => {
            load_scene(Some(&scene)).and_then(|s| rt::bench::sky(s, size, spp, adapter))
        }
        BenchCommand::WatchLatency { asset, size, runs } => {
            rt::watch::latency::watch_latency(&asset, size, runs, adapter)
        }
        BenchCommand::StreamLatency { scene, asset, size, runs } => {
            rt::watch::stream::latency::stream_latency(scene.as_deref(), &asset, size, runs, adapter)
        }
        BenchCommand::FirstPixel { scene, size, child: true } => {
            load_scene(scene.as_deref()).and_then(|s| rt::bench::first_pixel::child(s, size, adapter))
        }
        BenchCommand::FirstPixel { scene, size, child: false } => {
            rt::bench::first_pixel::first_pixel(scene.as_deref(), size, adapter)
        }
        BenchCommand::Denoise { scene, size, runs, spp } => {
            let options = rt::bench::DenoiseBenchOptions { size, runs, spp };
            load_scene(scene.as_deref()).and_then(|s| rt::bench::denoise_bench(s, &options, adapter).map(|_| ()))
        }
        BenchCommand::Accuracy(args) => bench_accuracy(args, adapter),
        BenchCommand::Effects { scene, size, spp, repeats } => {
            load_scene(scene.as_deref()).and_then(|s| rt::bench::commands::effects(s, size, spp, repeats, adapter))
        }
        BenchCommand::Fireflies(a) => load_scene(a.scene.as_deref()).and_then(|s| {
            let options =
                rt::bench::FireflyOptions { size: (0, 0), samples: a.samples, seeds: a.seeds, clamp: a.clamp };
            rt::bench::commands::fireflies(&s, options, a.size, a.out.as_deref(), adapter)
        }),
        BenchCommand::Headline { out, size, spp, reference_spp, docs } => {
            let accuracy = rt::bench::AccuracyOptions { out, size, levels: spp, reference_spp, ..Default::default() };
            rt::bench::commands::headline(accuracy, docs.then(|| PathBuf::from("docs/benchmarks.md")), adapter)
        }
    }
}

/// Logs through env_logger (warnings by default); with `--progress json`, as JSON events.
fn init_logging(json: bool) {
    let mut logger = env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"));
    if json {
        logger.format(|out, record| {
            use std::io::Write;
            writeln!(out, "{}", json_event("warning", serde_json::json!({ "message": record.args().to_string() })))
        });
    }
    logger.init();
}

fn main() -> ExitCode {
    rt::gpu::ensure_runtime_dir();
    let cli = Cli::parse();
    let json = matches!(&cli.command, Command::Render(args) if args.progress == Progress::Json);
    init_logging(json);
    let adapter = cli.adapter.as_deref();
    let result = match cli.command {
        Command::Pack { paths, quality, force } => pack(&paths, quality, force),
        Command::Render(args) => render(args, adapter),
        Command::Merge { parts, output } => merge(&parts, &output),
        Command::Watch(args) => watch(args, adapter),
        Command::Info { scene, quality, inputs: true } => rt::info::print_inputs(scene.as_deref(), quality),
        Command::Info { scene, quality, inputs: false } => {
            load_scene(scene.as_deref()).and_then(|s| rt::info::print_info(s, quality, adapter))
        }
        Command::Doctor => {
            rt::doctor::findings(VERSION, adapter).iter().for_each(|f| println!("{f}"));
            Ok(())
        }
        Command::Bench(command) => bench(command, adapter),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            match json {
                true => eprintln!("{}", json_event("error", serde_json::json!({ "message": format!("{e:#}") }))),
                false => eprintln!("error: {e:#}"),
            }
            if e.is::<StrictFinding>() { ExitCode::from(EXIT_STRICT) } else { ExitCode::FAILURE }
        }
    }
}
