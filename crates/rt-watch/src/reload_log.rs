//! One machine-readable line per reload, error and finished frame, on standard output
//! and, with `--frames-dir`, appended to `DIR/watch.log`:
//!
//! ```text
//! reload #3 kind=materials cause=scene.toml ms=12.3
//! reload #4 kind=materials cause=scene.toml ms=40.1 features=[triangles glass sky=uniform sampling=nee]
//! error cause=scene.toml message="scene.toml:4:9: expected `]`"
//! frame #3 spp=16 file=frame-0003.png first_frame_ms=35.0 converged_ms=180.2
//! denoise #4 spp=8 ms=21.4 refined_to=12
//! frame #4 spp=16 file=frame-0004.png raw=frame-0004-raw.png first_frame_ms=34.1 converged_ms=210.9
//! ```
//!
//! `features=` appears when the reload switched to another specialised pipeline; `denoise`
//! lines and `raw=` with `--denoise`.

use super::live::ReloadReport;
use super::sources::names;
use anyhow::{Context, Result};
use rt::gpu::ms;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The log file's name inside the frames folder.
pub const LOG_FILE: &str = "watch.log";

pub struct ReloadLog {
    file: Option<File>,
}

impl ReloadLog {
    /// Logs to standard output, and to `dir/watch.log` when given (the folder is created
    /// if missing); the previous run's log is kept as `watch.log.1`.
    pub fn new(dir: Option<&Path>) -> Result<Self> {
        let file = match dir {
            Some(dir) => {
                rt::files::check_folder(dir).context("--frames-dir")?;
                let path = dir.join(LOG_FILE);
                // A FIFO or device there would block the open or take the log: not rt's.
                rt::files::output::refuse_special(&path)?;
                if path.exists() {
                    let previous = dir.join(format!("{LOG_FILE}.1"));
                    std::fs::rename(&path, &previous)
                        .with_context(|| format!("cannot keep the last log as {}", previous.display()))?;
                }
                Some(File::create(&path).with_context(|| format!("cannot create {}", path.display()))?)
            }
            None => None,
        };
        Ok(Self { file })
    }

    pub fn reload(&mut self, report: &ReloadReport, cause: &[PathBuf]) {
        let mut line = format!(
            "reload #{} kind={} cause={} ms={:.1}",
            report.number,
            report.reload.kind(),
            names(cause),
            ms(report.elapsed)
        );
        if let Some(features) = report.new_features {
            line.push_str(&format!(" features=[{features}]"));
        }
        self.write(&line);
    }

    pub fn error(&mut self, cause: &[PathBuf], error: &anyhow::Error) {
        let message = format!("{error:#}").replace(['\n', '"'], " ");
        log::error!("{message}");
        self.write(&format!("error cause={} message=\"{message}\"", names(cause)));
    }

    /// A state reached its target: `first_frame` after the edit its first frame was done,
    /// `converged` after it the image was written (with `raw`, the raw one beside it).
    pub fn frame(
        &mut self,
        number: u32,
        spp: u32,
        file: &Path,
        raw: Option<&Path>,
        first_frame: Duration,
        converged: Duration,
    ) {
        let name = |file: &Path| file.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let raw = raw.map(|raw| format!(" raw={}", name(raw))).unwrap_or_default();
        self.write(&format!(
            "frame #{number} spp={spp} file={}{raw} first_frame_ms={:.1} converged_ms={:.1}",
            name(file),
            ms(first_frame),
            ms(converged)
        ));
    }

    pub fn write(&mut self, line: &str) {
        println!("{line}");
        if let Some(file) = &mut self.file
            && let Err(e) = writeln!(file, "{line}").and_then(|()| file.flush())
        {
            log::warn!("cannot write to {LOG_FILE}: {e}");
        }
    }
}
