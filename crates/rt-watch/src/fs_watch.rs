//! Watching the files a scene is made of, with debouncing.
//!
//! Parent folders are watched, not the files themselves: editors and exporters that
//! write a temporary file and rename it, or delete and recreate, replace the file's
//! inode, which a watch on the file would lose. Events are filtered down to the files
//! that matter and gathered until they fall quiet, so that a save that touches many
//! files, or many saves in a row, become one batch.

use anyhow::{Context, Result};
use notify::{EventKind, RecommendedWatcher, RecursiveMode, Watcher};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A batch ends once no event came for this long…
const QUIET: Duration = Duration::from_millis(40);
/// …or this long after its first event, so that a stream of saves still shows progress.
const MAX_WAIT: Duration = Duration::from_millis(250);

/// Files that changed together.
#[derive(Clone, Debug)]
pub struct Batch {
    /// Sorted, without repeats.
    pub paths: Vec<PathBuf>,
    /// When the first of them was seen: the start of an edit's latency.
    pub first_event: Instant,
}

impl Batch {
    /// Adds `other`'s paths; the first event stays the earlier one.
    pub fn merge(&mut self, other: Batch) {
        self.paths.extend(other.paths);
        self.paths.sort();
        self.paths.dedup();
        self.first_event = self.first_event.min(other.first_event);
    }
}

/// The files that matter, as the kernel names them (folders resolved through links).
#[derive(Default)]
struct WatchSet {
    files: BTreeSet<PathBuf>,
}

impl WatchSet {
    /// A changed `path` matters if it is one of the files, or a folder on the way to one
    /// (a missing folder that has just been created, maybe with the file in it).
    fn matters(&self, path: &Path) -> bool {
        self.files.iter().any(|f| f.starts_with(path))
    }
}

pub struct FileWatcher {
    watcher: RecommendedWatcher,
    set: Arc<Mutex<WatchSet>>,
    dirs: BTreeSet<PathBuf>,
}

impl FileWatcher {
    /// Starts watching nothing yet; `sink` receives each debounced batch, on a thread of its own.
    pub fn start(sink: impl Fn(Batch) + Send + 'static) -> Result<Self> {
        let set = Arc::new(Mutex::new(WatchSet::default()));
        let (tx, rx) = mpsc::channel::<(Vec<PathBuf>, Instant)>();
        let filter_set = set.clone();
        let watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
            let event = match event {
                Ok(event) => event,
                Err(e) => {
                    log::warn!("file watching: {e}");
                    return;
                }
            };
            let now = Instant::now();
            let Ok(set) = filter_set.lock() else { return };
            // The kernel's queue overflowed: anything may have changed.
            if event.need_rescan() {
                let _ = tx.send((set.files.iter().cloned().collect(), now));
                return;
            }
            // Reading a file (rt's own loads included) is not a change.
            if matches!(event.kind, EventKind::Access(_)) {
                return;
            }
            let paths: Vec<PathBuf> = event.paths.into_iter().filter(|p| set.matters(p)).collect();
            if !paths.is_empty() {
                let _ = tx.send((paths, now));
            }
        })
        .context("cannot start watching files")?;
        std::thread::Builder::new()
            .name("rt watch debounce".into())
            .spawn(move || debounce(&rx, &sink))
            .context("cannot start the file-watching thread")?;
        Ok(Self { watcher, set, dirs: BTreeSet::new() })
    }

    /// Watches exactly `files` from now on (the folders they are in, or for a missing
    /// folder the nearest one that exists). Returns the files as events will name them.
    pub fn watch(&mut self, files: &[PathBuf]) -> Vec<PathBuf> {
        let resolved: BTreeSet<PathBuf> = files.iter().map(|f| resolve(f)).collect();
        let dirs: BTreeSet<PathBuf> = resolved.iter().filter_map(|f| existing_ancestor(f)).collect();
        for gone in self.dirs.difference(&dirs) {
            // A folder that was deleted has lost its watch already.
            let _ = self.watcher.unwatch(gone);
        }
        let mut watching = BTreeSet::new();
        for dir in &dirs {
            if self.dirs.contains(dir) {
                watching.insert(dir.clone());
                continue;
            }
            match self.watcher.watch(dir, RecursiveMode::NonRecursive) {
                Ok(()) => {
                    log::debug!("watching {}", dir.display());
                    watching.insert(dir.clone());
                }
                Err(e) => log::warn!("{}: cannot watch: {e}", dir.display()),
            }
        }
        self.dirs = watching;
        if let Ok(mut set) = self.set.lock() {
            set.files = resolved.clone();
        }
        resolved.into_iter().collect()
    }
}

/// Gathers events into batches until the watcher (the only sender) is dropped.
fn debounce(rx: &mpsc::Receiver<(Vec<PathBuf>, Instant)>, sink: &dyn Fn(Batch)) {
    while let Ok((paths, first_event)) = rx.recv() {
        let mut batch = Batch { paths, first_event };
        let mut quiet_until = Instant::now() + QUIET;
        loop {
            let deadline = quiet_until.min(first_event + MAX_WAIT);
            match rx.recv_timeout(deadline.saturating_duration_since(Instant::now())) {
                Ok((paths, at)) => {
                    batch.merge(Batch { paths, first_event: at });
                    quiet_until = Instant::now() + QUIET;
                }
                Err(RecvTimeoutError::Timeout) => break,
                Err(RecvTimeoutError::Disconnected) => return,
            }
        }
        sink(batch);
    }
}

/// `path` made absolute with its folders resolved through links, as far as they exist.
fn resolve(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let Some(existing) = existing_ancestor(&absolute) else { return absolute };
    let canonical = existing.canonicalize().unwrap_or_else(|_| existing.clone());
    match absolute.strip_prefix(&existing) {
        Ok(rest) => canonical.join(rest),
        Err(_) => absolute,
    }
}

/// The nearest folder above `path` that exists.
fn existing_ancestor(path: &Path) -> Option<PathBuf> {
    path.ancestors().skip(1).find(|a| a.is_dir()).map(Path::to_path_buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_created_folder_on_the_way_to_a_file_matters() {
        let set = WatchSet { files: [PathBuf::from("/a/assets/dragon/dragon.rtmesh")].into() };
        assert!(set.matters(Path::new("/a/assets/dragon/dragon.rtmesh")));
        assert!(set.matters(Path::new("/a/assets/dragon")));
        assert!(!set.matters(Path::new("/a/assets/dragon/dragon.rtbvh")));
        assert!(!set.matters(Path::new("/a/assets/dragon/.dragon.rtmesh.12.tmp")));
        assert!(!set.matters(Path::new("/b")));
    }
}
