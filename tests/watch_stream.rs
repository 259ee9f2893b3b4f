//! `rt watch --stream` driven by a client of the test's own, which reads the protocol as
//! README.md documents it: frames arrive and refine, a camera command shows in the next
//! frames, a size command resizes them, a reload re-reads the scene, a malformed command
//! is reported and ignored, a camera with an aperture blurs by it where it is out of
//! focus, and a client that dies does not kill rt (on the standard streams rt exits
//! cleanly; on a socket the next client is served).

use crate::common;

use common::temp_dir;
use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A dark sphere in front of the camera under a uniform white sky: a camera ray that
/// misses it sees exactly the sky's radiance 1, whatever the samples.
fn scene(dir: &Path, sphere_color: f32) -> PathBuf {
    let path = dir.join("scene.toml");
    let text = format!(
        "[render]\nmax_bounces = 2\n\n[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n\
         fov_y_deg = 30.0\n\n[sky]\nkind = \"uniform\"\ncolor = [1.0, 1.0, 1.0]\n\n[materials.dark]\n\
         base_color = [{sphere_color}, {sphere_color}, {sphere_color}]\n\n\
         [[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"dark\"\n"
    );
    std::fs::write(&path, text).expect("scene file");
    path
}

/// The view matrix, row by row, of a camera at (0, 0, 5) looking along +Z: away from the sphere.
const LOOK_AWAY: &str = "-1,0,0,0, 0,1,0,0, 0,0,-1,5, 0,0,0,1";

fn rt_stream(scene: &Path, spp: u32, extra: &[&str], stderr: &Path) -> Child {
    Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["watch", "--stream", "--size", "24x24", "--spp", &spp.to_string()])
        .args(extra)
        .arg(scene)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(std::fs::File::create(stderr).expect("stderr file"))
        .spawn()
        .expect("start rt watch --stream")
}

#[derive(Debug)]
struct Frame {
    line: u64,
    spp: u32,
    width: u32,
    height: u32,
    rgba: Vec<[f32; 4]>,
}

impl Frame {
    fn at(&self, x: u32, y: u32) -> [f32; 4] {
        self.rgba[(y * self.width + x) as usize]
    }

    fn all_sky(&self) -> bool {
        self.rgba.iter().all(|p| p.iter().all(|&c| (c - 1.0).abs() < 1e-5))
    }
}

/// The test's own client: message lines, frames and their bytes.
struct Client {
    input: Box<dyn Write>,
    output: BufReader<Box<dyn Read>>,
    sent: u64,
    /// Message lines other than frames, in order.
    messages: Vec<String>,
}

impl Client {
    fn new(input: Box<dyn Write>, output: Box<dyn Read>) -> Self {
        let mut client = Self { input, output: BufReader::new(output), sent: 0, messages: Vec::new() };
        let hello = client.line();
        assert!(hello.starts_with("hello rt-stream version=1 "), "{hello}");
        client
    }

    fn of(child: &mut Child) -> Self {
        let input = child.stdin.take().expect("stdin");
        let output = child.stdout.take().expect("stdout");
        Self::new(Box::new(input), Box::new(output))
    }

    /// Sends a line; returns its number.
    fn send(&mut self, line: &str) -> u64 {
        writeln!(self.input, "{line}").and_then(|()| self.input.flush()).expect("rt reads");
        self.sent += 1;
        self.sent
    }

    fn line(&mut self) -> String {
        let mut line = String::new();
        let n = self.output.read_line(&mut line).expect("read from rt");
        assert!(n > 0, "rt closed its output; messages so far: {:?}", self.messages);
        line.trim_end().to_owned()
    }

