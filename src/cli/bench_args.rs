//! `rt bench`'s measurements and their options.

use super::args::parse_size;
use clap::{Args, Subcommand};
use std::path::PathBuf;

#[derive(Subcommand)]
pub(crate) enum BenchCommand {
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
    /// (a dictionary for `mi.load_dict`, loaded by `crates/rt-bench/src/mitsuba_scene.py`) and its
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
pub(crate) struct AccuracyArgs {
    /// Scene file; the built-in Cornell box when omitted.
    pub(crate) scene: Option<PathBuf>,
    /// Knob to sweep (repeatable) [default: all]: spp, max-bounces, sampling,
    /// light-sampler, ris-candidates, rough-glass, bvh-quality, samples-per-dispatch,
    /// denoise, adaptive, clean-image.
    #[arg(long = "knob")]
    pub(crate) knobs: Vec<String>,
    /// Folder of the report [default: out/bench/SCENE].
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
    /// Folder of cached references [default: OUT/reference].
    #[arg(long)]
    pub(crate) cache: Option<PathBuf>,
    /// Image size [default: 160x120 on a CPU adapter, 320x240 on a GPU].
    #[arg(long, value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// Samples-per-pixel levels, at least three [default: 1,4,16 on a CPU adapter, 16,64,256,1024 on a GPU].
    #[arg(long, value_delimiter = ',')]
    pub(crate) spp: Option<Vec<u32>>,
    /// Timed renders per level, each with its own seed [default: 2 on a CPU adapter, 3 on a GPU].
    #[arg(long)]
    pub(crate) repeats: Option<u32>,
    /// Samples per pixel of the reference [default: 256 on a CPU adapter, 16384 on a GPU].
    #[arg(long)]
    pub(crate) reference_spp: Option<u32>,
    /// Error to reach, as a relative RMSE in percent of the reference's mean radiance.
    #[arg(long, default_value_t = 1.0)]
    pub(crate) target_percent: f64,
    /// SSIM to reach, the perceptual view (of the display transform's luma; 1: the reference).
    #[arg(long, default_value_t = 0.99)]
    pub(crate) target_ssim: f64,
    /// Time budget of the equal-time view [default: the scene defaults at the highest level].
    #[arg(long)]
    pub(crate) budget_ms: Option<f64>,
}

#[derive(Args)]
pub(crate) struct FireflyArgs {
    /// Scene file; the built-in Cornell box when omitted (try scenes/specular_pillars.toml).
    pub(crate) scene: Option<PathBuf>,
    /// Image size [default: 160x120 on a CPU adapter, 320x240 on a GPU].
    #[arg(long, value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// Samples per pixel of each seed's image.
    #[arg(long, default_value_t = 16)]
    pub(crate) samples: u32,
    /// Independent images per strategy.
    #[arg(long, default_value_t = 8)]
    pub(crate) seeds: u32,
    /// Clamp luminance of the clamped rows [default: ten times the NEE image's mean].
    #[arg(long)]
    pub(crate) clamp: Option<f32>,
    /// Also write the table to this Markdown file.
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
}
