//! Every input rt reads, corrupted thousands of ways: bit flips, truncation,
//! huge counts, NaN and infinity. Each must give an error or a valid result,
//! never a panic, and never an allocation beyond what the input's size can
//! justify. Cases that once failed live in `tests/fuzz_corpus/` and run first.
//!
//! `RT_FUZZ_ITERATIONS` (default 1500 per format) runs longer by hand.

use crate::common;

use common::{TestRng, repo, temp_dir};
use rt::asset::{MeshData, load_mesh, rtinst, rtmesh};
use rt::bvh::cache::{self, PackedMesh};
use rt::bvh::{BuildQuality, MeshBvh};
use rt::scene::Material;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::{Path, PathBuf};

/// Records the largest single allocation of the current thread.
struct LargestAllocation;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for LargestAllocation {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.with(|l| l.set(l.get().max(layout.size())));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.with(|l| l.set(l.get().max(new_size)));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: LargestAllocation = LargestAllocation;

/// Values that break parsers: counts near the integer limits, NaN, infinities.
const NASTY_WORDS: [u32; 8] = [0, 1, 0xffff_ffff, 0x7fff_ffff, 0x8000_0000, 0x7fc0_0000, 0x7f80_0000, 0xff80_0000];
const NASTY_NUMBERS: [&str; 9] = ["nan", "inf", "-inf", "1e39", "-1", "0", "4294967295", "1e-45", "99999999999"];

fn mutate(seed: &[u8], rng: &mut TestRng, text: bool) -> Vec<u8> {
    let mut b = seed.to_vec();
    let pick = |rng: &mut TestRng, n: usize| (rng.next_f64() * n as f64) as usize % n.max(1);
    match pick(rng, if text { 5 } else { 4 }) {
        0 => {
            for _ in 0..1 + pick(rng, 4) {
                let i = pick(rng, b.len());
                if let Some(byte) = b.get_mut(i) {
                    *byte ^= 1 << pick(rng, 8);
                }
            }
        }
        1 => b.truncate(pick(rng, b.len())),
        2 if b.len() >= 4 => {
            let i = pick(rng, b.len() / 4) * 4;
            b[i..i + 4].copy_from_slice(&NASTY_WORDS[pick(rng, NASTY_WORDS.len())].to_le_bytes());
        }
        3 => {
            let (i, j) = (pick(rng, b.len()), pick(rng, b.len()));
            let (i, j) = (i.min(j), i.max(j));
            let slice = b[i..j].to_vec();
            b.splice(j..j, slice);
        }
        _ => {
            // A number in the text becomes a nasty one.
            let s = String::from_utf8_lossy(&b).into_owned();
            let starts: Vec<usize> = s
                .char_indices()
                .filter(|&(i, c)| c.is_ascii_digit() && (i == 0 || !s.as_bytes()[i - 1].is_ascii_alphanumeric()))
                .map(|(i, _)| i)
                .collect();
            if let Some(&start) = starts.get(pick(rng, starts.len())) {
                let end = s[start..]
                    .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
                    .map_or(s.len(), |e| start + e);
                let replacement = NASTY_NUMBERS[pick(rng, NASTY_NUMBERS.len())];
                b = format!("{}{replacement}{}", &s[..start], &s[end..]).into_bytes();
            }
        }
    }
    b
}

/// Runs `parse` on `input` (its size in bytes is what justifies allocations):
/// it must not panic, nor allocate more than 64 × the input + 1 MiB at once.
fn check(what: &str, input: &[u8], budget_base: usize, parse: &dyn Fn(&[u8])) {
    LARGEST.with(|l| l.set(0));
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| parse(input)));
    let largest = LARGEST.with(|l| l.get());
    let budget = 64 * (input.len() + budget_base) + (1 << 20);
    if outcome.is_err() || largest > budget {
        let dir = temp_dir("fuzz-failures");
        let path = dir.join(format!("{what}-{:016x}", fnv(input)));
        let _ = std::fs::write(&path, input);
        panic!(
            "{what}: {} on a {}-byte input (largest allocation {largest} bytes); saved as {}",
            if outcome.is_err() { "panic" } else { "allocation too large" },
            input.len(),
            path.display()
        );
    }
}

fn fnv(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ b as u64).wrapping_mul(0x100_0000_01b3))
}

fn iterations() -> usize {
    std::env::var("RT_FUZZ_ITERATIONS").ok().and_then(|v| v.parse().ok()).unwrap_or(1500)
}

/// The corpus of one format, then `iterations()` mutants of each seed.
fn fuzz(format: &str, seeds: &[Vec<u8>], text: bool, parse: &dyn Fn(&[u8])) {
    let corpus = repo().join("tests/fuzz_corpus").join(format);
    let mut cases = 0;
    if let Ok(entries) = std::fs::read_dir(&corpus) {
        for entry in entries.flatten() {
            let bytes = std::fs::read(entry.path()).expect("corpus file");
            check(format, &bytes, 0, parse);
            cases += 1;
        }
    }
    let mut rng = TestRng(fnv(format.as_bytes()));
    for seed in seeds {
        for _ in 0..iterations() {
            let mutant = mutate(seed, &mut rng, text);
            check(format, &mutant, seed.len(), parse);
        }
    }
    println!(
        "{format}: {cases} corpus cases and {} mutants, no panic, allocations within bounds",
        seeds.len() * iterations()
    );
}

