//! Benchmarks: speed measured on the real pipeline, never in tests.

mod throughput;

pub use throughput::throughput;
