//! Writing output files atomically: the bytes go to a temporary beside the target,
//! `.NAME.PID.RANDOM.tmp`, created exclusively (so no two writers, and no unrelated
//! file, ever share it), synced, and renamed into place. A reader never sees half a
//! file and an existing file is only ever replaced whole. The temporary is removed on
//! any error, and on SIGINT/SIGTERM (see [`super::interrupt`]); one left by a killed
//! run is removed by the next write of the same file once its process is gone.

use std::collections::hash_map::RandomState;
use std::fs::{File, OpenOptions};
use std::hash::{BuildHasher, Hasher};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Why an output file could not be written, naming it.
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct OutputError {
    pub path: PathBuf,
    pub message: String,
}

impl OutputError {
    fn new(path: &Path, message: impl Into<String>) -> Self {
        Self { path: path.to_path_buf(), message: message.into() }
    }
}

/// Temporaries being written now, removed by the signal handler.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// An I/O error in words, naming a full disk plainly.
fn describe(e: &io::Error) -> String {
    match e.kind() {
        io::ErrorKind::StorageFull => "no space left on device".to_owned(),
        io::ErrorKind::QuotaExceeded => "disk quota exceeded".to_owned(),
        _ => e.to_string(),
    }
}

/// Writes `bytes` to `path` atomically.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_with(path, |file| file.write_all(bytes))
}

/// Writes what `fill` writes into the temporary to `path`, atomically.
pub fn write_with(path: &Path, fill: impl FnOnce(&mut File) -> io::Result<()>) -> Result<(), OutputError> {
    refuse_special(path)?;
    remove_stale_temporaries(path);
    let mut temporary = Temporary::create(path).map_err(|e| {
        OutputError::new(path, format!("cannot create a file in {}: {}", folder_of(path).display(), describe(&e)))
    })?;
    let written = fill(&mut temporary.file).and_then(|()| temporary.file.sync_all());
    if let Err(e) = written {
        return Err(OutputError::new(path, format!("cannot write: {} (nothing was left behind)", describe(&e))));
    }
    std::fs::rename(&temporary.path, path)
        .map_err(|e| OutputError::new(path, format!("cannot move the new file into place: {}", describe(&e))))?;
    temporary.renamed = true;
    Ok(())
}

/// The rename would replace a FIFO, a device (as root, `/dev/full` itself) or a folder:
/// only regular files (or nothing) are replaced.
pub fn refuse_special(path: &Path) -> Result<(), OutputError> {
    match std::fs::metadata(path) {
        Ok(m) if !m.is_file() => {
            let what = super::input::describe(m.file_type());
            Err(OutputError::new(path, format!("is {what}, not a file: rt replaces only files")))
        }
        _ => Ok(()),
    }
}

/// Checks that files can be created in `dir`, by creating (and removing) a temporary there.
pub fn probe_writable(dir: &Path) -> Result<(), OutputError> {
    Temporary::create(&dir.join("write-check"))
        .map(drop)
        .map_err(|e| OutputError::new(dir, format!("cannot create files in this folder: {}", describe(&e))))
}

/// `dir` as a folder to write into: created if missing; an error if it is a file or
/// cannot be written.
pub fn check_folder(dir: &Path) -> Result<(), OutputError> {
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(m) => {
            return Err(OutputError::new(dir, format!("is {}, not a folder", super::input::describe(m.file_type()))));
        }
        Err(e) if e.kind() == io::ErrorKind::NotFound => std::fs::create_dir_all(dir)
            .map_err(|e| OutputError::new(dir, format!("cannot create the folder: {}", describe(&e))))?,
        Err(e) => return Err(OutputError::new(dir, format!("cannot use as a folder: {}", describe(&e)))),
    }
    probe_writable(dir)
}

/// Removes the temporaries of this process that are being written (for the signal
/// handler: the process exits right after).
pub fn remove_temporaries_in_progress() {
    let list = TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    for path in list.iter() {
        let _ = std::fs::remove_file(path);
    }
}

/// A temporary file being written; removed on drop unless it was renamed into place.
struct Temporary {
    path: PathBuf,
    file: File,
    renamed: bool,
}

