//! The inputs each target's corpus starts from: small valid files of every kind, made
//! here so that the committed corpus (`fuzz/corpus/TARGET/`) can be made again
//! (`RT_FUZZ_WRITE_SEEDS=1 cargo test --release --test fuzz`).

use crate::asset::{MeshData, rtinst, rtmesh};
use crate::bvh::{BuildQuality, MeshBvh, cache};
use crate::scene::Material;
use std::io::Cursor;

pub const MTL: &str = "newmtl a\nKd 0.5 0.5 0.5\nKe 1 1 1\nNi 1.5\nd 0.5\nmap_Kd missing.png\n";
pub const OBJ_WITH_MTL: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
const OBJ: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n\
                   usemtl a\nf 1/1/1 2/2/1 3/3/1\nf 1 2 4\ng second\nf -1 -2 -3\n";

/// The source hash the rtbvh seed carries (the target reads with it).
pub const RTBVH_SOURCE: [u8; 32] = [7; 32];

/// Seeds of the target called `name`.
pub fn of(name: &str) -> Vec<Vec<u8>> {
    match name {
        "scene" => SCENES.iter().map(|s| s.as_bytes().to_vec()).chain([coincident_spheres(300)]).collect(),
        "obj" => vec![OBJ.into(), OBJ_WITH_MTL.into()],
        "mtl" => vec![MTL.into()],
        "gltf" => vec![gltf_files().0.into_bytes()],
        "gltf_bin" => vec![gltf_files().1],
        "glb" => vec![gltf_files().2],
        "rtmesh" => vec![rtmesh::encode(&small_mesh())],
        "rtbvh" => vec![rtbvh()],
        "rtinst" => vec![rtinst_file()],
        "texture" => [image::ImageFormat::Png, image::ImageFormat::Jpeg].map(small_image).to_vec(),
        "environment" => [image::ImageFormat::Hdr, image::ImageFormat::OpenExr].map(small_image).to_vec(),
        "stream" => vec![STREAM.into()],
        "writer" => WRITES.iter().map(|w| w.as_bytes().to_vec()).collect(),
        _ => Vec::new(),
    }
}

const SCENES: [&str; 3] = [
    "[render]\nwidth = 64\nheight = 48\nspp = 4\nmax_bounces = 3\n\n[camera]\nposition = [0.0, 1.0, 5.0]\n\
     look_at = [0.0, 0.5, 0.0]\nfov_y_deg = 40.0\n\n[sky]\nkind = \"uniform\"\ncolor = [0.8, 0.9, 1.0]\n\n\
     [sun]\nelevation_deg = 30.0\nazimuth_deg = 120.0\n\n[materials.glass]\ntransmission = 1.0\nior = 1.5\n\
     roughness = 0.1\nabsorption = [0.1, 0.2, 0.3]\n\n[materials.lamp]\nemission = [4.0, 4.0, 3.0]\n\n\
     [[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 1.0\nmaterial = \"glass\"\n\n\
     [[sphere]]\ncenter = [2.0, 0.5, -1.0]\nradius = 0.5\nmaterial = \"lamp\"\n",
    "[camera]\nposition = [0.0, 0.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\n\n[[mesh]]\nasset = \"mesh.obj\"\n\
     rotate_deg = [-90.0, 0.0, 0.0]\ntranslate = [0.0, 0.0, -1.0]\nscale = [1.0, 2.0, 1.0]\n\n\
     [[mesh]]\nasset = \"mesh.gltf\"\nmatrix = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]\n",
    "[camera]\nposition = [0.0, 2.0, 6.0]\nlook_at = [0.0, 0.0, 0.0]\nfocal_length_mm = 50.0\nfstop = 2.8\nfocus_distance = 6.0\n\n[sky]\nkind = \"atmosphere\"\n\n\
     [[light]]\nkind = \"spot\"\nposition = [0.0, 3.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\npower = 100.0\n\
     spot_size_deg = 45.0\n\n[[light]]\nkind = \"area\"\nshape = \"disk\"\nsize = 0.5\nposition = [1.0, 2.0, 0.0]\npower = 20.0\n\n[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n",
];

/// Many spheres in one place: a top-level build that once took quadratic time.
fn coincident_spheres(count: usize) -> Vec<u8> {
    let mut text = String::from("[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n");
    for _ in 0..count {
        text.push_str("[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n");
    }
    text.into_bytes()
}

const STREAM: &str = "camera view=1,0,0,0,0,1,0,0,0,0,1,-5,0,0,0,1 fov=40\n\
    camera view=1,0,0,0,0,1,0,0,0,0,1,-5,0,0,0,1 lens=50 sensor=36,24 fit=auto shift=0.1,0 aperture=0.05 focus=5 blades=6\n\
    camera view=1,0,0,0,0,1,0,0,0,0,1,-5,0,0,0,1 ortho=4\n\
    camera view=1,0,0,0,0,1,0,0,0,0,1,-5,0,0,0,1 projection=1,0,0,0,0,1,0,0,0,0,-1,-0.2,0,0,-1,0\n\
    size 64 48\nspp 16\nreload scene.toml a.gltf\n# a comment\n\nquit\n";

