//! The files rt reads and writes, handled the same way everywhere: inputs are opened
//! only when they are regular files and read no further than their size (`input`);
//! outputs are written to a temporary and renamed into place, and the temporaries of a
//! failed, interrupted or killed run never stay behind (`output`, `interrupt`); rt's own
//! working folders are new ones it removes when done (`scratch`).

pub mod image;
pub mod input;
pub mod interrupt;
pub mod output;
pub mod scratch;

pub use input::{InputError, read, read_to_string};
pub use output::{OutputError, check_folder, write_atomically};
pub use scratch::ScratchDir;
