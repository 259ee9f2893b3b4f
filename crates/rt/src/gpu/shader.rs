//! WGSL assembly: the module of a program, specialised to a feature set, is built
//! from its entry file and the files that one includes, with the lines of absent
//! effects removed.
//!
//! Each program has one entry file: `integrator.wgsl` (the path tracer),
//! `trace_kernel.wgsl` (traversal alone) and `atmosphere_tables.wgsl` (the
//! atmosphere's table passes). A file names the files it uses on lines
//! `//#include "name.wgsl"` at its top (files of the same folder). The assembler
//! follows them depth first from the entry and writes each file once, after the
//! files it includes, so that the module shows every file after what it uses. A
//! missing file, or an include that closes a cycle, is an error naming the file and
//! line of the include and the file included.
//!
//! Inside a file, `//#if NAME`, `//#if !NAME`, `//#else` and `//#endif` (on
//! lines of their own, nestable) keep or drop lines by the feature flags of
//! [`FeatureSet::flag`]; an include inside a dropped block is not followed, so a
//! scene pays for the files of the effects it uses only. Being comments, both kinds
//! of directive leave every file valid-looking WGSL.
//!
//! The same resolver reads the copies compiled into the binary or a folder on disk
//! (`rt watch --dev`), see [`ShaderFiles`].

#[cfg(test)]
mod covering;
mod resolve;
#[cfg(test)]
mod tests;

use crate::scene::FeatureSet;
use resolve::resolve;
use std::path::PathBuf;

macro_rules! shader {
    ($name:literal) => {
        ($name, include_str!(concat!("../../shaders/", $name)))
    };
}

pub type Part = (&'static str, &'static str);

/// Every shader file compiled into the binary, by name (in no particular order: the
/// includes decide it): the built-in copies the assembler reads, and with `--dev` the
/// files that `rt watch` watches. `display.wgsl`, the viewer's own, is not one.
pub const ALL_PARTS: &[Part] = &[
    shader!("adaptive.wgsl"),
    shader!("aovs.wgsl"),
    shader!("atmosphere.wgsl"),
    shader!("atmosphere_lut.wgsl"),
    shader!("atmosphere_path.wgsl"),
    shader!("atmosphere_scattering.wgsl"),
    shader!("atmosphere_sky.wgsl"),
    shader!("atmosphere_steps.wgsl"),
    shader!("atmosphere_tables.wgsl"),
    shader!("anisotropy.wgsl"),
    shader!("bottom_level.wgsl"),
    shader!("bsdf.wgsl"),
    shader!("bsdf_eval.wgsl"),
    shader!("bvh_walk.wgsl"),
    shader!("camera.wgsl"),
    shader!("coat_normal.wgsl"),
    shader!("common.wgsl"),
    shader!("constants.wgsl"),
    shader!("dielectric.wgsl"),
    shader!("directions.wgsl"),
    shader!("environment.wgsl"),
    shader!("exact_sums.wgsl"),
    shader!("srgb.wgsl"),
    shader!("hit.wgsl"),
    shader!("integrator.wgsl"),
    shader!("lamps.wgsl"),
    shader!("layered_emission.wgsl"),
    shader!("light_tree.wgsl"),
    shader!("lobe_hemispheres.wgsl"),
    shader!("lights.wgsl"),
    shader!("microfacet.wgsl"),
    shader!("microfacet_tables.wgsl"),
    shader!("motion.wgsl"),
    shader!("principled.wgsl"),
    shader!("ray.wgsl"),
    shader!("reflectance.wgsl"),
    shader!("rng.wgsl"),
    shader!("sample_lanes.wgsl"),
    shader!("sampling.wgsl"),
    shader!("segment.wgsl"),
    shader!("sheen.wgsl"),
    shader!("sky.wgsl"),
    shader!("smooth_shading.wgsl"),
    shader!("sphere.wgsl"),
    shader!("sphere_test.wgsl"),
    shader!("sun.wgsl"),
    shader!("texture.wgsl"),
    shader!("thin_film.wgsl"),
    shader!("node_math.wgsl"),
    shader!("node_inputs.wgsl"),
    shader!("node_hash.wgsl"),
    shader!("node_noise.wgsl"),
    shader!("node_perlin.wgsl"),
    shader!("node_ops.wgsl"),
    shader!("node_program.wgsl"),
    shader!("node_spectrum.wgsl"),
    shader!("node_bump.wgsl"),
    shader!("node_attribute.wgsl"),
    shader!("sky_graph.wgsl"),
    shader!("node_step.wgsl"),
    shader!("node_voronoi.wgsl"),
    shader!("node_voronoi_dimensions.wgsl"),
    shader!("normal_map.wgsl"),
    shader!("path_steps.wgsl"),
    shader!("oren_nayar.wgsl"),
    shader!("panorama.wgsl"),
    shader!("surface.wgsl"),
    shader!("terminator_offset.wgsl"),
    shader!("holdout.wgsl"),
    shader!("trace_kernel.wgsl"),
    shader!("transform.wgsl"),
    shader!("traverse.wgsl"),
    shader!("triangle.wgsl"),
    shader!("valid_reflection.wgsl"),
    shader!("wide_bvh.wgsl"),
];

