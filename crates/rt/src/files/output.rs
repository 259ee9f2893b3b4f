//! Writing output files atomically. The bytes go to a temporary in the target's folder,
//! are synced, and the temporary is renamed into place: a reader never sees half a
//! file, and an existing file is only ever replaced whole.
//!
//! On Linux the temporary has no name while it is written (`O_TMPFILE`): if rt is
//! killed, even by SIGKILL or a power cut, the kernel frees it and nothing is left
//! behind. It gets a name, `.NAME.rt-PID-RANDOM.tmp` (RANDOM: 16 hex digits), only for
//! the instant between being linked and being renamed over NAME. Where a filesystem
//! cannot make unnamed files, the temporary has that name from the start.
//!
//! A temporary is removed on any error and on SIGINT/SIGTERM (see [`super::interrupt`]).
//! One left by a killed run is removed by the next write of the same file only when rt
//! can prove it made it: its name is exactly rt's pattern for that file, it is a regular
//! file of this user's carrying rt's mark (an extended attribute, `user.rt.temporary`,
//! set when it was made), and the process its name gives is gone. Nothing else in a
//! folder is ever removed, whatever its name looks like.

use std::collections::hash_map::RandomState;
use std::fs::{File, OpenOptions};
use std::hash::{BuildHasher, Hasher};
use std::io::{self, Seek, Write};
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
    temporary.name().map_err(|e| OutputError::new(path, format!("cannot name the new file: {}", describe(&e))))?;
    temporary.rename_to(path)
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

/// A temporary file being written, with the name it has (none while it is an unnamed
/// `O_TMPFILE`); removed on drop unless it was renamed into place.
struct Temporary {
    target: PathBuf,
    file: File,
    path: Option<PathBuf>,
    renamed: bool,
}

impl Temporary {
    fn create(target: &Path) -> io::Result<Self> {
        super::interrupt::install();
        let target = target.to_path_buf();
        if let Some(file) = unnamed_file(folder_of(&target)) {
            mark(&file);
            return Ok(Self { target, file, path: None, renamed: false });
        }
        let (path, file) = claim_name(&target, |path| OpenOptions::new().write(true).create_new(true).open(path))?;
        mark(&file);
        Ok(Self { target, file, path: Some(path), renamed: false })
    }

    /// Gives an unnamed temporary its name (a hard link of its open file), just before
    /// it is renamed over the target.
    fn name(&mut self) -> io::Result<()> {
        if self.path.is_some() {
            return Ok(());
        }
        let from = std::ffi::CString::new(format!("/proc/self/fd/{}", std::os::fd::AsRawFd::as_raw_fd(&self.file)))
            .map_err(io::Error::other)?;
        match claim_name(&self.target, |path| link_proc_fd(&from, path)) {
            Ok((path, ())) => self.path = Some(path),
            // A filesystem that makes unnamed files but cannot link them: copied into a
            // named temporary instead.
            Err(e) => {
                log::debug!("{}: cannot link the unnamed temporary ({e}); copying it", self.target.display());
                let open = |path: &Path| OpenOptions::new().write(true).create_new(true).open(path);
                let (path, mut named) = claim_name(&self.target, open)?;
                mark(&named);
                self.path = Some(path);
                self.file.seek(io::SeekFrom::Start(0))?;
                io::copy(&mut self.file, &mut named)?;
                named.sync_all()?;
            }
        }
        Ok(())
    }

    fn rename_to(mut self, target: &Path) -> Result<(), OutputError> {
        let Some(path) = &self.path else { return Err(OutputError::new(target, "the new file has no name")) };
        std::fs::rename(path, target)
            .map_err(|e| OutputError::new(target, format!("cannot move the new file into place: {}", describe(&e))))?;
        self.renamed = true;
        Ok(())
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if let Some(path) = &self.path {
            if !self.renamed {
                let _ = std::fs::remove_file(path);
            }
            unregister(path);
        }
    }
}

