//! The image textures of a glTF file's materials: images embedded in a buffer view
//! (`.glb`), in data URIs, or in PNG/JPEG files beside the glTF, with their samplers'
//! wrap modes and filters. Each (image, colour space or re-encoding, wrap modes, filter, uv transform) becomes one
//! [`TextureImage`], however many materials use it; those of one image with other uv
//! transforms share its texels.

use super::texture::{Filter, TextureImage, UvTransform, Wrap, decode};
use gltf::texture::{MagFilter, WrappingMode};
use std::collections::HashMap;
use std::path::Path;

/// How a texture's bytes are meant: colour (sRGB-encoded) or linear data.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ColorSpace {
    Srgb,
    Linear,
}

/// How a texture's texels are read: in a colour space, or re-encoded at import into the
/// channels of the rt slot it fills (linear data).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Reading {
    As(ColorSpace),
    /// `KHR_materials_sheen.sheenRoughnessTexture` (A) as rt's sheen texture: R the
    /// weight (1), G the roughness.
    SheenRoughness,
}

pub struct TextureLoader<'a> {
    buffers: &'a [gltf::buffer::Data],
    /// The glTF's folder, where relative image URIs point.
    dir: &'a Path,
    /// The first texture of each (image, reading, wraps), and each texture by its filter and
    /// uv transform too.
    decoded: HashMap<ImageKey, u32>,
    loaded: HashMap<(ImageKey, Filter, [u32; 6]), u32>,
    pub textures: Vec<TextureImage>,
}

/// An image as decoded for a reading: its index, the reading, its wrap codes.
type ImageKey = (usize, Reading, [u32; 2]);

fn wrap(mode: WrappingMode) -> Wrap {
    match mode {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
    }
}

impl<'a> TextureLoader<'a> {
    pub fn new(buffers: &'a [gltf::buffer::Data], dir: &'a Path) -> Self {
        Self { buffers, dir, decoded: HashMap::new(), loaded: HashMap::new(), textures: Vec::new() }
    }

    /// The index in [`Self::textures`] of `texture` read through `transform`, decoding its
    /// image on first use.
    pub fn load(&mut self, texture: &gltf::Texture, space: ColorSpace, transform: UvTransform) -> Result<u32, String> {
        self.load_as(texture, Reading::As(space), transform)
    }

    /// [`Self::load`] of a texture read as `reading` says.
    pub fn load_as(
        &mut self,
        texture: &gltf::Texture,
        reading: Reading,
        transform: UvTransform,
    ) -> Result<u32, String> {
        let sampler = texture.sampler();
        let wraps = [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())];
        // What a texel covering many pixels shows: Blender's Closest is written as NEAREST.
        let filter = match sampler.mag_filter() {
            Some(MagFilter::Nearest) => Filter::Closest,
            _ => Filter::Linear,
        };
        let image = texture.source();
        let key = (image.index(), reading, wraps.map(Wrap::code));
        let transform_bits: [u32; 6] = bytemuck::cast(transform);
        if let Some(&index) = self.loaded.get(&(key, filter, transform_bits)) {
            return Ok(index);
        }
        let reference = match self.decoded.get(&key) {
            Some(&first) => self.textures[first as usize].with_uv_transform(transform),
            None => {
                let (what, bytes) = self.image_bytes(&image)?;
                let (width, height, mut rgba) = decode(&bytes, &what)?;
                if reading == Reading::SheenRoughness {
                    for texel in rgba.chunks_exact_mut(4) {
                        let roughness = texel[3];
                        texel.copy_from_slice(&[255, roughness, 0, 255]);
                    }
                }
                self.decoded.insert(key, self.textures.len() as u32);
                let srgb = reading == Reading::As(ColorSpace::Srgb);
                TextureImage::new(width, height, &rgba, wraps, srgb).with_uv_transform(transform)
            }
        };
        self.textures.push(reference.with_filter(filter));
        let index = (self.textures.len() - 1) as u32;
        self.loaded.insert((key, filter, transform_bits), index);
        Ok(index)
    }

    /// The encoded bytes of an image and a name for it in messages.
    fn image_bytes(&self, image: &gltf::Image) -> Result<(String, Vec<u8>), String> {
        match image.source() {
            gltf::image::Source::View { view, .. } => {
                let what = format!("image {} (buffer view {})", image.index(), view.index());
                let buffer = self.buffers.get(view.buffer().index()).ok_or_else(|| format!("{what}: no buffer"))?;
                let bytes = buffer
                    .0
                    .get(view.offset()..view.offset() + view.length())
                    .ok_or_else(|| format!("{what}: the view runs past its buffer"))?;
                Ok((what, bytes.to_vec()))
            }
            gltf::image::Source::Uri { uri, .. } => {
                if let Some(data) = uri.strip_prefix("data:") {
                    let what = format!("image {} (data URI)", image.index());
                    let (_, encoded) =
                        data.split_once(";base64,").ok_or_else(|| format!("{what}: only base64 data URIs are read"))?;
                    let bytes = base64::decode(encoded).map_err(|e| format!("{what}: bad base64: {e}"))?;
                    return Ok((what, bytes));
                }
                let path = self.dir.join(super::gltf_buffers::percent_decode(uri));
                let what = path.display().to_string();
                let bytes = crate::files::read(&path).map_err(|e| format!("cannot read image {e}"))?;
                Ok((what, bytes))
            }
        }
    }
}

/// The file names of a document's images that live in files beside it.
pub fn image_files(document: &gltf::Document) -> impl Iterator<Item = String> + '_ {
    document.images().filter_map(|image| match image.source() {
        gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
            Some(super::gltf_buffers::percent_decode(uri))
        }
        _ => None,
    })
}
