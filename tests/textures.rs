//! Image textures through the whole pipeline on the GPU: a glTF's base colour
//! texture shows its texels (sRGB decoded, the right way up), alpha cut-outs let
//! camera and shadow rays through, and bad images are errors naming the material
//! and the file.

use crate::common;

use common::quad_gltf::textured_quad;
use common::{render, scene_from, temp_dir, write};
use rt::asset::load_mesh;
use rt::render::Image;
use std::path::Path;

/// A 64×64 PNG whose texel (x, y), y from the top, is `texel(x, y)`.
fn png(texel: impl Fn(u32, u32) -> [u8; 4]) -> Vec<u8> {
    let image = image::RgbaImage::from_fn(64, 64, |x, y| image::Rgba(texel(x, y)));
    let mut bytes = Vec::new();
    image.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).expect("encode PNG");
    bytes
}

/// A textured quad (`common::quad_gltf::textured_quad`) with one set of texture coordinates.
fn quad_gltf(corners: [[f32; 3]; 4], material: &str, image_uri: &str) -> String {
    textured_quad(corners, material, image_uri, None)
}

fn srgb_to_linear(c: u8) -> f64 {
    let c = c as f64 / 255.0;
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// Mean colour of the 8×8 block at (x0, y0), and the standard error of its luminance.
fn block(image: &Image, x0: usize, y0: usize) -> ([f64; 3], f64) {
    let (mut sum, mut var) = ([0.0; 3], 0.0);
    for y in y0..y0 + 8 {
        for x in x0..x0 + 8 {
            let i = y * image.width as usize + x;
            for (s, p) in sum.iter_mut().zip(image.pixels[i]) {
                *s += p as f64 / 64.0;
            }
            var += (image.std_error[i] as f64).powi(2);
        }
    }
    (sum, var.sqrt() / 64.0)
}

#[test]
fn base_colour_texture_shows_its_texels_in_linear_light_the_right_way_up() {
    // Quadrants, rows from the top: grey (sRGB 128), orange; blue, white.
    let quadrants = [[[128, 128, 128, 255], [255, 64, 0, 255]], [[0, 0, 255, 255], [255, 255, 255, 255]]];
    let dir = temp_dir("texture-quadrants");
    std::fs::write(dir.join("quadrants.png"), png(|x, y| quadrants[(y / 32) as usize][(x / 32) as usize]))
        .expect("png");
    let corners = [[-1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, -1.0, 0.0]];
    // A plain diffuse: specular factor 0 takes off glTF's default dielectric specular layer.
    let material = r#"{ "name": "painted", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0 },
        "extensions": { "KHR_materials_specular": { "specularFactor": 0.0 } } }"#;
    write(&dir.join("quad.gltf"), &quad_gltf(corners, material, "quadrants.png"));
    // A diffuse plane under a uniform white sky that it alone sees has radiance = albedo.
    let scene = scene_from(&format!(
        "[sky]\nkind = \"uniform\"\ncolor = [1.0, 1.0, 1.0]\n\
         [camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 30.0\n\
         [[mesh]]\nasset = {:?}\n",
        dir.join("quad.gltf").display().to_string()
    ));
    let image = render(scene, 64, 64, 16, 2);
    for (row, texels) in quadrants.iter().enumerate() {
        for (column, texel) in texels.iter().enumerate() {
            let (mean, se) = block(&image, 12 + 32 * column, 12 + 32 * row);
            let expected: [f64; 3] = std::array::from_fn(|c| srgb_to_linear(texel[c]));
            println!("quadrant ({row}, {column}): rt {mean:.4?} ± {se:.1e}, texel {expected:.4?}");
            for c in 0..3 {
                assert!(
                    (mean[c] - expected[c]).abs() <= 5.0 * se + 2e-3,
                    "quadrant ({row}, {column}): {mean:?} vs {expected:?}"
                );
            }
        }
    }
}

