//! Folders rt makes for its own work (a benchmark's scene, files for Mitsuba): each one
//! new, under the system's temporary folder, with a random part in its name, so that rt
//! never takes over a folder it did not make, and removes only the one it made.

use std::collections::hash_map::RandomState;
use std::hash::{BuildHasher, Hasher};
use std::io;
use std::path::{Path, PathBuf};

/// A folder made for this run, removed with its contents when dropped.
pub struct ScratchDir(PathBuf);

impl ScratchDir {
    /// A new folder `$TMPDIR/rt-PURPOSE-PID-RANDOM` (mode 0700).
    pub fn new(purpose: &str) -> io::Result<Self> {
        use std::os::unix::fs::DirBuilderExt;
        let random = RandomState::new();
        for attempt in 0..16u64 {
            let mut hasher = random.build_hasher();
            hasher.write_u64(attempt);
            let name = format!("rt-{purpose}-{}-{:016x}", std::process::id(), hasher.finish());
            let path = std::env::temp_dir().join(name);
            match std::fs::DirBuilder::new().mode(0o700).create(&path) {
                Ok(()) => return Ok(Self(path)),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(e),
            }
        }
        Err(io::Error::new(io::ErrorKind::AlreadyExists, "no unused folder name after 16 tries"))
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for ScratchDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_scratch_folder_is_new_and_goes_with_its_owner() {
        let (a, b) = (ScratchDir::new("test").expect("a"), ScratchDir::new("test").expect("b"));
        assert_ne!(a.path(), b.path());
        std::fs::write(a.path().join("x"), "x").expect("write");
        let path = a.path().to_path_buf();
        drop(a);
        assert!(!path.exists());
        assert!(b.path().is_dir());
    }
}