    /// The next frame, or the next message line.
    fn next(&mut self) -> Result<Frame, String> {
        let line = self.line();
        let Some(fields) = line.strip_prefix("frame ") else {
            return Err(line);
        };
        let field = |name: &str| -> u64 {
            let value = fields.split(' ').find_map(|f| f.strip_prefix(&format!("{name}=")));
            value.and_then(|v| v.parse().ok()).unwrap_or_else(|| panic!("no {name} in {line}"))
        };
        assert!(fields.contains("format=rgba32f"), "{line}");
        let (width, height, bytes) = (field("width") as u32, field("height") as u32, field("bytes") as usize);
        assert_eq!(bytes, (width * height * 16) as usize, "{line}");
        let mut data = vec![0u8; bytes];
        self.output.read_exact(&mut data).expect("the frame's bytes");
        let floats: Vec<f32> = data.chunks_exact(4).map(|b| f32::from_le_bytes(b.try_into().unwrap())).collect();
        let rgba = floats.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]).collect();
        Ok(Frame { line: field("line"), spp: field("spp") as u32, width, height, rgba })
    }

    /// The next frame; the messages before it are kept in `messages`.
    fn frame(&mut self) -> Frame {
        loop {
            match self.next() {
                Ok(frame) => return frame,
                Err(message) => self.messages.push(message),
            }
        }
    }

    /// Frames until one shows line `line` (every command up to it) at `spp`.
    fn frame_after(&mut self, line: u64, spp: u32) -> Frame {
        let deadline = Instant::now() + Duration::from_secs(120);
        loop {
            let frame = self.frame();
            if frame.line >= line && frame.spp >= spp {
                return frame;
            }
            assert!(Instant::now() < deadline, "no frame after line {line} at {spp} spp in 120 s");
        }
    }

    /// The next message that starts with `prefix`, skipping frames.
    fn message(&mut self, prefix: &str) -> String {
        loop {
            if let Some(i) = self.messages.iter().position(|m| m.starts_with(prefix)) {
                return self.messages.remove(i);
            }
            if let Err(message) = self.next() {
                self.messages.push(message);
            }
        }
    }
}

