//! `[sky] kind = "environment"`: an equirectangular image around the scene, as Blender's
//! World with an Environment Texture. The image is read and sampled in `src/sky/`.

use super::parse::{SceneError, Seg, Source};
use super::schema;
use glam::Vec3;
use std::path::{Path, PathBuf};

/// An HDRI environment: what a World of Environment Texture → Background holds.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// The equirectangular image (`.exr` or `.hdr`), resolved against the scene's folder.
    pub image: PathBuf,
    /// Multiplies every texel: the Background node's strength.
    pub strength: f32,
    /// The rotation of a Mapping node in front of the texture: XYZ Euler angles in
    /// degrees, about Blender's axes (Z up), applied to the direction before the lookup.
    pub rotation_deg: Vec3,
    /// Whether light samples follow the image's brightness (else uniform over the sphere).
    pub importance_sampling: bool,
    /// The texels are sRGB codes (an image whose Color Space in Blender is sRGB, float
    /// ones included): looked up as they are and decoded after, as Cycles filters them.
    pub srgb: bool,
}

/// The keys of `[sky]` that only an environment takes, to refuse them for other kinds.
pub(super) fn keys_present(s: &schema::Sky) -> Option<&'static str> {
    let present = [
        ("image", s.image.is_some()),
        ("strength", s.strength.is_some()),
        ("rotation_deg", s.rotation_deg.is_some()),
        ("importance_sampling", s.importance_sampling.is_some()),
        ("color_space", s.color_space.is_some()),
    ];
    present.iter().find(|(_, on)| *on).map(|(key, _)| *key)
}

pub(super) fn validate(src: &Source, p: &[Seg], s: &schema::Sky, base_dir: &Path) -> Result<Environment, SceneError> {
    let image = match s.image.as_deref() {
        None => return Err(src.error(p, "image", "is required with kind = \"environment\"")),
        Some("") => return Err(src.error(p, "image", "must name an .exr or .hdr file, got \"\"")),
        Some(name) => base_dir.join(name),
    };
    let strength = s.strength.unwrap_or(1.0);
    src.check(p, "strength", &[strength], "non-negative", |v| v >= 0.0)?;
    let rotation = s.rotation_deg.unwrap_or([0.0; 3]);
    src.finite(p, "rotation_deg", &rotation)?;
    let srgb = match s.color_space.as_deref() {
        None | Some("linear") => false,
        Some("srgb") => true,
        Some(other) => {
            return Err(src.error(p, "color_space", format!("must be \"linear\" or \"srgb\", got \"{other}\"")));
        }
    };
    Ok(Environment {
        srgb,
        image,
        strength,
        rotation_deg: rotation.into(),
        importance_sampling: s.importance_sampling.unwrap_or(true),
    })
}
