//! `rt watch --headless`: no window; each state of the scene (the first, then one per
//! reload) is refined to the target spp and written to the frames folder as
//! `frame-NNNN.png` (or `.exr`), NNNN being the reload's number. For tests, CI and
//! measuring latency. It stops when `DIR/stop` appears, or after `--max-reloads`.
//! With `--denoise`, the frame is the denoise of the converged image, and the raw image
//! is written beside it as `frame-NNNN-raw.png` (or `.exr`).

use super::fs_watch::{Batch, FileWatcher};
use super::headless_denoise::HeadlessDenoise;
use super::live::LiveScene;
use super::reload_log::ReloadLog;
use anyhow::Result;
use rt::denoise::Denoiser;
use rt::render::{Image, ImageFormat, Pacing, Session, write_image};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender};
use std::time::{Duration, Instant};

/// The file whose appearance in the frames folder stops `rt watch --headless`.
pub const STOP_FILE: &str = "stop";

/// How often an idle headless watcher looks for the stop file.
const STOP_POLL: Duration = Duration::from_millis(50);

/// Headless frames take as long as they need: no window waits for them.
const PACING: Pacing = Pacing { target: Duration::from_millis(100), max_samples: 64 };

pub struct HeadlessOptions {
    pub frames_dir: PathBuf,
    pub format: ImageFormat,
    /// Stop once the frame of this reload is written (0: the first state's).
    pub max_reloads: Option<u32>,
    /// Told (reload number, when) as each state's first frame is done: for latency benchmarks.
    pub first_frames: Option<Sender<(u32, Instant)>>,
    /// With `--denoise`.
    pub denoiser: Option<Denoiser>,
}

/// The state being refined: which reload made it, and when its edit was seen.
struct State {
    number: u32,
    since: Instant,
    first_frame: Option<Duration>,
    written: bool,
}

pub fn run(
    live: &mut LiveScene,
    watcher: &mut FileWatcher,
    batches: &Receiver<Batch>,
    mut options: HeadlessOptions,
    log: &mut ReloadLog,
    opened_at: Instant,
) -> Result<()> {
    live.session.set_pacing(PACING);
    let mut denoise = options.denoiser.take().map(HeadlessDenoise::new);
    let mut state = State { number: 0, since: opened_at, first_frame: None, written: false };
    let stop_file = options.frames_dir.join(STOP_FILE);
    let mut pending: Option<Batch> = None;
    loop {
        while let Ok(batch) = batches.try_recv() {
            merge(&mut pending, batch);
        }
        if let Some(batch) = pending.take() {
            match live.reload(&batch.paths) {
                Ok(report) => {
                    log.reload(&report, &batch.paths);
                    state =
                        State { number: report.number, since: batch.first_event, first_frame: None, written: false };
                }
                Err(e) => log.error(&batch.paths, &e),
            }
            // The files may have moved: a new asset, a folder that came back.
            watcher.watch(&live.watched_files());
            continue;
        }
        if stop_file.exists() {
            // Consumed, so that the next run in this folder does not stop at once.
            let _ = std::fs::remove_file(&stop_file);
            log.write("stop: the stop file appeared");
            return Ok(());
        }
        live.session.step(None)?;
        if state.first_frame.is_none() {
            let now = Instant::now();
            state.first_frame = Some(now - state.since);
            if let Some(tx) = &options.first_frames {
                let _ = tx.send((state.number, now));
            }
        }
        let session = &live.session;
        if let Some(denoise) = &mut denoise {
            denoise.refine(session, state.number, log)?;
        }
        if session.converged() && !state.written {
            write_frame(session, &state, &options, denoise.as_mut(), log)?;
            state.written = true;
            if options.max_reloads.is_some_and(|max| state.number >= max) {
                return Ok(());
            }
        }
        if live.session.converged() {
            match batches.recv_timeout(STOP_POLL) {
                Ok(batch) => merge(&mut pending, batch),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => return Ok(()),
            }
        }
    }
}

/// Writes the converged frame (and, denoised, its raw image beside it) and logs it.
fn write_frame(
    session: &Session,
    state: &State,
    options: &HeadlessOptions,
    denoise: Option<&mut HeadlessDenoise>,
    log: &mut ReloadLog,
) -> Result<()> {
    let name = |suffix: &str| format!("frame-{:04}{suffix}.{}", state.number, options.format.extension());
    let file = options.frames_dir.join(name(""));
    let raw = session.image()?;
    let raw_file = match denoise {
        Some(denoise) => {
            let clean = denoise.converged(session, state.number, log)?;
            write(session, &Image { pixels: clean, ..raw.clone() }, &file)?;
            let raw_file = options.frames_dir.join(name("-raw"));
            write(session, &raw, &raw_file)?;
            Some(raw_file)
        }
        None => {
            write(session, &raw, &file)?;
            None
        }
    };
    let first_frame = state.first_frame.unwrap_or_default();
    log.frame(state.number, session.samples(), &file, raw_file.as_deref(), first_frame, state.since.elapsed());
    Ok(())
}

fn write(session: &Session, image: &Image, file: &Path) -> Result<()> {
    write_image(image, file, session.scene().render.exposure)
}

/// A stop file left from an earlier run (one that was killed before it saw it) must
/// not stop this one.
pub fn remove_stale_stop_file(frames_dir: &Path, log: &mut ReloadLog) {
    let stop_file = frames_dir.join(STOP_FILE);
    if stop_file.exists() && std::fs::remove_file(&stop_file).is_ok() {
        log.write("removed a stale stop file left by an earlier run");
    }
}

fn merge(pending: &mut Option<Batch>, batch: Batch) {
    match pending {
        Some(p) => p.merge(batch),
        None => *pending = Some(batch),
    }
}
