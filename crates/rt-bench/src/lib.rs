//! Benchmarks: speed measured on the real pipeline, and accuracy against time
//! (the price tag of every knob that trades one for the other).

pub mod accuracy;
mod agreement;
mod clocks;
pub mod commands;
mod compare;
mod compare_rt;
pub mod denoise_timing;
pub mod effects;
pub mod fireflies;
pub mod first_pixel;
pub mod headline;
mod instances;
pub mod knobs;
pub mod metrics;
mod mitsuba;
pub mod mitsuba_scene;
pub mod model;
mod plot;
pub mod reference;
pub mod report;
mod sky;
pub mod ssim;
pub mod sweep;
mod throughput;
pub mod timing;
pub mod views;

pub use accuracy::{AccuracyOptions, accuracy};
pub use compare::{CompareOptions, compare};
pub use denoise_timing::{DenoiseBenchOptions, denoise_bench};
pub use effects::effects;
pub use fireflies::{FireflyOptions, fireflies};
pub use headline::{HeadlineOptions, headline};
pub use instances::{InstanceScaleOptions, instances};
pub use sky::sky;
pub use throughput::{ThroughputOptions, throughput};
