//! What the viewer's keys and mouse do to the view: camera moves, the sun, exposure,
//! reset, screenshots (the bindings themselves are in `input`).

use super::camera_control::{fly, look, orbit, pan, turn_sun};
use super::input::{Action, Drag, HELP, action, fly_direction};
use super::live::Overrides;
use super::viewer::Viewer;
use rt::layout::{EMPTY_LINK, GpuTraceRay};
use rt::scene::{Camera, DepthOfField};
use std::time::Instant;
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::KeyCode;

impl Viewer<'_> {
    pub(super) fn key(&mut self, event_loop: &ActiveEventLoop, key: KeyCode) {
        let Some(action) = action(key) else { return };
        let mut overrides = self.live.overrides().clone();
        match action {
            Action::Sun { elevation, azimuth } => {
                let Some(sun) = &self.live.scene().sun else {
                    self.log.write("the scene has no [sun] to turn");
                    return;
                };
                overrides.sun = Some(turn_sun(sun, elevation, azimuth));
            }
            Action::Exposure(ev) => overrides.exposure = Some(self.live.scene().render.exposure + ev),
            Action::Reset => overrides = Overrides::default(),
            Action::ScreenshotPng | Action::ScreenshotExr => {
                if let Err(e) = self.screenshot(action == Action::ScreenshotExr) {
                    self.fail(&[], &e);
                }
                return;
            }
            Action::Help => {
                self.log.write(HELP);
                return;
            }
            Action::ToggleDenoise => {
                match &mut self.denoised {
                    Some(view) => view.shown = !view.shown,
                    None => self.log.write("start rt watch with --denoise to see the denoised image"),
                }
                return self.request_redraw();
            }
            Action::Focus => match self.focus_under_cursor() {
                Ok(Some(camera)) => overrides.camera = Some(camera),
                Ok(None) => return,
                Err(e) => return self.fail(&[], &e),
            },
            Action::Quit => {
                event_loop.exit();
                return;
            }
        }
        self.set_overrides(overrides);
    }

    /// Renders with `overrides` from now on (the samples so far are dropped if the view moved).
    fn set_overrides(&mut self, overrides: Overrides) {
        if let Err(e) = self.live.set_overrides(overrides) {
            self.fail(&[], &e);
        }
        self.request_redraw();
    }

    pub(super) fn drag(&mut self, mode: Drag, dx: f32, dy: f32) {
        let (width, height) = self.window.as_ref().map_or((1, 1), |w| (w.config.width, w.config.height));
        match mode {
            Drag::Orbit => self.move_camera(|c| orbit(c, dx, dy)),
            Drag::Look => self.move_camera(|c| look(c, dx, dy)),
            Drag::Pan => self.move_camera(|c| pan(c, dx, dy, width, height)),
        }
    }

    /// The camera focused at the depth of the surface under the mouse (the window's centre
    /// without one), found by the trace program; `None` (and a note) when there is nothing to do.
    /// Cycles focuses a perspective or orthographic camera on a plane across the view, a
    /// panorama on a sphere about the camera.
    fn focus_under_cursor(&mut self) -> anyhow::Result<Option<Camera>> {
        let camera = self.live.scene().camera.clone();
        let Some(dof) = camera.depth_of_field else {
            self.log.write("the camera has no depth of field to focus (set fstop in [camera])");
            return Ok(None);
        };
        let (width, height) = self.window.as_ref().map_or((1, 1), |w| (w.config.width, w.config.height));
        let (x, y) = self.cursor.map_or((width as f32 / 2.0, height as f32 / 2.0), |(x, y)| (x as f32, y as f32));
        let Some((origin, direction)) = camera.pixel_ray(x, y, width, height) else {
            self.log.write("the mouse is outside the panorama's image");
            return Ok(None);
        };
        let ray =
            GpuTraceRay { origin: origin.to_array(), t_max: f32::INFINITY, direction: direction.to_array(), _pad: 0 };
        let hit = self.live.session.trace(&[ray])?[0];
        if hit.primitive == EMPTY_LINK {
            self.log.write("nothing under the mouse to focus on");
            return Ok(None);
        }
        let focus_distance = camera.focus_distance_of(direction, hit.t);
        self.log.write(&format!("focus at {focus_distance:.3} m"));
        Ok(Some(Camera { depth_of_field: Some(DepthOfField { focus_distance, ..dof }), ..camera }))
    }

    pub(super) fn move_camera(&mut self, to: impl FnOnce(&Camera) -> Camera) {
        let mut overrides = self.live.overrides().clone();
        overrides.camera = Some(to(&self.live.scene().camera));
        self.set_overrides(overrides);
    }

    /// Moves by the fly keys held, at a speed that crosses the scene in about 4 s.
    pub(super) fn fly_step(&mut self) {
        let now = Instant::now();
        let dt = (now - self.last_tick).as_secs_f32().min(0.1);
        self.last_tick = now;
        let direction = fly_direction(&self.held);
        if direction == glam::Vec3::ZERO {
            return;
        }
        let g = self.live.session.geometry();
        let size = (g.bounds_max - g.bounds_min).length();
        let speed = if size.is_finite() && size > 0.0 { size / 4.0 } else { 1.0 };
        let boost = if self.shift { 5.0 } else { 1.0 };
        self.move_camera(|c| fly(c, direction * speed * boost * dt));
    }
}
