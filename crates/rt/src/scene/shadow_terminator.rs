//! An object's Shadow Terminator settings (Blender's Object > Shading > Shadow Terminator),
//! which Cycles applies to smooth-shaded low-poly meshes: `[[mesh]]` and `[[instances]]`
//! entries carry them as `shadow_terminator_geometry_offset` and
//! `shadow_terminator_shading_offset`.

use super::parse::{SceneError, Seg, Source};

/// The two offsets of one object, each in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowTerminator {
    /// Shadow rays from smooth-shaded triangles within about this cosine of the
    /// terminator start from the smooth surface that the normals describe (0: never).
    pub geometry_offset: f32,
    /// Pushes the terminator towards the light: the lobes' cosine falls to zero before the
    /// horizon, at an angle shrunk by [`Self::frequency_multiplier`] (0: no shift).
    pub shading_offset: f32,
}

impl Default for ShadowTerminator {
    /// Blender's defaults.
    fn default() -> Self {
        Self { geometry_offset: 0.1, shading_offset: 0.0 }
    }
}

impl ShadowTerminator {
    /// The factor by which the Shading Offset multiplies the angle to the lobe's normal
    /// (Cycles' object sync: 1 / (1 - offset / 2), so 1 to 2).
    pub fn frequency_multiplier(&self) -> f32 {
        1.0 / (1.0 - 0.5 * self.shading_offset)
    }

    /// The settings of the entry at `p`, each left out being Blender's default; each given
    /// one must lie in [0, 1], as Blender's own do.
    pub(super) fn validate(
        src: &Source,
        p: &[Seg],
        geometry_offset: Option<f32>,
        shading_offset: Option<f32>,
    ) -> Result<Self, SceneError> {
        let default = Self::default();
        let in_unit = |field: &str, value: Option<f32>, default: f32| -> Result<f32, SceneError> {
            let v = value.unwrap_or(default);
            src.check(p, field, &[v], "in [0, 1]", |v| (0.0..=1.0).contains(&v))?;
            Ok(v)
        };
        Ok(Self {
            geometry_offset: in_unit("shadow_terminator_geometry_offset", geometry_offset, default.geometry_offset)?,
            shading_offset: in_unit("shadow_terminator_shading_offset", shading_offset, default.shading_offset)?,
        })
    }
}
