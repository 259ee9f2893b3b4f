//! Fuzz targets: every parser rt has, as a function of a byte string, for the fuzzing
//! harnesses (`tests/fuzz.rs` on the stable toolchain, in CI; `fuzz/` for cargo-fuzz and
//! libFuzzer). A target returns the error rt gives (or nothing, for an input it accepts);
//! what it must never do is panic, hang, or use memory beyond what the input's evident
//! size justifies (the harness measures that). The writer target also checks that a
//! write leaves every other file in its folder byte for byte as it was.
//!
//! Seeds (`seeds`) are what the committed corpus in `fuzz/corpus/` was made from; the
//! mutator (`mutate`) is the stable harness's.

pub mod mutate;
pub mod seeds;
mod writer;

use crate::asset::{load_mesh, rtinst, rtmesh};
use crate::bvh::{BuildQuality, SceneGeometry, cache};
use std::path::{Path, PathBuf};

/// One parser under test.
pub struct Target {
    pub name: &'static str,
    /// Inputs are text: the mutator also swaps numbers for nasty ones.
    pub text: bool,
    /// Bytes a valid input may use beyond what its own size justifies: a decoded image is
    /// as large as it declares itself, up to the limit the harness sets.
    pub allowance: usize,
    run: fn(&Workspace, &[u8]) -> Result<(), String>,
}

impl Target {
    /// A target of a crate above this one (the viewport stream's commands, in `rt-watch`).
    pub const fn new(
        name: &'static str,
        text: bool,
        allowance: usize,
        run: fn(&Workspace, &[u8]) -> Result<(), String>,
    ) -> Self {
        Self { name, text, allowance, run }
    }

    /// Runs the parser on `input`; the error rt gives, if any.
    pub fn run(&self, workspace: &Workspace, input: &[u8]) -> Result<(), String> {
        (self.run)(workspace, input)
    }
}

/// Every target of the renderer's parsers (the viewport stream's is `rt_watch`'s).
pub fn targets() -> &'static [Target] {
    const IMAGE: usize = 256 << 20;
    &[
        Target { name: "scene", text: true, allowance: 0, run: scene },
        Target { name: "obj", text: true, allowance: 0, run: obj },
        Target { name: "mtl", text: true, allowance: 0, run: mtl },
        Target { name: "gltf", text: true, allowance: 0, run: gltf },
        Target { name: "gltf_bin", text: false, allowance: 0, run: gltf_bin },
        Target { name: "glb", text: false, allowance: 0, run: glb },
        Target { name: "rtmesh", text: false, allowance: 0, run: rtmesh_file },
        Target { name: "rtbvh", text: false, allowance: 0, run: rtbvh },
        Target { name: "rtinst", text: false, allowance: 0, run: rtinst_file },
        Target { name: "texture", text: false, allowance: IMAGE, run: texture },
        Target { name: "environment", text: false, allowance: IMAGE, run: environment },
        Target { name: "writer", text: false, allowance: 0, run: writer::run },
    ]
}

/// A folder of the files the targets read beside their input (an `.mtl` for an `.obj`,
/// a buffer for a `.gltf`), one per thread of a harness; removed when dropped.
pub struct Workspace {
    scratch: crate::files::ScratchDir,
}

impl Workspace {
    pub fn new() -> std::io::Result<Self> {
        let scratch = crate::files::ScratchDir::new("fuzz")?;
        let dir = scratch.path();
        std::fs::write(dir.join("m.mtl"), seeds::MTL)?;
        std::fs::write(dir.join("mesh.obj"), seeds::OBJ_WITH_MTL)?;
        let (gltf, bin, _) = seeds::gltf_files();
        std::fs::write(dir.join("fuzz.bin"), bin)?;
        std::fs::write(dir.join("mesh.gltf"), gltf.replace("fuzz.bin", "mesh.bin"))?;
        std::fs::write(dir.join("mesh.bin"), seeds::gltf_files().1)?;
        std::fs::create_dir_all(dir.join("writes"))?;
        Ok(Self { scratch })
    }

    pub fn dir(&self) -> &Path {
        self.scratch.path()
    }

    fn file(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, String> {
        let path = self.dir().join(name);
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(path)
    }
}

fn text(input: &[u8]) -> String {
    String::from_utf8_lossy(input).into_owned()
}

/// A scene file, then its geometry built (spheres and meshes placed, the top level built):
/// where a list of many coincident entries once took quadratic time.
fn scene(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    let scene = crate::scene::parse(&text(input), "fuzz.toml", workspace.dir()).map_err(|e| e.to_string())?;
    SceneGeometry::build_in_memory(&scene, BuildQuality::Fastest).map(drop).map_err(|e| format!("{e:#}"))
}

fn mesh(path: &Path) -> Result<(), String> {
    load_mesh(path).map(drop).map_err(|e| e.to_string())
}

fn obj(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    mesh(&workspace.file("fuzz.obj", input)?)
}

fn mtl(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    workspace.file("m.mtl", input)?;
    mesh(&workspace.dir().join("mesh.obj"))
}

fn gltf(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    mesh(&workspace.file("fuzz.gltf", input)?)
}

fn gltf_bin(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    workspace.file("mesh.bin", input)?;
    mesh(&workspace.dir().join("mesh.gltf"))
}

fn glb(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    mesh(&workspace.file("fuzz.glb", input)?)
}

fn rtmesh_file(_: &Workspace, input: &[u8]) -> Result<(), String> {
    rtmesh::parse(Path::new("fuzz.rtmesh"), input).map(drop).map_err(|e| e.to_string())
}

fn rtinst_file(_: &Workspace, input: &[u8]) -> Result<(), String> {
    rtinst::parse(Path::new("fuzz.rtinst"), input).map(drop).map_err(|e| e.to_string())
}

fn rtbvh(workspace: &Workspace, input: &[u8]) -> Result<(), String> {
    let path = workspace.file("fuzz.rtbvh", input)?;
    cache::read(&path, seeds::RTBVH_SOURCE, cache::params_hash(BuildQuality::Medium))
        .map(drop)
        .map_err(|e| format!("{e:?}"))
}

fn texture(_: &Workspace, input: &[u8]) -> Result<(), String> {
    crate::asset::texture::decode(input, "fuzz image").map(drop)
}

fn environment(_: &Workspace, input: &[u8]) -> Result<(), String> {
    crate::sky::EnvironmentImage::decode(input, "fuzz environment").map(drop).map_err(|e| format!("{e:#}"))
}
