//! Progress as the command line shows it: the library's meters drawn as indicatif bars on
//! stderr (only when stderr is a terminal).

use indicatif::{ProgressBar, ProgressStyle};
use rt::progress::{Meter, MeterSpec, Meters};

/// Bars on the terminal.
pub(crate) struct TerminalBars;

impl Meters for TerminalBars {
    fn meter(&self, spec: &MeterSpec) -> Box<dyn Meter> {
        let head = match spec.label {
            "" => "{bar:40}".to_owned(),
            label => format!("{label} {{bar:30}}"),
        };
        let tail = if spec.time_left { "{msg}  ETA {eta}" } else { "{elapsed}" };
        let template = format!("{head} {{pos}}/{{len}} {}  {tail}", spec.unit);
        let bar = ProgressBar::new(spec.total);
        bar.set_style(ProgressStyle::with_template(&template).unwrap_or_else(|_| ProgressStyle::default_bar()));
        Box::new(TerminalBar(bar))
    }
}

struct TerminalBar(ProgressBar);

impl Meter for TerminalBar {
    fn set_position(&self, done: u64) {
        self.0.set_position(done);
    }
    fn inc(&self, n: u64) {
        self.0.inc(n);
    }
    fn set_message(&self, message: String) {
        self.0.set_message(message);
    }
    fn finish(&self) {
        self.0.finish_and_clear();
    }
}
