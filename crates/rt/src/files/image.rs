//! Decoding the images rt reads (PNG and JPEG textures, OpenEXR and Radiance `.hdr`
//! environments, cached references), all the same way: the file through the safe opener
//! ([`super::input`]), the size the image declares checked against a limit before a
//! pixel is decoded, the decoder held to the memory that size needs, and a truncated or
//! corrupt image an error that names it, never a picture with its end missing.
//!
//! The limit is [`DEFAULT_MAX_MEGAPIXELS`] (a 16384 × 8192 environment, the largest
//! common HDRI); `RT_MAX_IMAGE_MEGAPIXELS` raises or lowers it.

use image::{DynamicImage, ImageDecoder, ImageFormat, ImageReader, Limits};
use std::io::Cursor;
use std::path::Path;

/// The default limit on an image's pixels, in millions (2²⁷ pixels: 16384 × 8192).
pub const DEFAULT_MAX_MEGAPIXELS: f64 = 134.217728;

/// The variable that sets the limit, in millions of pixels.
pub const MAX_MEGAPIXELS_VARIABLE: &str = "RT_MAX_IMAGE_MEGAPIXELS";

/// The largest image rt decodes, in pixels: `RT_MAX_IMAGE_MEGAPIXELS` or the default.
pub fn max_pixels() -> u64 {
    let megapixels = std::env::var(MAX_MEGAPIXELS_VARIABLE)
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|m| m.is_finite() && *m > 0.0)
        .unwrap_or(DEFAULT_MAX_MEGAPIXELS);
    (megapixels * 1e6) as u64
}

/// Reads and decodes the image file at `path`; errors name `what` (e.g. "environment
/// image scenes/sky.exr").
pub fn read(path: &Path, what: &str) -> Result<DynamicImage, String> {
    let bytes = super::read(path).map_err(|e| format!("{what}: {}", e.message()))?;
    decode(&bytes, what)
}

/// Decodes PNG, JPEG, OpenEXR or Radiance HDR bytes; see the module's text.
pub fn decode(bytes: &[u8], what: &str) -> Result<DynamicImage, String> {
    decode_checked(bytes, what, |_, _| Ok(()))
}

/// [`decode`], with `check` given the declared size first (a caller's own limits).
pub fn decode_checked(
    bytes: &[u8],
    what: &str,
    check: impl FnOnce(u32, u32) -> Result<(), String>,
) -> Result<DynamicImage, String> {
    let reader = ImageReader::new(Cursor::new(bytes)).with_guessed_format().map_err(|e| format!("{what}: {e}"))?;
    let format = reader.format().ok_or_else(|| {
        format!("{what}: not an image rt reads (PNG, JPEG, OpenEXR or Radiance .hdr, told by its first bytes)")
    })?;
    let mut decoder = reader.into_decoder().map_err(|e| format!("{what}: cannot read the image's header: {e}"))?;
    let (width, height) = decoder.dimensions();
    check_size(width, height, what)?;
    check(width, height)?;
    // What the pixels take, and room for the decoder's own buffers (an EXR's blocks, a
    // JPEG's component planes): a header that lies cannot make it take more.
    let pixel_bytes = decoder.total_bytes();
    let mut limits = Limits::default();
    limits.max_image_width = Some(width);
    limits.max_image_height = Some(height);
    limits.max_alloc = Some(pixel_bytes.saturating_mul(2).saturating_add(64 << 20));
    decoder.set_limits(limits).map_err(|e| format!("{what}: {e}"))?;
    match format {
        ImageFormat::Jpeg => jpeg_is_whole(bytes).map_err(|e| format!("{what}: a broken JPEG file: {e}"))?,
        ImageFormat::Png if !png_is_whole(bytes) => {
            return Err(format!("{what}: a broken PNG file: it stops before its end chunk (a truncated file)"));
        }
        _ => {}
    }
    DynamicImage::from_decoder(decoder).map_err(|e| format!("{what}: cannot decode the image: {e}"))
}

/// Refuses an image of more pixels than [`max_pixels`], before any is decoded.
pub fn check_size(width: u32, height: u32, what: &str) -> Result<(), String> {
    let pixels = width as u64 * height as u64;
    let max = max_pixels();
    if pixels > max {
        return Err(format!(
            "{what}: the image is {width}×{height} ({:.1} megapixels), more than rt decodes ({:.1} megapixels); \
             set {MAX_MEGAPIXELS_VARIABLE}={} to read it (decoding takes about {} MB)",
            pixels as f64 / 1e6,
            max as f64 / 1e6,
            (pixels as f64 / 1e6).ceil(),
            pixels * 12 / 1_000_000
        ));
    }
    Ok(())
}

/// Whether a PNG stream holds its end chunk (IEND, with its fixed CRC): the decoder
/// reads an image whose last chunks are missing without a word.
fn png_is_whole(bytes: &[u8]) -> bool {
    const IEND: [u8; 12] = [0, 0, 0, 0, b'I', b'E', b'N', b'D', 0xAE, 0x42, 0x60, 0x82];
    bytes.windows(IEND.len()).rev().any(|w| w == IEND)
}

