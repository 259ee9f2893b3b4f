//! The texture store: every texture of a scene, mip chains included, in one storage
//! buffer of RGBA8 texels, with a table of where each lies (`shaders/texture.wgsl`).
//! One buffer rather than one texture binding each: lavapipe has no binding arrays.
//!
//! A texture set larger than the GPU binds in one buffer (128 MiB on lavapipe) is
//! downscaled, never refused: the largest texture loses its finest mip level (halving
//! its width and height) until the set fits, with a warning naming the sizes. The mip
//! chains are already built, so this costs no filtering.

use crate::asset::{Filter, TextureImage};
use crate::layout::GpuTexture;
use crate::shared_constants::{TEXTURE_CLOSEST, TEXTURE_SRGB, TEXTURE_WRAP_U_SHIFT, TEXTURE_WRAP_V_SHIFT};
use std::borrow::Cow;
use std::collections::HashMap;

pub struct TextureStore {
    pub table: Vec<GpuTexture>,
    pub texels: Vec<u32>,
}

/// The most texels a store holds: offsets into it are u32.
const MAX_TEXELS: u64 = u32::MAX as u64;

impl TextureStore {
    /// Packs `textures` into at most `max_bytes` of texels (see the module's documentation).
    /// References to one image ([`TextureImage::texels_id`]) share its texels
    /// here too: one table entry each, one copy of the texels.
    pub fn pack<'a>(textures: impl Iterator<Item = &'a TextureImage>, max_bytes: u64) -> Self {
        let references: Vec<&TextureImage> = textures.collect();
        // Each reference's image: the first reference with its texels.
        let mut image_of = Vec::with_capacity(references.len());
        let mut images: Vec<Cow<TextureImage>> = Vec::new();
        let mut first_of_texels = HashMap::new();
        for t in &references {
            let index = *first_of_texels.entry(t.texels_id()).or_insert_with(|| {
                images.push(Cow::Borrowed(*t));
                images.len() - 1
            });
            image_of.push(index);
        }
        let budget = (max_bytes / 4).min(MAX_TEXELS);
        let total = |set: &[Cow<TextureImage>]| set.iter().map(|t| t.texels.len() as u64).sum::<u64>();
        while total(&images) > budget {
            let Some(largest) =
                (0..images.len()).filter(|&i| images[i].levels() > 1).max_by_key(|&i| images[i].texels.len())
            else {
                break;
            };
            let t = &images[largest];
            let smaller = t.without_finest_levels(1);
            log::warn!(
                "textures take {} MiB but this GPU binds at most {} MiB per buffer: a {}×{} texture is downscaled to {}×{}",
                (total(&images) * 4) >> 20,
                max_bytes >> 20,
                t.width,
                t.height,
                smaller.width,
                smaller.height
            );
            images[largest] = Cow::Owned(smaller);
        }
        let mut offsets = Vec::with_capacity(images.len());
        let mut texels = Vec::with_capacity(total(&images) as usize);
        for t in &images {
            offsets.push(texels.len() as u32);
            texels.extend_from_slice(&t.texels);
        }
        let table = references
            .iter()
            .zip(image_of)
            .map(|(reference, i)| {
                let t = &images[i];
                let [u_row, v_row] = reference.uv_transform;
                let det = u_row[0] * v_row[1] - u_row[1] * v_row[0];
                GpuTexture {
                    offset: offsets[i],
                    width: t.width,
                    height: t.height,
                    levels: t.levels(),
                    flags: (reference.srgb as u32 * TEXTURE_SRGB)
                        | ((reference.filter == Filter::Closest) as u32 * TEXTURE_CLOSEST)
                        | (reference.wrap[0].code() << TEXTURE_WRAP_U_SHIFT)
                        | (reference.wrap[1].code() << TEXTURE_WRAP_V_SHIFT),
                    // A degenerate transform reads one texel: the coarsest level, as a footprint of all of it.
                    transform_lod: if det != 0.0 { 0.5 * det.abs().log2() } else { f32::MAX },
                    _pad: [0; 2],
                    u_row: [u_row[0], u_row[1], u_row[2], 0.0],
                    v_row: [v_row[0], v_row[1], v_row[2], 0.0],
                }
            })
            .collect();
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

    #[test]
    fn references_to_one_image_share_its_texels_and_carry_their_own_transforms() {
        let image = TextureImage::new(4, 4, &[9; 64], [Wrap::Repeat; 2], true);
        let tiled = image.with_uv_transform([[8.0, 0.0, 0.5], [0.0, 8.0, 0.0]]);
        let copy = TextureImage::new(4, 4, &[9; 64], [Wrap::Repeat; 2], true);
        let store = TextureStore::pack([&image, &tiled, &copy].into_iter(), 1 << 20);
        assert_eq!(store.texels.len(), 2 * image.texels.len(), "the copy is not the same image; the tiled one is");
        assert_eq!((store.table[0].offset, store.table[1].offset, store.table[2].offset), (0, 0, 21));
        assert_eq!((store.table[0].transform_lod, store.table[1].transform_lod), (0.0, 3.0));
        assert_eq!((store.table[1].u_row, store.table[1].v_row), ([8.0, 0.0, 0.5, 0.0], [0.0, 8.0, 0.0, 0.0]));
    }
}
