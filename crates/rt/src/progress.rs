//! How long work says how far it has come, without drawing anything itself. As the library
//! logs through `log` and leaves the writing of records to the program, it reports progress
//! to the [`Meters`] the program installs: the `rt` command line draws bars on a terminal;
//! a program that installs none sees nothing.

use std::sync::OnceLock;

/// What one meter counts.
pub struct MeterSpec<'a> {
    /// Shown before the count ("packing", "loading BVHs"); empty for none.
    pub label: &'a str,
    /// What is counted ("assets", "spp").
    pub unit: &'a str,
    pub total: u64,
    /// Whether the time left is worth showing (a render), rather than the time spent.
    pub time_left: bool,
}

/// One piece of long work's progress; shared by the threads that do it.
pub trait Meter: Send + Sync {
    fn set_position(&self, done: u64);
    fn inc(&self, n: u64);
    /// A short note beside the count (a rate, say).
    fn set_message(&self, message: String);
    /// The work is over: the meter goes away.
    fn finish(&self);
}

/// Makes meters: the program's choice of how progress looks.
pub trait Meters: Send + Sync {
    fn meter(&self, spec: &MeterSpec) -> Box<dyn Meter>;
}

static METERS: OnceLock<&'static dyn Meters> = OnceLock::new();

/// Installs the program's meters (once; a later call changes nothing).
pub fn set_meters(meters: &'static dyn Meters) {
    let _ = METERS.set(meters);
}

/// A meter for `spec`: the program's, or one that shows nothing when it installed none.
pub fn meter(spec: &MeterSpec) -> Box<dyn Meter> {
    METERS.get().map_or_else(hidden, |meters| meters.meter(spec))
}

/// A meter that shows nothing.
pub fn hidden() -> Box<dyn Meter> {
    Box::new(Hidden)
}

struct Hidden;

impl Meter for Hidden {
    fn set_position(&self, _: u64) {}
    fn inc(&self, _: u64) {}
    fn set_message(&self, _: String) {}
    fn finish(&self) {}
}
