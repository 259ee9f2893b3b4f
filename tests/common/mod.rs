//! Shared by the GPU integration tests: one device for the whole test binary, and scene helpers.
#![allow(dead_code)]

pub mod bounded;
pub mod layers;
pub mod measured;
pub mod paired;
pub mod quad_gltf;
pub mod reference;

use rt::bvh::BuildQuality;
use rt::gpu::GpuContext;
use rt::render::{Image, RenderRequest, Session};
use rt::scene::{FeatureSet, Scene};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Rec. 709 luminance of a linear RGB value.
pub fn luminance(p: [f32; 3]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Squared error of the displayed (tone-mapped, 8-bit sRGB) images, in 0..255 per
/// value: what a viewer sees, so that the emitters' radiance does not drown the rest.
#[cfg(feature = "denoise")]
pub fn display_mse(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    use rt::render::tonemap::display_pixel;
    let sum: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(a, b)| {
            let (a, b) = (display_pixel(*a, 0.0), display_pixel(*b, 0.0));
            (0..3).map(move |c| (a[c] as f64 - b[c] as f64).powi(2))
        })
        .sum();
    sum / (a.len() * 3) as f64
}

/// Every effect compiled into one pipeline, as `rt bench` forces them, but the node-graph
/// interpreter: it is compiled and tested by the node-graph tests, and each pipeline that
/// holds it takes minutes to compile on lavapipe.
pub fn all_features_but_node_graphs(own: FeatureSet, scene: &Scene) -> FeatureSet {
    FeatureSet { node_graphs: false, ..FeatureSet::all(own.sky, own.sampling, scene.render.rough_transmission) }
}

pub fn gpu() -> &'static GpuContext {
    static GPU: OnceLock<GpuContext> = OnceLock::new();
    GPU.get_or_init(new_gpu)
}

/// A device of the caller's own (`RT_ADAPTER`, else the default adapter), for tests whose
/// GPU errors must not reach the tests sharing [`gpu`].
pub fn new_gpu() -> GpuContext {
    GpuContext::new(std::env::var("RT_ADAPTER").ok().as_deref()).expect("a Vulkan adapter (lavapipe in CI)")
}

/// A ray for the trace kernel from `o` along `d` (normalised here), unbounded.
pub fn trace_ray(o: glam::DVec3, d: glam::DVec3) -> rt::layout::GpuTraceRay {
    rt::layout::GpuTraceRay {
        origin: o.as_vec3().to_array(),
        t_max: f32::MAX,
        direction: d.normalize().as_vec3().to_array(),
        _pad: 0,
    }
}

/// The scene files of `scenes/`, sorted.
pub fn scene_files() -> Vec<PathBuf> {
    let mut scenes: Vec<_> = std::fs::read_dir(repo().join("scenes"))
        .expect("scenes/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    scenes
}

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A scene from TOML text whose relative paths resolve against the repository root.
pub fn scene_from(text: &str) -> Scene {
    rt::scene::parse(text, "test.toml", &repo()).unwrap_or_else(|e| panic!("{e}"))
}

pub fn render(scene: Scene, width: u32, height: u32, spp: u32, max_bounces: u32) -> Image {
    render_request(scene, |r| (r.width, r.height, r.spp, r.max_bounces) = (width, height, spp, max_bounces)).0
}

/// Renders `scene` with the request its own settings give, changed by `adjust`; returns the
/// image and the feature set the session specialised for. No sample may be dropped.
pub fn render_request(scene: Scene, adjust: impl FnOnce(&mut RenderRequest)) -> (Image, FeatureSet) {
    let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let mut request = RenderRequest::from_scene(session.scene());
    adjust(&mut request);
    let (image, report) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(report.dropped.is_clean(), "{}", report.dropped);
    (image, session.features())
}

pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rt-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// [`temp_dir`] emptied of what an earlier run left there.
pub fn empty_temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rt-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    temp_dir(name)
}

