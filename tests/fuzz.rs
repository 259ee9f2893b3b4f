//! rt's fuzzing harness on the stable toolchain: every target (`rt_watch::stream::fuzz_targets`:
//! `rt::fuzz`'s and the viewport stream's) runs its
//! regressions (`fuzz/regressions/TARGET/`, inputs that once failed) and its corpus
//! (`fuzz/corpus/TARGET/`), then mutants of them until its time is up. Each input must
//! give an error or a result, never a panic; finish within [`HANG`]; and never hold more
//! memory at once than 128 × its size + 1 MiB (plus the target's allowance for what an
//! image declares). Mutants with an outcome not seen before (a new error, say) join the
//! corpus in memory, a cheap stand-in for coverage.
//!
//! `RT_FUZZ_SECONDS` (default 30) per target; `RT_FUZZ_TARGETS=obj,scene` for some;
//! `RT_FUZZ_SEED` to vary the mutants; `RT_FUZZ_WRITE_SEEDS=1` writes the built-in seeds
//! into `fuzz/corpus/` instead. A failing input is saved under `target/fuzz-failures/`
//! with the command that replays it (`RT_FUZZ_TRACE=1` also keeps the input running,
//! for a crash that kills the process); copied into `fuzz/regressions/TARGET/`, it runs
//! first from then on. For a coverage-guided run, see `fuzz/README.md`.

use rt::fuzz::{Target, Workspace, mutate, seeds};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// An input that takes longer than this is a hang.
const HANG: Duration = Duration::from_secs(10);
/// Mutants are cut to this size: larger inputs only run slower.
const MAX_INPUT: usize = 1 << 20;
/// The largest image the targets decode while fuzzing (RT_MAX_IMAGE_MEGAPIXELS).
const MEGAPIXELS: &str = "16";

/// Counts the bytes each thread holds, and the most it held since the last reset.
struct Counting;

thread_local! {
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

fn count(delta: isize) {
    // `try_with`: a thread's last frees come after its locals are gone.
    let _ = LIVE.try_with(|live| {
        live.set(live.get() + delta);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(live.get())));
    });
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size() as isize);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        count(-(layout.size() as isize));
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size as isize - layout.size() as isize);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// What one target's run found.
#[derive(Default)]
struct Summary {
    runs: u64,
    outcomes: usize,
    corpus: usize,
    slowest: Duration,
    most_memory: usize,
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn inputs_in(dir: &Path) -> Vec<Vec<u8>> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).filter(|p| p.is_file()).collect();
    paths.sort();
    paths.iter().filter_map(|p| std::fs::read(p).ok()).collect()
}

/// Saves a failing input and stops the harness with its story.
fn fail(target: &Target, input: &[u8], what: &str) -> ! {
    let dir = repo().join("target/fuzz-failures").join(target.name);
    let _ = std::fs::create_dir_all(&dir);
    let hash = input.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ b as u64).wrapping_mul(0x100_0000_01b3));
    let path = dir.join(format!("{hash:016x}"));
    let _ = std::fs::write(&path, input);
    eprintln!(
        "fuzz {}: {what} on a {}-byte input, saved as {}\nreplay: cp {} fuzz/regressions/{}/ && \
         RT_FUZZ_SECONDS=0 RT_FUZZ_TARGETS={} cargo test --release --test fuzz",
        target.name,
        input.len(),
        path.display(),
        path.display(),
        target.name,
        target.name
    );
    std::process::exit(1);
}

/// Runs one input: its outcome's signature (an error's words without its numbers).
fn check(target: &Target, workspace: &Workspace, input: &[u8], summary: &mut Summary, watch: &Watch) -> String {
    watch.start(input, summary.runs, target);
    let base = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(base));
    let clock = Instant::now();
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| target.run(workspace, input)));
    let elapsed = clock.elapsed();
    watch.running.store(0, Ordering::SeqCst);
    let used = (PEAK.with(Cell::get) - base).max(0) as usize;
    let budget = 128 * input.len() + (1 << 20) + target.allowance;
    summary.runs += 1;
    summary.slowest = summary.slowest.max(elapsed);
    summary.most_memory = summary.most_memory.max(used);
    match outcome {
        Err(panic) => {
            let message =
                panic.downcast_ref::<String>().cloned().or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()));
            fail(target, input, &format!("a panic ({})", message.unwrap_or_default()))
        }
        Ok(_) if used > budget => fail(target, input, &format!("{used} bytes held at once, over {budget}")),
        Ok(Ok(())) => "ok".to_owned(),
        // What the file said (a key's name, a value) is left out, and numbers.
        Ok(Err(e)) => {
            e.split(['`', '"', '\'']).step_by(2).flat_map(str::chars).filter(|c| !c.is_ascii_digit()).take(80).collect()
        }
    }
}

/// Fuzzes one target for `seconds`.
fn fuzz(target: &Target, seconds: f64, seed: u64, watch: &Watch) -> Summary {
    let workspace = Workspace::new().expect("a scratch folder for the targets' files");
    let mut summary = Summary::default();
    let mut outcomes = HashSet::new();
    for input in inputs_in(&repo().join("fuzz/regressions").join(target.name)) {
        outcomes.insert(check(target, &workspace, &input, &mut summary, watch));
    }
    let mut corpus = inputs_in(&repo().join("fuzz/corpus").join(target.name));
    if corpus.is_empty() {
        corpus = seeds::of(target.name);
    }
    for input in &corpus {
        outcomes.insert(check(target, &workspace, input, &mut summary, watch));
    }
    let mut rng =
        mutate::Rng(seed ^ target.name.bytes().fold(0x9e37_79b9_7f4a_7c15u64, |h, b| h.rotate_left(7) ^ b as u64));
    let deadline = Instant::now() + Duration::from_secs_f64(seconds);
    while Instant::now() < deadline && !corpus.is_empty() {
        let (a, b) = (rng.below(corpus.len()), rng.below(corpus.len()));
        let mut mutant = mutate::mutate(&corpus[a], &corpus[b], &mut rng, target.text);
        mutant.truncate(MAX_INPUT);
        if outcomes.insert(check(target, &workspace, &mutant, &mut summary, watch)) && corpus.len() < 4096 {
            corpus.push(mutant);
        }
    }
    summary.outcomes = outcomes.len();
    summary.corpus = corpus.len();
    summary
}