#[test]
fn a_texture_reads_the_uv_set_its_tex_coord_names() {
    // Quadrants as above; the second set turns the image half a turn on the quad.
    let quadrants = [[[128, 128, 128, 255], [255, 64, 0, 255]], [[0, 0, 255, 255], [255, 255, 255, 255]]];
    let dir = temp_dir("texture-second-uv-set");
    std::fs::write(dir.join("quadrants.png"), png(|x, y| quadrants[(y / 32) as usize][(x / 32) as usize]))
        .expect("png");
    let corners = [[-1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, -1.0, 0.0]];
    let half_turn = [[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0]];
    let material = r#"{ "name": "painted", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0, "texCoord": 1 },
        "metallicFactor": 0.0 }, "extensions": { "KHR_materials_specular": { "specularFactor": 0.0 } } }"#;
    write(&dir.join("quad.gltf"), &textured_quad(corners, material, "quadrants.png", Some(half_turn)));

    let mesh = load_mesh(&dir.join("quad.gltf")).expect("loads");
    assert!(mesh.materials[0].1.textures.reads_second_uv_set(0), "base colour reads TEXCOORD_1");
    // glTF's v from the top becomes rt's from the bottom, in both sets.
    let second = mesh.second_uvs.as_ref().expect("TEXCOORD_1 is kept: a texture reads it");
    assert_eq!(second, &half_turn.map(|[u, v]| [u, 1.0 - v]).to_vec());

    let scene = scene_from(&format!(
        "[sky]\nkind = \"uniform\"\ncolor = [1.0, 1.0, 1.0]\n\
         [camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 30.0\n\
         [[mesh]]\nasset = {:?}\n",
        dir.join("quad.gltf").display().to_string()
    ));
    let geometry = rt::bvh::SceneGeometry::build(&scene, rt::bvh::BuildQuality::Medium).expect("geometry");
    let features = rt::scene::FeatureSet::analyse(&scene, &geometry.summary());
    assert!(features.uv_sets, "{features}");
    assert_eq!(geometry.second_uvs.len(), geometry.triangles.len());
    let image = render(scene, 64, 64, 16, 2);
    for (row, texels) in quadrants.iter().enumerate() {
        for (column, texel) in texels.iter().enumerate() {
            // Half a turn: the texel of quadrant (row, column) shows at (1 - row, 1 - column).
            let (mean, se) = block(&image, 12 + 32 * (1 - column), 12 + 32 * (1 - row));
            let expected: [f64; 3] = std::array::from_fn(|c| srgb_to_linear(texel[c]));
            println!(
                "texel quadrant ({row}, {column}) through TEXCOORD_1: rt {mean:.4?} ± {se:.1e}, texel {expected:.4?}"
            );
            for c in 0..3 {
                assert!(
                    (mean[c] - expected[c]).abs() <= 5.0 * se + 2e-3,
                    "quadrant ({row}, {column}): {mean:?} vs {expected:?}"
                );
            }
        }
    }

    // Without the attribute the texture falls back to the first set (with a warning).
    write(&dir.join("plain.gltf"), &quad_gltf(corners, material, "quadrants.png"));
    let mesh = load_mesh(&dir.join("plain.gltf")).expect("loads");
    assert!(mesh.second_uvs.is_none() && !mesh.materials[0].1.textures.uses_second_uv_set());
}

