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

/// Writes `image`: an EXR holds the linear pixels (premultiplied, with an `A` channel, for
/// a transparent film), a PNG their display colours (straight alpha, as PNG keeps it).
pub fn write_image(image: &Image, path: &Path, exposure_ev: f32) -> Result<()> {
    let (width, height) = (image.width, image.height);
    match image_format(path)? {
        ImageFormat::Png => {
            let bytes = encode_png(image, exposure_ev)
                .with_context(|| format!("{}: cannot encode the image", path.display()))?;
            Ok(output::write_atomically(path, &bytes)?)
        }
        ImageFormat::Exr => {
            // Written by the AOVs' writer, whose scan lines go in increasing order: the
            // `image` crate's encoder writes tiles in the order its threads finish them, so
            // the same pixels made different files from run to run.
            let channels = super::beauty_channels(&image.pixels, image.alpha.as_deref());
            super::write_layered_exr(path, width, height, channels)
        }
    }
}

/// The PNG's bytes, encoded in memory first: encoders reword the I/O errors they meet, and
/// a full disk must be reported as one (the bytes are no larger than the pixels held).
fn encode_png(image: &Image, exposure_ev: f32) -> Result<Vec<u8>> {
    let (width, height) = (image.width, image.height);
    let mut bytes = Cursor::new(Vec::new());
    match &image.alpha {
        None => {
            let rgb: Vec<u8> = image.pixels.iter().flat_map(|p| display_pixel(*p, exposure_ev)).collect();
            let buf = image::RgbImage::from_raw(width, height, rgb).context("image size mismatch")?;
            buf.write_to(&mut bytes, image::ImageFormat::Png)?;
        }
        Some(alpha) => {
            let rgba: Vec<u8> =
                image.pixels.iter().zip(alpha).flat_map(|(p, &a)| straight_rgba(*p, a, exposure_ev)).collect();
            let buf = image::RgbaImage::from_raw(width, height, rgba).context("image size mismatch")?;
            buf.write_to(&mut bytes, image::ImageFormat::Png)?;
        }
    }
    Ok(bytes.into_inner())
}

/// A premultiplied pixel's display colour and alpha: the colour is tone-mapped divided by
/// alpha (where nothing covers the pixel, black).
fn straight_rgba(pixel: [f32; 3], alpha: f32, exposure_ev: f32) -> [u8; 4] {
    let colour = if alpha > 0.0 { pixel.map(|v| v / alpha) } else { [0.0; 3] };
    let [r, g, b] = display_pixel(colour, exposure_ev);
    [r, g, b, (alpha.clamp(0.0, 1.0) * 255.0 + 0.5) as u8]
}

/// An 8-bit sRGB image (a screenshot, a plot) as a PNG, written atomically.
pub fn write_png(image: &image::RgbImage, path: &Path) -> Result<()> {
    let mut bytes = Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .with_context(|| format!("{}: cannot encode", path.display()))?;
    Ok(output::write_atomically(path, bytes.get_ref())?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_pixels_make_the_same_exr_file_with_scan_lines_in_order() {
        let (width, height) = (300u32, 200u32);
        let pixels: Vec<[f32; 3]> = (0..width * height)
            .map(|i| [(i % 7) as f32 * 0.3, (i % 13) as f32 * 1e3, ((i * 7919) % 101) as f32])
            .collect();
        let n = pixels.len();
        let image = Image {
            width,
            height,
            samples: 1,
            pixels,
            std_error: vec![0.0; n],
            sample_counts: vec![1; n],
            alpha: None,
        };
        let dir = std::env::temp_dir().join(format!("rt-exr-order-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let files: Vec<Vec<u8>> = (0..4)
            .map(|i| {
                let path = dir.join(format!("{i}.exr"));
                write_image(&image, &path, 0.0).unwrap();
                std::fs::read(&path).unwrap()
            })
            .collect();
        let meta = exr::meta::MetaData::read_from_file(dir.join("0.exr"), false).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(meta.headers[0].line_order, exr::meta::attribute::LineOrder::Increasing);
        assert!(files.windows(2).all(|w| w[0] == w[1]), "the same image made different files");
        let read = image::load_from_memory(&files[0]).unwrap().to_rgb32f();
        assert_eq!(read.as_raw().chunks(3).map(|p| [p[0], p[1], p[2]]).collect::<Vec<_>>(), image.pixels);
    }
}