fn wait_exit(child: &mut Child, stderr: &Path) -> std::process::ExitStatus {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        if let Some(status) = child.try_wait().expect("rt's status") {
            let text = std::fs::read_to_string(stderr).unwrap_or_default();
            assert!(!text.contains("panicked"), "rt panicked:\n{text}");
            return status;
        }
        assert!(Instant::now() < deadline, "rt did not exit within 60 s");
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn frames_refine_and_commands_take_effect_in_the_next_frames() {
    let dir = temp_dir("stream-commands");
    let scene = scene(&dir, 0.1);
    let stderr = dir.join("rt.stderr");
    let mut rt = rt_stream(&scene, 4, &[], &stderr);
    let mut client = Client::of(&mut rt);

    let first = client.frame();
    assert_eq!((first.width, first.height, first.line), (24, 24, 0));
    let converged = client.frame_after(0, 4);
    assert_eq!(converged.spp, 4);
    assert!(converged.at(12, 12)[0] < 0.5, "the sphere is dark: {:?}", converged.at(12, 12));
    assert!((converged.at(0, 0)[0] - 1.0).abs() < 1e-5, "the corner is sky: {:?}", converged.at(0, 0));
    assert!(converged.rgba.iter().all(|p| p[3] == 1.0));

    // Every frame that shows the camera command looks away from the sphere: all sky.
    let turned = client.send(&format!("camera view={} fov=30", LOOK_AWAY.replace(' ', "")));
    let frame = client.frame_after(turned, 1);
    assert!(frame.all_sky(), "the first frame after the camera command still shows the sphere");
    let resized = client.send("size 16 8");
    let frame = client.frame_after(resized, 1);
    assert_eq!((frame.width, frame.height), (16, 8));
    assert!(frame.all_sky(), "the camera stays after a resize");
    let spp = client.send("spp 6");
    assert_eq!(client.frame_after(spp, 6).spp, 6);

    // A reload re-reads the scene: looking at the sphere again (the file's camera
    // changed), its new colour shows.
    std::fs::write(&scene, std::fs::read_to_string(&scene).unwrap().replace("fov_y_deg = 30.0", "fov_y_deg = 31.0"))
        .unwrap();
    let scene_text = std::fs::read_to_string(&scene).unwrap().replace("0.1, 0.1, 0.1", "0.9, 0.9, 0.9");
    std::fs::write(&scene, scene_text).unwrap();
    let reload = client.send(&format!("reload {}", scene.display()));
    let frame = client.frame_after(reload, 6);
    let message = client.message("reload ");
    assert!(
        message.starts_with(&format!("reload #1 line={reload} kind=camera+materials cause=scene.toml")),
        "{message}"
    );
    assert!(frame.at(8, 4)[0] > 0.5, "the sphere turned light: {:?}", frame.at(8, 4));

    assert_eq!(client.send("quit"), reload + 1);
    assert_eq!(client.message("bye"), "bye");
    assert!(wait_exit(&mut rt, &stderr).success());
}

#[test]
fn a_malformed_command_is_reported_and_ignored() {
    let dir = temp_dir("stream-errors");
    let scene = scene(&dir, 0.1);
    let stderr = dir.join("rt.stderr");
    let mut rt = rt_stream(&scene, 4, &[], &stderr);
    let mut client = Client::of(&mut rt);
    client.frame_after(0, 4);
    let typo = client.send("camra view=1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1");
    let bad_size = client.send("size 16");
    let no_camera = client.send("camera view=1,0,0,0,0,0,0,0,0,0,1,0,0,0,0,1");
    std::fs::write(&scene, "[render]\nwidht = 3\n").unwrap();
    let broken = client.send("reload scene.toml");
    let fine = client.send("size 16 8");
    let frame = client.frame_after(fine, 4);
    assert_eq!((frame.width, frame.height), (16, 8), "rt went on after the errors");
    assert!(frame.at(8, 4)[0] < 0.5, "the last good scene and camera still render");
    let expected = [
        format!("error line={typo} message=\"unknown command `camra`; did you mean `camera`?\""),
        format!("error line={bad_size} message=\"size takes a width and a height: `size 640 480`\""),
        format!("error line={no_camera} message=\"view: determinant 0: not a rotation and a translation\""),
    ];
    for line in expected {
        assert_eq!(client.message("error "), line);
    }
    let reload_error = client.message("error ");
    assert!(
        reload_error.starts_with(&format!("error line={broken} message=\""))
            && reload_error.contains("unknown key `widht` in [render]; did you mean `width`?"),
        "{reload_error}"
    );
    client.send("quit");
    assert!(wait_exit(&mut rt, &stderr).success());
}

#[test]
fn a_client_that_dies_on_the_standard_streams_ends_rt_cleanly() {
    let dir = temp_dir("stream-dead-stdio");
    let scene = scene(&dir, 0.1);
    let stderr = dir.join("rt.stderr");
    // Many samples: rt is still sending frames when the client goes.
    let mut rt = rt_stream(&scene, 100_000, &[], &stderr);
    let mut client = Client::of(&mut rt);
    client.frame();
    // Half a frame read, then the client is gone: rt's next write meets a closed pipe.
    let mut header = String::new();
    client.output.read_line(&mut header).expect("a header");
    drop(client);
    let status = wait_exit(&mut rt, &stderr);
    assert!(status.success(), "rt: {status}\n{}", std::fs::read_to_string(&stderr).unwrap_or_default());
}

#[cfg(unix)]
#[test]
fn a_client_that_dies_on_the_socket_leaves_rt_serving_the_next() {
    use std::os::unix::net::UnixStream;
    let dir = temp_dir("stream-dead-socket");
    let scene = scene(&dir, 0.1);
    let stderr = dir.join("rt.stderr");
    let socket = dir.join("rt.sock");
    let _ = std::fs::remove_file(&socket);
    let mut rt = rt_stream(&scene, 100_000, &["--socket", socket.to_str().unwrap()], &stderr);
    let deadline = Instant::now() + Duration::from_secs(120);
    let connect = || loop {
        match UnixStream::connect(&socket) {
            Ok(stream) => return stream,
            Err(_) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(50)),
            Err(e) => panic!("{}: {e}", socket.display()),
        }
    };
    let stream = connect();
    let mut first = Client::new(Box::new(stream.try_clone().unwrap()), Box::new(stream));
    let turned = first.send(&format!("camera view={} fov=30", LOOK_AWAY.replace(' ', "")));
    first.frame_after(turned, 1);
    drop(first);

    let stream = connect();
    let mut second = Client::new(Box::new(stream.try_clone().unwrap()), Box::new(stream));
    let frame = second.frame();
    assert!(frame.all_sky(), "the next client sees the scene as the last one left it");
    let resized = second.send("size 8 8");
    assert_eq!(second.frame_after(resized, 1).width, 8);
    second.send("quit");
    assert_eq!(second.message("bye"), "bye");
    assert!(wait_exit(&mut rt, &stderr).success());
    assert!(!socket.exists(), "rt removes its socket");
}