/// The Python with Blender's `bpy` that RT_BPY_PYTHON names (relative to the repository
/// root if relative), checked once to import bpy.
pub fn bpy_python() -> PathBuf {
    static PYTHON: OnceLock<PathBuf> = OnceLock::new();
    PYTHON
        .get_or_init(|| {
            let Some(python) = std::env::var_os("RT_BPY_PYTHON") else {
                panic!(
                    "RT_BPY_PYTHON is not set: it must name a Python 3.11 with bpy==5.0.1 \
                     (scripts/test creates .venv-bpy and sets it)"
                );
            };
            let python = PathBuf::from(python);
            let python = if python.is_relative() { repo().join(python) } else { python };
            match std::process::Command::new(&python).args(["-c", "import bpy"]).output() {
                Ok(out) if out.status.success() => python,
                Ok(out) => panic!(
                    "RT_BPY_PYTHON={} cannot import bpy:\n{}",
                    python.display(),
                    String::from_utf8_lossy(&out.stderr)
                ),
                Err(e) => panic!("RT_BPY_PYTHON={} does not run: {e}", python.display()),
            }
        })
        .clone()
}

/// Runs `tests/blender/<script>` with Blender's Python, its output folder `out` the
/// argument, and returns what it wrote to stderr; panics with that log if it fails.
pub fn run_bpy_script(script: &str, out: &Path) -> String {
    let result = std::process::Command::new(bpy_python())
        .arg(repo().join("tests/blender").join(script))
        .arg(out)
        .output()
        .expect("bpy runs");
    let log = String::from_utf8_lossy(&result.stderr).into_owned();
    assert!(result.status.success(), "{script} failed:\n{log}");
    log
}

/// A closed, subdivided icosahedron of unit radius as OBJ text.
pub fn icosphere_obj(subdivisions: u32) -> (String, Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut f: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let normalise = |p: [f64; 3]| {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        [p[0] / l, p[1] / l, p[2] / l]
    };
    for p in v.iter_mut() {
        *p = normalise(*p);
    }
    for _ in 0..subdivisions {
        let mut midpoint = std::collections::HashMap::new();
        let mut next = Vec::new();
        for tri in &f {
            let mut mid = |a: usize, b: usize| {
                *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let p =
                        normalise([(v[a][0] + v[b][0]) / 2.0, (v[a][1] + v[b][1]) / 2.0, (v[a][2] + v[b][2]) / 2.0]);
                    v.push(p);
                    v.len() - 1
                })
            };
            let (a, b, c) = (tri[0], tri[1], tri[2]);
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    // Positions as f32 so that the CPU reference sees exactly what the GPU does.
    let v: Vec<[f64; 3]> = v.iter().map(|p| p.map(|c| c as f32 as f64)).collect();
    let mut text = String::new();
    for p in &v {
        text.push_str(&format!("v {} {} {}\n", p[0] as f32, p[1] as f32, p[2] as f32));
    }
    for t in &f {
        text.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    (text, v, f)
}

pub fn write(path: &Path, text: &str) {
    std::fs::write(path, text).expect("write test file");
}

/// A small deterministic generator for test inputs (SplitMix64).
pub struct TestRng(pub u64);

impl TestRng {
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn unit_vector(&mut self) -> [f64; 3] {
        let z = 2.0 * self.next_f64() - 1.0;
        let phi = 2.0 * std::f64::consts::PI * self.next_f64();
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    }
}

/// `rt bench accuracy` of `knobs` at its smallest useful size (32×24, levels 1, 2 and 4 spp,
/// one repeat, a 16-spp reference), its report in `out`.
pub fn small_accuracy_options(knobs: &[&str], out: PathBuf) -> rt_bench::AccuracyOptions {
    rt_bench::AccuracyOptions {
        knobs: knobs.iter().map(|k| k.to_string()).collect(),
        out,
        size: Some((32, 24)),
        levels: Some(vec![1, 2, 4]),
        repeats: Some(1),
        reference_spp: Some(16),
        ..Default::default()
    }
}
