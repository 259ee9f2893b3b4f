//! Benchmarks: speed measured on the real pipeline, never in tests.

mod sky;
mod throughput;
mod watch_latency;

pub use sky::sky;
pub use throughput::throughput;
pub use watch_latency::watch_latency;
