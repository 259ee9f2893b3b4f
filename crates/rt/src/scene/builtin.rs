//! The default scene, compiled into the binary so that `rt render` with no
//! arguments makes a picture on a fresh machine.

use super::{Scene, SceneError, parse};
use std::path::Path;

/// Paths under this prefix name files embedded in the binary instead of files on disk.
pub const BUILTIN_PREFIX: &str = "<built-in>";

const DEFAULT_SCENE: &str = include_str!("../../../../scenes/cornell_box.toml");

/// `scenes/cornell_box.toml`, whose assets resolve to the embedded copies.
pub fn default_scene() -> Result<Scene, SceneError> {
    let base_dir = Path::new(BUILTIN_PREFIX).join("scenes");
    parse(DEFAULT_SCENE, &format!("{BUILTIN_PREFIX}/scenes/cornell_box.toml"), &base_dir)
}
