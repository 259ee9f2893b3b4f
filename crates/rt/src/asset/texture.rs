//! Image textures as rt keeps them: RGBA8 texels with their whole mip chain, built
//! once at import (so at pack time: the chain is part of the asset's cache), and the
//! sampler state the shader needs (wrap modes, colour space).
//!
//! Texels are packed one `u32` each, red in the low byte (WGSL's `unpack4x8unorm`
//! order), rows from the top of the image down. Level `l` is
//! `max(1, width >> l) × max(1, height >> l)`, levels stored finest first, down to 1×1.
//! Colour textures are stored as sRGB bytes and decoded in the shader; their mips
//! are averaged in linear light, so that a checker fades to its true mean, not to
//! the darker mean of its sRGB codes.

use std::sync::Arc;

/// The largest width or height of a texture rt reads.
pub const MAX_TEXTURE_SIDE: u32 = 8192;

/// What a texture coordinate outside [0, 1] does (glTF sampler wrap modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    #[default]
    Repeat,
    Clamp,
    Mirror,
}

impl Wrap {
    /// The code the shader reads (`WRAP_*`, shared constants).
    pub fn code(self) -> u32 {
        use crate::shared_constants::{WRAP_CLAMP, WRAP_MIRROR, WRAP_REPEAT};
        match self {
            Wrap::Repeat => WRAP_REPEAT,
            Wrap::Clamp => WRAP_CLAMP,
            Wrap::Mirror => WRAP_MIRROR,
        }
    }

    pub fn from_code(code: u32) -> Option<Self> {
        [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror].into_iter().find(|w| w.code() == code)
    }
}

/// How a texture reads between texels: Blender's Image Texture Interpolation, glTF's
/// sampler filters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Filter {
    /// Bilinear within a mip level, linear between the two levels the footprint falls in.
    #[default]
    Linear,
    /// The texel the point falls in, of the full-size image (Blender's Closest, glTF's
    /// NEAREST): pixel art stays sharp however far away, as in Cycles.
    Closest,
}

/// A 2×3 affine map of rt's texture coordinates (v from the bottom), rows `[a, b, c]`:
/// `u' = a₀u + b₀v + c₀`, `v' = a₁u + b₁v + c₁`. A texture reads its image at the map of
/// the uv set's coordinates (glTF's `KHR_texture_transform`, Blender's Mapping node).
pub type UvTransform = [[f32; 3]; 2];

pub const IDENTITY_UV_TRANSFORM: UvTransform = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

/// An image with its mip chain and the way one texture reference reads it (wrap modes,
/// colour space, uv transform), ready to be placed in the scene's texture store. Two
/// references to one image with other transforms are two of these sharing their texels.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    pub width: u32,
    pub height: u32,
    /// Horizontal (u) and vertical (v) wrap modes.
    pub wrap: [Wrap; 2],
    /// The bytes are sRGB-encoded colour (decoded by the shader); otherwise linear data.
    pub srgb: bool,
    /// Every level's texels, finest first (see the module's documentation); shared by the
    /// references to one image.
    pub texels: Arc<[u32]>,
    pub uv_transform: UvTransform,
    pub filter: Filter,
}

/// The size of mip level `level` of a `width × height` image.
pub fn level_size(width: u32, height: u32, level: u32) -> (u32, u32) {
    ((width >> level).max(1), (height >> level).max(1))
}

/// How many levels a full chain of a `width × height` image has, down to 1×1.
pub fn level_count(width: u32, height: u32) -> u32 {
    32 - width.max(height).max(1).leading_zeros()
}

/// Texels in levels `0..levels` of a `width × height` image.
pub fn texels_in_levels(width: u32, height: u32, levels: u32) -> u64 {
    (0..levels).map(|l| level_size(width, height, l)).map(|(w, h)| w as u64 * h as u64).sum()
}

fn srgb_to_linear(c: u8) -> f32 {
    crate::scene::srgb_decode(c as f32 / 255.0)
}

/// The byte whose value is nearest `v` (in [0, 1]) on the scale `value` maps bytes to,
/// with ties going up on one texel of a checkerboard and down on the other.
///
/// A mip texel is the mean of four, and of a smooth image two of them are often one
/// code apart: the mean then lies half-way between two codes. Always rounding such
/// ties one way (and, for colour, rounding the sRGB code rather than the light, whose
/// half-way point encodes above the codes' half-way) raised every level's mean a little
/// over the last: a smooth 2048² colour texture's 5th level was 0.7% brighter than its
/// image (`make_texture_refs.py`'s baked noise).
fn nearest_byte(v: f32, below: u8, value: impl Fn(u8) -> f32, tie_up: bool) -> u8 {
    let above = below.saturating_add(1);
    let (d_below, d_above) = ((v - value(below)).abs(), (value(above) - v).abs());
    let tie = (d_below - d_above).abs() <= 1e-6 * v.abs().max(1e-3);
    if tie {
        if tie_up { above } else { below }
    } else if d_above < d_below {
        above
    } else {
        below
    }
}

