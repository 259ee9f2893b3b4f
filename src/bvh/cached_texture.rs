//! Textures as a cache file stores them: a table of sizes and sampler state, and one
//! section of every texture's texels (mip chains included, in table order).

use crate::asset::texture::{TextureImage, Wrap, level_count, texels_in_levels};
use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct CachedTexture {
    pub width: u32,
    pub height: u32,
    pub wrap_u: u32,
    pub wrap_v: u32,
    /// 1: sRGB colour, 0: linear data.
    pub srgb: u32,
    pub _pad: u32,
    /// Where its texels start in the texel section, and how many (every level).
    pub texel_offset: u64,
    pub texel_count: u64,
}

/// The largest side a cached texture may claim: beyond any GPU's texture store.
const MAX_SIDE: u32 = 1 << 16;

/// The table and the texel section of `textures`.
pub fn encode(textures: &[TextureImage]) -> (Vec<CachedTexture>, Vec<u32>) {
    let mut table = Vec::with_capacity(textures.len());
    let mut texels = Vec::new();
    for t in textures {
        table.push(CachedTexture {
            width: t.width,
            height: t.height,
            wrap_u: t.wrap[0].code(),
            wrap_v: t.wrap[1].code(),
            srgb: t.srgb as u32,
            _pad: 0,
            texel_offset: texels.len() as u64,
            texel_count: t.texels.len() as u64,
        });
        texels.extend_from_slice(&t.texels);
    }
    (table, texels)
}

/// The textures of a table and its texel section, each entry checked against the
/// section: sizes, full mip chains, contiguous ranges, known wrap modes.
pub fn decode(table: &[CachedTexture], texels: &[u32]) -> Result<Vec<TextureImage>, String> {
    let mut next = 0u64;
    let mut textures = Vec::with_capacity(table.len());
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
        let expected = texels_in_levels(t.width, t.height, level_count(t.width, t.height));
        if t.texel_count != expected || t.texel_offset != next {
            return bad("its texel range does not match its size or follow the previous texture's");
        }
        next += expected;
        let Some(range) = texels.get(t.texel_offset as usize..next as usize) else {
            return bad("its texels run past the texel section");
        };
        textures.push(TextureImage {
            width: t.width,
            height: t.height,
            wrap: [wrap_u, wrap_v],
            srgb: t.srgb == 1,
            texels: range.to_vec(),
        });
    }
    if next != texels.len() as u64 {
        return Err(format!("{} texels for textures that hold {next}", texels.len()));
    }
    Ok(textures)
}
