//! Opening an input file safely. A path is checked before it is opened: a FIFO would
//! block the open (and then the read) forever, and a device such as `/dev/zero` never
//! ends, so only regular files are read. The open itself never blocks (`O_NONBLOCK`,
//! in case a FIFO replaced the file after the check), what was opened is checked
//! again, and a read stops at the size the file had when it was opened.

use std::collections::BTreeSet;
use std::fs::{File, FileType, OpenOptions};
use std::io::{self, Read};
use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The files opened since [`record_inputs`], when recording (`rt info --inputs`).
static RECORDED: Mutex<Option<BTreeSet<PathBuf>>> = Mutex::new(None);

/// From now on, remembers every file this process opens for reading.
pub fn record_inputs() {
    *RECORDED.lock().unwrap_or_else(|e| e.into_inner()) = Some(BTreeSet::new());
}

/// The files opened since [`record_inputs`] (absolute, as far as they resolve), in order.
pub fn recorded_inputs() -> Vec<PathBuf> {
    let recorded = RECORDED.lock().unwrap_or_else(|e| e.into_inner());
    recorded.iter().flatten().cloned().collect()
}

fn remember(path: &Path) {
    let mut recorded = RECORDED.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(set) = recorded.as_mut() {
        set.insert(std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()));
    }
}

/// Why an input file could not be read, naming it.
#[derive(Debug, thiserror::Error)]
#[error("{}: {problem}", path.display())]
pub struct InputError {
    pub path: PathBuf,
    pub problem: InputProblem,
}

#[derive(Debug, thiserror::Error)]
pub enum InputProblem {
    /// A FIFO, device, socket or folder where a file was expected.
    #[error("is {0}, not a file")]
    NotAFile(&'static str),
    #[error("is not UTF-8 text")]
    NotText,
    #[error("cannot read: {0}")]
    Io(io::Error),
}

impl InputError {
    fn new(path: &Path, problem: InputProblem) -> Self {
        Self { path: path.to_path_buf(), problem }
    }

    /// The message without the path, for errors that name the file themselves.
    pub fn message(&self) -> String {
        self.problem.to_string()
    }

    pub fn is_not_found(&self) -> bool {
        matches!(&self.problem, InputProblem::Io(e) if e.kind() == io::ErrorKind::NotFound)
    }
}

/// What a file type is, in words: "a FIFO", "a character device", ...
pub fn describe(file_type: FileType) -> &'static str {
    if file_type.is_dir() {
        "a folder"
    } else if file_type.is_fifo() {
        "a FIFO"
    } else if file_type.is_char_device() {
        "a character device"
    } else if file_type.is_block_device() {
        "a block device"
    } else if file_type.is_socket() {
        "a socket"
    } else if file_type.is_file() {
        "a file"
    } else {
        "not a regular file"
    }
}

/// Whether `path` (following symbolic links) is a regular file, without opening it:
/// `Ok(false)` for a FIFO, device or socket, `Err` if it cannot be looked at.
pub fn is_regular_file(path: &Path) -> io::Result<bool> {
    std::fs::metadata(path).map(|m| m.is_file())
}

/// Opens a regular file for reading without blocking; returns it with its size.
pub fn open(path: &Path) -> Result<(File, u64), InputError> {
    let fail = |problem| InputError::new(path, problem);
    let metadata = std::fs::metadata(path).map_err(|e| fail(InputProblem::Io(e)))?;
    if !metadata.is_file() {
        return Err(fail(InputProblem::NotAFile(describe(metadata.file_type()))));
    }
    let file = OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| fail(InputProblem::Io(e)))?;
    // The path may have been replaced between the check and the open.
    let metadata = file.metadata().map_err(|e| fail(InputProblem::Io(e)))?;
    if !metadata.is_file() {
        return Err(fail(InputProblem::NotAFile(describe(metadata.file_type()))));
    }
    remember(path);
    Ok((file, metadata.len()))
}

/// The bytes of a regular file, no more than its size when opened.
pub fn read(path: &Path) -> Result<Vec<u8>, InputError> {
    let (file, len) = open(path)?;
    let mut bytes = Vec::with_capacity(usize::try_from(len).unwrap_or(0));
    file.take(len).read_to_end(&mut bytes).map_err(|e| InputError::new(path, InputProblem::Io(e)))?;
    Ok(bytes)
}

/// A regular file's text; see [`read`].
pub fn read_to_string(path: &Path) -> Result<String, InputError> {
    String::from_utf8(read(path)?).map_err(|_| InputError::new(path, InputProblem::NotText))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_files_are_refused_before_they_are_opened() {
        let message = read(Path::new("/dev/zero")).expect_err("a device").to_string();
        assert_eq!(message, "/dev/zero: is a character device, not a file");
        let message = read(Path::new("/")).expect_err("a folder").to_string();
        assert_eq!(message, "/: is a folder, not a file");
        let missing = read(Path::new("/nonexistent/rt/x")).expect_err("missing");
        assert!(missing.is_not_found(), "{missing}");
    }
}
