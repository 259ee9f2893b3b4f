//! Benchmarks: speed measured on the real pipeline, never in tests.

mod sky;
mod throughput;

pub use sky::sky;
pub use throughput::throughput;
