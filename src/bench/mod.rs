//! Benchmarks: speed measured on the real pipeline, never in tests.

mod throughput;
mod watch_latency;

pub use throughput::throughput;
pub use watch_latency::watch_latency;
