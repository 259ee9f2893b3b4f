//! `rt watch SCENE --stream`: no window; a client (Blender's viewport, a test) drives the
//! scene with command lines and receives each refinement of the image as a frame.
//!
//! The transport is the standard streams of rt, or with `--socket PATH` a Unix socket
//! that serves one client after another (a client that dies leaves rt and its scene up
//! for the next). rt → client, text lines, `frame` ones followed by their bytes:
//!
//! ```text
//! hello rt-stream version=1 width=640 height=480 spp=64
//! frame line=3 spp=4 width=640 height=480 format=rgba32f bytes=4915200
//! reload #1 line=5 kind=asset cause=cube.gltf ms=12.0
//! error line=6 message="unknown command `camra`; did you mean `camera`?"
//! bye
//! ```
//!
//! A frame is the mean radiance so far, linear, as little-endian f32 RGBA, rows from the
//! top; alpha is 1, or with a transparent film the share of the pixel the scene covers (the
//! colour premultiplied by it, as Blender draws it); `line=L` says it shows every command up to the client's line L (a bad
//! one is answered by its error line, and changes nothing). Frames
//! follow each dispatch until the state reaches its spp. client → rt, one command a line:
//!
//! ```text
//! camera view=<16 numbers> [lens=MM sensor=W,H fit=auto|horizontal|vertical | fov=DEG
//!        | ortho=SCALE | projection=<16 numbers>] [shift=X,Y]
//!        [aperture=RADIUS focus=METRES [blades=N] [blade_rotation=DEG] [aperture_ratio=R]]
//! size WIDTH HEIGHT
//! reload [FILE...]
//! spp N
//! quit
//! ```
//!
//! Matrices are row by row; `view` maps rt's world (Y up) to the camera (looking down −Z,
//! +Y up); `projection` is an OpenGL projection matrix such as Blender's `window_matrix`.

mod command;
mod connection;
pub mod latency;
mod view;

pub use command::Command;

/// The commands in `input` as rt reads a client's lines (long lines refused, blank ones
/// and comments skipped): for the fuzzing harness.
pub fn read_commands(input: &[u8]) -> Vec<Result<Command, String>> {
    let mut reader = std::io::BufReader::new(input);
    std::iter::from_fn(|| connection::read_command(&mut reader)).flatten().collect()
}

/// The protocol's fuzz target (beside the renderer's, `rt::fuzz::targets`): lines read as
/// rt reads them, each parsed as a command.
pub const FUZZ_TARGET: rt::fuzz::Target = rt::fuzz::Target::new("stream", true, 0, fuzz_commands);

/// Every fuzz target the harnesses run: the renderer's parsers and this protocol's.
pub fn fuzz_targets() -> Vec<&'static rt::fuzz::Target> {
    rt::fuzz::targets().iter().chain([&FUZZ_TARGET]).collect()
}

fn fuzz_commands(_: &rt::fuzz::Workspace, input: &[u8]) -> Result<(), String> {
    let errors = read_commands(input).into_iter().filter_map(Result::err).count();
    if errors == 0 { Ok(()) } else { Err(format!("{errors} refused lines")) }
}

use super::WatchOptions;
use super::live::LiveScene;
use super::sources::names;
use anyhow::{Context, Result};
use connection::{Connection, Gone};
use rt::gpu::{GpuContext, ms};
use rt::render::{Image, Pacing};
use std::path::Path;
use std::time::Duration;

/// The protocol's version, in the hello line.
pub const VERSION: u32 = 1;

/// Dispatches aim at a viewport's frame rate.
const PACING: Pacing = Pacing { target: Duration::from_millis(50), max_samples: 64 };

/// How one client's session ended.
enum Ended {
    Quit,
    Gone,
}