/// Every built-in file: [`ALL_PARTS`] and the lobe modules' own (`scene::lobe`).
pub fn built_in_files() -> impl Iterator<Item = Part> {
    ALL_PARTS.iter().copied().chain(crate::scene::lobe::LOBES.iter().map(|l| l.wgsl))
}

/// Which entry points a module carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Program {
    /// `render`: the path-tracing megakernel.
    Integrator,
    /// `trace`, `generate_camera_rays`, `generate_diffuse_rays`, `generate_through_rays`.
    Trace,
}

impl Program {
    /// The file the program's module is assembled from.
    fn entry_file(self) -> &'static str {
        match self {
            Program::Integrator => "integrator.wgsl",
            Program::Trace => "trace_kernel.wgsl",
        }
    }
}

/// The file generated from [`crate::shared_constants`], in no folder: the constants the
/// shaders share with the host.
const SHARED_CONSTANTS: &str = "shared_constants.wgsl";

/// The file generated from [`crate::scene::lobe`]'s registry, in no folder: each lobe
/// module's file behind its flag, its parameters' accessors and the calls of its functions.
const LOBE_MODULES: &str = "lobe_modules.wgsl";

/// The ending of the files generated from [`crate::layout`]'s GPU structs, in no folder:
/// `Frame.struct.wgsl` declares the struct `Frame`.
const STRUCT_FILE: &str = ".struct.wgsl";

/// The ending of the files generated from the scene group's bindings
/// (`super::scene_bindings`): `lamps.bindings.wgsl` declares those of `lamps.wgsl`.
const BINDINGS_FILE: &str = ".bindings.wgsl";

/// The text of `name` if it is a file the assembler makes rather than reads.
fn generated(name: &str) -> Option<Result<String, String>> {
    if name == SHARED_CONSTANTS {
        return Some(Ok(crate::shared_constants::wgsl()));
    }
    if name == LOBE_MODULES {
        return Some(Ok(crate::scene::lobe::wgsl()));
    }
    if let Some(file) = name.strip_suffix(BINDINGS_FILE) {
        return Some(
            super::scene_bindings::declarations(file)
                .ok_or_else(|| format!("{name}: no binding of the scene group is declared in {file}.wgsl")),
        );
    }
    let name = name.strip_suffix(STRUCT_FILE)?;
    Some(
        crate::layout::struct_declaration(name)
            .ok_or_else(|| format!("{name}{STRUCT_FILE}: no GPU struct `{name}` is declared in src/layout.rs")),
    )
}

/// The entry file of the atmosphere's table passes.
const ATMOSPHERE_TABLES_ENTRY: &str = "atmosphere_tables.wgsl";

