//! Textures as a cache file stores them: a table of sizes, sampler state and uv
//! transforms, and one section of every image's texels (mip chains included, in table
//! order). Texture references to one image point at one range of texels.

use crate::asset::texture::{Filter, TextureImage, Wrap, level_count, texels_in_levels};
use bytemuck::{Pod, Zeroable};
use std::collections::HashMap;
use std::sync::Arc;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct CachedTexture {
    pub width: u32,
    pub height: u32,
    pub wrap_u: u32,
    pub wrap_v: u32,
    /// 1: sRGB colour, 0: linear data.
    pub srgb: u32,
    /// 1: the closest texel (`Filter::Closest`), 0: linear; from format version 15 on.
    pub closest: u32,
    /// Where its texels start in the texel section, and how many (every level).
    pub texel_offset: u64,
    pub texel_count: u64,
    /// Rows of its uv transform (`asset::UvTransform`), from format version 10 on.
    pub uv_transform: [[f32; 3]; 2],
}

/// The largest side a cached texture may claim: beyond any GPU's texture store.
const MAX_SIDE: u32 = 1 << 16;

/// The table and the texel section of `textures`: each image's texels once.
pub fn encode(textures: &[TextureImage]) -> (Vec<CachedTexture>, Vec<u32>) {
    let mut table = Vec::with_capacity(textures.len());
    let mut texels = Vec::new();
    let mut offsets = HashMap::new();
    for t in textures {
        let texel_offset = *offsets.entry(t.texels_id()).or_insert_with(|| {
            texels.extend_from_slice(&t.texels);
            (texels.len() - t.texels.len()) as u64
        });
        table.push(CachedTexture {
            width: t.width,
            height: t.height,
            wrap_u: t.wrap[0].code(),
            wrap_v: t.wrap[1].code(),
            srgb: t.srgb as u32,
            closest: (t.filter == Filter::Closest) as u32,
            texel_offset,
            texel_count: t.texels.len() as u64,
            uv_transform: t.uv_transform,
        });
    }
    (table, texels)
}

/// The textures of a table and its texel section, each entry checked against the
/// section: sizes, full mip chains, ranges that follow the previous image's or repeat an
/// earlier entry's exactly (one image), known wrap modes, finite uv transforms.
pub fn decode(table: &[CachedTexture], texels: &[u32]) -> Result<Vec<TextureImage>, String> {
    let mut next = 0u64;
    let mut textures: Vec<TextureImage> = Vec::with_capacity(table.len());
    // The first texture of each range start.
    let mut first_at: HashMap<u64, usize> = HashMap::new();
    for (i, t) in table.iter().enumerate() {
        let bad = |why: &str| Err(format!("texture {i}: {why}"));
        if !(1..=MAX_SIDE).contains(&t.width) || !(1..=MAX_SIDE).contains(&t.height) {
            return bad(&format!("size {}×{} is out of range", t.width, t.height));
        }
        let (Some(wrap_u), Some(wrap_v)) = (Wrap::from_code(t.wrap_u), Wrap::from_code(t.wrap_v)) else {
            return bad("unknown wrap mode");
        };
        if t.srgb > 1 {
            return bad("unknown colour space");
        }
        if t.closest > 1 {
            return bad("unknown filter");
        }
        if !t.uv_transform.iter().flatten().all(|c| c.is_finite()) {
            return bad("its uv transform is not finite");
        }
        let expected = texels_in_levels(t.width, t.height, level_count(t.width, t.height));
        if t.texel_count != expected {
            return bad("its texel count does not match its size");
        }
        let shared = match first_at.get(&t.texel_offset) {
            Some(&j) if (textures[j].width, textures[j].height) == (t.width, t.height) => {
                Some(textures[j].texels.clone())
            }
            Some(_) => return bad("it shares an earlier texture's texels but not its size"),
            None if t.texel_offset == next => None,
            None => return bad("its texel range neither follows the previous image's nor repeats an earlier one"),
        };
        let texels = match shared {
            Some(texels) => texels,
            None => {
                next += expected;
                let Some(range) = texels.get(t.texel_offset as usize..next as usize) else {
                    return bad("its texels run past the texel section");
                };
                first_at.insert(t.texel_offset, i);
                Arc::from(range)
            }
        };
        textures.push(TextureImage {
            width: t.width,
            height: t.height,
            wrap: [wrap_u, wrap_v],
            srgb: t.srgb == 1,
            texels,
            uv_transform: t.uv_transform,
            filter: if t.closest == 1 { Filter::Closest } else { Filter::Linear },
        });
    }
    if next != texels.len() as u64 {
        return Err(format!("{} texels for textures that hold {next}", texels.len()));
    }
    Ok(textures)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_to_one_image_round_trip_with_one_copy_of_its_texels() {
        let image = TextureImage::new(4, 2, &[7; 32], [Wrap::Repeat, Wrap::Clamp], true);
        let tiled = image.with_uv_transform([[8.0, 0.0, 0.0], [0.0, 8.0, -7.0]]).with_filter(Filter::Closest);
        let other = TextureImage::new(2, 2, &[3; 16], [Wrap::Mirror; 2], false);
        let (table, texels) = encode(&[image.clone(), other.clone(), tiled.clone()]);
        assert_eq!(texels.len(), image.texels.len() + other.texels.len(), "the tiled reference adds no texels");
        assert_eq!(table[2].texel_offset, table[0].texel_offset);
        let decoded = decode(&table, &texels).expect("decodes");
        assert_eq!(decoded, [image, other, tiled]);
        assert_eq!(decoded[0].texels_id(), decoded[2].texels_id(), "shared again after decoding");
        assert_eq!((decoded[0].filter, decoded[2].filter), (Filter::Linear, Filter::Closest));

        // A range that repeats an earlier one with another size, or that skips texels, is refused.
        let mut resized = table.clone();
        (resized[2].width, resized[2].height) = (2, 4);
        assert!(decode(&resized, &texels).unwrap_err().contains("not its size"));
        let mut gap = table.clone();
        gap[1].texel_offset += 1;
        assert!(decode(&gap, &texels).unwrap_err().contains("neither follows"));
        let mut bad = table.clone();
        bad[2].uv_transform[0][0] = f32::NAN;
        assert!(decode(&bad, &texels).unwrap_err().contains("not finite"));
        let mut filter = table;
        filter[1].closest = 2;
        assert!(decode(&filter, &texels).unwrap_err().contains("unknown filter"));
    }
}
