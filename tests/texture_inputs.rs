//! Hard texture inputs: each is refused at import with an error that names the asset,
//! the material and the image file, and says what is wrong; none crashes or reaches the
//! GPU. (A missing image and a truncated PNG: see tests/textures.rs.)

use crate::common;

use common::quad_gltf::textured_quad;
use common::{temp_dir, write};
use rt::asset::load_mesh;
use std::path::Path;

/// A unit quad whose material `name` has image 0, at `image_uri`, as base colour texture.
fn quad_gltf(name: &str, image_uri: &str) -> String {
    let corners = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let material =
        format!(r#"{{ "name": "{name}", "pbrMetallicRoughness": {{ "baseColorTexture": {{ "index": 0 }} }} }}"#);
    textured_quad(corners, &material, image_uri, None)
}

fn import_error(dir: &Path, material: &str, image_uri: &str) -> String {
    write(&dir.join("quad.gltf"), &quad_gltf(material, image_uri));
    load_mesh(&dir.join("quad.gltf")).expect_err("a bad image must not load").to_string()
}

/// One PNG chunk: length, type, data, CRC of type and data.
fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend((data.len() as u32).to_be_bytes());
    let mut crc = crc32fast::Hasher::new();
    crc.update(kind);
    crc.update(data);
    out.extend(kind);
    out.extend(data);
    out.extend(crc.finalize().to_be_bytes());
}

/// A valid black 1-bit greyscale PNG of `width` × `height`: a 16384² one is 33 KB,
/// without any 16k image in memory.
fn black_png(width: u32, height: u32) -> Vec<u8> {
    let row_bytes = 1 + width.div_ceil(8) as usize;
    let raw = vec![0u8; row_bytes * height as usize];
    let mut ihdr = Vec::new();
    ihdr.extend(width.to_be_bytes());
    ihdr.extend(height.to_be_bytes());
    ihdr.extend([1, 0, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    chunk(&mut png, b"IHDR", &ihdr);
    chunk(&mut png, b"IDAT", &miniz_oxide::deflate::compress_to_vec_zlib(&raw, 6));
    chunk(&mut png, b"IEND", &[]);
    png
}

/// Two limits, both read from the header before anything is decoded: the pixels rt
/// decodes at all (a 16k² image would take 3 GB), then the side a texture may have.
#[test]
fn a_16k_texture_is_refused_with_the_limit_before_it_is_decoded() {
    let dir = temp_dir("texture-16k");
    let png = black_png(16384, 16384);
    println!("16384² PNG: {} bytes", png.len());
    std::fs::write(dir.join("vast.png"), &png).expect("png");
    let message = import_error(&dir, "vast", "vast.png");
    println!("{message}");
    assert!(message.contains("quad.gltf") && message.contains("material `vast`"), "{message}");
    assert!(message.contains("vast.png") && message.contains("16384×16384"), "{message}");
    assert!(message.contains("more than rt decodes") && message.contains("RT_MAX_IMAGE_MEGAPIXELS="), "{message}");

    // Few pixels but a side over the texture limit: refused by the side.
    let side = rt::asset::texture::MAX_TEXTURE_SIDE;
    std::fs::write(dir.join("vast.png"), black_png(side + 1, 4)).expect("png");
    let message = import_error(&dir, "vast", "vast.png");
    println!("{message}");
    assert!(message.contains(&format!("{}×4", side + 1)), "{message}");
    assert!(message.contains(&format!("at most {side}×{side}")), "{message}");

    // At the limit the same file format is read.
    std::fs::write(dir.join("vast.png"), black_png(side, 4)).expect("png");
    write(&dir.join("quad.gltf"), &quad_gltf("vast", "vast.png"));
    let mesh = load_mesh(&dir.join("quad.gltf")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((mesh.textures[0].width, mesh.textures[0].height), (side, 4));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_exr_texture_with_nan_is_refused_naming_the_texel() {
    let dir = temp_dir("texture-nan");
    let mut image = image::Rgba32FImage::from_pixel(4, 4, image::Rgba([0.5, 0.5, 0.5, 1.0]));
    image.put_pixel(2, 1, image::Rgba([0.5, f32::NAN, 0.5, 1.0]));
    image.save(dir.join("poisoned.exr")).expect("write EXR");
    let message = import_error(&dir, "poisoned", "poisoned.exr");
    println!("{message}");
    assert!(message.contains("material `poisoned`") && message.contains("poisoned.exr"), "{message}");
    assert!(message.contains("texel (2, 1) is not finite"), "{message}");

    // Without the NaN the same file is read.
    image.put_pixel(2, 1, image::Rgba([0.5, 0.5, 0.5, 1.0]));
    image.save(dir.join("poisoned.exr")).expect("write EXR");
    let mesh = load_mesh(&dir.join("quad.gltf")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(mesh.textures.len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}
