//! The command line's rooms: its options (`args`, `bench_args`) and each command's call into
//! the library (`render`, `commands`).

pub mod args;
pub mod bench_args;
pub mod commands;
pub mod render;
