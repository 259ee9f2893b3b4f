//! Writing renders: linear EXR, or tone-mapped sRGB PNG. Each file is written
//! to a temporary name and renamed into place, so a failed write loses nothing.

use super::Image;
use super::tonemap::display_pixel;
use anyhow::{Context, Result, bail};
use std::path::Path;

pub fn write_image(image: &Image, path: &Path, exposure_ev: f32) -> Result<()> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let tmp = path.with_extension(format!("{}.partial", ext.as_deref().unwrap_or("img")));
    match ext.as_deref() {
        Some("png") => {
            let bytes: Vec<u8> = image.pixels.iter().flat_map(|p| display_pixel(*p, exposure_ev)).collect();
            let buf = image::RgbImage::from_raw(image.width, image.height, bytes).context("image size mismatch")?;
            buf.save_with_format(&tmp, image::ImageFormat::Png)
        }
        Some("exr") => {
            let floats: Vec<f32> = image.pixels.iter().flatten().copied().collect();
            let buf = image::Rgb32FImage::from_raw(image.width, image.height, floats).context("image size mismatch")?;
            buf.save_with_format(&tmp, image::ImageFormat::OpenExr)
        }
        _ => bail!("{}: unknown image type (use .png or .exr)", path.display()),
    }
    .with_context(|| format!("could not write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("could not move {} into place", path.display()))?;
    Ok(())
}
