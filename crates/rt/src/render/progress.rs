//! How a render shows its progress: a bar on a terminal, nothing, or one JSON object per
//! line on stderr for a program that drives rt (the Blender render engine reads them).

use crate::progress::{self, Meter, MeterSpec};
use serde_json::{Value, json};
use std::time::{Duration, Instant};

/// `--progress`: what `rt render` writes on stderr while it renders.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum Progress {
    /// Nothing.
    #[value(name = "none")]
    Hidden,
    /// A progress bar (drawn only on a terminal).
    #[default]
    Bar,
    /// One JSON object per line: `progress` events, then `done`, or `error`.
    Json,
}

/// JSON progress lines come at most this often (the last one always comes).
const JSON_INTERVAL: Duration = Duration::from_millis(100);

/// One line of `--progress json`: `{"event": EVENT, ...fields}`.
pub fn json_event(event: &str, fields: Value) -> String {
    let mut line = json!({ "event": event });
    if let (Some(line), Value::Object(fields)) = (line.as_object_mut(), fields) {
        line.extend(fields);
    }
    line.to_string()
}

/// Shows one render's progress towards its spp in the way its request asks.
pub(super) struct ProgressReporter {
    kind: Progress,
    bar: Box<dyn Meter>,
    spp: u32,
    last_json: Option<Instant>,
}

impl ProgressReporter {
    pub(super) fn new(kind: Progress, spp: u32) -> Self {
        let bar = match kind {
            Progress::Bar => progress::meter(&MeterSpec { label: "", unit: "spp", total: spp as u64, time_left: true }),
            Progress::Hidden | Progress::Json => progress::hidden(),
        };
        Self { kind, bar, spp, last_json: None }
    }

    /// `samples` per pixel are done after `elapsed`, at `rate` camera paths per second.
    pub(super) fn update(&mut self, samples: u32, elapsed: Duration, rate: f64) {
        match self.kind {
            Progress::Hidden => {}
            Progress::Bar => {
                self.bar.set_position(samples as u64);
                self.bar.set_message(format!("{} samples/s", super::human(rate)));
            }
            Progress::Json => {
                let due = self.last_json.is_none_or(|t| t.elapsed() >= JSON_INTERVAL);
                if !due && samples < self.spp {
                    return;
                }
                self.last_json = Some(Instant::now());
                let per_spp = elapsed.as_secs_f64() / samples.max(1) as f64;
                let eta = per_spp * self.spp.saturating_sub(samples) as f64;
                let fields = json!({ "spp": samples, "of": self.spp, "samples_per_second": rate, "eta_s": eta });
                eprintln!("{}", json_event("progress", fields));
            }
        }
    }

    pub(super) fn finish(&self) {
        self.bar.finish();
    }
}