impl TextureImage {
    /// A texture from `width × height` RGBA8 pixels (rows from the top), with its mip chain.
    pub fn new(width: u32, height: u32, rgba: &[u8], wrap: [Wrap; 2], srgb: bool) -> Self {
        debug_assert_eq!(rgba.len() as u64, 4 * width as u64 * height as u64);
        let mut texels: Vec<u32> =
            Vec::with_capacity(texels_in_levels(width, height, level_count(width, height)) as usize);
        texels.extend(rgba.chunks_exact(4).map(|p| u32::from_le_bytes([p[0], p[1], p[2], p[3]])));
        // Averaged as floats in the space the shader interpolates in: linear for colour.
        let is_colour = |channel: usize| srgb && channel < 3;
        let linear: Vec<f32> = (0..=255u8).map(srgb_to_linear).collect();
        let value = |c: u8, channel: usize| if is_colour(channel) { linear[c as usize] } else { c as f32 / 255.0 };
        let to_byte = |v: f32, channel: usize, tie_up: bool| {
            let v = v.clamp(0.0, 1.0);
            let scaled = if is_colour(channel) { crate::scene::srgb_encode(v) } else { v } * 255.0;
            let below = (scaled.floor() as i32).clamp(0, 255) as u8;
            nearest_byte(v, below, |c| value(c, channel), tie_up)
        };
        // Each level is the mean of the one before it as floats, not of its rounded bytes,
        // so that rounding errors do not build up level after level.
        let mut floats: Vec<[f32; 4]> = rgba.chunks_exact(4).map(|p| std::array::from_fn(|c| value(p[c], c))).collect();
        let (mut w, mut h) = (width, height);
        for level in 1..level_count(width, height) {
            let (nw, nh) = level_size(width, height, level);
            let mut next = Vec::with_capacity((nw * nh) as usize);
            for y in 0..nh {
                for x in 0..nw {
                    // A 2×2 box, or 2×1 / 1×2 once one side is a single texel; an odd
                    // side's last row or column is left out (a box filter, not a tent).
                    let xs = [2 * x, (2 * x + 1).min(w - 1)];
                    let ys = [2 * y, (2 * y + 1).min(h - 1)];
                    let mut sum = [0.0f32; 4];
                    for &sy in &ys {
                        for &sx in &xs {
                            let texel = floats[(sy * w + sx) as usize];
                            for (s, t) in sum.iter_mut().zip(texel) {
                                *s += t;
                            }
                        }
                    }
                    let mean = sum.map(|s| s / 4.0);
                    let tie_up = (x + y) % 2 == 0;
                    let bytes: [u8; 4] = std::array::from_fn(|c| to_byte(mean[c], c, tie_up));
                    texels.push(u32::from_le_bytes(bytes));
                    next.push(mean);
                }
            }
            (w, h, floats) = (nw, nh, next);
        }
        let uv_transform = IDENTITY_UV_TRANSFORM;
        Self { width, height, wrap, srgb, texels: texels.into(), uv_transform, filter: Filter::Linear }
    }

    /// The same image (its texels shared) read with `filter`.
    pub fn with_filter(self, filter: Filter) -> Self {
        Self { filter, ..self }
    }

    /// The same image (its texels shared) read through `uv_transform`.
    pub fn with_uv_transform(&self, uv_transform: UvTransform) -> Self {
        Self { uv_transform, ..self.clone() }
    }

    /// Which texels `self` holds: two references to one image (not to copies of it) alike.
    pub fn texels_id(&self) -> usize {
        Arc::as_ptr(&self.texels) as *const u32 as usize
    }

    pub fn levels(&self) -> u32 {
        level_count(self.width, self.height)
    }

    /// The same texture without its `dropped` finest levels: half the size per level.
    pub fn without_finest_levels(&self, dropped: u32) -> Self {
        let dropped = dropped.min(self.levels() - 1);
        let skip = texels_in_levels(self.width, self.height, dropped) as usize;
        let (width, height) = level_size(self.width, self.height, dropped);
        Self { width, height, texels: self.texels[skip..].into(), ..self.clone() }
    }
}

