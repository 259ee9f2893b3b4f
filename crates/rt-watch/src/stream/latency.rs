//! `rt bench stream-latency`: how long from a camera command written to `rt watch --stream`
//! to the first frame that shows it, seen by a client on the other end of the pipes, as a
//! viewport sees it: the command's parsing, the accumulation reset, one dispatch, the
//! read-back, and the frame's trip through the pipe (measured on its own too).
//!
//! rt runs as a child process (this executable), exactly as Blender's viewport runs it.

use anyhow::{Context, Result, anyhow, bail};
use rt::gpu::{median, ms};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::time::{Duration, Instant};

/// A frame's header fields.
struct Frame {
    line: u64,
    bytes: usize,
}

/// A client of `rt watch --stream` on the child's pipes.
struct Client {
    child: Child,
    input: ChildStdin,
    output: BufReader<ChildStdout>,
    lines_sent: u64,
    payload: Vec<u8>,
}

impl Client {
    fn start(scene: &Path, (width, height): (u32, u32), spp: u32, adapter: Option<&str>) -> Result<Self> {
        let exe = std::env::current_exe().context("cannot find rt's own executable")?;
        let mut command = Command::new(exe);
        command.arg("watch").arg(scene).args(["--stream", "--spp", &spp.to_string()]);
        command.args(["--size", &format!("{width}x{height}")]);
        if let Some(adapter) = adapter {
            command.args(["--adapter", adapter]);
        }
        let mut child = command.stdin(Stdio::piped()).stdout(Stdio::piped()).spawn().context("cannot start rt")?;
        let input = child.stdin.take().ok_or_else(|| anyhow!("no pipe to rt"))?;
        let output = BufReader::new(child.stdout.take().ok_or_else(|| anyhow!("no pipe from rt"))?);
        Ok(Self { child, input, output, lines_sent: 0, payload: Vec::new() })
    }

    fn send(&mut self, line: &str) -> Result<u64> {
        writeln!(self.input, "{line}").and_then(|()| self.input.flush()).context("rt stopped reading")?;
        self.lines_sent += 1;
        Ok(self.lines_sent)
    }

    /// The next message line.
    fn message(&mut self) -> Result<String> {
        let mut line = String::new();
        if self.output.read_line(&mut line)? == 0 {
            bail!("rt closed its output");
        }
        Ok(line.trim_end().to_owned())
    }

    /// The next frame's header, when it arrived, and how long its bytes took to arrive after it.
    fn frame(&mut self) -> Result<(Frame, Instant, Duration)> {
        loop {
            let line = self.message()?;
            let at = Instant::now();
            if let Some(error) = line.strip_prefix("error ") {
                bail!("rt: {error}");
            }
            let Some(fields) = line.strip_prefix("frame ") else { continue };
            let field = |name: &str| -> Result<u64> {
                fields
                    .split(' ')
                    .find_map(|f| f.strip_prefix(name)?.strip_prefix('='))
                    .and_then(|v| v.parse().ok())
                    .ok_or_else(|| anyhow!("frame header without {name}: {line}"))
            };
            let frame = Frame { line: field("line")?, bytes: field("bytes")? as usize };
            self.payload.resize(frame.bytes, 0);
            self.output.read_exact(&mut self.payload).context("a frame cut short")?;
            return Ok((frame, at, at.elapsed()));
        }
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        let _ = self.send("quit");
        // rt may be blocked writing a frame: it reads the quit once that frame is read.
        let _ = std::io::copy(&mut self.output, &mut std::io::sink());
        let _ = self.child.wait();
    }
}

/// A view matrix (rows) of a camera at `position` looking at `target`, Y up.
fn view_rows(position: glam::Vec3, target: glam::Vec3) -> String {
    let view = super::view::look_at(position, target).transpose();
    view.to_cols_array().iter().map(|v| format!("{v}")).collect::<Vec<_>>().join(",")
}

/// Times camera commands on `scene`, or without one on the scene of `rt bench watch-latency`
/// around `asset`, so that the two benchmarks compare.
pub fn stream_latency(
    scene: Option<&Path>,
    asset: &Path,
    size: (u32, u32),
    runs: u32,
    adapter: Option<&str>,
) -> Result<()> {
    let scratch = rt::files::ScratchDir::new("stream-latency").context("cannot make a scratch folder")?;
    let scene = match scene {
        Some(scene) => scene.to_path_buf(),
        None => {
            let asset = std::path::absolute(asset).with_context(|| format!("{}", asset.display()))?;
            let asset = asset.to_str().ok_or_else(|| anyhow!("{}: not UTF-8", asset.display()))?;
            let path = scratch.path().join("scene.toml");
            let text = super::super::latency::scene_text(&asset.replace('\\', "/"), 0.0, 0.8);
            rt::files::write_atomically(&path, text.as_bytes())?;
            path
        }
    };
    time_camera_commands(&scene, size, runs, adapter)
}

fn time_camera_commands(scene: &Path, size: (u32, u32), runs: u32, adapter: Option<&str>) -> Result<()> {
    let the_scene = rt::scene::load(scene)?;
    let (position, target) = (the_scene.camera.position, the_scene.camera.look_at);
    let mut client = Client::start(scene, size, 256, adapter)?;
    let hello = client.message()?;
    if !hello.starts_with("hello rt-stream") {
        bail!("rt said {hello:?} instead of hello");
    }
    client.frame()?;
    println!("scene     {} at {}x{}, {runs} camera commands, rt a child on pipes", scene.display(), size.0, size.1);
    let (mut latencies, mut transfers) = (Vec::new(), Vec::new());
    let mut bytes = 0;
    for run in 0..runs.max(1) {
        // Small orbits, as a viewport's drag makes; refined a while before the next.
        let angle = 0.02 * (run + 1) as f32;
        let offset = glam::Quat::from_rotation_y(angle) * (position - target);
        std::thread::sleep(Duration::from_millis(150));
        let line = client.send(&format!("camera view={} fov=40", view_rows(target + offset, target)))?;
        let sent = Instant::now();
        loop {
            let (frame, at, transfer) = client.frame()?;
            if frame.line >= line {
                latencies.push(at - sent);
                transfers.push(transfer);
                bytes = frame.bytes;
                break;
            }
        }
    }
    let worst = latencies.iter().max().copied().unwrap_or_default();
    let received: Vec<Duration> = latencies.iter().zip(&transfers).map(|(l, t)| *l + *t).collect();
    println!("camera command -> first new frame: median {:.1} ms, worst {:.1} ms", ms(median(latencies)), ms(worst));
    println!("camera command -> that frame received: median {:.1} ms", ms(median(received)));
    let transfer = median(transfers);
    println!(
        "frame through the pipe ({:.2} MB): median {:.2} ms ({:.0} MB/s)",
        bytes as f64 / 1e6,
        ms(transfer),
        bytes as f64 / 1e6 / transfer.as_secs_f64().max(1e-9)
    );
    Ok(())
}