/// Where the shader files are read from.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum ShaderFiles {
    /// The copies compiled into the binary.
    #[default]
    BuiltIn,
    /// A `shaders/` folder on disk, read at every assembly: `rt watch --dev` edits shaders live.
    Dir(PathBuf),
}

impl ShaderFiles {
    /// The text of one shader file, or why it cannot be had.
    fn read(&self, name: &str) -> Result<String, String> {
        if let Some(text) = generated(name) {
            return text;
        }
        match self {
            ShaderFiles::BuiltIn => built_in_files()
                .find(|(part, _)| *part == name)
                .map(|(_, text)| text.to_string())
                .ok_or_else(|| format!("shaders/{name}: no such file among the built-in shaders")),
            ShaderFiles::Dir(dir) => {
                let path = dir.join(name);
                crate::files::read_to_string(&path).map_err(|e| e.to_string())
            }
        }
    }
}

/// The program that builds the atmosphere's tables (entry points
/// `build_transmittance`, `build_second_order`, `build_third_order`,
/// `build_fourth_order`, `build_closure`). Its files take no `//#if`: it is the same
/// for every scene with an atmosphere.
pub fn atmosphere_tables_source() -> String {
    // The built-in files are checked by the tests.
    resolve(&ShaderFiles::BuiltIn, ATMOSPHERE_TABLES_ENTRY, &|_| None).unwrap_or_else(|e| panic!("{e}"))
}

/// The WGSL source of `program` specialised to `features`, from the built-in shaders.
pub fn assemble(program: Program, features: &FeatureSet) -> String {
    // The built-in files are checked by the tests for every feature set.
    assemble_from(&ShaderFiles::BuiltIn, program, features).unwrap_or_else(|e| panic!("{e}"))
}

/// The WGSL source of `program` specialised to `features`, from `files`; an error names
/// the file that cannot be read, or whose directives or (read from disk) syntax are wrong.
pub fn assemble_from(files: &ShaderFiles, program: Program, features: &FeatureSet) -> Result<String, String> {
    let source = resolve(files, program.entry_file(), &|flag| features.flag(flag))?;
    if let ShaderFiles::Dir(_) = files {
        check_syntax(&source)?;
    }
    Ok(source)
}

/// A WGSL syntax error in an assembled module, named by the file it is in and the line's
/// text: wgpu's own message counts lines of the whole module, which no file has.
fn check_syntax(source: &str) -> Result<(), String> {
    let Err(e) = wgpu::naga::front::wgsl::parse_str(source) else { return Ok(()) };
    let Some(at) = e.location(source) else { return Err(e.message().to_owned()) };
    let lines: Vec<&str> = source.lines().collect();
    let line = (at.line_number as usize).clamp(1, lines.len().max(1)) - 1;
    let file = lines.iter().take(line + 1).rev().find_map(|l| l.strip_prefix("// ---- ")).unwrap_or("shaders");
    let text = lines.get(line).map_or("", |l| l.trim());
    Err(format!("{file}: {}: `{text}`", e.message()))
}

/// Both programs with every flag on, under each sky that brings structs of its
/// own, and the atmosphere's tables program: for the struct layout test.
#[cfg(test)]
pub fn full_sources_for_layout_checks() -> [String; 5] {
    use crate::scene::{RoughTransmission, Sampling, SkyFeature};
    let all = FeatureSet::all(SkyFeature::Uniform, Sampling::Nee, RoughTransmission::Ggx);
    let atmosphere = FeatureSet { sky: SkyFeature::Atmosphere, ..all };
    let environment = FeatureSet { sky: SkyFeature::Environment, ..all };
    [
        assemble(Program::Integrator, &all),
        assemble(Program::Trace, &all),
        assemble(Program::Integrator, &atmosphere),
        assemble(Program::Integrator, &environment),
        atmosphere_tables_source(),
    ]
}
