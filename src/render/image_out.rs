//! Writing renders: linear EXR, or tone-mapped sRGB PNG. Each file is written
//! to a temporary name and renamed into place, so a failed write loses nothing.

use super::Image;
use super::tonemap::display_pixel;
use anyhow::{Context, Result, bail};
use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
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

impl ImageFormat {
    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Png => "png",
            ImageFormat::Exr => "exr",
        }
    }
}

/// A render to `path`: linear EXR, or exposed and tone-mapped sRGB PNG.
pub fn write_image(image: &Image, path: &Path, exposure_ev: f32) -> Result<()> {
    match image_format(path)? {
        ImageFormat::Png => {
            let pixels: Vec<[u8; 3]> = image.pixels.iter().map(|p| display_pixel(*p, exposure_ev)).collect();
            write_png(&pixels, image.width, image.height, path)
        }
        ImageFormat::Exr => write_exr(image, path),
    }
}

/// 8-bit sRGB pixels (rows from the top) to a PNG.
pub fn write_png(pixels: &[[u8; 3]], width: u32, height: u32, path: &Path) -> Result<()> {
    let bytes: Vec<u8> = pixels.iter().flatten().copied().collect();
    let buf = image::RgbImage::from_raw(width, height, bytes).context("image size mismatch")?;
    let tmp = path.with_extension("partial");
    buf.save_with_format(&tmp, image::ImageFormat::Png)
        .with_context(|| format!("could not write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("could not move {} into place", path.display()))
}

fn write_exr(image: &Image, path: &Path) -> Result<()> {
    let floats: Vec<f32> = image.pixels.iter().flatten().copied().collect();
    let buf = image::Rgb32FImage::from_raw(image.width, image.height, floats).context("image size mismatch")?;
    let tmp = path.with_extension("partial");
    buf.save_with_format(&tmp, image::ImageFormat::OpenExr)
        .with_context(|| format!("could not write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("could not move {} into place", path.display()))
}
