//! `rt watch`: the scene kept live while the artist edits it. Files are watched
//! (`fs_watch`), each batch of changes is planned into the least work (`plan`) and
//! applied to the scene on the GPU (`live`), which is refined frame by frame
//! in a window (`viewer`) or headless, writing frames (`headless`), or for a client that
//! drives it with commands and receives its frames (`stream`: Blender's viewport).

mod camera_control;
pub mod denoise_schedule;
pub mod denoise_worker;
mod denoised_view;
mod display;
pub mod fs_watch;
pub mod headless;
mod headless_denoise;
mod input;
pub mod latency;
pub mod live;
pub mod plan;
pub mod reload_log;
mod sources;
pub mod stream;
mod viewer;
mod viewer_controls;

pub use headless::{HeadlessOptions, STOP_FILE};
pub use live::LiveScene;
pub use reload_log::LOG_FILE;

use anyhow::{Context, Result};
use fs_watch::{Batch, FileWatcher};
use reload_log::ReloadLog;
use rt::bvh::BuildQuality;
use rt::denoise::Denoiser;
use rt::gpu::GpuContext;
use rt::render::{ImageFormat, RenderFlags};
use std::path::PathBuf;
use std::time::Instant;

pub struct WatchOptions {
    pub scene: PathBuf,
    pub quality: BuildQuality,
    /// Read `shaders/*.wgsl` from this folder, and reload them when they change.
    pub shader_dir: Option<PathBuf>,
    /// Where frames, screenshots and `watch.log` go; required headless.
    pub frames_dir: Option<PathBuf>,
    /// The command line's settings on top of the scene's `[render]` (spp, size, seed …).
    pub flags: RenderFlags,
    pub format: ImageFormat,
    pub max_reloads: Option<u32>,
}

/// `rt watch --headless`; with `denoiser`, each frame is written denoised, the raw one beside it.
pub fn run_headless(
    ctx: &GpuContext,
    options: &WatchOptions,
    first_frames: Option<std::sync::mpsc::Sender<(u32, Instant)>>,
    denoiser: Option<Denoiser>,
) -> Result<()> {
    let frames_dir = options.frames_dir.clone().context("--headless needs --frames-dir")?;
    let mut log = ReloadLog::new(Some(&frames_dir))?;
    headless::remove_stale_stop_file(&frames_dir, &mut log);
    let opened_at = Instant::now();
    let mut live = LiveScene::open(ctx, options)?;
    let (tx, rx) = std::sync::mpsc::channel::<Batch>();
    let mut watcher = FileWatcher::start(move |batch| {
        let _ = tx.send(batch);
    })?;
    watcher.watch(&live.watched_files());
    log.write(&format!("watching {} ({} files)", options.scene.display(), live.watched_files().len()));
    if let Some(denoiser) = &denoiser {
        log.write(&format!("denoising with Open Image Denoise on {}", denoiser.describe()));
    }
    let headless = HeadlessOptions {
        frames_dir,
        format: options.format,
        max_reloads: options.max_reloads,
        first_frames,
        denoiser,
    };
    headless::run(&mut live, &mut watcher, &rx, headless, &mut log, opened_at)
}

/// `rt watch`: a window; with `denoiser`, the denoised image is shown.
pub fn run_window(adapter: Option<&str>, options: WatchOptions, denoiser: Option<Denoiser>) -> Result<()> {
    viewer::run(adapter, options, denoiser)
}