/// The fraction of a pixel's thin-lens camera rays that meet the test scene's sphere
/// (radius 1, 5 m ahead), as rt makes the rays: a point of the pixel on the image plane
/// at distance 1 (`half` its half extent), a point of the round aperture of `radius`, and
/// the ray from that point through where the pinhole ray meets the plane `focus` ahead.
/// A 6×6 grid over the pixel and 8 rings × 16 spokes of equal area over the aperture.
fn hit_fraction(x: u32, y: u32, size: u32, half: f64, radius: f64, focus: f64) -> f64 {
    let (mut hits, mut rays) = (0, 0);
    for (jx, jy) in (0..36).map(|k| ((k % 6) as f64 + 0.5, (k / 6) as f64 + 0.5)) {
        let px = ((x as f64 + jx / 6.0) / size as f64 * 2.0 - 1.0) * half;
        let py = -((y as f64 + jy / 6.0) / size as f64 * 2.0 - 1.0) * half;
        for (ring, spoke) in (0..128).map(|k| (k / 16, k % 16)) {
            let r = radius * ((ring as f64 + 0.5) / 8.0).sqrt();
            let phi = (spoke as f64 + 0.5) / 16.0 * std::f64::consts::TAU;
            let origin = [r * phi.cos(), r * phi.sin(), 0.0];
            let d = [px * focus - origin[0], py * focus - origin[1], focus];
            // The sphere's centre (0, 0, 5) seen from the origin; the ray misses it when the
            // centre lies farther than 1 from the ray's line.
            let c = [-origin[0], -origin[1], 5.0];
            let along = (c[0] * d[0] + c[1] * d[1] + c[2] * d[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            let closest = (0..3).map(|i| (c[i] - along * d[i]).powi(2)).sum::<f64>();
            hits += usize::from(closest < 1.0);
            rays += 1;
        }
    }
    hits as f64 / rays as f64
}

/// A camera command from a viewport looking through a camera with depth of field: the
/// sphere's edge blurs by the aperture sent, focused where the command says. At 256 spp a
/// pixel a tenth of whose rays meet the dark sphere stays at the sky's 1 with probability
/// 0.9^256 < 1e-11; a pixel whose rays (and its neighbours') all miss is exactly 1.
#[test]
fn a_camera_with_an_aperture_blurs_what_lies_off_its_focus() {
    let dir = temp_dir("stream-aperture");
    let scene = scene(&dir, 0.1);
    let stderr = dir.join("rt.stderr");
    const SPP: u32 = 256;
    const SIZE: u32 = 24;
    let mut rt = rt_stream(&scene, SPP, &[], &stderr);
    let mut client = Client::of(&mut rt);
    client.frame_after(0, SPP);
    // Blender's window matrix for a 30° square view, as the viewport sends it.
    let half = 15f64.to_radians().tan();
    let s = 1.0 / half;
    let projection = format!("{s},0,0,0,0,{s},0,0,0,0,-1.001,-0.2,0,0,-1,0");
    let view = "1,0,0,0,0,1,0,0,0,0,1,-5,0,0,0,1";
    let radius = 0.4;
    // Far: the edge (4.8 m away) blurs by radius·(1/4.8 − 1/100) ≈ 3.6 pixels. At the edge: sharp.
    let (far_focus, edge_focus) = (100.0, 4.8);
    let fraction = |x: u32, y: u32, radius: f64, focus: f64| hit_fraction(x, y, SIZE, half, radius, focus);
    // No ray of the pixel or of its neighbours meets the sphere.
    let certainly_sky = |x: u32, y: u32, radius: f64, focus: f64| {
        (x.saturating_sub(1)..=(x + 1).min(SIZE - 1))
            .all(|nx| (y.saturating_sub(1)..=(y + 1).min(SIZE - 1)).all(|ny| fraction(nx, ny, radius, focus) == 0.0))
    };
    let pixels = || (0..SIZE * SIZE).map(|k| (k % SIZE, k / SIZE));
    let mut discriminating = 0;
    for focus in [far_focus, edge_focus] {
        let line = client.send(&format!("camera view={view} projection={projection} aperture={radius} focus={focus}"));
        let frame = client.frame_after(line, SPP);
        assert_eq!((frame.width, frame.height), (SIZE, SIZE));
        let (mut blurred, mut sky) = (0, 0);
        for (x, y) in pixels() {
            let value = frame.at(x, y)[0];
            if certainly_sky(x, y, radius, focus) {
                assert!((value - 1.0).abs() < 1e-5, "focus {focus}: ({x}, {y}) should see only sky, got {value}");
                sky += 1;
            }
            let pinhole_sky = certainly_sky(x, y, 0.0, 1.0);
            if fraction(x, y, radius, focus) >= 0.1 {
                assert!(value < 0.999, "focus {focus}: ({x}, {y}) should show the blurred sphere, got {value}");
                blurred += usize::from(pinhole_sky);
            }
            // Sharp at the edge but blurred with a far focus: a pixel that tells the two apart.
            let far_dark = pinhole_sky && fraction(x, y, radius, far_focus) >= 0.1;
            discriminating += usize::from(focus == edge_focus && far_dark && certainly_sky(x, y, radius, focus));
        }
        assert!(sky >= 20, "focus {focus}: only {sky} pixels certainly sky");
        if focus == far_focus {
            assert!(blurred >= 20, "only {blurred} pixels outside the pinhole's sphere are blurred dark");
        }
    }
    assert!(discriminating >= 16, "only {discriminating} pixels tell a far focus from one at the edge");

    // The pinhole again: no aperture, the sharp sphere.
    let line = client.send(&format!("camera view={view} projection={projection}"));
    let frame = client.frame_after(line, SPP);
    for (x, y) in pixels() {
        if certainly_sky(x, y, 0.0, 1.0) && fraction(x, y, radius, far_focus) >= 0.1 {
            assert!((frame.at(x, y)[0] - 1.0).abs() < 1e-5, "a pinhole shows sky at ({x}, {y})");
        }
    }
    client.send("quit");
    assert!(wait_exit(&mut rt, &stderr).success());
}

/// The peak resident memory of process `pid`, in MiB (Linux's VmHWM).
fn peak_mib(pid: u32) -> f64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).expect("/proc status");
    let kib: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .expect("VmHWM");
    kib / 1024.0
}