/// Decodes PNG or JPEG bytes into RGBA8 (a grey or RGB image gets alpha 1).
/// `what` names the image in the error: its file or the glTF image it is.
pub fn decode(bytes: &[u8], what: &str) -> Result<(u32, u32, Vec<u8>), String> {
    // Checked on the header, before anything is decoded: a 16k × 16k image would take
    // 1 GiB to decode and more for its mips, where the GPU binds far less anyway. The
    // texture store downscales what the GPU cannot hold (see `gpu::textures`).
    let image = crate::files::image::decode_checked(bytes, what, |width, height| {
        if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
            return Err(format!(
                "{what}: the image is {width}×{height}; rt reads textures of at most \
                 {MAX_TEXTURE_SIDE}×{MAX_TEXTURE_SIDE} (scale it down)"
            ));
        }
        Ok(())
    })?;
    // Float images (EXR) become 8-bit texels, where a NaN would turn silently into a
    // texel of 0: refused instead, with where it is.
    let floats = match &image {
        image::DynamicImage::ImageRgba32F(i) => Some((i.as_raw(), 4)),
        image::DynamicImage::ImageRgb32F(i) => Some((i.as_raw(), 3)),
        _ => None,
    };
    if let Some((values, channels)) = floats
        && let Some(i) = values.iter().position(|c| !c.is_finite())
    {
        let pixel = i / channels;
        let (x, y) = (pixel as u32 % image.width(), pixel as u32 / image.width());
        let texel = &values[pixel * channels..(pixel + 1) * channels];
        return Err(format!("{what}: texel ({x}, {y}) is not finite ({texel:?})"));
    }
    let rgba = image.into_rgba8();
    Ok((rgba.width(), rgba.height(), rgba.into_raw()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mip_chain_sizes_and_offsets() {
        assert_eq!(level_count(1, 1), 1);
        assert_eq!(level_count(4, 3), 3);
        assert_eq!(level_count(5, 1), 3);
        assert_eq!(texels_in_levels(4, 3, 3), 12 + 2 + 1);
        let t = TextureImage::new(4, 3, &[128; 48], [Wrap::Repeat; 2], false);
        assert_eq!((t.levels(), t.texels.len()), (3, 15));
        let smaller = t.without_finest_levels(1);
        assert_eq!((smaller.width, smaller.height, smaller.texels.len()), (2, 1, 3));
    }

    #[test]
    fn colour_mips_average_in_linear_light() {
        // A black and white checker of 2×2: its one-texel mip is mid grey in linear
        // light, sRGB code 188, not the code 128 that averaging the bytes gives.
        let (b, w) = ([0u8, 0, 0, 255], [255u8, 255, 255, 255]);
        let pixels: Vec<u8> = [b, w, w, b].concat();
        let colour = TextureImage::new(2, 2, &pixels, [Wrap::Repeat; 2], true);
        assert_eq!(colour.texels[4].to_le_bytes(), [188, 188, 188, 255]);
        let data = TextureImage::new(2, 2, &pixels, [Wrap::Repeat; 2], false);
        assert_eq!(data.texels[4].to_le_bytes(), [128, 128, 128, 255]);
    }

    #[test]
    fn mips_keep_the_mean_where_texels_fall_half_way_between_codes() {
        // Columns alternate between two neighbouring codes (as a smooth image's do where
        // its codes step), so every mip texel's mean lies half-way between them: rounded
        // the same way each time (and for colour, the sRGB code rather than the light),
        // each level came out brighter than the one before.
        let n = 256u32;
        let mut pixels = Vec::new();
        for y in 0..n {
            for x in 0..n {
                let c = (120 + y / 16 + x % 2) as u8;
                pixels.extend([c, c, c, 255]);
            }
        }
        for srgb in [true, false] {
            let t = TextureImage::new(n, n, &pixels, [Wrap::Repeat; 2], srgb);
            let value = |c: u8| if srgb { srgb_to_linear(c) as f64 } else { c as f64 / 255.0 };
            let mean_of_level = |level: u32| {
                let start = texels_in_levels(n, n, level) as usize;
                let (w, h) = level_size(n, n, level);
                let texels = &t.texels[start..start + (w * h) as usize];
                texels.iter().map(|t| value(t.to_le_bytes()[0])).sum::<f64>() / texels.len() as f64
            };
            let finest = mean_of_level(0);
            for level in 1..=4 {
                let drift = mean_of_level(level) - finest;
                assert!(drift.abs() < 1e-6, "sRGB {srgb}, level {level}: the mean drifts by {drift:.2e}");
            }
        }
    }

    #[test]
    fn truncated_image_is_an_error_naming_it() {
        let message = decode(b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR", "leaf.png").expect_err("truncated");
        assert!(message.starts_with("leaf.png: cannot read the image's header"), "{message}");
    }
}
