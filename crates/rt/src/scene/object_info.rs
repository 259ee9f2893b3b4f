//! What Blender's Object Info node reads of an object besides its place: its Object Color
//! (RGBA, Object › Viewport Display › Color), its Random number, as Cycles sets it
//! (`hash_uint2(hash_string(name), 0)` over 2³² − 1 for an object, the depsgraph's
//! `random_id` for an instance), and its Object Index (Object › Relations › Pass Index).
//! Scene keys `object_color`, `random` and `object_index` of a `[[mesh]]` or
//! `[[instances]]` entry.

use super::parse::{SceneError, Seg, Source};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectInfo {
    pub color: [f32; 4],
    /// In [0, 1].
    pub random: f32,
    /// Blender's Pass Index, at most [`MAX_OBJECT_INDEX`].
    pub index: u32,
}

/// The largest Pass Index Blender gives an object.
pub const MAX_OBJECT_INDEX: u32 = 32767;

impl Default for ObjectInfo {
    fn default() -> Self {
        Self { color: [1.0; 4], random: 0.0, index: 0 }
    }
}

impl ObjectInfo {
    pub(super) fn validate(
        src: &Source,
        p: &[Seg],
        color: Option<[f32; 4]>,
        random: Option<f32>,
        index: Option<u32>,
    ) -> Result<Self, SceneError> {
        let default = Self::default();
        let info = Self {
            color: color.unwrap_or(default.color),
            random: random.unwrap_or(default.random),
            index: index.unwrap_or(default.index),
        };
        src.finite(p, "object_color", &info.color)?;
        src.check(p, "random", &[info.random], "in [0, 1]", |r| (0.0..=1.0).contains(&r))?;
        let most = format!("at most {MAX_OBJECT_INDEX} (Blender's Pass Index)");
        src.check(p, "object_index", &[info.index as f32], &most, |i| i <= MAX_OBJECT_INDEX as f32)?;
        Ok(info)
    }
}