/// rt's lines, frames' bytes skipped, through a channel: a test never blocks on a read, so an
/// rt that stops answering fails it instead of hanging it.
fn lines_of(mut output: BufReader<std::process::ChildStdout>) -> std::sync::mpsc::Receiver<String> {
    let (lines, received) = std::sync::mpsc::channel::<String>();
    std::thread::spawn(move || {
        let mut line = String::new();
        while output.read_line(&mut line).is_ok_and(|n| n > 0) {
            if let Some(bytes) = line.split(' ').find_map(|f| f.trim().strip_prefix("bytes=")) {
                let mut data = vec![0u8; bytes.parse().unwrap_or(0)];
                if output.read_exact(&mut data).is_err() {
                    return;
                }
            }
            if lines.send(std::mem::take(&mut line)).is_err() {
                return;
            }
        }
    });
    received
}

/// Writes camera lines into `input` as fast as it takes them until `stop`, counting them in
/// `sent`; gives `input` back.
fn flood(
    mut input: std::process::ChildStdin,
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    sent: std::sync::Arc<std::sync::atomic::AtomicU64>,
) -> std::thread::JoinHandle<std::process::ChildStdin> {
    use std::sync::atomic::Ordering;
    std::thread::spawn(move || {
        let batch: String = (0..64)
            .map(|i| format!("camera view=1,0,0,{},0,1,0,0,0,0,1,-5,0,0,0,1 fov=30\n", i as f32 * 1e-3))
            .collect();
        while !stop.load(Ordering::Relaxed) && input.write_all(batch.as_bytes()).is_ok() {
            sent.fetch_add(64, Ordering::Relaxed);
        }
        input
    })
}

