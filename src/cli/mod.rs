//! The command line's rooms: its options (`args`, `bench_args`), each command's call into
//! the library (`render`, `commands`) and how progress looks on a terminal (`meters`).

pub mod args;
pub mod bench_args;
pub mod commands;
pub mod meters;
pub mod render;
