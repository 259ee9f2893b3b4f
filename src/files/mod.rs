//! The files rt reads and writes, handled the same way everywhere: inputs are opened
//! only when they are regular files and read no further than their size (`input`);
//! outputs are written to a unique hidden temporary and renamed into place, and the
//! temporaries of a failed, interrupted or killed run never stay behind (`output`,
//! `interrupt`).

pub mod input;
pub mod interrupt;
pub mod output;

pub use input::{InputError, read, read_to_string};
pub use output::{OutputError, check_folder, write_atomically};
