//! Writing renders: linear EXR, or tone-mapped sRGB PNG. Each file is written through
//! [`crate::files::output`]: a unique temporary renamed into place, so a failed or
//! interrupted write loses nothing and leaves nothing behind.

use super::Image;
use super::tonemap::display_pixel;
use crate::files::output;
use anyhow::{Context, Result, bail};
use std::io::Cursor;
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

/// Checks, before any rendering, that an image can be written at `path`: a known
/// format, a folder that exists and can be written, and no folder in the way.
pub fn check_output(path: &Path) -> Result<()> {
    image_format(path)?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => bail!("{}: cannot write there: {} is a file, not a folder", path.display(), dir.display()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            bail!("{}: cannot write there: the folder {} does not exist", path.display(), dir.display())
        }
        Err(e) => bail!("{}: cannot write there: {}: {e}", path.display(), dir.display()),
    }
    output::refuse_special(path)?;
    output::probe_writable(dir)?;
    Ok(())
}

pub fn write_image(image: &Image, path: &Path, exposure_ev: f32) -> Result<()> {
    let format = image_format(path)?;
    let (width, height) = (image.width, image.height);
    // Encoded in memory first: encoders reword the I/O errors they meet, and a full disk
    // must be reported as one (the bytes are no larger than the pixels already held).
    let mut bytes = Cursor::new(Vec::new());
    match format {
        ImageFormat::Png => {
            let rgb: Vec<u8> = image.pixels.iter().flat_map(|p| display_pixel(*p, exposure_ev)).collect();
            let buf = image::RgbImage::from_raw(width, height, rgb).context("image size mismatch")?;
            buf.write_to(&mut bytes, image::ImageFormat::Png)
        }
        ImageFormat::Exr => {
            let floats: Vec<f32> = image.pixels.iter().flatten().copied().collect();
            let buf = image::Rgb32FImage::from_raw(width, height, floats).context("image size mismatch")?;
            buf.write_to(&mut bytes, image::ImageFormat::OpenExr)
        }
    }
    .with_context(|| format!("{}: cannot encode the image", path.display()))?;
    Ok(output::write_atomically(path, bytes.get_ref())?)
}

/// An 8-bit sRGB image (a screenshot, a plot) as a PNG, written atomically.
pub fn write_png(image: &image::RgbImage, path: &Path) -> Result<()> {
    let mut bytes = Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .with_context(|| format!("{}: cannot encode", path.display()))?;
    Ok(output::write_atomically(path, bytes.get_ref())?)
}
