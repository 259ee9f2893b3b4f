//! A render with its AOVs as one multi-layer OpenEXR: the beauty as R, G, B (and A with
//! a transparent film) and each AOV as a layer of conventionally named channels (`albedo.R`, `normal.X`, `depth.Z`,
//! ...), linear 32-bit floats, written atomically like every output.

use super::{Aovs, Image};
use crate::files::output;
use anyhow::{Context, Result, bail};
use exr::prelude::{
    AnyChannel, AnyChannels, Encoding, FlatSamples, Layer, LayerAttributes, SmallVec, Vec2, WritableImage,
};
use std::io::Cursor;
use std::path::Path;

type Channels = Vec<(String, Vec<f32>)>;

const RGB: [&str; 3] = ["R", "G", "B"];
const XYZ: [&str; 3] = ["X", "Y", "Z"];

/// Adds `pixels` as three channels of `layer` named `names` (the beauty: no layer).
fn push_layer(channels: &mut Channels, layer: &str, names: [&str; 3], pixels: &[[f32; 3]]) {
    for (c, name) in names.iter().enumerate() {
        let full = if layer.is_empty() { name.to_string() } else { format!("{layer}.{name}") };
        channels.push((full, pixels.iter().map(|p| p[c]).collect()));
    }
}

/// The beauty's channels: R, G, B and, with a transparent film, its alpha as A.
pub fn beauty_channels(pixels: &[[f32; 3]], alpha: Option<&[f32]>) -> Channels {
    let mut channels = Vec::new();
    push_layer(&mut channels, "", RGB, pixels);
    if let Some(alpha) = alpha {
        channels.push(("A".into(), alpha.to_vec()));
    }
    channels
}

/// The channels of a render with AOVs, by name, rows from the top. With `denoised`,
/// the beauty is the denoised image and the raw one is kept as `noisy.R/G/B`.
pub fn aov_channels(image: &Image, aovs: &Aovs, denoised: Option<&[[f32; 3]]>) -> Channels {
    let mut channels = beauty_channels(denoised.unwrap_or(&image.pixels), image.alpha.as_deref());
    if denoised.is_some() {
        push_layer(&mut channels, "noisy", RGB, &image.pixels);
    }
    push_layer(&mut channels, "albedo", RGB, &aovs.albedo);
    push_layer(&mut channels, "normal", XYZ, &aovs.normal);
    push_layer(&mut channels, "position", XYZ, &aovs.position);
    push_layer(&mut channels, "emission", RGB, &aovs.emission);
    push_layer(&mut channels, "diffuse_color", RGB, &aovs.diffuse_color);
    channels.push(("depth.Z".into(), aovs.depth.clone()));
    channels.push(("error.Y".into(), image.std_error.clone()));
    channels.push(("samples.Y".into(), image.sample_counts.iter().map(|&n| n as f32).collect()));
    channels
}

/// Writes `channels` (each `width`×`height` values) as one OpenEXR at `path`.
pub fn write_layered_exr(path: &Path, width: u32, height: u32, channels: Vec<(String, Vec<f32>)>) -> Result<()> {
    if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
        bail!("{}: AOVs are written as a multi-layer OpenEXR: give an .exr path", path.display());
    }
    let pixels = width as usize * height as usize;
    let list: SmallVec<[AnyChannel<FlatSamples>; 4]> = channels
        .into_iter()
        .map(|(name, values)| {
            debug_assert_eq!(values.len(), pixels);
            AnyChannel::new(name.as_str(), FlatSamples::F32(values))
        })
        .collect();
    write_exr(path, (width, height), list, LayerAttributes::default(), "image")
}

/// Writes `channels` (of any sample type) and the header's `attributes` as one OpenEXR at
/// `path`, atomically; `what` names the content in an error.
pub(super) fn write_exr(
    path: &Path,
    (width, height): (u32, u32),
    channels: SmallVec<[AnyChannel<FlatSamples>; 4]>,
    attributes: LayerAttributes,
    what: &str,
) -> Result<()> {
    let layer = Layer::new(
        Vec2(width as usize, height as usize),
        attributes,
        // ZIP scan lines in increasing order: the same pixels always make the same file.
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels),
    );
    let mut bytes = Cursor::new(Vec::new());
    exr::prelude::Image::from_layer(layer)
        .write()
        .to_buffered(&mut bytes)
        .with_context(|| format!("{}: cannot encode the {what}", path.display()))?;
    Ok(output::write_atomically(path, bytes.get_ref())?)
}