#[test]
fn alpha_cut_outs_let_camera_and_shadow_rays_through() {
    // A black quad 1 m above a white floor, with a square hole (alpha 0) in its middle;
    // the sun straight above. Seen from above, through the hole, the floor is sunlit
    // (radiance 1: the default sun's irradiance is π) only if shadow rays pass the hole
    // too; around it the quad's black top.
    let dir = temp_dir("texture-cut-out");
    let hole = |x: u32, y: u32| (16..48).contains(&x) && (16..48).contains(&y);
    std::fs::write(dir.join("hole.png"), png(|x, y| [255, 255, 255, if hole(x, y) { 0 } else { 255 }])).expect("png");
    let corners = [[-1.0, 1.0, -1.0], [1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [-1.0, 1.0, 1.0]];
    let material = r#"{ "name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.5,
        "pbrMetallicRoughness": { "baseColorFactor": [0, 0, 0, 1], "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0 },
        "extensions": { "KHR_materials_specular": { "specularFactor": 0.0 } } }"#;
    write(&dir.join("leaf.gltf"), &quad_gltf(corners, material, "hole.png"));
    write(&dir.join("floor.obj"), "v -100 0 -100\nv -100 0 100\nv 100 0 100\nv 100 0 -100\nf 1 2 3 4\n");
    let scene = scene_from(&format!(
        "[sky]\nkind = \"black\"\n[sun]\nelevation_deg = 90.0\nazimuth_deg = 0.0\n\
         [camera]\nposition = [0.0, 3.0, 0.01]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 45.0\n\
         [[mesh]]\nasset = {:?}\n[[mesh]]\nasset = {:?}\n",
        dir.join("leaf.gltf").display().to_string(),
        dir.join("floor.obj").display().to_string()
    ));
    let image = render(scene, 64, 64, 16, 4);
    let (through, se) = block(&image, 28, 28);
    let (quad, quad_se) = block(&image, 4, 28);
    println!(
        "through the hole: {through:.4?} ± {se:.1e} (expected 1); the quad: {quad:.4?} ± {quad_se:.1e} (expected 0)"
    );
    for c in 0..3 {
        assert!((through[c] - 1.0).abs() <= 5.0 * se + 2e-3, "through the hole: {through:?}");
        assert!(quad[c].abs() <= 5.0 * quad_se + 1e-3, "the quad: {quad:?}");
    }
}

fn import_error(dir: &Path, image_uri: &str) -> String {
    let material = r#"{ "name": "leaf", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }"#;
    let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    write(&dir.join("leaf.gltf"), &quad_gltf(corners, material, image_uri));
    load_mesh(&dir.join("leaf.gltf")).expect_err("a bad image must not load").to_string()
}

#[test]
fn a_missing_or_truncated_image_is_an_error_naming_the_material_and_the_file_png_or_jpeg() {
    let dir = temp_dir("texture-bad-images");
    let message = import_error(&dir, "missing.png");
    assert!(message.contains("leaf.gltf") && message.contains("material `leaf`"), "{message}");
    assert!(message.contains("missing.png") && message.contains("cannot read image"), "{message}");

    let full = png(|_, _| [1, 2, 3, 255]);
    std::fs::write(dir.join("cut.png"), &full[..full.len() / 2]).expect("png");
    let message = import_error(&dir, "cut.png");
    assert!(message.contains("material `leaf`") && message.contains("cut.png: a broken PNG file"), "{message}");

    // A JPEG cut inside its image data once decoded without a word, its missing rows grey.
    let rgb = image::RgbImage::from_fn(64, 64, |x, y| image::Rgb([(x * 4) as u8, (y * 4) as u8, 90]));
    let mut jpeg = Vec::new();
    image::DynamicImage::ImageRgb8(rgb)
        .write_to(&mut std::io::Cursor::new(&mut jpeg), image::ImageFormat::Jpeg)
        .expect("jpeg");
    std::fs::write(dir.join("cut.jpg"), &jpeg[..jpeg.len() * 2 / 3]).expect("jpg");
    let message = import_error(&dir, "cut.jpg");
    assert!(message.contains("material `leaf`") && message.contains("cut.jpg: a broken JPEG file"), "{message}");
    assert!(message.contains("truncated"), "{message}");
}

#[test]
fn a_texture_larger_than_the_gpu_binds_is_downscaled_and_still_renders() {
    // 8192² RGBA8 with its mips is 341 MiB: over lavapipe's 128 MiB per binding, so the
    // store drops its finest levels (a warning says so) rather than failing.
    let gpu = common::gpu();
    let side = 8192u32;
    let texture_bytes = 4 * rt::asset::texture::texels_in_levels(side, side, 14);
    let max = gpu.device.limits().max_storage_buffer_binding_size;
    if texture_bytes <= max {
        println!("this GPU binds {} MiB: the texture fits, nothing to downscale", max >> 20);
    }
    let dir = temp_dir("texture-huge");
    let image = image::RgbaImage::from_pixel(side, side, image::Rgba([128, 128, 128, 255]));
    image.save(dir.join("huge.png")).expect("write PNG");
    let corners = [[-1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [-1.0, -1.0, 0.0]];
    let material =
        r#"{ "name": "huge", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0 } }"#;
    write(&dir.join("quad.gltf"), &quad_gltf(corners, material, "huge.png"));
    let scene = scene_from(&format!(
        "[sky]\nkind = \"uniform\"\ncolor = [1.0, 1.0, 1.0]\n\
         [camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 30.0\n\
         [[mesh]]\nasset = {:?}\n",
        dir.join("quad.gltf").display().to_string()
    ));
    let image = render(scene, 16, 16, 4, 2);
    let (mean, se) = block(&image, 4, 4);
    let expected = srgb_to_linear(128);
    println!("{side}² texture on a GPU binding {} MiB: {mean:.4?} ± {se:.1e}, expected {expected:.4}", max >> 20);
    for m in mean {
        assert!((m - expected).abs() <= 5.0 * se + 2e-3, "{mean:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `t` applied to rt's coordinates `[u, v]` (v from the bottom).
fn apply(t: rt::asset::UvTransform, [u, v]: [f32; 2]) -> [f32; 2] {
    [t[0][0] * u + t[0][1] * v + t[0][2], t[1][0] * u + t[1][1] * v + t[1][2]]
}

fn near(a: [f32; 2], b: [f32; 2]) -> bool {
    (a[0] - b[0]).abs() < 1e-6 && (a[1] - b[1]).abs() < 1e-6
}

#[test]
fn khr_texture_transform_is_the_textures_own_and_leaves_the_uvs_as_they_are() {
    let dir = temp_dir("texture-transform");
    std::fs::write(dir.join("t.png"), png(|_, _| [9, 9, 9, 255])).expect("png");
    let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    // Offset, then a quarter turn (glTF: translation · rotation · scale), then a scale of 2 in u.
    let material = r#"{ "name": "moved", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0,
        "extensions": { "KHR_texture_transform": { "offset": [0.5, 0.25], "rotation": 1.5707963, "scale": [2, 1] } } } } }"#;
    write(&dir.join("q.gltf"), &quad_gltf(corners, material, "t.png"));
    let mesh = load_mesh(&dir.join("q.gltf")).expect("loads");
    let uvs = mesh.uvs.as_ref().expect("uvs");
    let gltf_uvs = [[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    // rt stores v from the bottom: 1 - glTF's.
    assert_eq!(uvs, &gltf_uvs.map(|[u, v]| [u, 1.0 - v]).to_vec(), "the uvs are not transformed");
    let transform = mesh.textures[mesh.materials[0].1.textures.base_color.expect("a texture") as usize].uv_transform;
    // A quarter turn in glTF's uv space (v down), as its sample model and Blender rotate:
    // glTF (u, v) → (v + 0.5, 0.25 − 2u), which rt reads with v from the bottom.
    for [u, v] in gltf_uvs {
        let want = [v + 0.5, 1.0 - (0.25 - 2.0 * u)];
        assert!(near(apply(transform, [u, 1.0 - v]), want), "{transform:?} at ({u}, {v})");
    }
}

#[test]
fn two_textures_on_one_uv_set_keep_their_own_transforms_and_share_the_image() {
    let dir = temp_dir("texture-transform-per-texture");
    std::fs::write(dir.join("t.png"), png(|_, _| [9, 9, 9, 255])).expect("png");
    let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let second = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
    // On TEXCOORD_0: base colour moved by (0.5, 0.25), the normal map tiled 8 times, the
    // metallic-roughness map as it is; emission on TEXCOORD_1 scaled by 3, and a clearcoat
    // texture moved onto TEXCOORD_1 by its transform's own texCoord.
    let material = r#"{ "name": "two", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0,
        "extensions": { "KHR_texture_transform": { "offset": [0.5, 0.25] } } },
        "metallicRoughnessTexture": { "index": 0 } },
        "emissiveTexture": { "index": 0, "texCoord": 1, "extensions": { "KHR_texture_transform": { "scale": [3, 3] } } },
        "emissiveFactor": [1, 1, 1],
        "normalTexture": { "index": 0, "extensions": { "KHR_texture_transform": { "scale": [8, 8] } } },
        "extensions": { "KHR_materials_clearcoat": { "clearcoatFactor": 1, "clearcoatTexture": { "index": 0,
            "extensions": { "KHR_texture_transform": { "scale": [2, 2], "texCoord": 1 } } } } } }"#;
    write(&dir.join("q.gltf"), &textured_quad(corners, material, "t.png", Some(second)));
    let mesh = load_mesh(&dir.join("q.gltf")).expect("loads");
    let textures = &mesh.materials[0].1.textures;
    assert!(!textures.reads_second_uv_set(0) && textures.reads_second_uv_set(2), "{textures:?}");
    assert!(textures.reads_second_uv_set(4), "the clearcoat texture's transform moves it to TEXCOORD_1");
    assert_eq!(textures.normal_uv_set(), rt::scene::UvSet::First, "the normal map reads TEXCOORD_0");
    let reference = |slot: Option<u32>| &mesh.textures[slot.expect("a texture") as usize];
    let (base, metal_rough, emission, normal) = (
        reference(textures.base_color),
        reference(textures.metallic_roughness),
        reference(textures.emission),
        reference(textures.normal),
    );
    let coat = reference(textures.layers.coat);
    // Each transform maps rt's coordinates (v from the bottom) as glTF's maps its own.
    let cases = [(base, [1.0, 0.0, 0.5], [0.0, 1.0, -0.25]), (emission, [3.0, 0.0, 0.0], [0.0, 3.0, -2.0])];
    for (t, u_row, v_row) in cases.into_iter().chain([(normal, [8.0, 0.0, 0.0], [0.0, 8.0, -7.0])]) {
        assert!(near(apply(t.uv_transform, [0.0, 0.0]), [u_row[2], v_row[2]]), "{:?}", t.uv_transform);
        assert!(
            near(apply(t.uv_transform, [1.0, 1.0]), [u_row[0] + u_row[2], v_row[1] + v_row[2]]),
            "{:?}",
            t.uv_transform
        );
    }
    assert_eq!(metal_rough.uv_transform, rt::asset::IDENTITY_UV_TRANSFORM);
    assert_eq!(coat.uv_transform, [[2.0, 0.0, 0.0], [0.0, 2.0, -1.0]]);
    // One image (in the linear space of the normal and metallic-roughness maps) read two ways: its texels shared.
    assert_ne!(normal.uv_transform, metal_rough.uv_transform);
    assert_eq!(normal.texels_id(), metal_rough.texels_id(), "two references, one image");
    // The uvs are as the file has them, the transforms being the textures' own.
    let (first_set, second_set) = (mesh.uvs.as_ref().expect("uvs"), mesh.second_uvs.as_ref().expect("second uvs"));
    for (v, p) in mesh.positions.iter().enumerate() {
        let corner = corners.iter().position(|c| c == p).expect("a corner");
        let [u, w] = [[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]][corner];
        let [su, sw] = second[corner];
        assert_eq!(first_set[v], [u, 1.0 - w], "set 0 at {p:?}");
        assert_eq!(second_set[v], [su, 1.0 - sw], "set 1 at {p:?}");
    }
}