/// A fresh `.NAME.rt-PID-RANDOM.tmp` beside `target`, registered (before it exists, so
/// that a signal never misses it) and made by `make`, which fails if the name is taken.
fn claim_name<T>(target: &Path, make: impl Fn(&Path) -> io::Result<T>) -> io::Result<(PathBuf, T)> {
    let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let random = RandomState::new();
    for attempt in 0..16u64 {
        let mut hasher = random.build_hasher();
        hasher.write_u64(attempt);
        hasher.write_u128(std::time::SystemTime::UNIX_EPOCH.elapsed().map_or(0, |d| d.as_nanos()));
        let path = folder_of(target).join(temporary_name(&name, std::process::id(), hasher.finish()));
        lock().push(path.clone());
        match make(&path) {
            Ok(made) => return Ok((path, made)),
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

/// The name of rt's temporary for the file `name`: `.NAME.rt-PID-RANDOM.tmp`.
fn temporary_name(name: &str, pid: u32, random: u64) -> String {
    format!(".{name}.rt-{pid}-{random:016x}.tmp")
}

/// The process id in `file_name` if it is exactly rt's temporary name for `name`.
fn temporary_owner(file_name: &str, name: &str) -> Option<u32> {
    let rest = file_name.strip_prefix('.')?.strip_prefix(name)?.strip_prefix(".rt-")?.strip_suffix(".tmp")?;
    let (pid, random) = rest.split_once('-')?;
    let digits = |s: &str, radix: u32| s.chars().all(|c| c.is_digit(radix) && !c.is_ascii_uppercase());
    let canonical_pid = !pid.is_empty() && pid.len() <= 10 && digits(pid, 10) && !pid.starts_with('0');
    if !canonical_pid || random.len() != 16 || !digits(random, 16) {
        return None;
    }
    pid.parse().ok()
}

/// Whether `file_name` is exactly rt's temporary name for a file called `name`, of a
/// process that is gone.
pub fn is_stale_temporary(file_name: &str, name: &str) -> bool {
    temporary_owner(file_name, name)
        .is_some_and(|pid| pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists())
}

/// The extended attribute rt sets on each temporary it makes: with the name, the proof
/// that a leftover is rt's (a user's file named like one does not have it).
const MARK: &[u8] = b"user.rt.temporary\0";

/// Marks `file` as rt's temporary, where the filesystem keeps extended attributes (where
/// it does not, a leftover is never removed: rt cannot prove it made it).
#[cfg(target_os = "linux")]
fn mark(file: &File) {
    use std::os::fd::AsRawFd;
    // SAFETY: a valid descriptor, a NUL-terminated name and a 2-byte value.
    let status = unsafe { libc::fsetxattr(file.as_raw_fd(), MARK.as_ptr().cast(), b"rt".as_ptr().cast(), 2, 0) };
    if status != 0 {
        log::debug!("cannot mark a temporary as rt's: {}", io::Error::last_os_error());
    }
}

#[cfg(not(target_os = "linux"))]
fn mark(_file: &File) {}

/// Whether the file at `path` (not following a link) carries rt's mark.
#[cfg(target_os = "linux")]
fn is_marked(path: &Path) -> bool {
    use std::os::unix::ffi::OsStrExt;
    let Ok(c_path) = std::ffi::CString::new(path.as_os_str().as_bytes()) else { return false };
    let mut value = [0u8; 4];
    // SAFETY: valid NUL-terminated strings and a buffer of the length given.
    let len = unsafe { libc::lgetxattr(c_path.as_ptr(), MARK.as_ptr().cast(), value.as_mut_ptr().cast(), value.len()) };
    len == 2 && &value[..2] == b"rt"
}

#[cfg(not(target_os = "linux"))]
fn is_marked(_path: &Path) -> bool {
    false
}

/// An unnamed file in `dir` (Linux's `O_TMPFILE`), if the filesystem makes them and
/// `/proc` is there to name it later.
#[cfg(target_os = "linux")]
fn unnamed_file(dir: &Path) -> Option<File> {
    use std::os::unix::fs::OpenOptionsExt;
    if !Path::new("/proc/self/fd").is_dir() {
        return None;
    }
    OpenOptions::new().read(true).write(true).mode(0o666).custom_flags(libc::O_TMPFILE).open(dir).ok()
}

#[cfg(not(target_os = "linux"))]
fn unnamed_file(_dir: &Path) -> Option<File> {
    None
}

/// Links the open file `/proc/self/fd/N` at `path` (an error if `path` exists).
#[cfg(target_os = "linux")]
fn link_proc_fd(from: &std::ffi::CStr, path: &Path) -> io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let to = std::ffi::CString::new(path.as_os_str().as_bytes()).map_err(io::Error::other)?;
    // SAFETY: both are valid NUL-terminated paths that outlive the call.
    let status =
        unsafe { libc::linkat(libc::AT_FDCWD, from.as_ptr(), libc::AT_FDCWD, to.as_ptr(), libc::AT_SYMLINK_FOLLOW) };
    if status == 0 { Ok(()) } else { Err(io::Error::last_os_error()) }
}

#[cfg(not(target_os = "linux"))]
fn link_proc_fd(_from: &std::ffi::CStr, _path: &Path) -> io::Result<()> {
    Err(io::Error::from(io::ErrorKind::Unsupported))
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

/// Removes temporaries of `target` left by killed runs: those whose name is exactly
/// rt's pattern for it, that are regular files of this user's, and whose process is gone.
pub fn remove_stale_temporaries(target: &Path) {
    use std::os::unix::fs::MetadataExt;
    // Without /proc no process can be known to be gone, nor who this user is.
    let Ok(me) = std::fs::metadata("/proc/self").map(|m| m.uid()) else { return };
    let Some(name) = target.file_name().map(|n| n.to_string_lossy().into_owned()) else { return };
    let Ok(entries) = std::fs::read_dir(folder_of(target)) else { return };
    for entry in entries.flatten() {
        let Some(file_name) = entry.file_name().to_str().map(str::to_owned) else { continue };
        let path = entry.path();
        let ours = std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file() && m.uid() == me) && is_marked(&path);
        if !ours || !is_stale_temporary(&file_name, &name) {
            continue;
        }
        let pid = temporary_owner(&file_name, &name).unwrap_or_default();
        match std::fs::remove_file(&path) {
            Ok(()) => log::info!("removed {}, left by process {pid} that is gone", path.display()),
            Err(e) => log::warn!("cannot remove {}, left by process {pid}: {e}", path.display()),
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
    fn a_temporary_has_no_name_while_it_is_written() {
        let dir = temp_dir("unnamed");
        let target = dir.join("b.exr");
        let mut temporary = Temporary::create(&target).expect("temporary");
        temporary.file.write_all(b"half").expect("write");
        if temporary.path.is_none() {
            assert!(names(&dir).is_empty(), "an unnamed temporary: a kill now leaves nothing");
        }
        // What a kill leaves: the file handle is never closed by rt, nor the name removed.
        std::mem::forget(temporary);
        if unnamed_file(&dir).is_some() {
            assert!(names(&dir).is_empty(), "{:?}", names(&dir));
        }
        std::fs::remove_dir_all(&dir).expect("clean up");
    }

    #[test]
    fn the_signal_handler_removes_named_temporaries_in_progress() {
        let dir = temp_dir("signal");
        let target = dir.join("b.exr");
        let registered = || lock().iter().filter(|p| p.starts_with(&dir)).cloned().collect::<Vec<_>>();
        let open = |path: &Path| OpenOptions::new().write(true).create_new(true).open(path);
        let (path, _file) = claim_name(&target, open).expect("named temporary");
        assert_eq!(registered(), std::slice::from_ref(&path), "registered while it is written");
        remove_temporaries_in_progress();
        assert!(names(&dir).is_empty(), "{:?}", names(&dir));
        unregister(&path);
        assert!(registered().is_empty());
        std::fs::remove_dir_all(&dir).expect("clean up");
    }

    #[test]
    fn only_exact_temporary_names_are_read_as_rts() {
        let name = "o.png";
        assert_eq!(temporary_owner(&temporary_name(name, 42, 0xab), name), Some(42));
        assert_eq!(temporary_owner(".o.png.rt-42-0123456789abcdef.tmp", name), Some(42));
        for user_file in [
            ".o.png.20240105.tmp",
            ".o.png.99999-backup.tmp",
            ".o.png.999999999.00000000000000ab.tmp",
            ".o.png.999999998-3.tmp",
            ".o.png.rt-42-0123.tmp",
            ".o.png.rt-42-0123456789ABCDEF.tmp",
            ".o.png.rt-042-0123456789abcdef.tmp",
            ".o.png.rt-42-0123456789abcdef0.tmp",
            ".o.png.rt--0123456789abcdef.tmp",
            ".o.png.rt-42-0123456789abcdef.tmp.bak",
            ".o.png.rt-42-0123456789abcdeg.tmp",
            ".o.png.rt-+42-0123456789abcdef.tmp",
            ".xo.png.rt-42-0123456789abcdef.tmp",
        ] {
            assert_eq!(temporary_owner(user_file, name), None, "{user_file}");
        }
    }

    #[test]
    fn stale_temporaries_of_gone_processes_are_removed_and_nothing_else() {
        let dir = temp_dir("stale");
        let target = dir.join("m.rtbvh");
        // PIDs stop below 2^22 on Linux, so 999999999 is no process.
        let stale = temporary_name("m.rtbvh", 999_999_999, 0xff);
        let kept = [
            ".m.rtbvh.999999999.00ff.tmp".to_owned(),
            ".m.rtbvh.999999998-3.tmp".to_owned(),
            ".m.rtbvh.20240105.tmp".to_owned(),
            temporary_name("other", 999_999_999, 1),
            temporary_name("m.rtbvh", std::process::id(), 1),
        ];
        for name in kept.iter().chain([&stale]) {
            mark(&File::create(dir.join(name)).expect("write"));
        }
        // Named exactly like a stale temporary, but a folder, a link, and a file without
        // rt's mark: not rt's files.
        std::fs::create_dir(dir.join(temporary_name("m.rtbvh", 999_999_999, 2))).expect("folder");
        std::os::unix::fs::symlink("/nonexistent", dir.join(temporary_name("m.rtbvh", 999_999_999, 3))).expect("link");
        std::fs::write(dir.join(temporary_name("m.rtbvh", 999_999_999, 4)), "a user's").expect("write");
        let provable = is_marked(&dir.join(&stale));
        remove_stale_temporaries(&target);
        let mut expected: Vec<String> = kept.to_vec();
        expected.extend([2, 3, 4].map(|r| temporary_name("m.rtbvh", 999_999_999, r)));
        if !provable {
            // A filesystem without extended attributes: rt cannot prove the file its own.
            expected.push(stale.clone());
        }
        expected.sort();
        assert_eq!(names(&dir), expected);
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
