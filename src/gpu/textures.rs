//! The texture store: every texture of a scene, mip chains included, in one storage
//! buffer of RGBA8 texels, with a table of where each lies (`shaders/texture.wgsl`).
//! One buffer rather than one texture binding each: lavapipe has no binding arrays.
//!
//! A texture set larger than the GPU binds in one buffer (128 MiB on lavapipe) is
//! downscaled, never refused: the largest texture loses its finest mip level (halving
//! its width and height) until the set fits, with a warning naming the sizes. The mip
//! chains are already built, so this costs no filtering.

use crate::asset::TextureImage;
use crate::layout::GpuTexture;
use std::borrow::Cow;

pub struct TextureStore {
    pub table: Vec<GpuTexture>,
    pub texels: Vec<u32>,
}

/// The most texels a store holds: offsets into it are u32.
const MAX_TEXELS: u64 = u32::MAX as u64;

impl TextureStore {
    /// Packs `textures` into at most `max_bytes` of texels (see the module's documentation).
    pub fn pack<'a>(textures: impl Iterator<Item = &'a TextureImage>, max_bytes: u64) -> Self {
        let mut fitted: Vec<Cow<TextureImage>> = textures.map(Cow::Borrowed).collect();
        let budget = (max_bytes / 4).min(MAX_TEXELS);
        let total = |set: &[Cow<TextureImage>]| set.iter().map(|t| t.texels.len() as u64).sum::<u64>();
        while total(&fitted) > budget {
            let Some(largest) =
                (0..fitted.len()).filter(|&i| fitted[i].levels() > 1).max_by_key(|&i| fitted[i].texels.len())
            else {
                break;
            };
            let t = &fitted[largest];
            let smaller = t.without_finest_levels(1);
            log::warn!(
                "textures take {} MiB but this GPU binds at most {} MiB per buffer: a {}×{} texture is downscaled to {}×{}",
                (total(&fitted) * 4) >> 20,
                max_bytes >> 20,
                t.width,
                t.height,
                smaller.width,
                smaller.height
            );
            fitted[largest] = Cow::Owned(smaller);
        }
        let mut table = Vec::with_capacity(fitted.len());
        let mut texels = Vec::with_capacity(total(&fitted) as usize);
        for t in &fitted {
            table.push(GpuTexture {
                offset: texels.len() as u32,
                width: t.width,
                height: t.height,
                levels: t.levels(),
                flags: t.srgb as u32 | t.wrap[0].code() << 1 | t.wrap[1].code() << 3,
                _pad: [0; 3],
            });
            texels.extend_from_slice(&t.texels);
        }
        Self { table, texels }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::Wrap;

    #[test]
    fn a_set_too_large_for_the_gpu_is_downscaled_to_fit() {
        let big = TextureImage::new(64, 32, &[255; 64 * 32 * 4], [Wrap::Clamp, Wrap::Mirror], true);
        let small = TextureImage::new(4, 4, &[7; 64], [Wrap::Repeat; 2], false);
        let fits = TextureStore::pack([&big, &small].into_iter(), 1 << 20);
        assert_eq!(fits.table[0].width, 64);
        assert_eq!(fits.table[0].flags, 1 | 1 << 1 | 2 << 3);
        assert_eq!(fits.table[1].offset as usize, big.texels.len());

        // 2,731 + 21 texels; at most 200: the big one halves twice (to 683, then 171 texels).
        let squeezed = TextureStore::pack([&big, &small].into_iter(), 800);
        assert_eq!((squeezed.table[0].width, squeezed.table[0].height, squeezed.table[0].levels), (16, 8, 5));
        assert_eq!(squeezed.texels.len(), 171 + 21);
        assert_eq!(squeezed.table[1].offset, 171);
    }
}