fn write_seeds() {
    for target in rt_watch::stream::fuzz_targets() {
        let dir = repo().join("fuzz/corpus").join(target.name);
        std::fs::create_dir_all(&dir).expect("corpus folder");
        for (i, seed) in seeds::of(target.name).iter().enumerate() {
            std::fs::write(dir.join(format!("seed-{i}")), seed).expect("seed file");
        }
        println!("{}: {} seeds", dir.display(), seeds::of(target.name).len());
    }
}

fn main() {
    // Set before any thread starts: the targets read it.
    // SAFETY: no other thread exists yet.
    unsafe { std::env::set_var(rt::files::image::MAX_MEGAPIXELS_VARIABLE, MEGAPIXELS) };
    if std::env::args().any(|a| a == "--list") {
        rt_watch::stream::fuzz_targets().iter().for_each(|t| println!("{}: test", t.name));
        return;
    }
    if std::env::var_os("RT_FUZZ_WRITE_SEEDS").is_some() {
        return write_seeds();
    }
    let number = |name: &str, default: f64| std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default);
    let seconds = number("RT_FUZZ_SECONDS", 30.0);
    let seed = number("RT_FUZZ_SEED", 1.0) as u64;
    let chosen = std::env::var("RT_FUZZ_TARGETS").ok();
    let picked: Vec<&'static Target> = rt_watch::stream::fuzz_targets()
        .into_iter()
        .filter(|t| chosen.as_deref().is_none_or(|c| c.split(',').any(|n| n.trim() == t.name)))
        .collect();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()).min(picked.len().max(1));
    let queue = Mutex::new(picked.into_iter());
    let results = Mutex::new(Vec::new());
    println!("fuzzing for {seconds} s per target on {threads} threads (seed {seed})");
    std::thread::scope(|scope| {
        for _ in 0..threads {
            // rt parses on its main thread, whose stack is 8 MiB.
            let builder = std::thread::Builder::new().stack_size(8 << 20);
            let spawned = builder.spawn_scoped(scope, || {
                let watch = Watch::default();
                loop {
                    let Some(target) = queue.lock().expect("queue").next() else { return };
                    let summary = watched(target, || fuzz(target, seconds, seed, &watch), &watch);
                    results.lock().expect("results").push((target.name, summary));
                }
            });
            spawned.expect("a fuzzing thread");
        }
    });
    let mut results = results.into_inner().expect("results");
    results.sort_by_key(|(name, _)| *name);
    println!("| target | inputs run | outcomes | corpus | slowest input | most memory held |");
    for (name, s) in &results {
        println!(
            "| {name} | {} | {} | {} | {:.1} ms | {:.1} MiB |",
            s.runs,
            s.outcomes,
            s.corpus,
            s.slowest.as_secs_f64() * 1e3,
            s.most_memory as f64 / (1 << 20) as f64
        );
    }
    println!("fuzz: no panic, no hang, memory within bounds");
}

/// The input a fuzzing thread is running, for its watchdog.
#[derive(Default)]
struct Watch {
    /// The running input's number + 1; 0 between inputs.
    running: AtomicUsize,
    input: Mutex<Vec<u8>>,
}

impl Watch {
    /// With `RT_FUZZ_TRACE`, each input is also written to `target/fuzz-failures/NAME.last`
    /// before it runs: what a crash that kills the process (a stack overflow) ran on.
    fn start(&self, input: &[u8], number: u64, target: &Target) {
        if std::env::var_os("RT_FUZZ_TRACE").is_some() {
            let dir = repo().join("target/fuzz-failures");
            let _ = std::fs::create_dir_all(&dir);
            let _ = std::fs::write(dir.join(format!("{}.last", target.name)), input);
        }
        *self.input.lock().unwrap_or_else(|p| p.into_inner()) = input.to_vec();
        self.running.store(number as usize + 1, Ordering::SeqCst);
    }
}

/// Runs `work` with a watchdog: an input still running after [`HANG`] is saved and stops
/// the harness (a thread cannot be cancelled).
fn watched(target: &Target, work: impl FnOnce() -> Summary + Send, watch: &Watch) -> Summary {
    let done = std::sync::atomic::AtomicBool::new(false);
    std::thread::scope(|scope| {
        let watchdog = scope.spawn(|| {
            let mut running_since: Option<(usize, Instant)> = None;
            while !done.load(Ordering::SeqCst) {
                std::thread::sleep(Duration::from_millis(100));
                let now = watch.running.load(Ordering::SeqCst);
                running_since = match (now, running_since) {
                    (0, _) => None,
                    (n, Some((m, since))) if n == m => Some((m, since)),
                    (n, _) => Some((n, Instant::now())),
                };
                if running_since.is_some_and(|(_, since)| since.elapsed() > HANG) {
                    let input = watch.input.lock().unwrap_or_else(|p| p.into_inner()).clone();
                    fail(target, &input, &format!("a hang (still running after {HANG:?})"));
                }
            }
        });
        let summary = work();
        done.store(true, Ordering::SeqCst);
        let _ = watchdog.join();
        summary
    })
}
