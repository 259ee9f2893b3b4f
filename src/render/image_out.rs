//! Writing renders: linear EXR, or tone-mapped sRGB PNG. Each file is written
//! to a temporary name and renamed into place, so a failed write loses nothing.

use super::Image;
use super::tonemap::display_pixel;
use anyhow::{Context, Result, bail};
use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Png,
    Exr,
}

/// The format a path asks for, checked before any work is done.
pub fn image_format(path: &Path) -> Result<ImageFormat> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png") => Ok(ImageFormat::Png),
        Some("exr") => Ok(ImageFormat::Exr),
        _ => bail!("{}: unknown image type (use .png or .exr)", path.display()),
    }
}

pub fn write_image(image: &Image, path: &Path, exposure_ev: f32) -> Result<()> {
    let format = image_format(path)?;
    let tmp = path.with_extension("partial");
    match format {
        ImageFormat::Png => {
            let bytes: Vec<u8> = image.pixels.iter().flat_map(|p| display_pixel(*p, exposure_ev)).collect();
            let buf = image::RgbImage::from_raw(image.width, image.height, bytes).context("image size mismatch")?;
            buf.save_with_format(&tmp, image::ImageFormat::Png)
        }
        ImageFormat::Exr => {
            let floats: Vec<f32> = image.pixels.iter().flatten().copied().collect();
            let buf = image::Rgb32FImage::from_raw(image.width, image.height, floats).context("image size mismatch")?;
            buf.save_with_format(&tmp, image::ImageFormat::OpenExr)
        }
    }
    .with_context(|| format!("could not write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("could not move {} into place", path.display()))?;
    Ok(())
}
