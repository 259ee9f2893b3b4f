//! The viewer's keys and mouse: what each does, and the help that lists them.

use glam::Vec3;
use winit::event::MouseButton;
use winit::keyboard::KeyCode;

pub const HELP: &str = "\
rt watch keys and mouse:
  left drag            orbit about the point looked at
  right drag           look around
  middle / shift+left  pan
  wheel                dolly towards the point looked at
  W A S D  Q E         fly forward, left, back, right, down, up (shift: 5x faster)
  arrows up/down       sun elevation +/- 2 deg; left/right: azimuth -/+ 5 deg
  + / -                exposure +/- 0.5 EV
  F                    focus (with depth of field) on what is under the mouse
  R                    back to the scene file's camera, sun and exposure
  P / X                screenshot: PNG as shown / linear EXR
  N                    denoised / raw image (with --denoise)
  H                    this help
  Esc                  quit";

/// What a key press does (fly keys are held, see [`fly_direction`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    Sun { elevation: f32, azimuth: f32 },
    Exposure(f32),
    Focus,
    Reset,
    ScreenshotPng,
    ScreenshotExr,
    ToggleDenoise,
    Help,
    Quit,
}

pub fn action(key: KeyCode) -> Option<Action> {
    Some(match key {
        KeyCode::ArrowUp => Action::Sun { elevation: 2.0, azimuth: 0.0 },
        KeyCode::ArrowDown => Action::Sun { elevation: -2.0, azimuth: 0.0 },
        KeyCode::ArrowLeft => Action::Sun { elevation: 0.0, azimuth: -5.0 },
        KeyCode::ArrowRight => Action::Sun { elevation: 0.0, azimuth: 5.0 },
        KeyCode::Equal | KeyCode::NumpadAdd => Action::Exposure(0.5),
        KeyCode::Minus | KeyCode::NumpadSubtract => Action::Exposure(-0.5),
        KeyCode::KeyF => Action::Focus,
        KeyCode::KeyR => Action::Reset,
        KeyCode::KeyP => Action::ScreenshotPng,
        KeyCode::KeyX => Action::ScreenshotExr,
        KeyCode::KeyN => Action::ToggleDenoise,
        KeyCode::KeyH | KeyCode::F1 => Action::Help,
        KeyCode::Escape => Action::Quit,
        _ => return None,
    })
}

/// The fly direction (right, up, forward) of the keys held; zero when none is.
pub fn fly_direction(held: &[KeyCode]) -> Vec3 {
    let mut d = Vec3::ZERO;
    for key in held {
        d += match key {
            KeyCode::KeyW => Vec3::Z,
            KeyCode::KeyS => Vec3::NEG_Z,
            KeyCode::KeyD => Vec3::X,
            KeyCode::KeyA => Vec3::NEG_X,
            KeyCode::KeyE => Vec3::Y,
            KeyCode::KeyQ => Vec3::NEG_Y,
            _ => Vec3::ZERO,
        };
    }
    d.normalize_or_zero()
}

/// What dragging with a button does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Drag {
    Orbit,
    Look,
    Pan,
}

pub fn drag(button: MouseButton, shift: bool) -> Option<Drag> {
    match button {
        MouseButton::Left if shift => Some(Drag::Pan),
        MouseButton::Left => Some(Drag::Orbit),
        MouseButton::Right => Some(Drag::Look),
        MouseButton::Middle => Some(Drag::Pan),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_map_to_actions_and_flight() {
        assert_eq!(action(KeyCode::KeyR), Some(Action::Reset));
        assert_eq!(action(KeyCode::KeyW), None);
        assert_eq!(fly_direction(&[KeyCode::KeyW]), Vec3::Z);
        assert_eq!(fly_direction(&[KeyCode::KeyW, KeyCode::KeyS]), Vec3::ZERO);
        assert_eq!(drag(MouseButton::Left, true), Some(Drag::Pan));
    }
}