/// A client that writes camera lines as fast as it can (reading frames all the while)
/// must not grow rt's memory: each newer camera replaces the one still waiting. Then a
/// bad line is answered at once, and rt exits soon after its input closes.
#[test]
fn a_client_flooding_camera_lines_keeps_rt_small_and_answering() {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
    use std::sync::mpsc::RecvTimeoutError;
    let dir = temp_dir("stream-flood");
    let scene = scene(&dir, 0.1);
    let stderr = dir.join("rt.stderr");
    let mut rt = rt_stream(&scene, 100_000, &[], &stderr);
    let pid = rt.id();
    let input = rt.stdin.take().expect("stdin");
    let received = lines_of(BufReader::new(rt.stdout.take().expect("stdout")));
    let (stop, sent) = (Arc::new(AtomicBool::new(false)), Arc::new(AtomicU64::new(0)));
    let writer = flood(input, stop.clone(), sent.clone());
    let mut frames = 0u32;
    let flood_end = Instant::now() + Duration::from_secs(10);
    while Instant::now() < flood_end {
        match received.recv_timeout(Duration::from_millis(200)) {
            Ok(line) if line.starts_with("frame") => frames += 1,
            Ok(_) | Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => panic!("rt closed its output"),
        }
    }
    stop.store(true, Ordering::Relaxed);
    let sent = sent.load(Ordering::Relaxed);
    let peak = peak_mib(pid);
    eprintln!("{sent} camera lines in 10 s, {frames} frames, rt's peak {peak:.0} MiB");
    assert!(frames >= 3, "{frames} frames while flooded");
    // Several hundred thousand lines were sent; before, each took ~140 bytes queued.
    assert!(peak < 400.0, "rt's peak memory {peak:.0} MiB after {sent} camera lines");

    // A line after the flood is answered within seconds, not after the flood's backlog.
    let asked = Instant::now();
    let deadline = asked + Duration::from_secs(20);
    let mut input = loop {
        assert!(Instant::now() < deadline, "the flood's last writes were not taken in 20 s");
        if writer.is_finished() {
            break writer.join().expect("writer");
        }
        let _ = received.recv_timeout(Duration::from_millis(50));
    };
    writeln!(input, "camra").and_then(|()| input.flush()).expect("rt reads");
    let answer = loop {
        match received.recv_timeout(deadline.saturating_duration_since(Instant::now())) {
            Ok(line) if line.starts_with("error") => break line,
            Ok(_) => {}
            Err(e) => panic!("no answer to a bad line within 20 s after the flood ({e})"),
        }
    };
    assert!(answer.contains("did you mean `camera`"), "{answer}");
    let answered = asked.elapsed();
    drop(input);
    let closed = Instant::now();
    assert!(wait_exit(&mut rt, &stderr).success());
    eprintln!("answered in {answered:?}, exited {:?} after its input closed", closed.elapsed());
    assert!(closed.elapsed() < Duration::from_secs(20), "rt took {:?} to exit", closed.elapsed());
}

/// `--socket PATH` where another rt serves is refused, naming the path, and that server
/// stays reachable; a socket nobody listens on (left by a killed server) is replaced; a
/// file there is not rt's to remove.
#[cfg(unix)]
#[test]
fn a_socket_in_use_is_refused_and_its_server_keeps_it() {
    use std::os::unix::net::{UnixListener, UnixStream};
    let dir = temp_dir("stream-socket-in-use");
    let scene = scene(&dir, 0.1);
    let socket = dir.join("rt.sock");
    let _ = std::fs::remove_file(&socket);
    let path = socket.to_str().expect("UTF-8 path");
    let mut first = rt_stream(&scene, 100_000, &["--socket", path], &dir.join("first.stderr"));
    let deadline = Instant::now() + Duration::from_secs(120);
    let connect = || loop {
        match UnixStream::connect(&socket) {
            Ok(stream) => return Client::new(Box::new(stream.try_clone().expect("clone")), Box::new(stream)),
            Err(_) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(50)),
            Err(e) => panic!("{}: {e}", socket.display()),
        }
    };
    drop(connect());

    let second_err = dir.join("second.stderr");
    let mut second = rt_stream(&scene, 4, &["--socket", path], &second_err);
    assert_eq!(wait_exit(&mut second, &second_err).code(), Some(1));
    let message = std::fs::read_to_string(&second_err).expect("stderr");
    assert!(message.contains(&format!("{path}: another server is listening on this socket")), "{message}");
    let mut client = connect();
    client.frame();
    client.send("quit");
    assert_eq!(client.message("bye"), "bye");
    assert!(wait_exit(&mut first, &dir.join("first.stderr")).success());

    // A socket left behind with nobody listening is replaced.
    drop(UnixListener::bind(&socket).expect("a socket nobody will listen on"));
    let mut third = rt_stream(&scene, 4, &["--socket", path], &dir.join("third.stderr"));
    let mut client = connect();
    client.send("quit");
    assert_eq!(client.message("bye"), "bye");
    assert!(wait_exit(&mut third, &dir.join("third.stderr")).success());

    // A file at the path is refused and kept.
    std::fs::write(&socket, "notes").expect("a file");
    let fourth_err = dir.join("fourth.stderr");
    let mut fourth = rt_stream(&scene, 4, &["--socket", path], &fourth_err);
    assert_eq!(wait_exit(&mut fourth, &fourth_err).code(), Some(1));
    let message = std::fs::read_to_string(&fourth_err).expect("stderr");
    assert!(message.contains("is a file, not a socket"), "{message}");
    assert_eq!(std::fs::read_to_string(&socket).expect("kept"), "notes");
}
