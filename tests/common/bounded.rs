//! Running the `rt` binary as a hostile input would: with a deadline (a blocked read
//! must fail the test, not hang it) and its peak memory measured by the kernel.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

pub struct Outcome {
    /// `None` when it was killed at the deadline, or by a signal.
    pub code: Option<i32>,
    pub timed_out: bool,
    pub stdout: String,
    pub stderr: String,
    /// Peak resident memory (the kernel's `ru_maxrss`), in MiB.
    pub peak_mib: f64,
}

impl Outcome {
    /// Asserts the run ended by itself with `code` and no panic, naming `case`.
    pub fn expect(&self, case: &str, code: i32) -> &Self {
        assert!(!self.timed_out, "{case}: still running at the deadline (blocked?)\n{}", self.stderr);
        assert!(!self.stderr.contains("panicked"), "{case}: rt panicked:\n{}", self.stderr);
        assert_eq!(self.code, Some(code), "{case}: exit status, stderr:\n{}", self.stderr);
        self
    }

    /// Asserts stderr contains every needle.
    pub fn says(&self, case: &str, needles: &[&str]) -> &Self {
        for needle in needles {
            assert!(self.stderr.contains(needle), "{case}: {needle:?} missing from stderr:\n{}", self.stderr);
        }
        self
    }

    pub fn peak_below(&self, case: &str, mib: f64) -> &Self {
        assert!(self.peak_mib < mib, "{case}: peak memory {:.0} MiB, over {mib} MiB", self.peak_mib);
        self
    }
}

/// `rt ARGS` in `dir`, killed after `deadline`.
pub fn rt(dir: &Path, args: &[&str], deadline: Duration) -> Outcome {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rt"));
    command.args(args).current_dir(dir);
    run(command, deadline)
}

pub fn run(command: Command, deadline: Duration) -> Outcome {
    run_signalled(command, deadline, None)
}

/// [`run`], sending `signal` to the process `after` it started (if it still runs).
#[allow(clippy::zombie_processes, reason = "reaped by wait4 below, which also reports its peak memory")]
pub fn run_signalled(mut command: Command, deadline: Duration, signal: Option<(Duration, i32)>) -> Outcome {
    let mut child =
        command.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("start rt");
    let pipe = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut text = String::new();
            let _ = r.read_to_string(&mut text);
            text
        })
    };
    let stdout = pipe(Box::new(child.stdout.take().expect("stdout")));
    let stderr = pipe(Box::new(child.stderr.take().expect("stderr")));
    let pid = child.id() as libc::pid_t;
    let start = Instant::now();
    let mut timed_out = false;
    let mut signalled = false;
    let (status, usage) = loop {
        let mut status = 0;
        // SAFETY: a zeroed rusage is a valid value for wait4 to fill in.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        // SAFETY: `pid` is our child, not yet reaped; the pointers are to live locals.
        let reaped = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if reaped == pid {
            break (status, usage);
        }
        assert!(reaped == 0, "wait4 failed: {}", std::io::Error::last_os_error());
        if let Some((after, number)) = signal
            && !signalled
            && start.elapsed() > after
        {
            // SAFETY: kill has no memory effects; `pid` is our unreaped child.
            unsafe { libc::kill(pid, number) };
            signalled = true;
        }
        if !timed_out && start.elapsed() > deadline {
            timed_out = true;
            let _ = child.kill();
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let code = libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status));
    Outcome {
        code,
        timed_out,
        stdout: stdout.join().unwrap_or_default(),
        stderr: stderr.join().unwrap_or_default(),
        peak_mib: usage.ru_maxrss as f64 / 1024.0,
    }
}

/// The names in `dir`, sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("list folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Makes a FIFO at `path`.
pub fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().expect("run mkfifo");
    assert!(status.success(), "mkfifo {}", path.display());
}

/// A fresh, empty folder for one test.
pub fn fresh_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rt-robust-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("test folder");
    dir
}