/// Serves `options.scene` to one client on the standard streams, or to clients of the
/// Unix socket at `socket` one after another, until a client says `quit` (or, on the
/// standard streams, goes away).
pub fn run(ctx: &GpuContext, options: &WatchOptions, socket: Option<&Path>) -> Result<()> {
    let mut live = LiveScene::open(ctx, options)?;
    live.session.set_pacing(PACING);
    let Some(path) = socket else {
        serve(&mut live, Connection::new(std::io::stdin(), std::io::stdout()))?;
        return Ok(());
    };
    let listening = bind(path)?;
    eprintln!("rt watch --stream: listening on {}", path.display());
    loop {
        let stream = match listening.listener.accept() {
            Ok((stream, _)) => stream,
            Err(e) => break Err(e).with_context(|| format!("{}: cannot accept a client", path.display())),
        };
        let input = match stream.try_clone() {
            Ok(input) => input,
            Err(e) => break Err(e).context("cannot read from the client's socket"),
        };
        match serve(&mut live, Connection::new(input, stream)) {
            Ok(Ended::Quit) => break Ok(()),
            Ok(Ended::Gone) => eprintln!("rt watch --stream: the client left; waiting for the next"),
            Err(e) => break Err(e),
        }
    }
}

/// The socket rt listens on, removed when rt stops if it is still the one rt made.
struct Listening {
    listener: std::os::unix::net::UnixListener,
    path: std::path::PathBuf,
    identity: Option<(u64, u64)>,
}