fn write_and_load(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    let _ = load_mesh(&path);
    path
}

fn small_mesh() -> MeshData {
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

#[test]
fn scene_files() {
    let seeds: Vec<Vec<u8>> = std::fs::read_dir(repo().join("scenes"))
        .expect("scenes/")
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "toml"))
        .map(|e| std::fs::read(e.path()).expect("scene"))
        .take(3)
        .collect();
    let base = repo().join("scenes");
    fuzz("toml", &seeds, true, &|b| {
        let _ = rt::scene::parse(&String::from_utf8_lossy(b), "fuzz.toml", &base);
    });
}

#[test]
fn rtmesh_files() {
    let seed = rtmesh::encode(&small_mesh());
    fuzz("rtmesh", &[seed], false, &|b| {
        let _ = rtmesh::parse(Path::new("fuzz.rtmesh"), b);
    });
}

#[test]
fn rtinst_files() {
    let spin = glam::Mat4::from_rotation_y(0.5) * glam::Mat4::from_scale(glam::Vec3::splat(2.0));
    let records = [
        rtinst::InstanceRecord::new(&glam::Mat4::IDENTITY, rtinst::OWN_MATERIALS),
        rtinst::InstanceRecord::new(&spin, 0),
        rtinst::InstanceRecord::new(&spin, rtinst::MATERIAL_SET | 1),
    ];
    fuzz(
        "rtinst",
        &[rtinst::encode(&records, &rtinst::MaterialSets::new(1, &[vec![0], vec![0]]).expect("sets"))],
        false,
        &|b| {
            let _ = rtinst::parse(Path::new("fuzz.rtinst"), b);
        },
    );
}

#[test]
fn obj_files() {
    let dir = temp_dir("fuzz-obj");
    let seed =
        b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\nusemtl a\nf 1/1/1 2/1/1 3/1/1\nf 1 2 4\n"
            .to_vec();
    std::fs::write(dir.join("m.mtl"), "newmtl a\nKd 0.5 0.5 0.5\nKe 1 1 1\nNi 1.5\nd 0.5\n").expect("mtl");
    fuzz("obj", &[seed], true, &|b| {
        write_and_load(&dir, "fuzz.obj", b);
    });
    let mtl = b"newmtl a\nKd 0.5 0.5 0.5\nKe 1 1 1\nNi 1.5\nd 0.5\n".to_vec();
    std::fs::write(dir.join("mesh.obj"), b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n").expect("obj");
    fuzz("mtl", &[mtl], true, &|b| {
        std::fs::write(dir.join("m.mtl"), b).expect("mtl");
        let _ = load_mesh(&dir.join("mesh.obj"));
    });
}

/// A one-triangle glTF with an external buffer, and the same as a GLB.
fn gltf_seeds() -> (Vec<u8>, Vec<u8>, Vec<u8>) {
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
    let gltf = json(r#","uri":"fuzz.bin""#).into_bytes();
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

#[test]
fn gltf_and_glb_files() {
    let dir = temp_dir("fuzz-gltf");
    let (gltf, bin, glb) = gltf_seeds();
    std::fs::write(dir.join("fuzz.bin"), &bin).expect("bin");
    fuzz("gltf", std::slice::from_ref(&gltf), true, &|b| {
        write_and_load(&dir, "fuzz.gltf", b);
    });
    std::fs::write(dir.join("fuzz.gltf"), &gltf).expect("gltf");
    fuzz("gltf-bin", &[bin], false, &|b| {
        std::fs::write(dir.join("fuzz.bin"), b).expect("bin");
        let _ = load_mesh(&dir.join("fuzz.gltf"));
    });
    fuzz("glb", &[glb], false, &|b| {
        write_and_load(&dir, "fuzz.glb", b);
    });
}

#[test]
fn rtbvh_files() {
    let mesh = small_mesh();
    let packed = PackedMesh {
        bvh: MeshBvh::build(&mesh, BuildQuality::Medium),
        materials: mesh.materials.clone(),
        textures: Vec::new(),
        vertex_count: mesh.positions.len() as u32,
        triangle_count: mesh.indices.len() as u32,
    };
    let (source, params) = ([7u8; 32], cache::params_hash(BuildQuality::Medium));
    let seed = cache::encode(&packed, source, params);
    let dir = temp_dir("fuzz-rtbvh");
    let path = dir.join("fuzz.rtbvh");
    fuzz("rtbvh", &[seed], false, &|b| {
        std::fs::write(&path, b).expect("write");
        let _ = cache::read(&path, source, params);
    });
}