impl Temporary {
    fn create(target: &Path) -> io::Result<Self> {
        super::interrupt::install();
        let dir = folder_of(target);
        let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let random = RandomState::new();
        for attempt in 0..16u64 {
            let mut hasher = random.build_hasher();
            hasher.write_u64(attempt);
            hasher.write_u128(std::time::SystemTime::UNIX_EPOCH.elapsed().map_or(0, |d| d.as_nanos()));
            let path = dir.join(format!(".{name}.{}.{:016x}.tmp", std::process::id(), hasher.finish()));
            // Registered before it exists, so that a signal never misses it.
            lock().push(path.clone());
            match OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(file) => return Ok(Self { path, file, renamed: false }),
                Err(e) => {
                    unregister(&path);
                    if e.kind() != io::ErrorKind::AlreadyExists {
                        return Err(e);
                    }
                }
            }
        }
        Err(io::Error::new(io::ErrorKind::AlreadyExists, "no unused temporary name after 16 tries"))
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.renamed {
            let _ = std::fs::remove_file(&self.path);
        }
        unregister(&self.path);
    }
}

fn lock() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

fn unregister(path: &Path) {
    lock().retain(|p| p != path);
}

fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Removes temporaries of `target` (`.NAME.PID.*.tmp`, and the older `.NAME.PID-*.tmp`)
/// whose process is gone: a run that was killed cannot remove its own.
pub fn remove_stale_temporaries(target: &Path) {
    // Without /proc no process can be known to be gone.
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Some(name) = target.file_name().map(|n| n.to_string_lossy().into_owned()) else { return };
    let Ok(entries) = std::fs::read_dir(folder_of(target)) else { return };
    let prefix = format!(".{name}.");
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = file_name.strip_prefix(&prefix).filter(|_| file_name.ends_with(".tmp")) else { continue };
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        let Ok(pid) = digits.parse::<u32>() else { continue };
        let follows = rest[digits.len()..].chars().next();
        if pid == std::process::id() || !matches!(follows, Some('.' | '-')) {
            continue;
        }
        if !Path::new(&format!("/proc/{pid}")).exists() {
            let path = entry.path();
            match std::fs::remove_file(&path) {
                Ok(()) => log::info!("removed {}, left by process {pid} that is gone", path.display()),
                Err(e) => log::warn!("cannot remove {}, left by process {pid}: {e}", path.display()),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rt-output-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("list")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn writes_replace_whole_files_and_leave_nothing_behind() {
        let dir = temp_dir("replace");
        let target = dir.join("a.png");
        std::fs::write(dir.join("a.partial"), "unrelated").expect("write");
        write_atomically(&target, b"one").expect("first write");
        write_atomically(&target, b"two").expect("second write");
        assert_eq!(std::fs::read(&target).expect("read"), b"two");
        assert_eq!(names(&dir), ["a.partial", "a.png"]);

        let failed = write_with(&target, |_| Err(io::Error::from(io::ErrorKind::StorageFull)));
        let message = failed.expect_err("full disk").to_string();
        assert!(message.contains("no space left on device"), "{message}");
        assert_eq!(std::fs::read(&target).expect("read"), b"two", "a failed write kept the old file");
        assert_eq!(names(&dir), ["a.partial", "a.png"]);
        std::fs::remove_dir_all(&dir).expect("clean up");
    }

    #[test]
    fn the_signal_handler_removes_temporaries_in_progress() {
        let dir = temp_dir("signal");
        let target = dir.join("b.exr");
        let registered = || lock().iter().filter(|p| p.starts_with(&dir)).cloned().collect::<Vec<_>>();
        let result = write_with(&target, |file| {
            file.write_all(b"half")?;
            let temporaries = registered();
            assert_eq!(temporaries.len(), 1, "the temporary is registered while it is written");
            assert_eq!(names(&dir), [temporaries[0].file_name().expect("name").to_string_lossy()]);
            // What SIGINT's handler does to each before it exits (the handler removes every
            // registered one; tests running in parallel have theirs).
            std::fs::remove_file(&temporaries[0])
        });
        assert!(result.is_err(), "the temporary was gone, so the rename must fail");
        assert!(names(&dir).is_empty(), "{:?}", names(&dir));
        assert!(registered().is_empty(), "a finished write leaves the list");
        std::fs::remove_dir_all(&dir).expect("clean up");
    }

    #[test]
    fn stale_temporaries_of_gone_processes_are_removed() {
        let dir = temp_dir("stale");
        let target = dir.join("m.rtbvh");
        // PIDs stop below 2^22 on Linux, so 999999999 is no process.
        for name in [".m.rtbvh.999999999.00ff.tmp", ".m.rtbvh.999999998-3.tmp", ".other.999999999.1.tmp"] {
            std::fs::write(dir.join(name), "").expect("write");
        }
        let own = format!(".m.rtbvh.{}.1.tmp", std::process::id());
        std::fs::write(dir.join(&own), "").expect("write");
        remove_stale_temporaries(&target);
        assert_eq!(names(&dir), [own, ".other.999999999.1.tmp".to_owned()]);
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