/// Checks that a JPEG stream's segments are whole and that it ends (EOI) after its
/// last scan: the decoder fills a truncated scan with grey without a word.
pub fn jpeg_is_whole(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(&[0xFF, 0xD8]) {
        return Err("it does not start with a JPEG marker".into());
    }
    let mut i = 2;
    let mut scans = 0;
    while i + 1 < bytes.len() {
        if bytes[i] != 0xFF {
            return Err(format!("no marker at byte {i} where a segment should start"));
        }
        let marker = bytes[i + 1];
        match marker {
            // Fill bytes before a marker.
            0xFF => i += 1,
            0xD9 if scans > 0 => return Ok(()),
            0xD9 => return Err("it ends before any image data".into()),
            0x01 | 0xD0..=0xD7 => i += 2,
            _ => {
                let length = bytes.get(i + 2..i + 4).map(|l| u16::from_be_bytes([l[0], l[1]]) as usize);
                let end = length.filter(|&l| l >= 2).map(|l| i + 2 + l).filter(|&e| e <= bytes.len());
                let Some(end) = end else { return Err(format!("the segment at byte {i} runs past the end")) };
                i = end;
                if marker == 0xDA {
                    scans += 1;
                    i = end_of_scan(bytes, i).ok_or("the image data stops before its end (a truncated file)")?;
                }
            }
        }
    }
    Err("the file stops before its end marker (a truncated file)".into())
}

/// Where the entropy-coded data that starts at `i` ends: the next marker that is not a
/// stuffed 0xFF, a fill byte or a restart marker.
fn end_of_scan(bytes: &[u8], mut i: usize) -> Option<usize> {
    while i + 1 < bytes.len() {
        if bytes[i] == 0xFF {
            match bytes[i + 1] {
                0x00 | 0xD0..=0xD7 => i += 2,
                0xFF => i += 1,
                _ => return Some(i),
            }
        } else {
            i += 1;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn encoded(format: ImageFormat) -> Vec<u8> {
        let image = image::RgbImage::from_fn(64, 48, |x, y| image::Rgb([(x * 4) as u8, (y * 5) as u8, 128]));
        let mut bytes = Vec::new();
        DynamicImage::ImageRgb8(image).write_to(&mut Cursor::new(&mut bytes), format).expect("encode");
        bytes
    }

    #[test]
    fn whole_images_decode_and_truncated_ones_are_errors() {
        for format in [ImageFormat::Png, ImageFormat::Jpeg] {
            let bytes = encoded(format);
            let image = decode(&bytes, "whole").expect("a whole image");
            assert_eq!((image.width(), image.height()), (64, 48));
            for keep in [bytes.len() - 1, bytes.len() - 2, bytes.len() * 3 / 4, bytes.len() / 2, 40] {
                match decode(&bytes[..keep], "cut.img") {
                    Ok(_) => panic!("{format:?} cut at {keep} of {} bytes decoded", bytes.len()),
                    Err(message) => assert!(message.starts_with("cut.img: "), "{message}"),
                }
            }
        }
    }

    #[test]
    fn float_images_cut_short_are_errors() {
        let image = image::Rgb32FImage::from_fn(64, 48, |x, y| image::Rgb([x as f32 * 0.1, y as f32, 0.5]));
        for format in [ImageFormat::Hdr, ImageFormat::OpenExr] {
            let mut bytes = Vec::new();
            DynamicImage::ImageRgb32F(image.clone()).write_to(&mut Cursor::new(&mut bytes), format).expect("encode");
            assert!(decode(&bytes, "whole").is_ok(), "{format:?}");
            for keep in [bytes.len() - 1, bytes.len() / 2, 60] {
                match decode(&bytes[..keep], "cut.img") {
                    Ok(_) => panic!("{format:?} cut at {keep} of {} bytes decoded", bytes.len()),
                    Err(message) => assert!(message.starts_with("cut.img: "), "{message}"),
                }
            }
        }
    }

    #[test]
    fn a_jpeg_cut_inside_its_image_data_is_named_truncated() {
        let bytes = encoded(ImageFormat::Jpeg);
        let message = decode(&bytes[..bytes.len() * 3 / 4], "t.jpg").err().unwrap_or_default();
        assert!(message.contains("truncated"), "{message}");
        // Bytes after the end marker (some cameras append data) are no error.
        let mut padded = bytes.clone();
        padded.extend([0u8; 100]);
        assert!(decode(&padded, "padded").is_ok());
    }

    #[test]
    fn images_over_the_limit_are_refused_before_decoding_with_the_way_to_raise_it() {
        let message = check_size(20000, 10000, "big.hdr").expect_err("200 megapixels");
        assert!(message.contains("big.hdr: the image is 20000×10000 (200.0 megapixels)"), "{message}");
        assert!(message.contains("RT_MAX_IMAGE_MEGAPIXELS=200"), "{message}");
        assert!(check_size(16384, 8192, "ok").is_ok());
    }

    #[test]
    fn what_is_no_image_says_which_images_rt_reads() {
        let message = decode(b"hello, world", "notes.png").err().unwrap_or_default();
        assert!(message.contains("notes.png: not an image rt reads"), "{message}");
    }
}