const WRITES: [&str; 2] = [
    "o.png\n.o.png.20240105.tmp\n.o.png.99999-backup.tmp\n.o.png.rt-999999999-00000000000000ab.tmp\no.png.partial\n",
    "m.rtbvh\n.m.rtbvh.999999999.00ab.tmp\n.m.rtbvh.rt-1-0123456789abcdef.tmp\nm.rtbvh~\nwatch.log\n",
];

/// A 4-vertex, 4-triangle mesh with normals, uvs and an emissive second material.
pub fn small_mesh() -> MeshData {
    MeshData {
        positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        normals: Some(vec![[0.0, 0.0, 1.0]; 4]),
        uvs: Some(vec![[0.0, 0.0]; 4]),
        indices: vec![[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]],
        material_ids: vec![0, 0, 1, 1],
        materials: vec![
            ("a".into(), Material::default()),
            ("b".into(), Material { emission: [1.0; 3], ..Default::default() }),
        ],
        ..Default::default()
    }
}

fn rtbvh() -> Vec<u8> {
    let mesh = small_mesh();
    let packed = cache::PackedMesh {
        bvh: MeshBvh::build(&mesh, BuildQuality::Medium),
        materials: mesh.materials.clone(),
        textures: Vec::new(),
        vertex_count: mesh.positions.len() as u32,
        triangle_count: mesh.indices.len() as u32,
    };
    cache::encode(&packed, RTBVH_SOURCE, cache::params_hash(BuildQuality::Medium))
}

fn rtinst_file() -> Vec<u8> {
    let spin = glam::Mat4::from_rotation_y(0.5) * glam::Mat4::from_scale(glam::Vec3::splat(2.0));
    let records = [
        rtinst::InstanceRecord::new(&glam::Mat4::IDENTITY, rtinst::OWN_MATERIALS),
        rtinst::InstanceRecord::new(&spin, 0),
        rtinst::InstanceRecord::new(&spin, rtinst::MATERIAL_SET | 1),
    ];
    let sets = rtinst::MaterialSets::new(1, &[vec![0], vec![0]]).unwrap_or_default();
    // Two motion keys per instance: where each starts and where it ends.
    let moved = glam::Mat4::from_translation(glam::Vec3::X);
    let motion: Vec<[f32; 12]> = records
        .iter()
        .flat_map(|r| [r.rows, rtinst::InstanceRecord::new(&(moved * r.object_to_world()), 0).rows])
        .collect();
    rtinst::encode_moving(&records, &sets, 2, &motion)
}

/// A 24×16 image with a gradient, in `format` (floats for HDR and OpenEXR).
fn small_image(format: image::ImageFormat) -> Vec<u8> {
    let float = matches!(format, image::ImageFormat::Hdr | image::ImageFormat::OpenExr);
    let image = if float {
        image::DynamicImage::ImageRgb32F(image::Rgb32FImage::from_fn(24, 16, |x, y| {
            image::Rgb([x as f32 * 0.3, y as f32 * 0.1, 2.0])
        }))
    } else {
        image::DynamicImage::ImageRgb8(image::RgbImage::from_fn(24, 16, |x, y| {
            image::Rgb([(x * 10) as u8, (y * 15) as u8, 128])
        }))
    };
    let mut bytes = Vec::new();
    // Encoding an in-memory image of a fixed size cannot fail for these formats.
    let _ = image.write_to(&mut Cursor::new(&mut bytes), format);
    bytes
}

/// A one-triangle glTF with an external buffer `fuzz.bin`, that buffer, and the same as
/// a GLB.
pub fn gltf_files() -> (String, Vec<u8>, Vec<u8>) {
    let mut bin = Vec::new();
    for f in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        bin.extend(f.to_le_bytes());
    }
    for i in [0u32, 1, 2] {
        bin.extend(i.to_le_bytes());
    }
    let json = |uri: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
"nodes":[{{"mesh":0,"translation":[1,2,3],"scale":[1,-1,1]}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[1,0.5,0.2,1],"roughnessFactor":0.3}},
"extensions":{{"KHR_materials_volume":{{"attenuationColor":[0.5,0.5,0.5],"attenuationDistance":2}}}}}}],
"extensionsUsed":["KHR_materials_volume"],
"buffers":[{{"byteLength":48{uri}}}],
"bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":12}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}}]}}"#
        )
    };
    let gltf = json(r#","uri":"fuzz.bin""#);
    let mut glb_json = json("").into_bytes();
    while glb_json.len() % 4 != 0 {
        glb_json.push(b' ');
    }
    let mut glb = Vec::new();
    glb.extend(b"glTF");
    glb.extend(2u32.to_le_bytes());
    glb.extend(((12 + 8 + glb_json.len() + 8 + bin.len()) as u32).to_le_bytes());
    glb.extend((glb_json.len() as u32).to_le_bytes());
    glb.extend(b"JSON");
    glb.extend(&glb_json);
    glb.extend((bin.len() as u32).to_le_bytes());
    glb.extend(b"BIN\0");
    glb.extend(&bin);
    (gltf, bin, glb)
}
