//! `rt watch`'s window (winit + a wgpu surface): the running mean, refined every frame,
//! re-rendered as the scene's files change; the title shows spp, samples/s, ms per
//! frame and the last reload, or the error of the last failed one. With `--frames-dir`
//! it also writes each state's display as `frame-NNNN.png` once it reaches `--spp`
//! (with `--denoise`, once the denoise of that image is shown), and stops on `DIR/stop`
//! or `--max-reloads`, like headless mode.

use super::camera_control::dolly;
use super::denoised_view::DenoisedView;
use super::display::Display;
use super::fs_watch::{Batch, FileWatcher};
use super::headless::STOP_FILE;
use super::input::{Action, Drag, HELP, action, drag, fly_direction};
use super::live::LiveScene;
use super::reload_log::ReloadLog;
use super::{WatchOptions, sources};
use anyhow::{Context, Result, anyhow};
use rt::denoise::Denoiser;
use rt::gpu::{GpuContext, ms};
use rt::render::{Accumulation, Pacing, Session, human, write_image, write_png};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

/// GPU time per frame to aim for: 40 fps on a GPU that can.
const PACING: Pacing = Pacing { target: Duration::from_millis(25), max_samples: 64 };
/// How often an idle window with `--frames-dir` looks for the stop file.
const STOP_POLL: Duration = Duration::from_millis(100);