impl Drop for Listening {
    fn drop(&mut self) {
        if self.identity.is_some() && identity(&self.path) == self.identity {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// The device and inode of what is at `path`, if anything.
fn identity(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    std::fs::symlink_metadata(path).ok().map(|m| (m.dev(), m.ino()))
}

/// Listens at `path`. A socket there that a server answers is in use and refused; one
/// that nothing answers was left by a killed server and is replaced; anything else
/// there is not rt's to remove.
fn bind(path: &Path) -> Result<Listening> {
    use std::os::unix::fs::FileTypeExt;
    use std::os::unix::net::{UnixListener, UnixStream};
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_socket() => match UnixStream::connect(path) {
            Ok(_) => anyhow::bail!(
                "{}: another server is listening on this socket; stop it or give rt another --socket path",
                path.display()
            ),
            Err(e) if e.kind() == std::io::ErrorKind::ConnectionRefused => {
                log::info!("{}: replacing a socket that no server listens on", path.display());
                std::fs::remove_file(path)
                    .with_context(|| format!("{}: cannot remove the dead socket", path.display()))?;
            }
            Err(e) => anyhow::bail!(
                "{}: cannot tell whether a server listens on this socket ({e}); remove it if none does",
                path.display()
            ),
        },
        Ok(m) => anyhow::bail!(
            "{}: is {}, not a socket; rt will not replace it (give another --socket path)",
            path.display(),
            rt::files::input::describe(m.file_type())
        ),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(e).with_context(|| format!("{}: cannot look at this path", path.display())),
    }
    let listener = UnixListener::bind(path).with_context(|| format!("{}: cannot listen there", path.display()))?;
    Ok(Listening { listener, path: path.to_path_buf(), identity: identity(path) })
}

/// One client's session: its commands applied as they come, frames sent after each dispatch.
fn serve(live: &mut LiveScene, mut client: Connection) -> Result<Ended> {
    match serve_client(live, &mut client) {
        Ok(ended) => Ok(ended),
        Err(Failure::Gone(Gone)) => Ok(Ended::Gone),
        Err(Failure::Render(e)) => {
            // The client hears why rt stops, if it still listens.
            let _ = client.line(&error_line(None, &format!("{e:#}")));
            Err(e)
        }
    }
}

enum Failure {
    Gone(Gone),
    Render(anyhow::Error),
}

impl From<Gone> for Failure {
    fn from(gone: Gone) -> Self {
        Failure::Gone(gone)
    }
}

impl From<anyhow::Error> for Failure {
    fn from(e: anyhow::Error) -> Self {
        Failure::Render(e)
    }
}

fn serve_client(live: &mut LiveScene, client: &mut Connection) -> Result<Ended, Failure> {
    let request = live.session.request();
    client.line(&format!(
        "hello rt-stream version={VERSION} width={} height={} spp={}",
        request.width, request.height, request.spp
    ))?;
    // A client that joins a converged scene gets its image at once.
    let mut frame_due = live.session.samples() > 0;
    let mut shown_line = 0;
    loop {
        // Waits for a command only when there is nothing to refine or send.
        let batch = client.incoming.take(live.session.converged() && !frame_due);
        for (line, command) in batch.lines {
            match command {
                Err(message) => {
                    client.line(&error_line(Some(line), &message))?;
                    shown_line = line;
                }
                Ok(Command::Quit) => {
                    log::info!("stream: quit at line {line}");
                    client.line("bye")?;
                    return Ok(Ended::Quit);
                }
                Ok(command) => {
                    if let Err(e) = apply(live, client, line, command)? {
                        client.line(&error_line(Some(line), &format!("{e:#}")))?;
                    }
                    shown_line = line;
                    frame_due = true;
                }
            }
        }
        if batch.closed {
            return Ok(Ended::Gone);
        }
        if !live.session.converged() {
            live.session.step(None)?;
            frame_due = true;
        }
        if frame_due {
            let image = live.session.image()?;
            let header = format!(
                "frame line={shown_line} spp={} width={} height={} format=rgba32f",
                image.samples, image.width, image.height
            );
            client.frame(&header, &rgba32f(&image))?;
            frame_due = false;
        }
    }
}

/// Applies a command; the inner error is the client's (refused, nothing changed).
fn apply(live: &mut LiveScene, client: &mut Connection, line: u64, command: Command) -> Result<Result<()>, Gone> {
    Ok(match command {
        Command::Camera(camera) => {
            let mut overrides = live.overrides().clone();
            overrides.camera = Some(camera);
            live.set_overrides(overrides)
        }
        Command::Size { width, height } => {
            live.session.check_image_size(width, height).and_then(|()| live.set_window_size(width, height))
        }
        Command::Spp(spp) => live.set_spp(spp),
        Command::Reload(files) => match live.reload(&files) {
            Ok(report) => {
                let kind = report.reload.kind();
                client.line(&format!(
                    "reload #{} line={line} kind={kind} cause={} ms={:.1}",
                    report.number,
                    names(&files),
                    ms(report.elapsed)
                ))?;
                Ok(())
            }
            Err(e) => Err(e),
        },
        Command::Quit => Ok(()),
    })
}

fn error_line(line: Option<u64>, message: &str) -> String {
    let message = message.replace(['\n', '"'], " ");
    match line {
        Some(line) => format!("error line={line} message=\"{message}\""),
        None => format!("error message=\"{message}\""),
    }
}

/// The image as the protocol's frame bytes: little-endian f32 RGBA, rows from the top; the
/// alpha of a transparent film's image, else 1.
fn rgba32f(image: &Image) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(image.pixels.len() * 16);
    for (i, p) in image.pixels.iter().enumerate() {
        let alpha = image.alpha.as_ref().and_then(|a| a.get(i)).copied().unwrap_or(1.0);
        for c in [p[0], p[1], p[2], alpha] {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    bytes
}

#[cfg(test)]
mod frame_tests {
    use super::*;

    /// A transparent film's frame carries its coverage as alpha; an opaque one's is 1.
    #[test]
    fn frames_carry_the_films_alpha() {
        let mut image = Image {
            width: 2,
            height: 1,
            samples: 4,
            pixels: vec![[0.5, 0.25, 0.125], [0.0; 3]],
            std_error: vec![0.0; 2],
            sample_counts: vec![4; 2],
            alpha: None,
        };
        let alphas = |bytes: Vec<u8>| -> Vec<f32> {
            bytes.chunks(16).map(|p| f32::from_le_bytes([p[12], p[13], p[14], p[15]])).collect()
        };
        assert_eq!(alphas(rgba32f(&image)), [1.0, 1.0]);
        image.alpha = Some(vec![0.75, 0.0]);
        assert_eq!(alphas(rgba32f(&image)), [0.75, 0.0]);
        assert_eq!(f32::from_le_bytes(rgba32f(&image)[0..4].try_into().unwrap()), 0.5);
    }
}
