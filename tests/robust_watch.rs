//! `rt watch --headless` leaves nothing that spoils the next run: the stop file is
//! consumed when obeyed and a stale one is removed at start (with a log line), and the
//! previous run's log is kept as `watch.log.1` rather than truncated.

use crate::common;

use common::bounded::{fresh_dir, names, run};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

const DEADLINE: Duration = Duration::from_secs(120);

fn watch(dir: &Path, extra: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rt"));
    command
        .args(["watch", "--headless", "--frames-dir", "frames", "--spp", "1", "--size", "16x16", "scene.toml"])
        .args(extra)
        .current_dir(dir);
    command
}

fn project(name: &str) -> std::path::PathBuf {
    let dir = fresh_dir(name);
    std::fs::write(dir.join("scene.toml"), "[[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 0.5\n").expect("scene");
    std::fs::create_dir(dir.join("frames")).expect("frames");
    dir
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn a_stale_stop_file_is_removed_and_the_last_log_kept() {
    let dir = project("stale-stop");
    std::fs::write(dir.join("frames/stop"), "").expect("stale stop file");
    std::fs::write(dir.join("frames/watch.log"), "the previous run\n").expect("old log");
    let outcome = run(watch(&dir, &["--max-reloads", "0"]), DEADLINE);
    outcome.expect("stale stop file", 0);
    assert_eq!(names(&dir.join("frames")), ["frame-0000.png", "watch.log", "watch.log.1"]);
    assert_eq!(read(&dir.join("frames/watch.log.1")), "the previous run\n");
    let log = read(&dir.join("frames/watch.log"));
    assert!(log.contains("removed a stale stop file left by an earlier run"), "{log}");
    assert!(log.contains("frame #0 spp=1 file=frame-0000.png"), "{log}");
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn an_obeyed_stop_file_is_consumed_so_the_next_run_goes_on() {
    let dir = project("consumed-stop");
    let running = {
        let command = watch(&dir, &[]);
        std::thread::spawn(move || run(command, DEADLINE))
    };
    let start = Instant::now();
    while !dir.join("frames/frame-0000.png").exists() {
        assert!(start.elapsed() < DEADLINE, "no first frame");
        std::thread::sleep(Duration::from_millis(50));
    }
    std::fs::write(dir.join("frames/stop"), "").expect("stop file");
    running.join().expect("watch run").expect("stopped by the stop file", 0);
    let first_log = read(&dir.join("frames/watch.log"));
    assert!(first_log.contains("stop: the stop file appeared"), "{first_log}");
    assert_eq!(names(&dir.join("frames")), ["frame-0000.png", "watch.log"]);

    std::fs::remove_file(dir.join("frames/frame-0000.png")).expect("remove frame");
    run(watch(&dir, &["--max-reloads", "0"]), DEADLINE).expect("the next run", 0);
    assert_eq!(names(&dir.join("frames")), ["frame-0000.png", "watch.log", "watch.log.1"]);
    assert_eq!(read(&dir.join("frames/watch.log.1")), first_log, "the first run's log is kept whole");
    let log = read(&dir.join("frames/watch.log"));
    assert!(!log.contains("stale stop file") && log.contains("frame #0"), "{log}");
    std::fs::remove_dir_all(&dir).expect("clean up");
}
