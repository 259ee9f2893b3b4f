//! What the viewer's keys and mouse do to the view: camera moves, the sun, exposure,
//! reset, screenshots (the bindings themselves are in `input`).

use super::camera_control::{fly, look, orbit, pan, turn_sun};
use super::input::{Action, Drag, HELP, action, fly_direction};
use super::live::Overrides;
use super::viewer::Viewer;
use crate::scene::Camera;
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
                self.pending_reset = true;
            }
            Action::Exposure(ev) => overrides.exposure = Some(self.live.scene().render.exposure + ev),
            Action::Reset => {
                self.pending_reset |= overrides.camera.is_some() || overrides.sun.is_some();
                overrides = Overrides::default();
            }
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
            Action::Quit => {
                event_loop.exit();
                return;
            }
        }
        self.live.set_overrides(overrides);
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

    pub(super) fn move_camera(&mut self, to: impl FnOnce(&Camera) -> Camera) {
        let mut overrides = self.live.overrides().clone();
        overrides.camera = Some(to(&self.live.scene().camera));
        self.live.set_overrides(overrides);
        self.pending_reset = true;
        self.request_redraw();
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
        let g = &self.live.renderer.geometry;
        let size = (g.bounds_max - g.bounds_min).length();
        let speed = if size.is_finite() && size > 0.0 { size / 4.0 } else { 1.0 };
        let boost = if self.shift { 5.0 } else { 1.0 };
        self.move_camera(|c| fly(c, direction * speed * boost * dt));
    }
}