pub fn run(adapter: Option<&str>, options: WatchOptions, denoiser: Option<Denoiser>) -> Result<()> {
    let event_loop = EventLoop::<Batch>::with_user_event().build().context("cannot open a window")?;
    let ctx = GpuContext::new(adapter)?;
    println!("GPU: {}", ctx.describe());
    let mut live = LiveScene::open(&ctx, &options)?;
    live.session.set_pacing(PACING);
    let proxy = event_loop.create_proxy();
    let mut watcher = FileWatcher::start(move |batch| {
        let _ = proxy.send_event(batch);
    })?;
    watcher.watch(&live.watched_files());
    let mut app = Viewer {
        log: ReloadLog::new(options.frames_dir.as_deref())?,
        ctx: &ctx,
        live,
        watcher,
        options,
        window: None,
        state: State { number: 0, since: Instant::now(), first_frame: None, written: false },
        error: None,
        last_reload: String::new(),
        held: Vec::new(),
        shift: false,
        dragging: None,
        cursor: None,
        last_tick: Instant::now(),
        presented: 0,
        screenshots: 0,
        failure: None,
        denoised: None,
    };
    app.log.write(HELP);
    if let Some(denoiser) = denoiser {
        app.log.write(&format!("denoising with Open Image Denoise on {}", denoiser.describe()));
        app.denoised = Some(DenoisedView::new(denoiser));
    }
    if let Some(dir) = app.options.frames_dir.clone() {
        super::headless::remove_stale_stop_file(&dir, &mut app.log);
    }
    event_loop.run_app(&mut app).context("the window's event loop failed")?;
    match app.failure {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// What exists once the window does.
pub(super) struct WindowParts {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    pub(super) config: wgpu::SurfaceConfiguration,
    display: Display,
}

/// The state being refined: which reload made it, and when its edit was seen.
struct State {
    number: u32,
    since: Instant,
    first_frame: Option<Duration>,
    written: bool,
}

pub(super) struct Viewer<'a> {
    ctx: &'a GpuContext,
    pub(super) live: LiveScene<'a>,
    watcher: FileWatcher,
    options: WatchOptions,
    pub(super) log: ReloadLog,
    pub(super) window: Option<WindowParts>,
    state: State,
    /// The last reload's error, shown until a reload succeeds.
    error: Option<String>,
    last_reload: String,
    pub(super) held: Vec<KeyCode>,
    pub(super) shift: bool,
    dragging: Option<Drag>,
    pub(super) cursor: Option<(f64, f64)>,
    pub(super) last_tick: Instant,
    presented: u64,
    screenshots: u32,
    /// Why the window closed on its own, if it did.
    failure: Option<anyhow::Error>,
    /// With `--denoise`: the denoised image, refreshed beside refinement.
    pub(super) denoised: Option<DenoisedView>,
}

impl ApplicationHandler<Batch> for Viewer<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none()
            && let Err(e) = self.open_window(event_loop)
        {
            self.failure = Some(e);
            event_loop.exit();
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, batch: Batch) {
        self.apply(batch);
        self.request_redraw();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => self.resize(size),
            WindowEvent::ModifiersChanged(m) => self.shift = m.state().shift_key(),
            // Keys released while another window has the focus are never reported.
            WindowEvent::Focused(false) => self.held.clear(),
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(key) = event.physical_key else { return };
                self.held.retain(|&k| k != key);
                if event.state == ElementState::Pressed {
                    self.held.push(key);
                    if !event.repeat || matches!(action(key), Some(Action::Sun { .. } | Action::Exposure(_))) {
                        self.key(event_loop, key);
                    }
                }
                self.last_tick = Instant::now();
            }
            WindowEvent::MouseInput { state, button, .. } => {
                self.dragging = (state == ElementState::Pressed).then(|| drag(button, self.shift)).flatten();
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let (Some(mode), Some((x, y))) = (self.dragging, self.cursor) {
                    self.drag(mode, (position.x - x) as f32, (position.y - y) as f32);
                }
                self.cursor = Some((position.x, position.y));
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                self.move_camera(|c| dolly(c, steps));
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame(event_loop) {
                    self.failure = Some(e);
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(stop_file) = self.options.frames_dir.as_ref().map(|d| d.join(STOP_FILE)).filter(|f| f.exists()) {
            let _ = std::fs::remove_file(&stop_file);
            self.log.write("stop: the stop file appeared");
            event_loop.exit();
            return;
        }
        let flying = fly_direction(&self.held) != glam::Vec3::ZERO;
        // A denoise running or due after the last sample: drawn once it is back.
        let denoising = self.denoised.as_ref().is_some_and(|d| d.pending(&self.live.session));
        let refining = self.window.is_some() && (!self.live.session.converged() || denoising);
        if flying || refining {
            self.request_redraw();
        }
        event_loop.set_control_flow(match self.options.frames_dir {
            Some(_) => ControlFlow::WaitUntil(Instant::now() + STOP_POLL),
            None => ControlFlow::Wait,
        });
    }
}

impl Viewer<'_> {
    fn open_window(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let render = &self.live.scene().render;
        let (width, height) = (render.width, render.height);
        let attributes = Window::default_attributes()
            .with_title(format!("rt watch - {}", self.options.scene.display()))
            .with_inner_size(PhysicalSize::new(width, height));
        let window = Arc::new(event_loop.create_window(attributes).context("cannot open a window")?);
        let surface = self.ctx.instance.create_surface(window.clone()).context("cannot draw into the window")?;
        let size = window.inner_size();
        let (width, height) = (size.width.max(1), size.height.max(1));
        let mut config = surface
            .get_default_config(&self.ctx.adapter, width, height)
            .ok_or_else(|| anyhow!("the GPU {} cannot present to this window", self.ctx.adapter_info.name))?;
        // A format that does not encode sRGB itself: the display shader does, as tonemap.rs does.
        let formats = surface.get_capabilities(&self.ctx.adapter).formats;
        config.format = formats.iter().copied().find(|f| !f.is_srgb()).unwrap_or(config.format);
        config.present_mode = wgpu::PresentMode::AutoVsync;
        surface.configure(&self.ctx.device, &config);
        let display = Display::new(self.ctx, config.format, self.live.shader_dir())?;
        self.live.set_window_size(width, height)?;
        self.log.write(&format!("window {width}x{height}, surface {:?}", config.format));
        self.window = Some(WindowParts { window, surface, config, display });
        self.state.since = Instant::now();
        self.request_redraw();
        Ok(())
    }

    pub(super) fn request_redraw(&self) {
        if let Some(w) = &self.window {
            w.window.request_redraw();
        }
    }

    fn resize(&mut self, size: PhysicalSize<u32>) {
        let Some(w) = &mut self.window else { return };
        if size.width == 0 || size.height == 0 || (size.width, size.height) == (w.config.width, w.config.height) {
            return;
        }
        (w.config.width, w.config.height) = (size.width, size.height);
        w.surface.configure(&self.ctx.device, &w.config);
        if let Err(e) = self.live.set_window_size(size.width, size.height) {
            self.fail(&[], &e);
        }
        self.state.written = false;
        self.request_redraw();
    }

    /// Reloads after `batch`; a failure keeps the last good image and shows the error.
    fn apply(&mut self, batch: Batch) {
        match self.live.reload(&batch.paths) {
            Ok(report) => {
                self.log.reload(&report, &batch.paths);
                self.error = None;
                self.last_reload =
                    format!("reload #{} {} {:.0} ms", report.number, report.reload.kind(), ms(report.elapsed));
                let display_changed = report.reload.has(&super::plan::Change::Shaders);
                if let (Some(w), Some(dir)) = (&mut self.window, self.live.shader_dir())
                    && display_changed
                    && let Err(e) = w.display.reload_shader(self.ctx, dir)
                {
                    self.fail(&batch.paths, &e);
                }
                self.state =
                    State { number: report.number, since: batch.first_event, first_frame: None, written: false };
            }
            Err(e) => self.fail(&batch.paths, &e),
        }
        self.watcher.watch(&self.live.watched_files());
    }

    pub(super) fn fail(&mut self, cause: &[PathBuf], error: &anyhow::Error) {
        self.log.error(cause, error);
        self.error = Some(format!("{error:#}"));
    }

    fn frame(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        self.fly_step();
        let ctx = self.ctx;
        let Some(w) = &mut self.window else { return Ok(()) };
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        if self.live.session.samples() == 0 {
            self.state.written = false;
        }
        let samples = self.live.session.encode_step(&mut encoder, None)?;
        let texture = match w.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) | wgpu::CurrentSurfaceTexture::Suboptimal(t) => Some(t),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                w.surface.configure(&ctx.device, &w.config);
                None
            }
            _ => None,
        };
        let exposure = self.live.scene().render.exposure;
        if let Some(texture) = &texture {
            let view = texture.texture.create_view(&Default::default());
            let acc = self.live.session.accumulation();
            let error = self.error.is_some();
            match self.denoised.as_ref().and_then(|d| d.means(&self.live.session)) {
                Some(means) => w.display.encode_from(ctx, &mut encoder, &view, acc, means, exposure, error),
                None => w.display.encode(ctx, &mut encoder, &view, acc, exposure, error),
            }
        }
        let submitted = Instant::now();
        ctx.queue.submit([encoder.finish()]);
        if let Some(texture) = texture {
            ctx.queue.present(texture);
            self.presented += 1;
        }
        ctx.wait()?;
        self.live.session.observe(samples, submitted.elapsed());
        // After the wait: the image sent to the denoiser has the samples it says it has.
        if let Some(denoised) = &mut self.denoised
            && let Err(e) = denoised.update(ctx, &self.live.session)
        {
            self.log.write(&format!("{e:#}; the window shows the raw image from now on"));
            self.denoised = None;
        }
        if self.state.first_frame.is_none() {
            self.state.first_frame = Some(self.state.since.elapsed());
        }
        let mut title = title(&self.options.scene, &self.live.session, &self.last_reload, self.error.as_deref());
        if let Some(d) = &self.denoised {
            title.push_str(if d.means(&self.live.session).is_some() { " | denoised" } else { " | raw" });
        }
        w.window.set_title(&title);
        // A converged state's frame shows its own denoise, not one of fewer samples.
        let denoised = self.denoised.as_ref().is_none_or(|d| !d.shown || d.up_to_date(&self.live.session));
        if self.live.session.converged() && !self.state.written && denoised {
            self.state.written = true;
            self.write_frame(event_loop)?;
        }
        Ok(())
    }

    /// With `--frames-dir`: the display of a converged state, as `frame-NNNN.png`.
    fn write_frame(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let (Some(dir), Some(w)) = (&self.options.frames_dir, &self.window) else { return Ok(()) };
        let file = dir.join(format!("frame-{:04}.png", self.state.number));
        let acc = self.live.session.accumulation();
        let means = self.denoised.as_ref().and_then(|d| d.means(&self.live.session)).unwrap_or(acc.means());
        let pixels = w.display.screenshot(self.ctx, acc, means, self.live.scene().render.exposure)?;
        write_png(&rgb_image(pixels, acc)?, &file)?;
        let first = self.state.first_frame.unwrap_or_default();
        self.log.frame(self.state.number, acc.samples, &file, None, first, self.state.since.elapsed());
        self.log.write(&format!("presented {} frames", self.presented));
        if self.options.max_reloads.is_some_and(|max| self.state.number >= max) {
            event_loop.exit();
        }
        Ok(())
    }

    pub(super) fn screenshot(&mut self, exr: bool) -> Result<()> {
        let Some(w) = &self.window else { return Ok(()) };
        let dir = self.options.frames_dir.clone().unwrap_or_else(|| PathBuf::from("."));
        self.screenshots += 1;
        let file = dir.join(format!("rt-screenshot-{:03}.{}", self.screenshots, if exr { "exr" } else { "png" }));
        let exposure = self.live.scene().render.exposure;
        let acc = self.live.session.accumulation();
        if exr {
            write_image(&self.live.session.image()?, &file, exposure)?;
        } else {
            let means = self.denoised.as_ref().and_then(|d| d.means(&self.live.session)).unwrap_or(acc.means());
            let pixels = w.display.screenshot(self.ctx, acc, means, exposure)?;
            write_png(&rgb_image(pixels, acc)?, &file)?;
        }
        self.log.write(&format!("screenshot {} ({} spp)", file.display(), acc.samples));
        Ok(())
    }
}

fn title(scene: &Path, session: &Session, last_reload: &str, error: Option<&str>) -> String {
    let name = sources::names(&[scene.to_path_buf()]);
    if let Some(error) = error {
        return format!("rt watch - {name} - ERROR: {error}");
    }
    let step = session.last_step();
    let pixels = session.request().width as f64 * session.request().height as f64;
    let rate = step.samples as f64 * pixels / step.took.as_secs_f64().max(1e-9);
    // ASCII only: some window managers draw titles in Latin-1 fonts.
    format!(
        "rt watch - {name} - {}/{} spp | {}samples/s | {:.1} ms/frame{}{last_reload}",
        session.samples(),
        session.request().spp,
        human(rate),
        ms(step.took),
        if last_reload.is_empty() { "" } else { " | " },
    )
}

/// A screenshot's pixels as an image of the accumulation's size.
fn rgb_image(pixels: Vec<[u8; 3]>, acc: &Accumulation) -> Result<image::RgbImage> {
    image::RgbImage::from_raw(acc.width, acc.height, pixels.concat()).context("screenshot size mismatch")
}
